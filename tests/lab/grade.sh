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
# scores 0 of the TEST()s in its source.  The last line is for scripts:
#   GRADE lab=05_bvh score=42.9 lab_passed=3 lab_total=7 earlier_passed=40 earlier_total=40 build=ok
# score = 100 * lab_passed / lab_total (skipped tests do not count).
#
# Options:
#   --pristine     grade with the project's own copy of the tests, not the
#                  handout's: a fresh handout of the same stage gets the
#                  student's stages/NN_name/ (what make grade does); files
#                  the student changed outside stages/ are listed
#   --pages DIR    where the report pages go (default LAB/grade): one
#                  compare page per reference render (grade-pages.sh)
#   --timeout SEC  time limit of one test program (default 300; 0: none)
#   --jobs N       parallel make jobs (default: the number of processors)
#   --root DIR     the project, for --pristine (default: this script's)
#   --help
# Exit status: 0 graded (whatever the score), 1 could not grade, 2 usage.
set -eu

PROG=grade.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

root=$(cd "$LAB_DIR/../.." && pwd)
pristine=0
pages=
limit=300
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
while [ $# -gt 0 ]; do
    case $1 in
        -h | --help) show_help "$0"; exit 0 ;;
        --pristine) pristine=1 ;;
        --timeout | --jobs | --root | --pages)
            [ $# -ge 2 ] || usage_error "$1 needs a value"
            case $1 in
                --pages) pages=$2 ;;
                --timeout) limit=$2 ;;
                --jobs) jobs=$2 ;;
                --root) root=$(abs_dir "$2") ;;
            esac
            shift
            ;;
        --) shift; break ;;
        -*) usage_error "unknown option: $1" ;;
        *) break ;;
    esac
    shift
done
[ $# -eq 1 ] || usage_error "expected one handout directory, got $# argument(s)"
case $limit in '' | *[!0-9]*) usage_error "--timeout needs a number of seconds, got '$limit'" ;; esac
case $jobs in '' | *[!0-9]*) usage_error "--jobs needs a number, got '$jobs'" ;; esac
[ -d "$1" ] || die "no such directory: $1"
lab=$(abs_dir "$1")
is_handout "$lab" || die "$1 is not a lab handout (its Makefile was not written by make-lab.sh)"
stage=$(handout_stage "$lab") || die "$1: expected exactly one stage in stages/"
nn=${stage%%_*}

work=$(mktemp -d "${TMPDIR:-/tmp}/grade.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT TERM

echo "grade: lab $nn ($stage) in $1"

# --pristine: the student's stage in a fresh handout.
dir=$lab
if [ "$pristine" -eq 1 ]; then
    [ -d "$root/stages/$stage" ] || die "the project in $root has no stage $stage"
    "$LAB_DIR/make-lab.sh" --quiet --root "$root" "$stage" "$work/lab" ||
        die "could not write a fresh handout of $stage"
    changed=$(cd "$lab" && find . -path ./build -prune -o -path "./stages/$stage" -prune -o \
        -type f -print | sed 's|^\./||' | sort | while IFS= read -r f; do
        cmp -s "$lab/$f" "$work/lab/$f" || echo "$f"
    done)
    if [ -n "$changed" ]; then
        echo "note: these files differ from the project's copy and are not used:"
        echo "$changed" | sed 's/^/    /'
    fi
    rm -rf "$work/lab/stages/$stage"
    mkdir -p "$work/lab/stages/$stage"
    cp -R "$lab/stages/$stage/." "$work/lab/stages/$stage/"
    rm -rf "$work/lab/stages/$stage/build"
    dir=$work/lab
fi

# No program of an earlier build may stand in for one that does not build now.
rm -rf "$dir/build/tests/$stage" "$dir/build/$stage/render"
build=ok
if ! handout_build "$dir" "$work/build.log" all -j"$jobs"; then
    if lab_make -C "$dir" -j"$jobs" all >/dev/null 2>&1; then
        build=tests-partly
        echo "note: some test programs do not compile against this stage (they score 0):"
    else
        build=failed
        echo "note: the stage does not build (every test scores 0):"
    fi
    build_errors "$work/build.log" | head -n 20 | sed 's/^/    /'
fi

# One line per program: FROM NAME PASSED TOTAL NOTE FAILED-TESTS
: >"$work/results"
for src in $(handout_tests "$dir"); do
    name=$(basename "$src" .c)
    res=$(run_handout_test "$dir" "$src" "$work/$name.log" "$limit")
    set -- $res
    note=$5
    [ "$note" = - ] && note=
    names=$(sed -n 's/^FAIL //p' "$work/$name.log" | head -n 5 | awk '{ printf "%s%s", (NR > 1 ? ", " : ""), $0 }')
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$(test_from "$src")" "$name" "$1" "$(($1 + $2))" "$note" "$names" \
        >>"$work/results"
done

if [ "$build" != failed ]; then
    echo "report pages (how to read them: LAB.md, \"Reading the report pages\"):"
    "$LAB_DIR/grade-pages.sh" "$dir" "$stage" "${pages:-$lab/grade}" || echo "note: some pages could not be written"
fi

awk -F '\t' -v nn="$nn" -v stage="$stage" -v build="$build" '
function line(name, p, t, note, names,    s) {
    s = sprintf("    %-32s %4d/%-4d %s%s", name, p, t, (note != "" ? note " " : ""), (names != "" ? "failed: " names : ""))
    sub(/ +$/, "", s)
    print s
}
{
    n++
    from[n] = $1; name[n] = $2; p[n] = $3; t[n] = $4; note[n] = $5; names[n] = $6
    if ($1 == nn) { lp += $3; lt += $4 } else { ep += $3; et += $4; gp[$1] += $3; gt[$1] += $4; groups[$1] = 1 }
}
END {
    printf "\nthis lab (tests of stage %s):\n", nn
    for (i = 1; i <= n; i++) if (from[i] == nn) line(name[i], p[i], t[i], note[i], names[i])
    printf "    %-32s %4d/%d\n", "total", lp, lt
    ng = 0
    for (g in groups) order[++ng] = g
    for (i = 2; i <= ng; i++) for (j = i; j > 1 && order[j - 1] > order[j]; j--) {
        x = order[j]; order[j] = order[j - 1]; order[j - 1] = x
    }
    for (k = 1; k <= ng; k++) {
        g = order[k]
        printf "\nearlier: tests from stage %s (features the handout came with):\n", g
        for (i = 1; i <= n; i++) if (from[i] == g) line(name[i], p[i], t[i], note[i], names[i])
        printf "    %-32s %4d/%d\n", "total", gp[g], gt[g]
    }
    score = lt > 0 ? 100 * lp / lt : 0
    printf "\nscore: %.1f%% (%d of %d tests of lab %s); earlier stages: %d of %d", score, lp, lt, nn, ep, et
    if (ep < et) printf " (%d regression(s))", et - ep
    printf "\n"
    printf "GRADE lab=%s score=%.1f lab_passed=%d lab_total=%d earlier_passed=%d earlier_total=%d build=%s\n", stage, score, lp, lt, ep, et, build
}' "$work/results"
