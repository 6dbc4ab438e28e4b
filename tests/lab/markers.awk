# markers.awk - reads C sources that carry LAB markers (tests/lab/README.md).
#
#   awk -v mode=MODE [-v lab=NN] [-v stage=NN] [-v docref=TEXT] -f markers.awk FILE...
#
# A region is
#       /* LAB NN: hint, one or more comment lines
#        * stub: code that replaces the region in the handout
#        * more stub lines */
#       ... the solution ...
#       /* END LAB */
# Modes:
#   lint     check the markers; print nothing
#   handout  print the file (one FILE) as the lab handout of LAB `lab`: its
#            regions become hint + TODO + stub; other labs' regions keep their
#            code and lose their marker lines
#   regions  FILE <tab> open line <tab> end line <tab> NN <tab> first hint line
#   inside   FILE <tab> LINE <tab> text: the body lines of LAB `lab` regions
#   outside  FILE <tab> LINE <tab> text: every other line but marker lines,
#            and the stub lines of LAB `lab` regions (the handout has them)
# `stage` (optional): the stage the files belong to; a label above it is an
# error.  `docref` (optional, handout mode): text in hints to replace by
# LAB.md (the handout's copy of the docs page's Lab section).
# Errors go to stderr as "FILE:LINE: error: ..."; the exit status is then 1.

function err(file, line, msg) {
    printf "%s:%d: error: %s\n", file, line, msg > "/dev/stderr"
    errors++
}

function rtrim(s) {
    sub(/[ \t\r]+$/, "", s)
    return s
}

function replace_all(s, from, to,    out, i) {
    if (from == "") return s
    out = ""
    while ((i = index(s, from)) > 0) {
        out = out substr(s, 1, i - 1) to
        s = substr(s, i + length(from))
    }
    return out s
}

function is_open(s) { return s ~ /^[ \t]*\/\* LAB [0-9][0-9]:/ }
function is_end(s) { return s ~ /^[ \t]*\/\* END LAB( [0-9][0-9])? \*\/[ \t\r]*$/ }
function looks_like_marker(s) { return s ~ /\/\*[ \t]*(END[ \t]*)?LAB([ \t0-9:]|$)/ }

function start_region(s,    rest, pos) {
    match(s, /^[ \t]*/)
    r_indent = substr(s, 1, RLENGTH)
    rest = substr(s, RLENGTH + 1)
    r_label = substr(rest, 8, 2)
    rest = substr(rest, 11)
    sub(/^[ \t]+/, "", rest)
    r_file = FILENAME
    r_open = FNR
    r_body = 0
    n_hint = 0
    n_stub = 0
    in_stub = 0
    if (stage != "" && r_label + 0 > stage + 0)
        err(FILENAME, FNR, "LAB " r_label " in stage " stage ": a stage holds only its own and earlier labs")
    pos = index(rest, "*/")
    if (pos > 0) {
        if (substr(rest, pos + 2) !~ /^[ \t\r]*$/)
            err(FILENAME, FNR, "text after the */ that closes a LAB marker")
        rest = rtrim(substr(rest, 1, pos - 1))
    }
    if (index(rest, "stub:") > 0)
        err(FILENAME, FNR, "'stub:' must begin a comment line of its own (' * stub: ...')")
    rest = rtrim(rest)
    if (rest == "")
        err(FILENAME, FNR, "a LAB marker needs a hint after 'LAB " r_label ":'")
    hint[++n_hint] = rest
    st = 1
    if (pos > 0) comment_done()
}

function comment_line(s,    pos, closing, c) {
    pos = index(s, "*/")
    closing = pos > 0
    c = s
    if (closing) {
        if (substr(s, pos + 2) !~ /^[ \t\r]*$/)
            err(FILENAME, FNR, "text after the */ that closes a LAB marker")
        c = substr(s, 1, pos - 1)
    }
    if (c ~ /^[ \t]*\*/) {
        sub(/^[ \t]*\*/, "", c)
        sub(/^ /, "", c)
    } else if (c !~ /^[ \t\r]*$/) {
        err(FILENAME, FNR, "a continuation line of a LAB marker must start with ' * '")
    }
    c = rtrim(c)
    if (!in_stub && c ~ /^stub:/) {
        in_stub = 1
        c = substr(c, 6)
        sub(/^[ \t]+/, "", c)
        if (c != "") stub[++n_stub] = c
    } else if (in_stub) {
        stub[++n_stub] = c
    } else if (c !~ /^[ \t]*$/) {
        hint[++n_hint] = c
    }
    if (closing) comment_done()
}

