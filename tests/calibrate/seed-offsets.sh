#!/bin/sh
# seed-offsets.sh - the statistical stage tests under other seeds: how often
# each fails on correct code (make calibrate-compare --seed-offsets N).
#
#   seed-offsets.sh [--help] [--stage NN] N [PROGRAM...]
#
# A statistical test of make test renders with fixed seeds, so it passes or
# fails the same way on every run; what its level promises is how rarely it
# fails at a seed nobody chose.  Runs each test program (default: those
# whose renders take PATHCHECK_SEED, tests/lib/pathcheck.h) N times with
# PATHCHECK_SEED = 1000000 + 10000 k, k = 1..N (far from the tests' own
# seeds and from each other's), against every stage make test runs it
# against (07_reference: 07_pathtrace and 08_variance_reduction; each
# stage's noise is its own), or only stage NN with --stage, and counts the
# runs with a failure.  Prints one line per program and stage,
#   PROGRAM@STAGE RUNS FAILED_RUNS SECONDS
# (SECONDS: the runs' wall-clock time; calibrate.sh's table adds the
# rate's interval), and the failing runs' FAIL lines on standard error.
# Builds each test program and its stage first.
# Exit status: 0 run (whatever the failures), 1 a program could not run, 2 usage.
set -eu

PROG=seed-offsets.sh
LAB_DIR=$(cd "$(dirname "$0")/../lab" && pwd)
. "$LAB_DIR/lablib.sh"
root=$(cd "$LAB_DIR/../.." && pwd)

only=
case ${1:-} in -h | --help) show_help "$0"; exit 0 ;; esac
if [ "${1:-}" = --stage ]; then
    [ $# -ge 2 ] || usage_error "--stage needs a stage number"
    only=$(resolve_stage "$root" "$2") || exit 2
    shift 2
fi
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

# run_offsets PROGRAM STAGE - the N runs of PROGRAM against STAGE; its line.
run_offsets() {
    ro_bin=$root/build/tests/$2/$1
    # The stage and this one program (make -C tests stage would run them all).
    { plain_make -C "$root" "$2" && plain_make -C "$root/tests" STAGE="$2" "$ro_bin"; } >/dev/null 2>&1 || true
    [ -x "$ro_bin" ] || die "$ro_bin was not built"
    ro_failed=0
    ro_start=$(date +%s)
    ro_k=1
    while [ "$ro_k" -le "$n" ]; do
        ro_status=0
        (cd "$root/tests" && PATHCHECK_SEED=$((1000000 + 10000 * ro_k)) RENDER=$root/build/$2/render \
            STAGE=$2 ROOT=$root "$ro_bin") >"$work/log" 2>&1 </dev/null || ro_status=$?
        if [ "$ro_status" -ne 0 ]; then
            ro_failed=$((ro_failed + 1))
            grep '^FAIL' "$work/log" | sed "s/^/$1@$2 seed offset $ro_k: /" >&2 || true
        fi
        ro_k=$((ro_k + 1))
    done
    echo "$1@$2 $n $ro_failed $(($(date +%s) - ro_start))"
}

for prog in $programs; do
    from=$(test_from "$prog.c")
    # NN_name applies from stage NN on; NN-MM_name to stages NN..MM only.
    range=${prog%%_*}
    upto=99
    case $range in *-*) upto=${range#*-} ;; esac
    stages=$(stage_list "$root" | awk -v from="$from" -v upto="$upto" -v only="$only" '
        { nn = substr($0, 1, 2) } nn >= from && nn <= upto && (only == "" || $0 == only)')
    if [ -z "$stages" ]; then
        [ -n "$only" ] && continue
        die "no stage for $prog"
    fi
    for stage in $stages; do
        run_offsets "$prog" "$stage"
    done
done
