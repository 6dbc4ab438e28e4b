#!/usr/bin/env bash
# run-fuzz.sh NAME BINARY SECONDS OUT SEED_DIR... - run one libFuzzer harness.
#
# Runs BINARY for SECONDS of wall-clock time on its corpus OUT/corpus/NAME
# (kept between runs) plus the seed directories, with a memory limit
# ($FUZZ_RSS_MB, also the largest single allocation) and a hang limit
# ($FUZZ_TIMEOUT seconds per input) and the dictionary $FUZZ_DICT if set.
# A crash, leak, hang, out-of-memory or UBSan report fails it: the input is minimised into
# OUT/artifacts/NAME/minimized-* and the way to replay it is printed.
# Writes one summary line to OUT/logs/NAME.summary.
#
# With FUZZ_CPU_SECONDS set, the harness runs until it has used that much
# CPU time instead (SECONDS is then only a wall-clock ceiling): on a shared
# machine a niced long run gets a fraction of a core, and the CPU time is
# what says how much fuzzing was done.  A watchdog reads the harness's
# /proc/PID/stat every few seconds and interrupts it at the budget.
set -u
name=$1 bin=$2 seconds=$3 out=$4
shift 4
corpus=$out/corpus/$name
artifacts=$out/artifacts/$name
log=$out/logs/$name.log
summary=$out/logs/$name.summary
rm -rf "$artifacts"
mkdir -p "$corpus" "$artifacts" "$out/logs"
# The harnesses that read files write each input to one: on tmpfs when
# there is one (twenty times faster than a disk here), removed afterwards.
if [ -d /dev/shm ] && [ -w /dev/shm ]; then
    scratch=$(mktemp -d "/dev/shm/stagelight-fuzz-$name.XXXXXX")
else
    scratch=$out/tmp/$name
    rm -rf "$scratch"
    mkdir -p "$scratch"
fi
trap 'rm -rf "$scratch" "$scratch.time" "$scratch.budget"' EXIT
trap 'exit 1' HUP INT PIPE TERM
seeds=()
for d in "$@"; do
    [ -d "$d" ] && seeds+=("$d")
done
dict=()
[ -n "${FUZZ_DICT:-}" ] && dict=(-dict="$FUZZ_DICT")
# cpu_watchdog PID BUDGET MARK - interrupt PID once its user+system CPU time
# reaches BUDGET seconds, and leave MARK behind to say it was us.
cpu_watchdog() {
    local pid=$1 budget=$2 mark=$3 tck fields
    tck=$(getconf CLK_TCK)
    while kill -0 "$pid" 2>/dev/null; do
        # Fields 14 and 15 of /proc/PID/stat (after the parenthesised name).
        fields=$(sed 's/^.*) //' "/proc/$pid/stat" 2>/dev/null) || return 0
        set -- $fields
        if [ $(((${12} + ${13}) / tck)) -ge "$budget" ]; then
            : >"$mark"
            kill -INT "$pid"
            return 0
        fi
        sleep 5
    done
}
mark=$scratch.budget
TIMEFORMAT='%U %S %R'
start_wall=$(date +%s)
{ time {
    TMPDIR=$scratch "$bin" -max_total_time="$seconds" -rss_limit_mb="${FUZZ_RSS_MB:-2048}" \
        -malloc_limit_mb="${FUZZ_RSS_MB:-2048}" -timeout="${FUZZ_TIMEOUT:-10}" \
        -artifact_prefix="$artifacts/" "${dict[@]}" -print_final_stats=1 "$corpus" "${seeds[@]}" \
        >"$log" 2>&1 &
    pid=$!
    [ -n "${FUZZ_CPU_SECONDS:-}" ] && cpu_watchdog "$pid" "$FUZZ_CPU_SECONDS" "$mark" &
    wait "$pid"
}; } 2>"$scratch.time"
status=$?
# libFuzzer exits 72 when interrupted; the watchdog's interruption is the
# planned end of a CPU-budgeted run.
[ "$status" -eq 72 ] && [ -f "$mark" ] && status=0
rm -f "$mark"
seconds=$(($(date +%s) - start_wall))
cpu=$(awk '{printf "%.1f", $1 + $2}' "$scratch.time")
runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$log" | tail -n 1)
last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -n 1)
cov=$(echo "$last" | sed -nE 's/.*cov: ([0-9]+).*/\1/p')
ft=$(echo "$last" | sed -nE 's/.*ft: ([0-9]+).*/\1/p')
files=$(find "$corpus" -type f | wc -l)
figures="${runs:-?} runs in ${seconds} s (CPU ${cpu} s), cov ${cov:-?} edges, ft ${ft:-?}, corpus ${files} files, peak RSS ${rss:-?} MB"
if [ "$status" -eq 0 ] && ! grep -q 'runtime error:' "$log"; then
    echo "ok   fuzz $name: $figures" >"$summary"
    exit 0
fi
artifact=$(find "$artifacts" -type f | head -n 1)
kind=$(grep -m1 -oE 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer|UndefinedBehaviorSanitizer): [a-z-]+|runtime error: .*|broken promise: .*' "$log")
{
    echo "FAIL fuzz $name: ${kind:-exit $status} (log: $log)"
    if [ -n "$artifact" ]; then
        small=$artifacts/minimized-$(basename "$artifact")
        TMPDIR=$scratch "$bin" -minimize_crash=1 -max_total_time=60 -timeout="${FUZZ_TIMEOUT:-10}" \
            -rss_limit_mb="${FUZZ_RSS_MB:-2048}" -exact_artifact_path="$small" "$artifact" \
            >"$log.minimize" 2>&1
        [ -f "$small" ] || small=$artifact
        echo "    reproducer: $small"
        echo "    replay it:  build/tests/fuzz/replay --run $name $small"
        echo "    once fixed: cp it to tests/fuzz/regressions/$name/ (make test replays it)"
    fi
} >"$summary"
exit 1
