#!/bin/sh
# ab_render.sh - two builds of a stage's render on the same scene, runs
# interleaved (A B A B ...), for a change that must not cost speed (the
# --pixel tracer's hooks: docs/inspect.md).  Prints, per build, the median
# over the runs of the rays traced per processor-second of the render
# (camera + shadow + secondary rays over seconds_render_cpu: steadier than
# wall time on a shared machine), and the ratio B / A.  The images of A
# and B must be identical: the script says when they are not.
#
#   sh tests/bench/ab_render.sh OLD_RENDER NEW_RENDER SCENE RUNS [render options...]
set -eu
if [ $# -lt 4 ] || [ "${1:-}" = --help ]; then
    echo "usage: $0 OLD_RENDER NEW_RENDER SCENE RUNS [render options...]"
    [ "${1:-}" = --help ] && exit 0
    exit 2
fi
old=$1 new=$2 scene=$3 runs=$4
shift 4
dir=$(mktemp -d "${TMPDIR:-/tmp}/ab_render.XXXXXX")
trap 'rm -rf "$dir"' EXIT
trap 'exit 1' HUP INT PIPE TERM
# Rays per processor-second from one --stats file.
rate() {
    awk -F'[:,]' '{ for (i = 1; i < NF; i++) { k = $i; gsub(/[ "{}]/, "", k); v[k] = $(i + 1) } }
        END { printf "%.0f\n", (v["rays_camera"] + v["rays_shadow"] + v["rays_secondary"]) / v["seconds_render_cpu"] }' "$1"
}
i=0
while [ $i -lt "$runs" ]; do
    for which in a b; do
        bin=$old
        [ $which = b ] && bin=$new
        "$bin" -q "$scene" "$@" -o "$dir/$which.pfm" --stats "$dir/$which.json"
        rate "$dir/$which.json" >> "$dir/$which.rates"
    done
    cmp -s "$dir/a.pfm" "$dir/b.pfm" || echo "the images of A and B differ"
    i=$((i + 1))
done
median() { sort -n "$1" | awk '{ r[NR] = $1 } END { print (NR % 2) ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2 }'; }
a=$(median "$dir/a.rates")
b=$(median "$dir/b.rates")
echo "$scene $*: A $a rays/CPU-s, B $b rays/CPU-s (median of $runs), B/A $(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b / a }')"
echo "  A runs: $(tr '\n' ' ' < "$dir/a.rates")"
echo "  B runs: $(tr '\n' ' ' < "$dir/b.rates")"
