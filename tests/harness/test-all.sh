#!/bin/sh
# test-all.sh [--logs DIR] [--stage NN|NAME] - the run behind `make test`
# and `make sanitize` (the variant comes from make: REAL=, SANITIZE= ...).
#
# Without --stage: builds everything (make all), then runs the unit tests of
# common/, the tests of every stage and the parts listed in
# tests/harness/parts.  With --stage: only that stage's tests (its build in
# double and float), nothing else; an unknown stage is refused with the list
# of stages (exit 2).
#
# SKIP_PARTS="NAME ..." (make test SKIP_PARTS=labs) skips those parts of
# tests/harness/parts, each counted as one skipped with its reason (CI: it
# runs make check-labs, the full checks, after make test).
#
# Every part is accounted for: one that prints no result line, or exits
# non-zero with no failure counted, counts as failed by name.  The closing
# lines are one per part (passed, failed, skipped, seconds), then the grand
# total "N passed, N failed, N skipped in S s"; the exit status is 1 when
# anything failed.
#
# The run gets a temporary directory of its own (TMPDIR for everything it
# starts), removed at the end, also on failure or interrupt; the run fails
# when something was left in it (a test that does not clean up after itself).
# Its name and run-tests.sh's are short: a Unix socket's path (Chromium's, in
# test_report_browser) must stay under 108 bytes.
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root" || exit 2
MAKE=${MAKE:-make}
logs=$root/build/test-logs
stage=
while [ $# -gt 0 ]; do
    case $1 in
        --logs) logs=$2; shift ;;
        --stage) stage=$2; shift ;;
        *) echo "test-all.sh: unexpected argument: $1" >&2; exit 2 ;;
    esac
    shift
done

# The command that ran us, for messages: make sanitize is make test with
# SANITIZE=1 (make puts its command line's variables in our environment).
command="make test"
[ "${SANITIZE:-0}" = 1 ] && command="make sanitize"
[ "${REAL:-double}" = float ] && command="make REAL=float ${command#make }"

stages=
for d in stages/[0-9][0-9]_*; do
    [ -f "$d/Makefile" ] && stages="$stages ${d#stages/}"
done
if [ -n "$stage" ]; then
    found=
    for s in $stages; do
        if [ "$s" = "$stage" ] || [ "${s%%_*}" = "$stage" ]; then
            found=$s
        fi
    done
    if [ -z "$found" ]; then
        echo "$command: unknown stage '$stage'; the stages are:" >&2
        for s in $stages; do echo "  $s" >&2; done
        exit 2
    fi
    stage=$found
fi

mkdir -p "$logs" || exit 2
run_tmp=$(mktemp -d "${TMPDIR:-/tmp}/sl-run.XXXXXX") || exit 2
trap 'rm -rf "$run_tmp"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM HUP
trap 'exit 141' PIPE
user_tmp=${TMPDIR:-/tmp}
TMPDIR=$run_tmp
export TMPDIR

rows=$logs/rows
: >"$rows"
run_start=$(date +%s)

# row NAME PASSED FAILED SKIPPED SECONDS
row() {
    echo "$*" >>"$rows"
}

# part NAME COMMAND... - run one part, its output shown and kept in
# LOGS/NAME.log; record its row.
part() {
    p_name=$1
    shift
    p_log=$logs/$p_name.log
    p_start=$(date +%s)
    { "$@" 2>&1; echo $? >"$p_log.status"; } | tee "$p_log"
    p_status=$(cat "$p_log.status" 2>/dev/null || echo "?")
    rm -f "$p_log.status"
    p_secs=$(($(date +%s) - p_start))
    p_line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$p_log" | tail -n 1)
    if [ -z "$p_line" ]; then
        echo "FAIL $p_name: exit $p_status, no result line (log: $p_log)"
        row "$p_name" 0 1 0 "$p_secs"
        return
    fi
    set -- $p_line
    p_p=$1
    p_f=$3
    p_s=${5:-0}
    if [ "$p_status" != 0 ] && [ "$p_f" -eq 0 ]; then
        echo "FAIL $p_name: exit $p_status with no failure counted (log: $p_log)"
        p_f=1
    fi
    row "$p_name" "$p_p" "$p_f" "$p_s" "$p_secs"
}

# check NAME STATUS SECONDS - a check of the runner's own: 1 passed or 1 failed.
check() {
    if [ "$2" -eq 0 ]; then row "$1" 1 0 0 "$3"; else row "$1" 0 1 0 "$3"; fi
}

if [ -n "$stage" ]; then
    part "$stage" $MAKE --no-print-directory -C "stages/$stage" test
else
    b_start=$(date +%s)
    b_status=0
    $MAKE --no-print-directory all || b_status=$?
    [ "$b_status" -eq 0 ] || echo "FAIL build: make all exited $b_status"
    check build "$b_status" $(($(date +%s) - b_start))
    part common $MAKE --no-print-directory -C tests common
    for s in $stages; do
        part "$s" $MAKE --no-print-directory -C "stages/$s" test
    done
    plain=1
    [ "${SANITIZE:-0}" = 1 ] || [ "${REAL:-double}" != double ] && plain=0
    while read -r p_name p_when p_cmd; do
        case $p_name in '' | '#'*) continue ;; esac
        if [ "$p_when" = plain ] && [ "$plain" = 0 ]; then
            echo "skip $p_name: the same in every build (it does not use this build's programs): make test runs it"
            row "$p_name" 0 0 1 0
            continue
        fi
        case " ${SKIP_PARTS:-} " in
            *" $p_name "*)
                echo "skip $p_name: SKIP_PARTS names it"
                row "$p_name" 0 0 1 0
                continue
                ;;
        esac
        part "$p_name" sh -c "$p_cmd"
    done <tests/harness/parts
fi

# Nothing may be left in the run's temporary directory.
left=$(cd "$run_tmp" && ls -A)
if [ -n "$left" ]; then
    echo "FAIL tmpdir: the run left $(echo "$left" | wc -l) file(s) in TMPDIR ($user_tmp):"
    echo "$left" | head -n 10 | sed 's/^/    /'
    t_status=1
else
    echo "ok   tmpdir: the run left nothing in TMPDIR"
    t_status=0
fi
if [ -n "$stage" ]; then
    # Counted with the stage: its total stays the stage's when it is clean.
    if [ "$t_status" -ne 0 ]; then
        awk '{ $3 += 1; print }' "$rows" >"$rows.new" && mv "$rows.new" "$rows"
    fi
else
    check tmpdir "$t_status" 0
fi

echo
awk -v secs=$(($(date +%s) - run_start)) '
    { printf "%-20s %5d passed, %d failed, %d skipped, %d s\n", $1, $2, $3, $4, $5
      p += $2; f += $3; s += $4 }
    END { printf "%d passed, %d failed, %d skipped in %d s\n", p, f, s, secs; exit (f > 0) }' "$rows"
