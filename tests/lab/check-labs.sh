#!/bin/sh
# check-labs.sh - check the lab handouts of the stages (part of make test).
#
#   check-labs.sh [options] [STAGE...]        (default: every stage)
#
# Writes each stage's handout into OUT/NN (make-lab.sh) and checks:
#   handout    make-lab.sh writes it without a warning: the markers are well
#              formed, stage NN has a LAB NN region, its docs page a Lab
#              section
#   build      the handout builds with WERROR=1 and no warning (--quick: the
#              stage and the lab's own test programs; else every program)
#   lab-fails  the lab's tests (tests/stage/NN_*.c, NN-MM_*.c) fail: at least
#              one reports a failure (a handout whose tests pass is broken);
#              --quick runs them one TEST() at a time up to the first failure
#   untouched  grade.sh scores the handout 0%: every lab test that passes
#              without the work is a control, not scored; the controls
#              are those of tests/course/controls/NN_name, where it exists
#              (the course tools' list)                             [full]
#   earlier    the other tests (earlier stages' features) pass     [full]
#   no-leaks   no line of a LAB NN region is in the handout, unless it is
#              also outside the regions or trivial (leaks.awk)
#   solution   with the stage's solution copied in, grade.sh scores it
#              100% (the same controls aside): the handout is a complete
#              harness.  Only the lab's own tests run (grade.sh
#              --lab-only): the earlier stages' tests of the solution are
#              those of the project's stage, which make test runs   [full]
# The [full] checks grade the handout with grade.sh, as make grade does
# (without report pages), its report in OUT/logs/NN/grade-*.log.
# One result line per check, as tests/harness/run-tests.sh prints them, details
# indented, and the closing line "N passed, N failed, N skipped".
#
# Cost: the handouts stay in OUT between runs and are updated in place, so
# make rebuilds only what changed; the common core and the test support
# code, the same in every handout, are compiled once for all of them
# (OUT/shared/); a stage whose handout, solution and tools did not change
# since all its checks last passed is not checked again ("cached"), unless
# --no-cache.
#
# Options:
#   --quick        skip the [full] checks, build and run only the lab's own
#                  test programs (what make test runs)
#   --full         every check (the default; make check-labs)
#   --no-cache     check every stage, changed or not
#   --no-earlier   full checks but "earlier": the untouched handout is graded
#                  on the lab's own tests (grade.sh --lab-only); CI, whose
#                  make test and make sanitize run every stage's tests
#   --out DIR      where the handouts go (default: build/labs)
#   --jobs N       parallel make jobs (default: the number of processors)
#   --timeout SEC  time limit of one test program (default 300; 0: none)
#   --root DIR     the project (default: the one this script belongs to)
#   --help
# Exit status: 0 every check passed, 1 a check failed, 2 usage.
set -eu

PROG=check-labs.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

root=$(cd "$LAB_DIR/../.." && pwd)
mode=full
cache=1
earlier=1
out=
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
limit=300
parse_options '--quick mode=quick --full mode=full --no-cache cache=0 --no-earlier earlier=0 --out out=VALUE --jobs jobs=VALUE
    --timeout limit=VALUE --root root=DIR' "$@"
shift "$po_used"
case $jobs in '' | *[!0-9]*) usage_error "--jobs needs a number, got '$jobs'" ;; esac
case $limit in '' | *[!0-9]*) usage_error "--timeout needs a number of seconds, got '$limit'" ;; esac
[ -n "$out" ] || out=$root/build/labs
mkdir -p "$out"
out=$(abs_dir "$out")

