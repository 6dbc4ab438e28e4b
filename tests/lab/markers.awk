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
# `stubs` (optional): the stub store, a directory holding NN_name.stubs for
# a stage whose markers are one line each (below).
# Errors go to stderr as "FILE:LINE: error: ..."; the exit status is then 1.
#
# The stub store keeps hints and stubs out of the solution: in a stage with
# a store file, a region's opening marker is one line, `/* LAB NN: name */`,
# and STORE/NN_name.stubs holds, for each LAB NN region of that stage, the
# marker comment the region would otherwise carry, under a line naming the
# file and the one-line marker:
#       render.c: /* LAB 07: Russian roulette */
#       /* LAB 07: past RR_MIN_DEPTH, survive with probability q ...
#        * stub: (void)path;
#        * (void)rng; */
# Every mode reads the region as if that comment stood in the source in
# place of the one-line marker (line numbers stay the source's).  Blank
# lines and lines starting with '#' between entries are comments.  In
# handout and lint modes, a stage with a store file must have one-line
# markers only, an entry for each of its own lab's markers, and no entry
# that no marker of a file read uses.

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
        printf "%s\t%d\t%d\t%s\t%s\n", FILENAME, r_open, FNR, r_label, whole_hint()
    st = 0
}

# The region's hint, its lines joined (LAB.md's list of places quotes it
# whole: its first line alone can stop mid-sentence).
function whole_hint(    i, h) {
    h = ""
    for (i = 1; i <= n_hint; i++)
        h = h (i > 1 ? " " : "") hint[i]
    return h
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

# --- the stub store ------------------------------------------------------

# cur_file, cur_stage: FILENAME's base name and its directory's name.
function split_path(f,    n, parts) {
    n = split(f, parts, "/")
    cur_file = parts[n]
    cur_stage = n > 1 ? parts[n - 1] : ""
}

function is_entry_head(s) {
    return s ~ /^[A-Za-z0-9_.-]+: \/\* LAB [0-9][0-9]: .*\*\/$/
}

# Reads STORE/STAGE.stubs once; has_store[STAGE] says whether it exists.
function load_store(stage,    path, line, status, n, key, in_entry, head_line) {
    if (stage in has_store) return
    has_store[stage] = 0
    if (stubs == "" || stage == "") return
    path = stubs "/" stage ".stubs"
    n = 0
    in_entry = 0
    while ((status = (getline line < path)) > 0) {
        n++
        has_store[stage] = 1
        sub(/\r$/, "", line)
        if (in_entry) {
            if (entry_n[key] == 0 && (line !~ /^\/\* LAB [0-9][0-9]:/ || substr(line, 8, 2) != e_label[n_entries]))
                err(path, n, "an entry's text starts with its marker comment, '/* LAB " e_label[n_entries] ": hint'")
            entry_line[key, ++entry_n[key]] = line
            if (index(line, "*/") > 0) in_entry = 0
            continue
        }
        if (line ~ /^[ \t\r]*$/ || line ~ /^#/) continue
        if (!is_entry_head(line)) {
            err(path, n, "expected 'FILE: /* LAB NN: name */' to start an entry, found '" line "'")
            continue
        }
        head_line = n
        key = stage SUBSEP line
        if (key in entry_n) {
            err(path, n, "a second entry for '" line "'")
            continue
        }
        entry_n[key] = 0
        n_entries++
        e_key[n_entries] = key
        e_stage[n_entries] = stage
        e_file[n_entries] = substr(line, 1, index(line, ":") - 1)
        e_label[n_entries] = substr(line, index(line, "LAB ") + 4, 2)
        e_where[n_entries] = path
        e_line[n_entries] = head_line
        in_entry = 1
    }
    if (status == 0 || n > 0) has_store[stage] = 1
    close(path)
    if (in_entry) err(path, head_line, "the entry's comment is never closed with */")
}

# The store is enforced (one-line markers, every entry used) where it exists,
# in the modes that read a stage's solution as a whole.
function strict_here() {
    return (mode == "handout" || mode == "lint") && has_store[cur_stage]
}

# A marker line as its entry's heading names it.
function store_key(s,    t) {
    t = s
    sub(/^[ \t]+/, "", t)
    t = rtrim(t)
    return cur_stage SUBSEP cur_file ": " t
}

function open_marker(s,    k, i, lbl) {
    k = store_key(s)
    lbl = substr(s, index(s, "LAB ") + 4, 2)
    if (strict_here() && s !~ /\*\/[ \t\r]*$/)
        err(FILENAME, FNR, "a marker over several lines in a stage with a stub store: the marker is one line, '/* LAB " lbl ": name */', its hint and stub go in " stubs "/" cur_stage ".stubs")
    if (!(k in entry_n)) {
        if (strict_here() && lbl == substr(cur_stage, 1, 2))
            err(FILENAME, FNR, "no entry '" cur_file ": " substr(k, index(k, ": ") + 2) "' in " stubs "/" cur_stage ".stubs")
        start_region(s)
        return
    }
    if (entry_used[k] && strict_here())
        err(FILENAME, FNR, "a second marker '" rtrim(s) "' in this file: a marker names one region")
    entry_used[k] = 1
    match(s, /^[ \t]*/)
    start_region(substr(s, 1, RLENGTH) entry_line[k, 1])
    for (i = 2; i <= entry_n[k]; i++) comment_line(entry_line[k, i])
}

# Entries for file F of its stage that no marker used.
function check_unused(f,    j) {
    split_path(f)
    if (!strict_here()) return
    for (j = 1; j <= n_entries; j++)
        if (e_stage[j] == cur_stage && e_file[j] == cur_file && !entry_used[e_key[j]])
            err(e_where[j], e_line[j], "no marker in " f " uses this entry")
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

FNR == 1 && NR > 1 { unclosed(prev_file); check_unused(prev_file) }
FNR == 1 { split_path(FILENAME); load_store(cur_stage) }
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
    if (is_open($0)) open_marker($0)
    else if (is_end($0)) err(FILENAME, FNR, "/* END LAB */ without an open LAB region")
    else {
        if (looks_like_marker($0)) err(FILENAME, FNR, "malformed LAB marker (a marker line is '/* LAB NN: hint' or '/* END LAB */', alone on its line)")
        code_line($0)
    }
}

END {
    if (bad_usage) exit 2
    unclosed(prev_file)
    if (prev_file != "") check_unused(prev_file)
    exit errors > 0 ? 1 : 0
}
