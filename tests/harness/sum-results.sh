#!/bin/sh
# sum-results.sh LOG... - add up the closing lines of several test runs and
# print the grand total as "N passed, N failed, N skipped".
awk '/^[0-9]+ passed, [0-9]+ failed/ {
        p += $1; f += $3; s += ($5 == "" ? 0 : $5)
     }
     END { printf "%d passed, %d failed, %d skipped\n", p, f, s; exit (f > 0) }' "$@"
