#!/bin/sh
# run-tests.sh [options] LABEL PROGRAM... - run test programs, sum their
# closing lines.
#
# Each program prints "N passed, N failed, N skipped" as its last line (see
# lib/check.h).  Every PROGRAM given is accounted for: one that did not
# build, crashes, times out, exits non-zero or prints no such line counts as
# failed, by name ("FAIL 05_bvh/02_spawn: did not build").  Prints one line
# per program and the total last; exits 1 when anything failed.
#
# Options:
#   --built        a program counts as built only when PROGRAM.built exists
#                  (tests/Makefile removes the markers, then makes them after
#                  each program that builds, so a stale binary never runs)
#   --build-log F  the build's log: its errors are shown for what did not build
#   --require NAME=FILE   FILE must exist (a build marker, e.g. the stage's
#                  render); if it does not, NAME counts as failed and no
#                  program runs (each counts as failed: not run)
# Environment: TEST_LOG_DIR (each program's log; default the current
# directory),
# TEST_TIMEOUT (seconds a program may run, default 600),
# TEST_JOBS (programs run at once, default one a processor: the programs are
# dealt round-robin to that many lanes, each running its share one after
# another; the lines are printed in the programs' order all the same).
# Each program runs with a private TMPDIR (also its TEST_TMPDIR: testlib's
# directory) that is removed when it ends, also when it crashes or the run is
# interrupted, so a run leaves nothing behind.
built=0
build_log=
required=
while [ $# -gt 0 ]; do
    case $1 in
        --built) built=1 ;;
        --build-log) build_log=$2; shift ;;
        --require) required="$required $2"; shift ;;
        *) break ;;
    esac
    shift
done
label=$1
shift
passed=0
failed=0
skipped=0
logdir=${TEST_LOG_DIR:-.}
limit=${TEST_TIMEOUT:-600}

jobs=${TEST_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
case $jobs in '' | *[!0-9]* | 0) jobs=1 ;; esac

# The lanes running now, and where they leave each program's exit status
# and seconds ($runs/K for the K-th program), for the interrupt handler.
lanes=
runs=
cleanup() {
    for l in $lanes; do
        kill -TERM "$l" 2>/dev/null
    done
    for l in $lanes; do
        wait "$l" 2>/dev/null
    done
    [ -n "$runs" ] && rm -rf "$runs"
}
trap 'cleanup; exit 130' INT
trap 'cleanup; exit 143' TERM HUP

fail() {
    echo "FAIL $label/$1"
    failed=$((failed + 1))
}

# The build errors that concern NAME (else the first errors of the log).
show_build_errors() {
    [ -n "$build_log" ] && [ -f "$build_log" ] || return 0
    { grep -F "$1" "$build_log" | grep -Ei 'error|undefined' ||
        grep -Ei 'error:|undefined reference' "$build_log"; } | head -n 20 | sed 's/^/    /'
}

missing=
for req in $required; do
    if [ ! -e "${req#*=}" ]; then
        fail "${req%%=*}: did not build"
        show_build_errors "${req%%=*}"
        missing=1
    fi
done

# runnable PROGRAM - whether PROGRAM is there to run (built, when --built).
runnable() {
    [ -z "$missing" ] && [ -x "$1" ] && { [ "$built" -eq 0 ] || [ -e "$1.built" ]; }
}

# run_lane LANE PROGRAM... - run the programs dealt to lane LANE (the K-th
# when K mod jobs is LANE), one after another, each with a private TMPDIR
# (also its TEST_TMPDIR: testlib's directory), removed when it ends; its
# status and seconds go to $runs/K.  On TERM: stop the program running (in
# the background, so that the signal reaches the handler at once; timeout
# runs it in a process group of its own: with-timeout.sh), remove its
# directory, exit.
run_lane() {
    lane=$1
    shift
    pid=
    private=
    trap '[ -n "$pid" ] && { kill -TERM "$pid" 2>/dev/null; wait "$pid" 2>/dev/null; }; [ -n "$private" ] && rm -rf "$private"; exit 143' TERM
    k=0
    for prog in "$@"; do
        if [ $((k % jobs)) -eq "$lane" ] && runnable "$prog"; then
            private=$(mktemp -d "${TMPDIR:-/tmp}/p.XXXXXX") || exit 2
            start=$(date +%s)
            TMPDIR=$private TEST_TMPDIR=$private "$(dirname "$0")/with-timeout.sh" "$limit" "$prog" \
                >"$logdir/$label-$(basename "$prog").log" 2>&1 </dev/null &
            pid=$!
            wait "$pid"
            status=$?
            pid=
            rm -rf "$private"
            private=
            echo "$status $(($(date +%s) - start))" >"$runs/$k"
        fi
        k=$((k + 1))
    done
}

runs=$(mktemp -d "${TMPDIR:-/tmp}/runs.XXXXXX") || exit 2
lane=0
while [ "$lane" -lt "$jobs" ] && [ "$lane" -lt $# ]; do
    run_lane "$lane" "$@" &
    lanes="$lanes $!"
    lane=$((lane + 1))
done
for l in $lanes; do
    wait "$l"
done
lanes=

k=0
for prog in "$@"; do
    name=$(basename "$prog")
    this=$k
    k=$((k + 1))
    if [ -n "$missing" ]; then
        fail "$name: not run (a program it needs did not build)"
        continue
    fi
    if ! runnable "$prog"; then
        fail "$name: did not build"
        show_build_errors "$name"
        continue
    fi
    log="$logdir/$label-$name.log"
    status=125
    secs=0
    [ -f "$runs/$this" ] && read -r status secs <"$runs/$this"
    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1)
    if [ "$status" -eq 124 ] || [ "$status" -eq 137 ]; then
        fail "$name: timed out after $limit s (log: $log)"
        tail -n 10 "$log" | sed 's/^/    /'
        continue
    fi
    if [ -z "$line" ]; then
        if [ "$status" -gt 128 ]; then
            fail "$name: crashed (signal $((status - 128))), no result line (log: $log)"
        else
            fail "$name: exit $status, no result line (log: $log)"
        fi
        tail -n 20 "$log" | sed 's/^/    /'
        continue
    fi
    p=$(echo "$line" | sed -E 's/^([0-9]+) passed.*/\1/')
    f=$(echo "$line" | sed -E 's/^[0-9]+ passed, ([0-9]+) failed.*/\1/')
    s=$(echo "$line" | sed -nE 's/.*, ([0-9]+) skipped.*/\1/p')
    s=${s:-0}
    if [ "$f" -gt 0 ] || [ "$status" -ne 0 ]; then
        echo "FAIL $label/$name: $line (exit $status, $secs s)"
        grep -E 'check failed|^FAIL|ERROR|runtime error' "$log" | head -n 20 | sed 's/^/    /'
        [ "$f" -eq 0 ] && f=1
    else
        echo "ok   $label/$name: $line ($secs s)"
    fi
    passed=$((passed + p))
    failed=$((failed + f))
    skipped=$((skipped + s))
done
rm -rf "$runs"
runs=
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
