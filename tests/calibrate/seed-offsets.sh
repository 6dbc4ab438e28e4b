#!/bin/sh
# seed-offsets.sh - the statistical stage tests under other seeds: how often
# each fails on correct code (make calibrate --seed-offsets N).
#
#   seed-offsets.sh [--help] N [PROGRAM...]
#
# A statistical test of make test renders with fixed seeds, so it passes or
# fails the same way on every run; what its level promises is how rarely it
# fails at a seed nobody chose.  Runs each test program (default: those
# whose renders take PATHCHECK_SEED, tests/lib/pathcheck.h) N times with
# PATHCHECK_SEED = 1000000 + 10000 k, k = 1..N (far from the tests' own
# seeds and from each other's), against the project's own stage, and counts
# the runs with a failure.  Prints one line per program,
#   PROGRAM RUNS FAILED_RUNS SECONDS
# (SECONDS: the runs' wall-clock time; calibrate.sh's table adds the
# rate's interval), and the failing runs' FAIL lines on standard error.
# Builds each test program and its stage first.
# Exit status: 0 run (whatever the failures), 1 a program could not run, 2 usage.
set -eu

PROG=seed-offsets.sh
LAB_DIR=$(cd "$(dirname "$0")/../lab" && pwd)
. "$LAB_DIR/lablib.sh"
root=$(cd "$LAB_DIR/../.." && pwd)

case ${1:-} in -h | --help) show_help "$0"; exit 0 ;; esac
[ $# -ge 1 ] || usage_error "expected N, the number of seed offsets"
n=$1
shift
case $n in '' | *[!0-9]*) usage_error "N must be a whole number, got '$n'" ;; esac
programs=$*
[ -n "$programs" ] ||
    programs=$(grep -l 'pathcheck_seed(' "$root"/tests/stage/*.c | xargs -n 1 basename | sed 's/\.c$//')
work=$(mktemp -d "${TMPDIR:-/tmp}/seeds.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM

for prog in $programs; do
    # The last stage the program applies to (its tests of that stage).
    from=$(test_from "$prog.c")
    # NN_name applies from stage NN on; NN-MM_name to stages NN..MM only.
    range=${prog%%_*}
    upto=99
    case $range in *-*) upto=${range#*-} ;; esac
    stage=$(stage_list "$root" | awk -v from="$from" -v upto="$upto" '
        { nn = substr($0, 1, 2) } nn >= from && nn <= upto { last = $0 } END { print last }')
    [ -n "$stage" ] || die "no stage for $prog"
    bin=$root/build/tests/$stage/$prog
    # The stage and this one program (make -C tests stage would run them all).
    { plain_make -C "$root" "$stage" && plain_make -C "$root/tests" STAGE="$stage" "$bin"; } >/dev/null 2>&1 || true
    [ -x "$bin" ] || die "$bin was not built"
    failed=0
    start=$(date +%s)
    k=1
    while [ "$k" -le "$n" ]; do
        status=0
        (cd "$root/tests" && PATHCHECK_SEED=$((1000000 + 10000 * k)) RENDER=$root/build/$stage/render \
            STAGE=$stage ROOT=$root "$bin") >"$work/log" 2>&1 </dev/null || status=$?
        if [ "$status" -ne 0 ]; then
            failed=$((failed + 1))
            grep '^FAIL' "$work/log" | sed "s/^/$prog seed offset $k: /" >&2 || true
        fi
        k=$((k + 1))
    done
    echo "$prog $n $failed $(($(date +%s) - start))"
done
