#!/bin/sh
# emitters_bench.sh - many emitting triangles (make bench; issue: a car's
# emissive lamps from Blender, 88,837 triangles, stalled the stages): the
# scene of build/tools/gen_meshes' lamps_100k.glb (100,352 emitting
# triangles) over a floor and a sphere, 64x64 at 4 spp, in every stage that
# samples area lights (03-08), and the same scene with the lamp as one
# `area_light` rectangle beside it.  A shading point's shadow rays go to one
# triangle, picked (picker.c), so the two cost about the same from stage 05
# on; stages 03-04 test every triangle for every ray (no BVH yet), which is
# what their time is.  A second view, from under the lamp looking down at
# the lit floor, is their worst case: every shadow ray of every pixel is
# aimed into the 100k triangles and must test them all (stage 05's page
# quotes it as the BVH's reason).  Prints the wall seconds (fastest of ROUNDS runs, on
# every core; from stage 05 on mostly the 100k-triangle file's load and
# tree), shadow rays per camera ray and their ratio.  Run from the
# project root after make.
set -eu
ROUNDS=${ROUNDS:-3}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sl-emitbench.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' HUP INT PIPE TERM
build/tools/gen_meshes "$tmp" >/dev/null
common='camera origin 0 1 3.5 target 0 0.8 0 up 0 1 0 fov 50
image width 64 height 64
material floor diffuse albedo 0.5 0.5 0.5
quad corner -4 0 -4 edge1 0 0 8 edge2 8 0 0 material floor
sphere center 0 0.5 0 radius 0.5 material floor'
printf '%s\nmesh file lamps_100k.glb\n' "$common" >"$tmp/lamps.scene"
# Under the lamp (y = 2), looking straight down: the whole view is floor
# and sphere that the lamp lights.
sed 's/^camera .*/camera origin 0 1.5 0.01 target 0 0 0 up 0 0 -1 fov 50/' "$tmp/lamps.scene" \
    >"$tmp/under.scene"
# The field's footprint, 1 x 1 at y = 2, facing down, radiance 4.
printf '%s\narea_light corner -0.5 2 -0.5 edge1 1 0 0 edge2 0 0 1 radiance 4 4 4\n' "$common" \
    >"$tmp/rect.scene"

# run STAGE SCENE - "seconds shadow_rays camera_rays": the fastest of ROUNDS.
run() {
    b=
    i=0
    while [ "$i" -lt "$ROUNDS" ]; do
        build/"$1"/render -q --spp 4 --stats "$tmp/s.json" -o "$tmp/o.pfm" "$tmp/$2.scene" 2>/dev/null
        r=$(tr -d '\n ' <"$tmp/s.json" | sed 's/.*"seconds_total":\([0-9.e+-]*\).*"rays_camera":\([0-9]*\).*"rays_shadow":\([0-9]*\).*/\1 \3 \2/')
        b=$(echo "$b|$r" | awk -F'|' '{ split($2, r, " "); split($1, o, " ");
            print ($1 == "" || r[1] < o[1]) ? $2 : $1 }')
        i=$((i + 1))
    done
    echo "$b"
}

printf 'many emitters: 100,352 emitting triangles against one rectangle, 64x64 at 4 spp, fastest of %d\n' "$ROUNDS"
printf '%-24s %12s %12s %8s %16s %16s %14s\n' stage "100k s" "rect s" ratio "100k shadow/ray" \
    "rect shadow/ray" "under lamp s"
for dir in stages/0[3-9]_*; do
    stage=$(basename "$dir")
    [ -x "build/$stage/render" ] || continue
    set -- $(run "$stage" lamps) $(run "$stage" rect) $(run "$stage" under)
    awk -v s="$stage" -v a="$1" -v sa="$2" -v ca="$3" -v b="$4" -v sb="$5" -v cb="$6" -v u="$7" 'BEGIN {
        printf "%-24s %12.3f %12.3f %8.2f %16.2f %16.2f %14.3f\n", s, a, b, a / b, sa / ca, sb / cb, u }'
done
