#!/bin/sh
# run-tests.sh LABEL PROGRAM... - run test programs, sum their closing lines.
#
# Each program prints "N passed, N failed, N skipped" as its last line (see
# check.h).  A program that crashes or prints no such line counts as one
# failed test.  Prints one line per program and the total last.
label=$1
shift
passed=0
failed=0
skipped=0
logdir=${TEST_LOG_DIR:-${TMPDIR:-/tmp}}
for prog in "$@"; do
    name=$(basename "$prog")
    log="$logdir/$label-$name.log"
    "$prog" >"$log" 2>&1
    status=$?
    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1)
    if [ -z "$line" ]; then
        echo "FAIL $label/$name: exit $status, no result line (log: $log)"
        tail -n 20 "$log" | sed 's/^/    /'
        failed=$((failed + 1))
        continue
    fi
    p=$(echo "$line" | sed -E 's/^([0-9]+) passed.*/\1/')
    f=$(echo "$line" | sed -E 's/^[0-9]+ passed, ([0-9]+) failed.*/\1/')
    s=$(echo "$line" | sed -nE 's/.*, ([0-9]+) skipped.*/\1/p')
    s=${s:-0}
    if [ "$f" -gt 0 ] || [ "$status" -ne 0 ]; then
        echo "FAIL $label/$name: $line (exit $status)"
        grep -E 'check failed|^FAIL|ERROR|runtime error' "$log" | head -n 20 | sed 's/^/    /'
        [ "$f" -eq 0 ] && f=1
    else
        echo "ok   $label/$name: $line"
    fi
    passed=$((passed + p))
    failed=$((failed + f))
    skipped=$((skipped + s))
done
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
