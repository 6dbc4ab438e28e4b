#!/bin/sh
# log-figures.sh LOG... - the figures docs/robustness.md gives for a long
# run, read from libFuzzer logs (build/fuzz/logs/NAME.log): executions,
# coverage (edges) when the corpus was loaded, after 10% of the run's
# executions and at the end, features, and where in the run (percent of the
# executions) the last new edge was found.  Positions are by executions,
# not by time: on a shared machine a harness's speed varies with the load.
for log in "$@"; do
    awk -v name="$(basename "$log" .log)" '
        /^#[0-9]+/ && / cov: / {
            n = substr($1, 2) + 0
            for (i = 2; i < NF; i++) {
                if ($i == "cov:") cov = $(i + 1) + 0
                if ($i == "ft:") ft = $(i + 1) + 0
            }
            if (!started && $2 == "INITED") { started = 1; start_cov = cov }
            count++; at[count] = n; covs[count] = cov
            if (cov > best) { best = cov; last_new = n }
            last_n = n; last_ft = ft
        }
        /^stat::number_of_executed_units:/ { total = $2 + 0 }
        END {
            if (!count) { printf "%s: no coverage lines\n", name; exit 1 }
            if (!total) total = last_n
            tenth = covs[1]
            for (i = 1; i <= count; i++) if (at[i] <= total / 10) tenth = covs[i]
            printf "%s: %d executions, cov %d -> %d (10%%) -> %d, ft %d, last new edge at %.0f%%\n",
                name, total, start_cov, tenth, best, last_ft, 100 * last_new / total
        }' "$log"
done
