#!/bin/sh
# tests/extremes/report.sh - the table of docs/extremes.md, from the
# expectation table (tests/extremes/expect.tsv) and the measured figures of
# the last run of the extremes battery.
#
#   tests/extremes/report.sh            print the table
#   tests/extremes/report.sh --write    put it into docs/extremes.md, between
#                                       the lines <!-- extremes:begin --> and
#                                       <!-- extremes:end -->
#
# The results are the logs the battery's programs write (expect.h): every
# build/tests/logs/extremes-*.tsv and build/float/tests/logs/extremes-*.tsv
# (run `make test`, and `make REAL=float test` for the float runs of the
# white-box cases), or the directories in $EXTREMES_LOGS (space-separated).
# One row per case and precision, one column per stage; a cell is the
# outcome and the figure:  pass 3e-12 | xfail 0.047 (expected to fail, did,
# within its documented band) | FAIL ... (unexpected: the run failed) |
# skip | . (not run).
set -eu

root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
logs=${EXTREMES_LOGS:-build/tests/logs build/float/tests/logs}
doc=docs/extremes.md

table() {
    results=$(mktemp)
    trap 'rm -f "$results"' EXIT
    trap 'exit 1' HUP INT PIPE TERM
    for dir in $logs; do
        cat "$dir"/extremes-*.tsv 2>/dev/null || true
    done >"$results"
    awk -F '\t' '
    # Pass 1: the cases in the order expect.tsv first names them.
    FNR == NR {
        if ($0 ~ /^#/ || NF < 7) next
        if (!($1 in seen)) { seen[$1] = 1; order[n++] = $1 }
        next
    }
    # Pass 2: the results (a later line for the same cell replaces an
    # earlier one, unless it is a skip: the float run of `make REAL=float
    # test` skips the double rows that `make test` measured).
    {
        cell = $1 SUBSEP substr($2, 1, 2) SUBSEP $3
        figure = $6 == "nan" ? "" : sprintf(" %.2g", $6)
        if ($7 != "ok") text = "**FAIL** " $7 figure
        else if ($5 == "skip") text = "skip"
        else if ($4 == "xfail") text = "xfail" figure
        else text = $5 figure
        if (text == "skip" && (cell in out)) next
        out[cell] = text
        ran[$1 SUBSEP $3] = 1
    }
    END {
        print "| case | precision | 01 | 02 | 03 | 04 | 05 | 06 | 07 |"
        print "|---|---|---|---|---|---|---|---|---|"
        for (i = 0; i < n; i++) {
            for (p = 0; p < 2; p++) {
                precision = p ? "float" : "double"
                if (!((order[i], precision) in ran)) continue
                line = "| `" order[i] "` | " precision
                for (s = 1; s <= 7; s++) {
                    key = order[i] SUBSEP sprintf("%02d", s) SUBSEP precision
                    line = line " | " (key in out ? out[key] : ".")
                }
                print line " |"
            }
        }
    }' tests/extremes/expect.tsv "$results"
}

if [ "${1:-}" = "--write" ]; then
    new=$(mktemp)
    table >"$new.table"
    awk -v table="$new.table" '
        /<!-- extremes:end -->/ { skipping = 0 }
        !skipping { print }
        /<!-- extremes:begin -->/ {
            while ((getline line < table) > 0) print line
            skipping = 1
        }' "$doc" >"$new"
    mv "$new" "$doc"
    rm -f "$new.table"
    echo "wrote the table into $doc"
else
    table
fi
