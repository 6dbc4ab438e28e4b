#!/bin/sh
# grade.sh - grade a lab handout: run its tests, score them per group.
#
#   grade.sh [options] LAB                   (make grade LAB=path)
#
# LAB is a handout written by make-lab.sh, with a student's work in it.
# Builds it, runs each of its test programs (with a time limit) and prints
# passed/total per program, grouped by the stage each test comes from: the
# lab's own stage first (NN_*.c, NN-MM_*.c: the score), then the earlier
# stages (their features come with the handout: a failure there is a
# regression).  A program that does not compile, crashes or times out
# fails every TEST() in its source.
#
# Controls: a test of the lab that passes in the untouched handout (a
# fresh one from the project, as make-lab.sh writes it) measures nothing of
# the student's work; it is listed as a control, not scored.  With
# --pristine they are the stored list tests/course/controls/NN_name (which
# check-labs keeps equal to what an untouched handout gives); otherwise,
# or without that file, grade.sh finds them by building and running the
# untouched handout's lab tests first (--controls FILE gives them instead);
# LAB itself when it is untouched (without --pristine).
#
# The last line is for scripts:
#   GRADE lab=05_bvh score=42.9 lab_passed=3 lab_total=7 controls=2 earlier_passed=40 earlier_total=40 regressions=0 build=ok
# score = 100 * lab_passed / (lab_total + regressions), where lab_total
# leaves out the controls and the skipped tests, and a regression is a
# control or an earlier test that fails (the report and score: grade.awk).
#
# Options:
#   --pristine     grade with the project's own copy of the tests, not the
#                  handout's: a fresh handout of the same stage gets the
#                  student's stages/NN_name/ (what make grade does); files
#                  the student changed outside stages/ are listed
#   --controls FILE  the controls are the TEST()s FILE lists, one
#                  "PROGRAM TEST" a line (no untouched handout is run)
#   --save-controls FILE  write the controls to FILE, in that form (to
#                  grade many handouts of one lab with one untouched run)
#   --pages DIR    where the report pages go (default LAB/grade): one
#                  compare page per reference render (grade-pages.sh)
#   --no-pages     write no report pages
#   --spp N|auto|paired  the pages (grade-pages.sh; default grade-pages.sh's,
#                  paired: the scored paired pages and 16-spp Mitsuba
#                  pages; auto: as many as each Mitsuba page
#                  needs to find a 2% bias in a 32x32 window, from a pilot
#                  of GRADE_DEFAULT_SPP, up to GRADE_MAX_SPP; N, e.g. 64,
#                  for a quicker look that finds less:
#                  docs/calibration/README.md)
#   --keep DIR     keep what the grading read in DIR: its records, the
#                  test programs' logs (NAME.log), the build's (build.log),
#                  and how each TEST() counted (tests: grade.awk's tests=)
#                  (for the course tools, tests/course/)
#   --full         run every test program; without it, those whose header
#                  says "Grading: make grade FULL=1 only" (slow programs
#                  whose bugs the function tests and the paired pages find)
#                  are not run, and the report lists them
#   --lab-only     build and run only the lab's own tests, not the earlier
#                  stages' (check-labs grades the solution so: make test
#                  runs the earlier tests on the same code)
#   --timeout SEC  time limit of one test program (default 300; 0: none)
#   --jobs N       parallel make jobs (default: the number of processors)
#   --root DIR     the project, for --pristine and the controls (default:
#                  this script's)
#   --help
# Exit status: 0 graded (whatever the score), 1 could not grade, 2 usage.
set -eu

PROG=grade.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

root=$(cd "$LAB_DIR/../.." && pwd)
pristine=0
lab_only=0
pages=
no_pages=0
spp=
controls=
save_controls=
keep=
limit=300
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
full=0
parse_options '--pristine pristine=1 --full full=1 --lab-only lab_only=1 --no-pages no_pages=1 --pages pages=VALUE --spp spp=VALUE --controls controls=VALUE
    --save-controls save_controls=VALUE --keep keep=VALUE --timeout limit=VALUE --jobs jobs=VALUE --root root=DIR' "$@"