if [ $# -gt 0 ]; then
    stages=
    for a in "$@"; do stages="$stages $(resolve_stage "$root" "$a")"; done
else
    stages=$(stage_list "$root")
fi

passed=0
failed=0
skipped=0

# result ok|FAIL|skip STAGE WHAT - one result line (the main loop counts them).
result() {
    printf '%-4s labs/%s: %s\n' "$1" "$2" "$3"
}

# Indented lines of detail (never taken for a result line).
detail() {
    sed -e 's/^/        /' "$@" | head -n 30
}

rel() {
    echo "${1#"$root"/}"
}

# grade_handout DIR LOG [OPTION...] - grade.sh on a handout (no report
# pages), its report into LOG; prints the fields of its GRADE line
# ("score=0.0 lab_passed=0 ..."), nothing when it could not grade.
grade_handout() {
    gh_dir=$1
    gh_log=$2
    shift 2
    "$LAB_DIR/grade.sh" --full --no-pages --root "$root" --timeout "$limit" --jobs "$jobs" "$@" "$gh_dir" \
        >"$gh_log" 2>&1 || true
    sed -n 's/^GRADE //p' "$gh_log" | tail -n 1
}

# field FIELDS KEY - the value of KEY=value in a GRADE line's fields.
field() {
    echo "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"
}

# The report lines of a grade log that name failures.
grade_failures() {
    grep -E 'failed:|fails now|^note:' "$1" | head -n 20 | detail
}

# first_failure DIR NN LOGDIR - run the lab's tests one TEST() at a time,
# in order, until one fails; print "PROGRAM/TEST" of that one, or nothing
# when all pass.  (--quick: a broken handout's first test usually fails,
# so this costs one test instead of the lab's whole suite.)
first_failure() {
    ff_dir=$1
    mkdir -p "$3"
    for ff_src in $(handout_tests "$ff_dir"); do
        [ "$(test_from "$ff_src")" = "$2" ] || continue
        ff_name=$(basename "$ff_src" .c)
        for ff_test in $(test_names "$ff_src"); do
            ff_res=$(run_handout_test "$ff_dir" "$ff_src" "$3/$ff_name.$ff_test.log" "$limit" "$ff_test")
            read -r ff_p ff_f ff_rest <<EOF
$ff_res
EOF
            if [ "$ff_f" -gt 0 ]; then
                echo "$ff_name/$ff_test"
                return 0
            fi
        done
    done
}

# The common core and the test support code are the same in every handout:
# their build directories point into one shared directory, named after a
# checksum of their sources, so a change makes a fresh one.
share_builds() {
    sb_dir=$1
    sb_key=$( (echo "${CC:-cc} ${CFLAGS:-}"
        cd "$root" && { find common -type f; find tests tests/lib -maxdepth 1 -type f; } | LC_ALL=C sort |
            xargs cksum) |
        cksum | awk '{ print $1 }')
    sb_shared=$out/shared/$sb_key
    mkdir -p "$sb_shared/common" "$sb_shared/support" "$sb_dir/build/tests"
    for sb_d in common tests/support; do
        sb_link=$sb_dir/build/$sb_d
        sb_target=$sb_shared/${sb_d#tests/}
        # (A link into an older, removed shared build dangles: replaced.)
        if [ -L "$sb_link" ] && [ "$(cd "$sb_link" 2>/dev/null && pwd -P)" = "$(cd "$sb_target" && pwd -P)" ]; then
            continue
        fi
        rm -rf "$sb_link"
        ln -s "$sb_target" "$sb_link"
    done
    for sb_old in "$out"/shared/*; do
        [ "$sb_old" = "$sb_shared" ] || rm -rf "$sb_old"
    done
}

# The key of a stage's check: everything its outcome depends on.
check_key() {
    {
        echo "$mode $earlier $limit ${CC:-cc} ${CFLAGS:-}"
        ${CC:-cc} --version 2>/dev/null | head -n 1
        (cd "$1" && find . -path ./build -prune -o -type f -print | LC_ALL=C sort | xargs cksum)
        (cd "$root/stages/$2" && find . -type f | LC_ALL=C sort | xargs cksum)
        (cd "$LAB_DIR" && find . -type f | LC_ALL=C sort | xargs cksum)
    } | cksum | awk '{ print $1 "-" $2 }'
}

# The solution lines of the stage's LAB NN regions found in the handout.
find_leaks() {
    fl_stage=$1
    fl_dir=$2
    fl_tmp=$3
    fl_nn=${fl_stage%%_*}
    (cd "$root" && awk -v mode=inside -v lab="$fl_nn" -v stubs="$LAB_DIR/stubs" \
        -f "$LAB_DIR/markers.awk" stages/"$fl_stage"/*.[ch]) >"$fl_tmp/inside"
    (cd "$root" && awk -v mode=outside -v lab="$fl_nn" -v stubs="$LAB_DIR/stubs" \
        -f "$LAB_DIR/markers.awk" stages/"$fl_stage"/*.[ch]) | cut -f 3- >"$fl_tmp/outside"
    : >"$fl_tmp/known"
    : >"$fl_tmp/targets"
    (cd "$fl_dir" && find . -path ./build -prune -o -type f -print | sed 's|^\./||' | LC_ALL=C sort) |
        while IFS= read -r fl_f; do
            grep -Iq '' "$fl_dir/$fl_f" 2>/dev/null || continue
            echo "$fl_f" >>"$fl_tmp/targets"
            case $fl_f in
                stages/* | LAB.md) ;;
                *) echo "$fl_f" >>"$fl_tmp/known" ;;
            esac
        done
    (cd "$fl_dir" && awk -f "$LAB_DIR/leaks.awk" pass=known "$fl_tmp/outside" $(cat "$fl_tmp/known") \
        pass=solution "$fl_tmp/inside" pass=handout $(cat "$fl_tmp/targets"))
}

check_leaks() {
    if find_leaks "$1" "$2" "$3" >"$3/leaks"; then
        result ok "$1" "no-leaks: no solution line in the handout"
    else
        result FAIL "$1" "no-leaks: the handout holds lines of the solution"
        detail "$3/leaks"
    fi
}

# Copy the solution into the handout, grade it (with the controls of the
# untouched handout, CONTROLS), put the handout back.
check_solution() {
    csl_stage=$1
    csl_dir=$2
    csl_logs=$3
    cp "$root/stages/$csl_stage"/* "$csl_dir/stages/$csl_stage/"
    csl_g=$(grade_handout "$csl_dir" "$csl_logs/grade-solution.log" --lab-only --controls "$4")
    csl_log="(log: $(rel "$csl_logs")/grade-solution.log)"
    if [ -z "$csl_g" ]; then
        result FAIL "$csl_stage" "solution: grade.sh could not grade the handout with the solution $csl_log"
        tail -n 5 "$csl_logs/grade-solution.log" | detail
    elif [ "$(field "$csl_g" build)" != ok ]; then
        result FAIL "$csl_stage" "solution: the solution does not build in the handout $csl_log"
        grade_failures "$csl_logs/grade-solution.log"
    elif [ "$(field "$csl_g" score)" = 100.0 ] &&
        [ "$(field "$csl_g" earlier_passed)" = "$(field "$csl_g" earlier_total)" ] &&
        ! grep -q 'fails now' "$csl_logs/grade-solution.log"; then
        result ok "$csl_stage" "solution: with the solution copied in, it scores 100% ($(field "$csl_g" lab_passed) tests, $(field "$csl_g" controls) controls aside; the earlier stages' tests: make test)"
    else
        result FAIL "$csl_stage" "solution: with the solution copied in, it scores $(field "$csl_g" score)%, not 100% $csl_log"
        grade_failures "$csl_logs/grade-solution.log"
    fi
    "$LAB_DIR/make-lab.sh" --quiet --discard-changes --root "$root" "$csl_stage" "$csl_dir" 2>/dev/null ||
        warn "could not restore the handout in $csl_dir"
}

# Write a stage's handout; "ok" when that went without a warning.
write_handout() {
    wh_stage=$1
    wh_dir=$out/${wh_stage%%_*}
    wh_log=$out/logs/${wh_stage%%_*}/make-lab.log
    mkdir -p "${wh_log%/*}"
    if "$LAB_DIR/make-lab.sh" --quiet --discard-changes --root "$root" "$wh_stage" "$wh_dir" 2>"$wh_log"; then
        share_builds "$wh_dir"
        [ -s "$wh_log" ] && echo warned || echo ok
    else
        echo failed
    fi
}

# check_stage STAGE STATUS - the checks of one stage whose handout was
# written with STATUS (ok, warned, failed).
check_stage() {
    cs_stage=$1
    cs_nn=${cs_stage%%_*}
    cs_dir=$out/$cs_nn
    cs_logs=$out/logs/$cs_nn
    cs_n=0
    if [ "$2" != failed ]; then
        cs_n=$(cd "$cs_dir" && awk -v mode=regions -f "$LAB_DIR/markers.awk" stages/"$cs_stage"/*.[ch] |
            awk -F '\t' -v nn="$cs_nn" '$4 == nn' | wc -l)
    fi
    cs_what="handout: $(rel "$cs_dir"), $((cs_n)) LAB $cs_nn region(s)"
    case $2 in
        ok) result ok "$cs_stage" "$cs_what, LAB.md from docs/stages/$cs_stage.md" ;;
        warned)
            result FAIL "$cs_stage" "$cs_what; make-lab.sh warns"
            detail "$cs_logs/make-lab.log"
            ;;
        failed)
            result FAIL "$cs_stage" "make-lab.sh failed"
            detail "$cs_logs/make-lab.log"
            for cs_w in build lab-fails untouched earlier no-leaks solution; do
                result skip "$cs_stage" "$cs_w: no handout"
            done
            return 0
            ;;
    esac

    cs_which=all
    [ "$mode" = quick ] && cs_which=lab
    if handout_build "$cs_dir" "$cs_logs/build.log" "$cs_which" -j"$jobs" WERROR=1; then
        build_warnings "$cs_logs/build.log" >"$cs_logs/warnings"
        if [ -s "$cs_logs/warnings" ]; then
            result FAIL "$cs_stage" "build: the handout builds with warnings (log: $(rel "$cs_logs")/build.log)"
            detail "$cs_logs/warnings"
        else
            result ok "$cs_stage" "build: the handout builds with WERROR=1, no warning"
        fi
    else
        result FAIL "$cs_stage" "build: the handout does not build with WERROR=1 (log: $(rel "$cs_logs")/build.log)"
        build_errors "$cs_logs/build.log" | detail
        result skip "$cs_stage" "lab-fails: the handout does not build"
        result skip "$cs_stage" "untouched: the handout does not build"
        result skip "$cs_stage" "earlier: the handout does not build"
        check_leaks "$cs_stage" "$cs_dir" "$cs_logs"
        result skip "$cs_stage" "solution: the handout does not build"
        return 0
    fi

    cs_own=$(for cs_t in $(handout_tests "$cs_dir"); do
        [ "$(test_from "$cs_t")" = "$cs_nn" ] && echo "$cs_t"; done; true)
    if [ -z "$cs_own" ]; then
        result FAIL "$cs_stage" "lab-fails: stage $cs_nn has no tests of its own (tests/stage/${cs_nn}_*.c)"
    elif [ "$mode" = quick ]; then
        cs_first=$(first_failure "$cs_dir" "$cs_nn" "$cs_logs/tests")
        if [ -n "$cs_first" ]; then
            result ok "$cs_stage" "lab-fails: the lab's tests fail in the handout, as they must (first: $cs_first)"
        else
            result FAIL "$cs_stage" "lab-fails: the lab's tests pass in the handout: a stub implements the feature, or the tests miss it"
        fi
    fi

    # [full] grade.sh on the untouched handout: its controls, 0%, the
    # earlier tests.
    cs_g=
    if [ "$mode" = quick ]; then
        result skip "$cs_stage" "untouched: --quick (make check-labs runs it)"
        result skip "$cs_stage" "earlier: --quick (make check-labs runs it)"
    elif [ -n "$cs_own" ]; then
        cs_only=
        [ "$earlier" = 1 ] || cs_only=--lab-only
        cs_g=$(grade_handout "$cs_dir" "$cs_logs/grade-untouched.log" $cs_only --save-controls "$cs_logs/controls")
        cs_log="(log: $(rel "$cs_logs")/grade-untouched.log)"
        if [ -z "$cs_g" ] || [ "$(field "$cs_g" build)" != ok ]; then
            result FAIL "$cs_stage" "lab-fails: grade.sh could not grade the handout $cs_log"
            tail -n 5 "$cs_logs/grade-untouched.log" | detail
            result skip "$cs_stage" "untouched: no grade"
            result skip "$cs_stage" "earlier: no grade"
        else
            cs_total=$(field "$cs_g" lab_total)
            cs_controls=$(field "$cs_g" controls)
            if [ "$cs_total" -gt 0 ]; then
                result ok "$cs_stage" "lab-fails: the lab's tests fail in the handout, as they must ($cs_total of them; $cs_controls control(s) pass)"
            else
                result FAIL "$cs_stage" "lab-fails: the lab's tests pass in the handout: a stub implements the feature, or the tests miss it"
            fi
            # The course tools' list of the lab's controls must be these.
            cs_list=$root/tests/course/controls/$cs_stage
            if [ -f "$cs_list" ] && ! LC_ALL=C sort "$cs_logs/controls" | cmp -s - "$cs_list"; then
                result FAIL "$cs_stage" "untouched: its controls are not tests/course/controls/$cs_stage's (rewrite it: tests/course/controls.sh $cs_nn)"
                LC_ALL=C sort "$cs_logs/controls" | diff "$cs_list" - | detail
            elif [ "$(field "$cs_g" score)" = 0.0 ] && [ "$(field "$cs_g" lab_passed)" = 0 ] && [ "$cs_total" -gt 0 ]; then
                result ok "$cs_stage" "untouched: grade.sh scores the handout 0% (0 of $cs_total; $cs_controls control(s) not scored)"
            else
                result FAIL "$cs_stage" "untouched: grade.sh scores the handout $(field "$cs_g" score)%, not 0% $cs_log"
                grep -A3 '^this lab' "$cs_logs/grade-untouched.log" | detail
            fi
            if [ "$earlier" = 0 ]; then
                result skip "$cs_stage" "earlier: --no-earlier (make check-labs runs it)"
            elif [ "$(field "$cs_g" earlier_passed)" = "$(field "$cs_g" earlier_total)" ]; then
                result ok "$cs_stage" "earlier: the earlier stages' tests pass in the handout ($(field "$cs_g" earlier_total) tests)"
            else
                result FAIL "$cs_stage" "earlier: earlier stages' tests fail in the handout: a stub breaks more than lab $cs_nn $cs_log"
                { grep '^note:' "$cs_logs/grade-untouched.log" || true; earlier_failures "$cs_logs/grade-untouched.log"; } |
                    head -n 20 | detail
            fi
        fi
    else
        result skip "$cs_stage" "untouched: no tests of its own"
        result skip "$cs_stage" "earlier: no tests of its own"
    fi

    check_leaks "$cs_stage" "$cs_dir" "$cs_logs"

    if [ "$mode" = quick ]; then
        result skip "$cs_stage" "solution: --quick (make check-labs runs it)"
    elif [ -z "$cs_g" ]; then
        result skip "$cs_stage" "solution: no controls (the untouched handout was not graded)"
    else
        check_solution "$cs_stage" "$cs_dir" "$cs_logs" "$cs_logs/controls"
    fi
}

# Every handout first: the shared builds must be newer than every copy of
# their sources.
mkdir -p "$out/logs" "$out/cache"
statuses=
for s in $stages; do
    rm -rf "$out/logs/${s%%_*}"
    statuses="$statuses $s:$(write_handout "$s")"
done

for entry in $statuses; do
    s=${entry%%:*}
    nn=${s%%_*}
    key=
    if [ "$cache" -eq 1 ] && [ "${entry#*:}" = ok ]; then
        key=$(check_key "$out/$nn" "$s")
        if [ -f "$out/cache/$nn.out" ] && [ "$(cat "$out/cache/$nn.key" 2>/dev/null)" = "$key" ]; then
            sed 's/^\(ok   labs\/.*\)$/\1 (cached: unchanged since it passed)/' "$out/cache/$nn.out"
            passed=$((passed + $(grep -c '^ok ' "$out/cache/$nn.out" || true)))
            skipped=$((skipped + $(grep -c '^skip ' "$out/cache/$nn.out" || true)))
            continue
        fi
    fi
    rm -f "$out/cache/$nn.key" "$out/cache/$nn.out"
    check_stage "$s" "${entry#*:}" | tee "$out/cache/$nn.out.tmp"
    passed=$((passed + $(grep -c '^ok ' "$out/cache/$nn.out.tmp" || true)))
    failed=$((failed + $(grep -c '^FAIL ' "$out/cache/$nn.out.tmp" || true)))
    skipped=$((skipped + $(grep -c '^skip ' "$out/cache/$nn.out.tmp" || true)))
    if [ -n "$key" ] && ! grep -q '^FAIL ' "$out/cache/$nn.out.tmp"; then
        mv "$out/cache/$nn.out.tmp" "$out/cache/$nn.out"
        echo "$key" >"$out/cache/$nn.key"
    else
        rm -f "$out/cache/$nn.out.tmp"
    fi
done
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
