# grade.awk - the report and the score of grade.sh, from its records.
#
#   awk -v nn=05 -v stage=05_bvh -v build=ok -v controls=known -f grade.awk RECORDS
#
# RECORDS, tab-separated, a program's P line before its T lines:
#   C PROGRAM TEST               a control: a TEST() of the lab that passes in
#                                the untouched handout (grade.sh finds them)
#   P FROM PROGRAM NOTE          a test program, from stage FROM; NOTE is
#                                did-not-compile, crashed, timed-out, exit-N
#                                or - (lablib.sh, run_handout_test)
#   T FROM PROGRAM TEST STATUS   one of its TEST()s: ok, FAIL or skip
#                                (lablib.sh, test_statuses)
#   S FROM PROGRAM               a test program not run: only a full grade
#                                runs it (grade.sh --full); listed, its
#                                tests neither passed nor failed
#   R FROM PROGRAM TEST          a statistical TEST() that failed at its
#                                first seed and passed at the grade's second
#                                (grade.sh, second_seed): its T line says
#                                ok; the report names it
#   M FROM PROGRAM TEST MESSAGE  the first failure message of a failing
#                                TEST() of a function test program
#                                (NN_lab_functions: each TEST() is named for
#                                the LAB function it tests)
# controls: "known" (the C lines are all of them) or "unknown" (none could
# be found: every test is scored).
# tests=FILE (optional): also write how each TEST() counted, one line each,
# tab-separated: KIND FROM PROGRAM TEST STATUS NOTE, KIND one of lab (scored:
# one of lab_total), control, skipped (a skipped test of the lab) or earlier;
# NOTE is the program's (for the course tools: tests/course/).
#
# The score is the share of the lab's own tests (FROM = nn) that pass,
# leaving out the skipped ones and the controls (a test that passes without
# the student's work measures nothing of it), where every regression - a
# control or an earlier stage's test that fails now - counts as one more
# failed test of the lab:
#   score = 100 lab_passed / (lab_total + regressions)
# A regression is caught by a test that passes in the untouched handout, so
# it cannot be the untouched handout's (0%) or the solution's (100%); the
# student's code is the only code that changed, so it is this lab's bug,
# and it costs what a failed test of the lab costs.  The controls are
# listed, with their status now.  The last line is for scripts:
#   GRADE lab=05_bvh score=42.9 lab_passed=3 lab_total=7 controls=2 earlier_passed=40 earlier_total=40 regressions=0 build=ok
BEGIN { FS = "\t" }

$1 == "C" { control[$2 SUBSEP $3] = 1; next }

$1 == "P" {
    n++
    from[n] = $2; prog[n] = $3; note[n] = ($4 == "-" ? "" : $4)
    index_of[$3] = n
    next
}

$1 == "M" { message[$3 SUBSEP $4] = $5; next }

$1 == "R" { second = second (second != "" ? ", " : "") $3 "/" $4; next }

$1 == "S" { not_run = not_run (not_run != "" ? ", " : "") $3; next }

$1 == "T" {
    i = index_of[$3]
    if ($2 == nn && $3 ~ /_lab_functions$/) {
        nfn++
        fn_prog[nfn] = $3; fn_test[nfn] = $4; fn_status[nfn] = $5
    }
    if ($2 == nn && (($3 SUBSEP $4) in control)) {
        nc++
        cname[nc] = $3 "/" $4
        cstatus[nc] = $5
        if ($5 == "FAIL") cfailed++
        counted("control", i)
        next
    }
    if ($5 == "skip") {
        counted($2 == nn ? "skipped" : "earlier", i)
        next
    }
    counted($2 == nn ? "lab" : "earlier", i)
    total[i]++
    if ($5 == "ok") passed[i]++
    else {
        nf[i]++
        if (nf[i] <= 5) failed[i] = failed[i] (nf[i] > 1 ? ", " : "") $4
        else if (nf[i] == 6) failed[i] = failed[i] ", ..."
    }
}

function counted(kind, i) {
    if (tests != "") printf "%s\t%s\t%s\t%s\t%s\t%s\n", kind, $2, $3, $4, $5, (note[i] == "" ? "-" : note[i]) > tests
}

function line(i,    s) {
    s = sprintf("    %-32s %4d/%-4d %s%s", prog[i], passed[i], total[i], (note[i] != "" ? note[i] " " : ""),
        (failed[i] != "" ? "failed: " failed[i] : ""))
    sub(/ +$/, "", s)
    print s
}

END {
    for (i = 1; i <= n; i++) {
        if (from[i] == nn) {
            lp += passed[i]; lt += total[i]
        } else {
            ep += passed[i]; et += total[i]
            gp[from[i]] += passed[i]; gt[from[i]] += total[i]; groups[from[i]] = 1
        }
    }
    if (nfn > 0) {
        printf "\nyour functions (each test named for the LAB function it tests):\n"
        for (k = 1; k <= nfn; k++) {
            printf "    %-4s %s\n", fn_status[k], fn_test[k]
            if (fn_status[k] == "FAIL" && ((fn_prog[k] SUBSEP fn_test[k]) in message))
                printf "         %s\n", message[fn_prog[k] SUBSEP fn_test[k]]
        }
    }
    printf "\nthis lab (tests of stage %s):\n", nn
    for (i = 1; i <= n; i++) if (from[i] == nn) line(i)
    printf "    %-32s %4d/%d\n", "total", lp, lt
    if (controls != "known") {
        print "    controls: unknown (no untouched handout to find them): every test is scored"
    } else if (nc == 0) {
        print "    controls: none (every test of this lab fails without your work)"
    } else {
        s = ""
        for (k = 1; k <= nc; k++)
            s = s (k > 1 ? ", " : "") cname[k] (cstatus[k] == "FAIL" ? " (fails now)" : "")
        printf "    controls (pass without your work, not scored): %s\n", s
    }
    ng = 0
    for (g in groups) order[++ng] = g
    for (i = 2; i <= ng; i++) for (j = i; j > 1 && order[j - 1] > order[j]; j--) {
        x = order[j]; order[j] = order[j - 1]; order[j - 1] = x
    }
    for (k = 1; k <= ng; k++) {
        g = order[k]
        printf "\nearlier: tests from stage %s (features the handout came with):\n", g
        for (i = 1; i <= n; i++) if (from[i] == g) line(i)
        printf "    %-32s %4d/%d\n", "total", gp[g], gt[g]
    }
    if (second != "")
        printf "\npassed at the second seed (failed at the first: chance, at each test's level; a bug fails at both): %s\n", second
    if (not_run != "")
        printf "\nnot run (slow; their bugs are the function tests' and the pages'; make grade FULL=1 runs them): %s\n", not_run
    reg = et - ep + cfailed
    score = lt + reg > 0 ? 100 * lp / (lt + reg) : 0
    printf "\nscore: %.1f%% (%d of %d tests of lab %s", score, lp, lt, nn
    if (nc > 0) printf "; %d control(s) not scored", nc
    printf "); earlier stages: %d of %d", ep, et
    if (reg > 0) printf " (%d regression(s), each counted as a failed test of lab %s: your code is the code that changed)", reg, nn
    printf "\n"
    printf "GRADE lab=%s score=%.1f lab_passed=%d lab_total=%d controls=%d earlier_passed=%d earlier_total=%d regressions=%d build=%s\n",
        stage, score, lp, lt, nc, ep, et, reg, build
}
