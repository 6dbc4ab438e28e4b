#!/bin/sh
# check-limits.sh - the size limits that keep each stage one idea a learner
# can read (part of make test; issue 27).
#
#   check-limits.sh [options]
#
# Reads the diff table of docs/README.md (written by make diffs; check-diffs.sh
# says whether it is current) and the files themselves.  Checks:
#   diff NN       the diff into stage NN (02 on) changes at most 450 lines
#                 (added + removed, new files included)
#   lab NN        it adds at most 250 lines in LAB regions (what the lab
#                 asks a student to write)
#   source        no .c or .h file of a stage is over 500 lines
#   lesson        no docs/stages/*.md page is over 500 lines
# Each offender is named with its size and the limit.  One result line per
# check, like tests/harness/run-tests.sh, and the closing line "N passed,
# N failed, N skipped".
#
# Options:
#   --root DIR    the project (default: the one this script belongs to)
#   --table FILE  read the diff table from FILE instead of docs/README.md
#                 (test-lab-tools.sh checks a doctored one)
#   --help
# Exit status: 0 every limit kept, 1 one exceeded (or no table), 2 usage.
set -eu

PROG=check-limits.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

MAX_DIFF=450
MAX_LAB=250
MAX_SOURCE=500
MAX_LESSON=500

root=$(cd "$LAB_DIR/../.." && pwd)
table=
parse_options '--root root=DIR --table table=VALUE' "$@"
shift "$po_used"
[ $# -eq 0 ] || usage_error "unexpected argument: $1"
[ -n "$table" ] || table=$root/docs/README.md

passed=0
failed=0
result() {
    case $1 in
        ok) passed=$((passed + 1)); printf 'ok   limits/%s\n' "$2" ;;
        FAIL) failed=$((failed + 1)); printf 'FAIL limits/%s\n' "$2" ;;
    esac
}

# The table's rows between its markers: stage, added, removed, LAB lines.
rows=$(awk -F'|' '
    /<!-- diff-table -->/ { inside = 1; next }
    /<!-- \/diff-table -->/ { inside = 0 }
    inside && $2 ~ /\[[0-9][0-9]_/ {
        stage = $2; sub(/^ *\[/, "", stage); sub(/\].*/, "", stage)
        gsub(/ /, "", $6); gsub(/ /, "", $7); gsub(/ /, "", $8)
        print stage, $6, $7, $8
    }' "$table" 2>/dev/null || true)
if [ -z "$rows" ]; then
    result FAIL "table: no diff table in $table (run make diffs)"
    echo "$passed passed, $failed failed, 0 skipped"
    exit 1
fi

while read -r stage added removed lab; do
    case $stage in 01_*) continue ;; esac
    changed=$((added + removed))
    if [ "$changed" -le "$MAX_DIFF" ]; then
        result ok "diff $stage: $changed changed lines (at most $MAX_DIFF)"
    else
        result FAIL "diff $stage: $changed changed lines ($added added, $removed removed), over $MAX_DIFF"
    fi
    if [ "$lab" -le "$MAX_LAB" ]; then
        result ok "lab $stage: $lab lines in LAB regions (at most $MAX_LAB)"
    else
        result FAIL "lab $stage: $lab lines in LAB regions, over $MAX_LAB"
    fi
done <<EOF_ROWS
$rows
EOF_ROWS

# check_sizes WHAT LIMIT FILE...: one failure per file over LIMIT lines.
check_sizes() {
    what=$1
    limit=$2
    shift 2
    n_over=0
    for f in "$@"; do
        [ -f "$f" ] || continue
        n=$(wc -l <"$f" | tr -d ' ')
        if [ "$n" -gt "$limit" ]; then
            result FAIL "$what: ${f#"$root"/} has $n lines, over $limit"
            n_over=$((n_over + 1))
        fi
    done
    [ "$n_over" -gt 0 ] || result ok "$what: no file over $limit lines"
}

check_sizes source "$MAX_SOURCE" "$root"/stages/*/*.c "$root"/stages/*/*.h
check_sizes lesson "$MAX_LESSON" "$root"/docs/stages/*.md

echo "$passed passed, $failed failed, 0 skipped"
[ "$failed" -eq 0 ]
