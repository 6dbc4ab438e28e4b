#!/bin/sh
# pathtrace_bench.sh - how fast stage 07 converges on the Cornell scenes.
#
# Prints, for each reference scene: paths (camera samples) per second with
# 1 and 2 threads, and spp x relMSE against Mitsuba's converged image (a
# constant for an unbiased estimator: relMSE falls as 1/spp).  For
# cornell_diffuse_area, the seconds stage 07 needs to reach relMSE 1e-3 at
# 256x256 (2 threads): predicted from that constant and the measured time
# per sample, then checked by rendering at the predicted spp.
#
# Times, so never part of `make test`.  Run from the project root after
# `make` and `make -C tests tools`:  sh tests/bench/pathtrace_bench.sh
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
render=$root/build/07_pathtrace/render
imgcmp=$root/build/tools/imgcmp
work=${TMPDIR:-/tmp}/pathtrace-bench.$$
mkdir -p "$work"
trap 'rm -rf "$work"' EXIT INT TERM

# stat FILE KEY: a number from a --stats JSON file.
stat() {
    sed -n "s/.*\"$2\": \([-0-9.e+]*\).*/\1/p" "$1" | head -n 1
}

# run SCENE THREADS SPP: render, print "seconds paths_per_second relmse".
run() {
    "$render" -q -t "$2" --spp "$3" --seed 7 -o "$work/img.pfm" --stats "$work/s.json" \
        "$root/scenes/$1.scene"
    seconds=$(stat "$work/s.json" seconds_render)
    paths=$(stat "$work/s.json" rays_camera)
    relmse=$("$imgcmp" --csv "$work/img.pfm" "$root/tests/reference/${1}_gi.pfm" |
        awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "relmse") c = i }
                 NR == 2 { print $c }')
    echo "$seconds $(awk -v p="$paths" -v s="$seconds" 'BEGIN { printf "%.0f", p / s }') $relmse"
}

[ -x "$render" ] && [ -x "$imgcmp" ] || {
    echo "pathtrace_bench.sh: run make and make -C tests tools first" >&2
    exit 2
}
echo "stage 07 path tracing, 256x256, load average $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-24s %14s %14s %16s\n' scene "paths/s (1 t)" "paths/s (2 t)" "spp x relMSE"
for scene in cornell_diffuse_area cornell_diffuse_point cornell_specular_area; do
    one=$(run "$scene" 1 16)
    two=$(run "$scene" 2 64)
    printf '%-24s %14s %14s %16s\n' "$scene" "$(echo "$one" | cut -d' ' -f2)" \
        "$(echo "$two" | cut -d' ' -f2)" "$(echo "$two" | awk '{ printf "%.3f", $3 * 64 }')"
    if [ "$scene" = cornell_diffuse_area ]; then
        predicted=$(echo "$two" | awk '{ c = $3 * 64; spp = int(c / 1e-3 + 0.999);
            printf "%d %.2f", spp, $1 / 64 * spp }')
        spp=${predicted% *}
    fi
done
echo "cornell_diffuse_area to relMSE 1e-3 (2 threads): predicted ${predicted#* } s at $spp spp"
check=$(run cornell_diffuse_area 2 "$spp")
echo "  rendered at $spp spp: $(echo "$check" | awk '{ printf "%.2f s, relMSE %.2e", $1, $3 }')"
