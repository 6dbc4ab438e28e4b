#!/bin/sh
# functions.sh - how often each lab's function tests fail correct code
# (make calibrate-functions; docs/calibration/README.md, "The function
# tests").
#
#   functions.sh [--help] [N]                 (default N: 2000)
#
# The statistical function test programs (tests/stage/NN_lab_functions.c
# that take pathcheck_seed()) run N times each on their own lab's stage,
# under N seed offsets (seed-offsets.sh); a run that fails is a false
# alarm, since the stage is the solution.  Prints a Markdown table: program,
# runs, false alarms, the rate with its Wilson 95% interval, and the
# seconds.  The other function programs are deterministic (fixed inputs,
# no seed): their outcome on correct code is the one make test shows.
# Cost: about 150 processor s for N = 2000 (the four programs); CI's quick
# mode, N = 200, about 15 s.
# Exit status: 0 measured, 1 a program could not run, 2 usage.
set -eu

PROG=functions.sh
LAB_DIR=$(cd "$(dirname "$0")/../lab" && pwd)
. "$LAB_DIR/lablib.sh"
root=$(cd "$LAB_DIR/../.." && pwd)
case ${1:-} in -h | --help) show_help "$0"; exit 0 ;; esac
n=${1:-2000}
case $n in '' | *[!0-9]*) usage_error "N must be a whole number, got '$n'" ;; esac
[ $# -le 1 ] || usage_error "expected at most one argument, N"

echo "| program | runs | false alarms | rate (Wilson 95%) | seconds |"
echo "|---|--:|--:|---|--:|"
for src in $(grep -l 'pathcheck_seed(' "$root"/tests/stage/*_lab_functions.c); do
    name=$(basename "$src" .c)
    "$root/tests/calibrate/seed-offsets.sh" --stage "$(test_from "$src")" "$n" "$name" 2>/dev/null |
        while read -r prog runs k secs; do
            set -- $(wilson "$k" "$runs")
            awk -v prog="${prog%@*}" -v n="$runs" -v k="$k" -v p="$1" -v lo="$2" -v hi="$3" -v s="$secs" 'BEGIN {
                printf "| `%s` | %d | %d | %.2f%% (%.2f%%-%.2f%%) | %d |\n", prog, n, k, 100 * p, 100 * lo, 100 * hi, s }'
        done
done