shift "$po_used"
[ $# -eq 1 ] || usage_error "expected one handout directory, got $# argument(s)"
case $limit in '' | *[!0-9]*) usage_error "--timeout needs a number of seconds, got '$limit'" ;; esac
[ -z "$spp" ] || check_spp "$spp" auto
case $jobs in '' | *[!0-9]*) usage_error "--jobs needs a number, got '$jobs'" ;; esac
[ -d "$1" ] || die "no such directory: $1"
[ -z "$controls" ] || [ -f "$controls" ] || die "no such file: $controls"
lab=$(abs_dir "$1")
is_handout "$lab" || die "$1 is not a lab handout (its Makefile was not written by make-lab.sh)"
stage=$(handout_stage "$lab") || die "$1: expected exactly one stage in stages/"
nn=${stage%%_*}

work=$(mktemp -d "${TMPDIR:-/tmp}/grade.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM

echo "grade: lab $nn ($stage) in $1"

# find_controls DIR - build DIR, an untouched handout, and write the lab's
# controls, "PROGRAM TEST" a line, into $work/controls.
find_controls() {
    echo "controls: running the lab's tests in an untouched handout"
    handout_build "$1" "$work/untouched-build.log" lab -j"$jobs" ||
        die "the untouched handout of $stage does not build: $(build_errors "$work/untouched-build.log" | head -n 3)"
    handout_controls "$1" "$work/untouched" "$limit" | awk '$3 == "ok" { print $1, $2 }' >"$work/controls"
}

# --pristine: the student's stage in a fresh handout, which first runs
# untouched for the controls.
dir=$lab
controls_known=known
# make grade (--pristine) takes the course tools' stored list of the lab's
# controls, which check-labs checks is the one an untouched handout gives
# (tests/course/controls/NN_name): the untouched handout's run would cost
# as much as the grading itself.
if [ -z "$controls" ] && [ "$pristine" -eq 1 ] && [ -f "$root/tests/course/controls/$stage" ]; then
    controls=$root/tests/course/controls/$stage
    echo "controls: the stored list, tests/course/controls/$stage"
fi
if [ -n "$controls" ]; then
    cp "$controls" "$work/controls"
fi
if [ "$pristine" -eq 1 ]; then
    [ -d "$root/stages/$stage" ] || die "the project in $root has no stage $stage"
    "$LAB_DIR/make-lab.sh" --quiet --root "$root" "$stage" "$work/lab" ||
        die "could not write a fresh handout of $stage"
    changed=$(handout_differences "$lab" "$work/lab" | grep -v "^stages/$stage/" || true)
    if [ -n "$changed" ]; then
        echo "note: these files differ from the project's copy and are not used:"
        echo "$changed" | sed 's/^/    /'
    fi
    [ -n "$controls" ] || find_controls "$work/lab"
    rm -rf "$work/lab/stages/$stage" "$work/lab/build/$stage"
    mkdir -p "$work/lab/stages/$stage"
    cp -R "$lab/stages/$stage/." "$work/lab/stages/$stage/"
    rm -rf "$work/lab/stages/$stage/build"
    dir=$work/lab
elif [ -z "$controls" ]; then
    if [ -d "$root/stages/$stage" ] &&
        "$LAB_DIR/make-lab.sh" --quiet --root "$root" "$stage" "$work/untouched-lab" 2>/dev/null; then
        # An untouched LAB is its own control (its build serves both runs).
        if [ -z "$(handout_differences "$lab" "$work/untouched-lab")" ]; then
            find_controls "$lab"
        else
            find_controls "$work/untouched-lab"
        fi
        rm -rf "$work/untouched-lab"
    else
        controls_known=unknown
        echo "note: no untouched handout of $stage from the project in $root: no controls, every test is scored"
    fi
fi
[ -f "$work/controls" ] || : >"$work/controls"
if [ -n "$save_controls" ]; then
    cp "$work/controls" "$save_controls" || die "cannot write $save_controls"
fi

# The build compiles only what the stage's changes touch; a program (or
# the render) that does not build now is removed (handout_build), so no
# earlier one stands in for it.
build=ok
# The programs this grade runs: a default grade not the FULL=1-only ones.
programs=all
[ "$full" -eq 1 ] || programs=default
[ "$lab_only" -eq 0 ] || programs=lab
if ! handout_build "$dir" "$work/build.log" "$programs" -j"$jobs"; then
    if lab_make -C "$dir" -j"$jobs" all >/dev/null 2>&1; then
        build=tests-partly
        echo "note: some test programs do not compile against this stage (they score 0):"
    else
        build=failed
        echo "note: the stage does not build (every test scores 0):"
    fi
    build_errors "$work/build.log" | head -n 20 | sed 's/^/    /'
fi

# run_one SRC LOG TEST - one TEST() of SRC's program in the handout.
run_one() {
    run_handout_test "$dir" "$1" "$2" "$limit" "$3" >/dev/null
}

# The records of grade.awk: the controls, then each program and its TEST()s.
awk '{ printf "C\t%s\t%s\n", $1, $2 }' "$work/controls" >"$work/records"
for src in $(handout_tests "$dir"); do
    name=$(basename "$src" .c)
    from=$(test_from "$src")
    [ "$lab_only" -eq 0 ] || [ "$from" = "$nn" ] || continue
    if [ "$full" -eq 0 ] && full_only "$src"; then
        printf 'S\t%s\t%s\n' "$from" "$name" >>"$work/records"
        continue
    fi
    set -- $(run_handout_test "$dir" "$src" "$work/$name.log" "$limit")
    printf 'P\t%s\t%s\t%s\n' "$from" "$name" "$5" >>"$work/records"
    if [ "$5" = crashed ]; then
        # A crash (an assertion on a NaN, a bad pointer) fails only the
        # TEST() that crashes: each is run again on its own, so that the
        # report names the function at fault, not every test of the program.
        for t in $(test_names "$src"); do
            note=$(run_handout_test "$dir" "$src" "$work/$name.$t.log" "$limit" "$t" | awk '{ print $5 }')
            test_statuses "$src" "$work/$name.$t.log" "$note" | awk -v t="$t" '$1 == t'
        done
    else
        test_statuses "$src" "$work/$name.log" "$5" |
            second_seed "$src" "$GRADE_SECOND_SEED" "$work/$name" run_one "$src"
    fi | awk -v from="$from" -v name="$name" '{
        printf "T\t%s\t%s\t%s\t%s\n", from, name, $1, $2
        if ($3 == "second") printf "R\t%s\t%s\t%s\n", from, name, $1
    }' >>"$work/records"
    # The function tests' first failure message of each failing TEST(), for
    # the report's list of the lab's functions (M records, grade.awk).
    case $name in
        *_lab_functions) cat "$work/$name.log" "$work/$name".*.log 2>/dev/null |
            awk -v from="$from" -v name="$name" '
                /^(ok  |FAIL|skip) [A-Za-z_0-9]+$/ {
                    if ($1 == "FAIL") printf "M\t%s\t%s\t%s\t%s\n", from, name, $2, (msg != "" ? msg : "(no message: it crashed)")
                    msg = ""
                    next
                }
                msg == "" && /check failed: / { msg = substr($0, index($0, "check failed: ") + 14, 400) }' >>"$work/records" ;;
    esac
