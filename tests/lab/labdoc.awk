# labdoc.awk - prints the "Lab" section of a stage's docs page for LAB.md.
#
#   awk -v dir=docs/stages -v assets=FILE -f labdoc.awk PAGE
#
# The section runs from a heading "## Lab" (or "## Lab: ...") to the next
# heading of level 1 or 2; its own heading is dropped and its subheadings
# move up one level (LAB.md has its own title).  Inline links and images
# are rewritten for LAB.md, which sits at the top of the handout:
#   - a link to a file that is not a .md page becomes a project-relative
#     path and the path goes to `assets` (one a line), for the caller to
#     copy into the handout;
#   - a link to a .md page becomes plain text naming the page (pages are
#     not copied: they may explain the solution);
#   - URLs, absolute paths and #anchors are kept.
# `dir` is the page's directory, relative to the project root.
# Exit status 3 when the page has no Lab section.

function normalize(path,    n, parts, out, k, i) {
    n = split(path, parts, "/")
    k = 0
    for (i = 1; i <= n; i++) {
        if (parts[i] == "" || parts[i] == ".") continue
        if (parts[i] == ".." && k > 0 && out[k] != "..") { k--; continue }
        out[++k] = parts[i]
    }
    path = ""
    for (i = 1; i <= k; i++) path = path (i > 1 ? "/" : "") out[i]
    return path
}

# The position of the last "[" in s, 0 when there is none.
function last_bracket(s,    i, p) {
    p = 0
    while ((i = index(substr(s, p + 1), "[")) > 0) p += i
    return p
}

function rewrite(s,    out, i, j, target, file, anchor, title, pre, k, path) {
    out = ""
    while ((i = index(s, "](")) > 0) {
        pre = substr(s, 1, i - 1)
        s = substr(s, i + 2)
        j = index(s, ")")
        if (j == 0) { out = out pre "]("; break }
        target = substr(s, 1, j - 1)
        s = substr(s, j + 1)
        title = ""
        if ((k = index(target, " ")) > 0) {
            title = substr(target, k)
            target = substr(target, 1, k - 1)
        }
        if (target ~ /^([a-zA-Z][a-zA-Z0-9+.-]*:|\/|#)/ || target == "") {
            out = out pre "](" target title ")"
            continue
        }
        file = target
        anchor = ""
        if ((k = index(file, "#")) > 0) {
            anchor = substr(file, k)
            file = substr(file, 1, k - 1)
        }
        path = normalize(dir "/" file)
        if (path ~ /\.md$/) {
            k = last_bracket(pre)
            if (k > 0) {
                out = out substr(pre, 1, k - 1) substr(pre, k + 1) " (stagelight's `" path "`)"
            } else {
                out = out pre "](" path anchor title ")"
            }
            continue
        }
        print path > assets
        out = out pre "](" path anchor title ")"
    }
    return out s
}

# Blank lines are held back: none at the start or the end of the section.
function emit(s) {
    if (s ~ /^[ \t]*$/) {
        if (printed) pending++
        return
    }
    for (; pending > 0; pending--) print ""
    print s
    printed = 1
}

BEGIN { found = 0; insec = 0; done = 0; fence = 0 }

/^[ \t]*(```|~~~)/ {
    fence = !fence
    if (insec) emit($0)
    next
}

!fence && /^#+[ \t]/ {
    match($0, /^#+/)
    level = RLENGTH
    if (insec && level <= 2) { insec = 0; done = 1 }
    if (!insec && !done && level == 2 && $0 ~ /^##[ \t]+Lab([ \t:.,-]|$)/) {
        insec = 1
        found = 1
        next
    }
    if (insec) {
        emit(rewrite(substr($0, 2)))
        next
    }
}

insec { emit(rewrite($0)) }

END { exit found ? 0 : 3 }
