#!/bin/sh
# grade-cost.sh - what make grade costs a student, lab by lab, and whether
# its score depends on the machine's load (make grade-cost).
#
#   grade-cost.sh [--load N] [--help] [NN...]          (default: every lab)
#
# For each lab: writes the solution's handout (make-lab.sh --solution) into
# a temporary directory, builds it (make), then runs the handout's own
# `make grade` three times and prints one Markdown row a lab:
#   first     the first grade after make: it compiles the test programs
#   again     a second grade: the test programs' objects stand, only what
#             includes a changed file compiles again (as after make test)
#   loaded    a third, with N busy loops beside it (default 2: one per
#             processor of the machines this project is measured on)
#   submitted the autograder's grade of one submission, as Gradescope and
#             grade-class run it (tests/course/run_autograder.in): the
#             image is the untouched handout built with its test programs
#             once (setup.sh; not counted), and each submission's
#             stages/NN_name/ (here the solution's) goes into a copy of it,
#             so only what the submission's files reach compiles again
# with the processor seconds (user + sys of make grade, or run_autograder,
# and everything it ran) of each, and each run's score.  The four scores
# must be equal: a score that depends on the machine's load is a bug
# (exit 1).
# Exit status: 0 measured, 1 a grade failed or the scores differ, 2 usage.
set -eu

PROG=grade-cost.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"
root=$(cd "$LAB_DIR/../.." && pwd)

load=2
while [ $# -gt 0 ]; do
    case $1 in
        -h | --help) show_help "$0"; exit 0 ;;
        --load)
            [ $# -ge 2 ] || usage_error "--load needs a number"
            load=$2
            case $load in '' | *[!0-9]*) usage_error "--load must be a whole number, got '$load'" ;; esac
            shift 2 ;;
        -*) usage_error "unknown option $1" ;;
        *) break ;;
    esac
done
labs=$*
if [ -z "$labs" ]; then
    for d in "$root"/stages/[0-9][0-9]_*; do labs="$labs $(basename "$d" | cut -c1-2)"; done
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/grade-cost.XXXXXX")
busy=
stop_load() {
    for p in $busy; do kill "$p" 2>/dev/null || :; done
    busy=
}
trap 'stop_load; rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM

# cost_and_score LOG - "SECONDS SCORE": the processor seconds in LOG.times
# (the output of the shell's `times` after a run) and the score of LOG's
# GRADE line (none without one).
cost_and_score() {
    # times: the shell's own times, then its children's, "user system".
    awk 'NR == 2 {
             t = 0
             for (i = 1; i <= 2; i++) { split($i, p, "m"); sub(/s$/, "", p[2]); t += 60 * p[1] + p[2] }
             printf "%.1f", t
         }' "$1.times"
    awk '/^GRADE / { for (i = 2; i <= NF; i++) if ($i ~ /^score=/) s = substr($i, 7) }
         END { printf " %s\n", s == "" ? "none" : s }' "$1"
}

# timed_grade DIR LOG - runs make grade in DIR; prints "SECONDS SCORE", the
# processor seconds of everything it ran and the score of its GRADE line.
timed_grade() {
    sh -c 'cd "$1" && ${MAKE:-make} --no-print-directory grade >"$2" 2>&1; s=$?; times >"$2.times"; exit $s' \
        sh "$1" "$2" </dev/null || :
    cost_and_score "$2"
}

# timed_submission STAGE SOLUTION LOG: the autograder of STAGE (autograder.sh)
# with its image built as setup.sh builds it, then run_autograder on the
# stage of the SOLUTION handout; prints "SECONDS SCORE" as timed_grade does.
timed_submission() {
    ag=$work/ag.$1
    # AUTOGRADER_ROOT=$ag: source/ (the autograder, its handout built where
    # it lies, as Gradescope's setup.sh builds it), submission/, results/.
    "$LAB_DIR/../course/autograder.sh" --root "$root" "$1" "$ag/out" >"$3.setup" 2>&1 &&
        mv "$ag/out/autograder" "$ag/source" &&
        plain_make -C "$ag/source/handout" -j2 tests >>"$3.setup" 2>&1 ||
        die "could not build the autograder of $1 (see $3.setup)"
    mkdir -p "$ag/submission/stages" "$ag/results"
    cp -R "$2/stages/$1" "$ag/submission/stages/$1"
    rm -rf "$ag/submission/stages/$1/build"
    sh -c 'AUTOGRADER_ROOT=$1 sh "$1/source/run_autograder" >"$2" 2>&1; s=$?; times >"$2.times"; exit $s' \
        sh "$ag" "$3" </dev/null || :
    cost_and_score "$3"
    rm -rf "$ag"
}

status=0
echo "| lab | first grade (processor s) | again | loaded ($load busy loops) | submitted (autograder) | scores |"
echo "|---|--:|--:|--:|--:|---|"
for nn in $labs; do
    stage=$(resolve_stage "$root" "$nn") || exit 2
    dir=$work/$nn
    "$LAB_DIR/make-lab.sh" --quiet --solution --root "$root" "$stage" "$dir" >/dev/null 2>&1 ||
        die "could not write the solution's handout of $stage"
    plain_make -C "$dir" -j2 all >"$work/$nn.build.log" 2>&1 ||
        die "the solution's handout of $stage does not build (see make -C $dir)"
    set -- $(timed_grade "$dir" "$work/$nn.first.log")
    first=$1 s1=$2
    set -- $(timed_grade "$dir" "$work/$nn.again.log")
    again=$1 s2=$2
    i=0
    while [ "$i" -lt "$load" ]; do
        sh -c 'while :; do :; done' &
        busy="$busy $!"
        i=$((i + 1))
    done
    set -- $(timed_grade "$dir" "$work/$nn.loaded.log")
    stop_load
    loaded=$1 s3=$2
    set -- $(timed_submission "$stage" "$dir" "$work/$nn.submitted.log")
    submitted=$1 s4=$2
    verdict="$s1%, $s2%, $s3%, $s4%"
    if [ "$s1" = none ] || [ "$s1" != "$s2" ] || [ "$s1" != "$s3" ] || [ "$s1" != "$s4" ]; then
        verdict="$verdict: DIFFER"
        status=1
        tail -n 5 "$work/$nn.first.log" "$work/$nn.loaded.log" "$work/$nn.submitted.log" >&2
    fi
    echo "| $stage | $first | $again | $loaded | $submitted | $verdict |"
    rm -rf "$dir"
done
exit $status