done

if [ "$build" != failed ] && [ "$no_pages" -eq 0 ]; then
    echo "report pages (how to read them: LAB.md, \"Reading the report pages\"):"
    : >"$work/paired"
    "$LAB_DIR/grade-pages.sh" ${spp:+--spp "$spp"} --records "$work/paired" "$dir" "$stage" "${pages:-$lab/grade}" ||
        echo "note: some pages could not be written"
    # The paired pages are tests of the lab: "pages" in its group.
    if [ -s "$work/paired" ]; then
        printf 'P\t%s\tpages\t-\n' "$nn" >>"$work/records"
        awk -v nn="$nn" '{
            printf "T\t%s\tpages\t%s_paired\t%s\n", nn, $1, $2
            if ($2 == "FAIL") { m = $0; sub(/^[^ ]+ FAIL /, "", m); printf "M\t%s\tpages\t%s_paired\t%s\n", nn, $1, m }
        }' "$work/paired" >>"$work/records"
        # ... and their log, as a test program's (the course tools read it).
        awk '{ m = $0; sub(/^[^ ]+ [^ ]+ ?/, "", m); if (m != "") print "  " m
               printf "%-4s %s_paired\n", $2, $1 }' "$work/paired" >"$work/pages.log"
    fi
fi

if [ -n "$keep" ]; then
    mkdir -p "$keep" || die "cannot write $keep"
    cp "$work"/*.log "$work/records" "$keep/" 2>/dev/null || true
fi
awk -v nn="$nn" -v stage="$stage" -v build="$build" -v controls="$controls_known" \
    -v tests="${keep:+$keep/tests}" -f "$LAB_DIR/grade.awk" "$work/records"
