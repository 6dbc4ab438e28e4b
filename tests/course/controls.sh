#!/bin/sh
# controls.sh - write the controls of the labs: tests/course/controls/NN_name.
#
#   controls.sh [options] [STAGE...]          (default: every stage)
#
# A control is a TEST() of a lab that passes in the untouched handout (its
# stubs only): make grade lists it and does not score it (tests/lab/
# README.md, "Grading").  grade.sh finds them by running the untouched
# handout at every grading; the course tools, which grade many submissions
# or hand the list to another grader (the Gradescope autograder, the GitHub
# Classroom workflow), read them from this directory instead: one file per
# stage, one "PROGRAM TEST" a line, sorted (empty: no control).  This script
# writes them the way grade.sh finds them (grade.sh --save-controls on a
# fresh untouched handout).
#
# Options:
#   --check      write nothing; fail when a file's lines name a TEST() that
#                is not a test of that lab, skip (saying so) a stage without
#                a file (cheap: runs no test; make test runs it)
#   --timeout SEC  time limit of one test program (default 300)
#   --root DIR   the project (default: this script's)
#   --help
# Exit status: 0 written (or checked), 1 failure, 2 usage.
set -eu

PROG=controls.sh
COURSE_DIR=$(cd "$(dirname "$0")" && pwd)
LAB_DIR=$COURSE_DIR/../lab
. "$LAB_DIR/lablib.sh"

root=$(cd "$COURSE_DIR/../.." && pwd)
check=0
limit=300
parse_options '--check check=1 --timeout limit=VALUE --root root=DIR' "$@"
shift "$po_used"
if [ $# -gt 0 ]; then
    stages=
    for a in "$@"; do stages="$stages $(resolve_stage "$root" "$a")"; done
else
    stages=$(stage_list "$root")
fi

# lab_tests STAGE - "PROGRAM TEST" for every TEST() of the lab's own tests.
lab_tests() {
    for lt_src in "$root"/tests/stage/*.c; do
        [ "$(test_from "$lt_src")" = "${1%%_*}" ] || continue
        test_names "$lt_src" | sed "s/^/$(basename "$lt_src" .c) /"
    done
}

if [ "$check" -eq 1 ]; then
    bad=0
    none=0
    for s in $stages; do
        f=$root/tests/course/controls/$s
        if [ ! -f "$f" ]; then
            # (a new stage: its tools find the controls at grading time; its
            # Classroom workflow scores every test until the list is written)
            echo "skip controls/$s: no list of the lab's controls yet (write it: tests/course/controls.sh $s)"
            none=$((none + 1))
            continue
        fi
        unknown=$(lab_tests "$s" | LC_ALL=C sort | LC_ALL=C comm -13 - "$f")
        if [ -n "$unknown" ]; then
            echo "FAIL controls/$s: names tests that lab $s does not have (rewrite it: tests/course/controls.sh $s):"
            echo "$unknown" | sed 's/^/    /'
            bad=$((bad + 1))
        else
            echo "ok   controls/$s: $(wc -l <"$f" | tr -d ' ') control(s), all tests of the lab"
        fi
    done
    n=$(echo $stages | wc -w | tr -d ' ')
    echo "$((n - bad - none)) passed, $bad failed, $none skipped"
    [ "$bad" -eq 0 ]
    exit
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/controls.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM
for s in $stages; do
    "$LAB_DIR/make-lab.sh" --quiet --root "$root" "$s" "$work/$s" || die "could not write the handout of $s"
    "$LAB_DIR/grade.sh" --no-pages --root "$root" --timeout "$limit" --save-controls "$work/$s.controls" \
        "$work/$s" >"$work/$s.log" 2>&1 || { cat "$work/$s.log" >&2; die "could not grade the untouched handout of $s"; }
    LC_ALL=C sort "$work/$s.controls" >"$root/tests/course/controls/$s"
    echo "$PROG: tests/course/controls/$s: $(wc -l <"$work/$s.controls" | tr -d ' ') control(s) ($(sed -n 's/^GRADE //p' "$work/$s.log"))"
    rm -rf "$work/$s"
done