function comment_done(    i) {
    st = 2
    while (n_stub > 0 && stub[n_stub] ~ /^[ \t]*$/) n_stub--
    if (mode == "handout" && r_label == lab) print_stub()
    # The stub is in the handout too.
    if (mode == "outside" && r_label == lab)
        for (i = 1; i <= n_stub; i++) printf "%s\t%d\t%s\n", FILENAME, r_open, stub[i]
}

function print_stub(    i, h) {
    for (i = 1; i <= n_hint; i++) {
        h = replace_all(replace_all(hint[i], docref "#lab", "LAB.md"), docref, "LAB.md")
        if (i == 1) h = r_indent "/* LAB " r_label ": " h
        else h = r_indent " * " h
        if (i == n_hint) h = h " */"
        print h
    }
    if (n_stub > 0)
        print r_indent "/* TODO: write this part; the stub below only keeps the program compiling. */"
    else
        print r_indent "/* TODO: write this part. */"
    for (i = 1; i <= n_stub; i++)
        print (stub[i] == "" ? "" : r_indent stub[i])
}

function end_region(s,    t) {
    t = s
    if (match(t, /LAB [0-9][0-9]/) && substr(t, RSTART + 4, 2) != r_label)
        err(FILENAME, FNR, "'" rtrim(s) "' closes LAB " r_label " (opened at line " r_open ")")
    if (r_body == 0)
        err(FILENAME, r_open, "empty LAB " r_label " region")
    if (mode == "handout" && r_label == lab) print s
    if (mode == "regions")
        printf "%s\t%d\t%d\t%s\t%s\n", FILENAME, r_open, FNR, r_label, hint[1]
    st = 0
}

function body_line(s) {
    if (s !~ /^[ \t\r]*$/) r_body++
    if (r_label == lab) {
        if (mode == "inside") printf "%s\t%d\t%s\n", FILENAME, FNR, s
    } else {
        code_line(s)
    }
}

function code_line(s) {
    if (mode == "handout") print s
    else if (mode == "outside") printf "%s\t%d\t%s\n", FILENAME, FNR, s
}

function unclosed(file) {
    if (st == 1)
        err(file, r_open, "LAB " r_label " marker comment never closed with */")
    else if (st == 2)
        err(file, r_open, "LAB " r_label " region never closed with /* END LAB */")
    st = 0
}

BEGIN {
    if (mode !~ /^(lint|handout|regions|inside|outside)$/) {
        print "markers.awk: error: mode must be lint, handout, regions, inside or outside" > "/dev/stderr"
        bad_usage = 1
        exit 2
    }
    if (mode == "handout" && lab !~ /^[0-9][0-9]$/) {
        print "markers.awk: error: handout mode needs -v lab=NN" > "/dev/stderr"
        bad_usage = 1
        exit 2
    }
    st = 0
    errors = 0
}

FNR == 1 && NR > 1 { unclosed(prev_file) }
{ prev_file = FILENAME }

st == 1 {
    comment_line($0)
    next
}

st == 2 {
    if (is_end($0)) end_region($0)
    else if (is_open($0)) err(FILENAME, FNR, "LAB region inside LAB " r_label " (opened at line " r_open ")")
    else {
        if (looks_like_marker($0)) err(FILENAME, FNR, "malformed LAB marker (a marker line is '/* LAB NN: hint' or '/* END LAB */', alone on its line)")
        body_line($0)
    }
    next
}

{
    if (is_open($0)) start_region($0)
    else if (is_end($0)) err(FILENAME, FNR, "/* END LAB */ without an open LAB region")
    else {
        if (looks_like_marker($0)) err(FILENAME, FNR, "malformed LAB marker (a marker line is '/* LAB NN: hint' or '/* END LAB */', alone on its line)")
        code_line($0)
    }
}

END {
    if (bad_usage) exit 2
    unclosed(prev_file)
    exit errors > 0 ? 1 : 0
}
