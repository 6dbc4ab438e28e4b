#!/bin/sh
# check-one.sh - one scored test of a lab, run and counted as make grade
# counts it (a handout's make check TEST=PROGRAM/NAME: GitHub Classroom's
# steps, one a test).
#
#   check-one.sh [--help] HANDOUT PROGRAM/NAME
#
# PROGRAM/NAME is a TEST() of the handout's tests/stage/PROGRAM.c, or
# pages/PAGE_paired, one of the lab's paired pages (grade-pages.sh
# --paired-only PAGE).  A statistical test that fails runs again at the
# grade's second seed and passes when it passes there, as in make grade
# (lablib.sh, GRADE_SECOND_SEED).  Prints the test's output.
# Exit status: 0 it passes, 1 it fails (or does not build), 2 usage.
set -eu

PROG=check-one.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

case ${1:-} in -h | --help) show_help "$0"; exit 0 ;; esac
[ $# -eq 2 ] || usage_error "expected HANDOUT PROGRAM/NAME, got $# argument(s)"
dir=$(abs_dir "$1")
prog=${2%%/*}
name=${2#*/}
[ -n "$prog" ] && [ -n "$name" ] && [ "$prog" != "$2" ] || usage_error "expected PROGRAM/NAME, got '$2'"
stage=$(handout_stage "$dir") || die "$dir: no stage in stages/"
work=$(mktemp -d "${TMPDIR:-/tmp}/check-one.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM

if [ "$prog" = pages ]; then
    page=${name%_paired}
    "$LAB_DIR/grade-pages.sh" --paired-only "$page" --records "$work/records" "$dir" "$stage" "$dir/grade" || :
    grep -q "^$page ok\$" "$work/records"
    exit
fi

src=$dir/tests/stage/$prog.c
[ -f "$src" ] || usage_error "no test program tests/stage/$prog.c in $dir"
grep -q "^TEST($name)" "$src" || usage_error "tests/stage/$prog.c has no TEST($name)"
if ! lab_make -C "$dir/tests" STAGE="$stage" "$dir/build/tests/$stage/$prog" >"$work/build.log" 2>&1; then
    cat "$work/build.log"
    exit 1
fi
run_handout_test "$dir" "$src" "$work/first.log" 0 "$name" >/dev/null
cat "$work/first.log"
one_test_passed "$work/first.log" "$name" && exit 0
is_statistical "$src" || exit 1
echo "(a statistical test: run again at the grade's second seed, $GRADE_SECOND_SEED)"
PATHCHECK_SEED=$GRADE_SECOND_SEED run_handout_test "$dir" "$src" "$work/second.log" 0 "$name" >/dev/null
cat "$work/second.log"
one_test_passed "$work/second.log" "$name"
