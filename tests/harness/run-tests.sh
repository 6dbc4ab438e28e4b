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
# TEST_TIMEOUT (seconds a program may run, default 600).
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

# The program running now and its private temporary directory, for the
# interrupt handler.
pid=
private=
cleanup() {
    if [ -n "$pid" ]; then
        kill -TERM "$pid" 2>/dev/null
        wait "$pid" 2>/dev/null
    fi
    [ -n "$private" ] && rm -rf "$private"
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

for prog in "$@"; do
    name=$(basename "$prog")
    if [ -n "$missing" ]; then
        fail "$name: not run (a program it needs did not build)"
        continue
    fi
    if [ ! -x "$prog" ] || { [ "$built" -eq 1 ] && [ ! -e "$prog.built" ]; }; then
        fail "$name: did not build"
        show_build_errors "$name"
        continue
    fi
    log="$logdir/$label-$name.log"
    private=$(mktemp -d "${TMPDIR:-/tmp}/p.XXXXXX") || exit 2
    start=$(date +%s)
    # In the background so that an interrupt reaches the handler at once;
    # timeout runs the program in a process group of its own (with-timeout.sh:
    # timeout(1), or a shell watchdog where it is absent).
    TMPDIR=$private TEST_TMPDIR=$private "$(dirname "$0")/with-timeout.sh" "$limit" "$prog" \
        >"$log" 2>&1 </dev/null &
    pid=$!
    wait "$pid"
    status=$?
    pid=
    rm -rf "$private"
    private=
    secs=$(($(date +%s) - start))
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
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
