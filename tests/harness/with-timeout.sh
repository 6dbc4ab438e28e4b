#!/bin/sh
# with-timeout.sh SECONDS COMMAND [ARG...] - run COMMAND, stopped when it
# runs longer than SECONDS: exit status 124 then (as timeout(1)), else
# COMMAND's own.
#
# With GNU (or BSD) timeout(1) on the PATH it is that, `timeout -k 10`: the
# command in a process group of its own, killed 10 s after SIGTERM if still
# running.  Without it (a stock macOS before 14, a BusyBox system without
# it), a POSIX shell watchdog: SIGTERM to the command after SECONDS, SIGKILL
# 10 s later; it signals the command only, so processes the command started
# and left behind finish on their own.  WITH_TIMEOUT=posix forces the
# watchdog (for its test: tests/course/test-course.sh).
case ${1:-} in '' | *[!0-9]*) echo "usage: with-timeout.sh SECONDS COMMAND [ARG...]" >&2; exit 125 ;; esac
limit=$1
shift
if [ "${WITH_TIMEOUT:-}" != posix ] && command -v timeout >/dev/null 2>&1; then
    exec timeout -k 10 "$limit" "$@"
fi

# The watchdog removes the mark when the time is up.
mark=$(mktemp "${TMPDIR:-/tmp}/with-timeout.XXXXXX") || exit 125
"$@" &
child=$!
# The watchdog: a sleep it can cut short, so that it leaves nothing behind.
(
    nap=
    trap '[ -n "$nap" ] && kill "$nap" 2>/dev/null; exit 0' TERM
    sleep "$limit" &
    nap=$!
    wait "$nap"
    nap=
    rm -f "$mark"
    kill -TERM "$child" 2>/dev/null || exit 0
    sleep 10 &
    nap=$!
    wait "$nap"
    nap=
    kill -KILL "$child" 2>/dev/null
    exit 0
) >/dev/null 2>&1 &
watchdog=$!
trap 'kill -TERM "$child" 2>/dev/null' HUP INT TERM
status=0
wait "$child" || status=$?
# An interrupted wait (a signal to this script) returns early: wait again.
while kill -0 "$child" 2>/dev/null; do
    wait "$child" || status=$?
done
kill -TERM "$watchdog" 2>/dev/null
wait "$watchdog" 2>/dev/null
if [ -e "$mark" ]; then
    rm -f "$mark"
    exit "$status"
fi
exit 124
