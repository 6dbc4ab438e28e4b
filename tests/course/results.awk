# results.awk - Gradescope's results.json from a grading by grade.sh.
#
#   awk -v report=FILE -v keep=DIR -v secs=N -f results.awk DIR/tests
#
# DIR is grade.sh --keep's directory: its tests file (how each TEST()
# counted, grade.awk's tests=: KIND FROM PROGRAM TEST STATUS NOTE), the test
# programs' logs and the build's; report is grade.sh's output (the report,
# its report pages' lines and the GRADE line); secs the grading's seconds.
# Writes, as Gradescope's autograder specification describes results.json:
#   score           the points: one per scored test of the lab that passes
#                   (grade.sh's lab_passed; the assignment's total is its
#                   lab_total), times lab_total / (lab_total + regressions)
#                   when controls or earlier tests fail (grade.awk), with a
#                   "regressions" entry of the difference
#   execution_time, output (make grade's report), visibility,
#   stdout_visibility
#   tests[]         {name, score, max_score, status, output, visibility},
#                   and output_format where it is HTML: first, when the
#                   stage or some test programs do not build, a failing
#                   "build" entry with the compiler's errors; then one entry
#                   per scored test of the lab (max_score 1), its controls
#                   and skipped tests (max_score 0: not scored, as make grade
#                   lists them), one per earlier stage's test program
#                   (max_score 0: a regression fails it), and one per report
#                   page (max_score 0: the region lines, then the page)
# why=TEXT: nothing was graded (run_autograder found no stage to grade):
# one failing "submission" entry says why.
# Nothing here decides what counts: grade.awk did (the KIND of each line).
BEGIN {
    FS = "\t"
    while ((getline l < report) > 0) {
        rep = rep l "\n"
        if (l ~ /^GRADE /) grade_line = l
        if (l ~ /^report pages/) { in_pages = 1; continue }
        if (in_pages && l ~ /^    [^ ]/) {
            np++
            pname[np] = substr(l, 5); sub(/:.*/, "", pname[np])
            ptext[np] = substr(l, 5) "\n"
            # compare's verdicts that pass: "consistent ...", "within the limit ...";
            # a paired page's line ends with its verdict
            if (l ~ /, paired with the solution's render /) pfailed[np] = (l !~ /: consistent$/)
            else pfailed[np] = (l !~ /^    [^ :]*: (consistent|within|not tested)/)
            continue
        }
        if (in_pages && l ~ /^        /) {
            if (l ~ /\.html$/) { ppath[np] = l; sub(/^ +/, "", ppath[np]) }
            ptext[np] = ptext[np] substr(l, 5) "\n"
            continue
        }
        in_pages = 0
    }
    close(report)
    n = split(grade_line, g, " ")
    for (i = 2; i <= n; i++) { split(g[i], kv, "="); gv[kv[1]] = kv[2] }
    build = gv["build"]
    for (i = 1; i < 32; i++) ctrl[i] = sprintf("%c", i)
}

# s with every match of the regular expression re (a string: a /re/
# argument would be the match of $0) replaced by rep, taken
# literally (gsub's replacement escapes differ between awks).
function replace(s, re, rep,    a, n, i, r) {
    n = split(s, a, re)
    r = a[1]
    for (i = 2; i <= n; i++) r = r rep a[i]
    return r
}

# A JSON string: backslash, quote and control characters escaped.
function jstr(s,    i) {
    s = replace(s, "\\\\", "\\\\")
    s = replace(s, "\"", "\\\"")
    s = replace(s, "\n", "\\n")
    s = replace(s, "\t", "\\t")
    s = replace(s, "\r", "\\r")
    for (i = 1; i < 32; i++)
        if (i != 9 && i != 10 && i != 13 && index(s, ctrl[i])) s = replace(s, ctrl[i], sprintf("\\u%04x", i))
    return "\"" s "\""
}

function html(s) {
    s = replace(s, "&", "&amp;")
    s = replace(s, "<", "&lt;")
    return replace(s, ">", "&gt;")
}

function entry(name, score, max, status, output, format) {
    # (concatenated: an awk's sprintf may hold no more than 8 KB)
    e[++ne] = "{\"name\": " jstr(name) ", \"score\": " score ", \"max_score\": " max ", \"status\": " jstr(status) \
        ", \"output\": " jstr(output) ", " (format != "" ? "\"output_format\": " jstr(format) ", " : "") "\"visibility\": \"visible\"}"
}

# The lines a test program printed for TEST() t: those after the previous
# test's result line, up to t's own.
function test_output(prog, t,    f, l, block, w) {
    if (!(prog in loaded)) {
        loaded[prog] = 1
        f = keep "/" prog ".log"
        block = ""
        while ((getline l < f) > 0) {
            if (split(l, w, " ") == 2 && (w[1] == "ok" || w[1] == "FAIL" || w[1] == "skip")) {
                out[prog, w[2]] = block l
                block = ""
            } else if (l !~ /^[0-9]+ passed, [0-9]+ failed/) block = block l "\n"
        }
        close(f)
    }
    return out[prog, t]
}

# The build log's errors about one program (all of them for the stage).
function build_errors(prog,    f, l, s, k) {
    f = keep "/build.log"
    while ((getline l < f) > 0)
        if ((prog == "" || index(l, prog)) && l ~ /(error|warning):|undefined reference/ && k < 20) { s = s l "\n"; k++ }
    close(f)
    return s
}

function program_note(prog, note) {
    if (note == "did-not-compile") {
        if (build == "failed") return "Your stage does not build, so no test ran (see the \"build\" entry).\n"
        return "tests/stage/" prog ".c does not compile against your stage:\n" build_errors(prog)
    }
    if (note == "crashed") return "The program " prog " crashed (no result line): every test in it fails.\n" test_output(prog, "")
    if (note == "timed-out") return "The program " prog " ran past the time limit: every test in it fails.\n"
    if (note ~ /^exit-/) return "The program " prog " exited with status " substr(note, 6) " after its tests.\n"
    return ""
}

{ kind[NR] = $1; from[NR] = $2; prog[NR] = $3; test[NR] = $4; status[NR] = $5; note[NR] = $6 }

END {
    if (why != "")
        entry("submission", 0, 0, "failed", why "\n")
    else if (build == "failed")
        entry("build", 0, 0, "failed", "Your stage does not build; every test scores 0. The compiler said:\n" build_errors(""))
    else if (build == "tests-partly")
        entry("build", 0, 0, "failed", "Some test programs do not compile against your stage (their tests score 0):\n" build_errors(""))
    for (i = 1; i <= NR; i++) {
        name = prog[i] "/" test[i]
        o = (note[i] != "-" ? program_note(prog[i], note[i]) : "") test_output(prog[i], test[i])
        ok = (status[i] == "ok")
        if (kind[i] == "lab") {
            entry(name, ok ? 1 : 0, 1, ok ? "passed" : "failed", o)
            score += ok
        } else if (kind[i] == "control") {
            entry(name " (control: passes without your work, not scored)", 0, 0, ok ? "passed" : "failed",
                (ok ? "" : "A control that fails now is a regression: your work broke it.\n") o)
        } else if (kind[i] == "skipped") {
            entry(name " (skipped, not scored)", 0, 0, "passed", o)
        } else {
            k = "earlier " from[i] " " prog[i]
            if (!(k in ek)) { ek[k] = ++nk; ekey[nk] = k; efrom[nk] = from[i]; eprog[nk] = prog[i]; enote[nk] = note[i] }
            j = ek[k]
            etotal[j]++
            if (status[i] == "ok" || status[i] == "skip") epassed[j]++
            else efail[j] = efail[j] test[i] "\n" o
        }
    }
    for (j = 1; j <= nk; j++) {
        o = epassed[j] " of " etotal[j] " pass" (etotal[j] > epassed[j] ? "; a failing one is a regression (this stage came with it working):\n" program_note(eprog[j], enote[j] == "-" ? "" : enote[j]) efail[j] : "")
        entry("earlier stage " efrom[j] ": " eprog[j] " (not scored)", 0, 0, epassed[j] == etotal[j] ? "passed" : "failed", o)
    }
    for (p = 1; p <= np; p++) {
        page = ""
        if (ppath[p] != "") {
            while ((getline l < ppath[p]) > 0) page = page l "\n"
            close(ppath[p])
        }
        if (page != "" && length(page) < 1000000)
            entry("report page: " pname[p] " (not scored)", 0, 0, pfailed[p] ? "failed" : "passed",
                "<pre>" html(ptext[p]) "</pre>\n" page, "html")
        else
            entry("report page: " pname[p] " (not scored)", 0, 0, pfailed[p] ? "failed" : "passed", ptext[p])
    }
    if (score != gv["lab_passed"] + 0)
        print "results.awk: the tests' score " score " is not the report's lab_passed " gv["lab_passed"] > "/dev/stderr"
    # Regressions (failing controls and earlier tests) count as failed tests
    # of the lab (grade.awk): the points become lab_total x grade.awk's
    # score, and one entry carries the difference, so that the entries add
    # up to the total and Gradescope shows make grade's percentage.
    reg = gv["regressions"] + 0
    if (reg > 0 && gv["lab_total"] + reg > 0) {
        scaled = score * gv["lab_total"] / (gv["lab_total"] + reg)
        entry("regressions: " reg " test(s) that pass without your work fail with it", scaled - score, 0, "failed",
            "Each counts as a failed test of this lab (the controls and the earlier stages' tests above say which).\n")
        score = scaled
    }
    print "{"
    print "  \"score\": " score + 0 ","
    print "  \"execution_time\": " secs + 0 ","
    print "  \"output\": " jstr(rep) ","
    print "  \"visibility\": \"visible\","
    print "  \"stdout_visibility\": \"visible\","
    print "  \"tests\": ["
    for (i = 1; i <= ne; i++) print "    " e[i] (i < ne ? "," : "")
    printf "  ]\n}\n"
}
