#!/bin/sh
# tests/extremes/images.sh - the images of docs/extremes.md, in
# docs/images/extremes/: the interesting failures of the extremes battery
# and, when a tree with the fixes is given, the same scenes fixed.
#
#   tests/extremes/images.sh [FIXED_BUILD]
#
# Needs `make` and `make REAL=float` (this tree's build/ and build/float/).
# FIXED_BUILD is the build/ directory of a copy of the tree with the
# proposed fixes of docs/extremes.md applied and built; without it the
# "fixed" images are left as they are.  The scenes are the battery's own:
# its render program writes them (EXTREMES_SCENES) and this script renders
# them again, larger where the scene allows (the pixel-aligned ones only
# mean something at the battery's 32 x 31).  Same tree, same images.
set -eu

root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
fixed=${1:-}
out=docs/images/extremes
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' HUP INT PIPE TERM
mkdir -p "$out"

# The battery's scenes, written by its render program for stages 01 and 03.
scenes() {
    stage=$1
    shift
    prog=build/tests/$stage/01_extremes_render
    ${MAKE:-make} --no-print-directory -s -C tests STAGE="$stage" "$root/$prog" >/dev/null
    EXTREMES_SCENES=$tmp RENDER=build/$stage/render RENDER_FLOAT=build/float/$stage/render \
        TEST_LOG_DIR=$tmp "$prog" "$@" >/dev/null || true
}

# render BINARY NAME SCENE [OPTIONS...]: one image, $out/NAME.png.  (sh
# has no local variables: these names are render's alone.)
render() {
    render_bin=$1
    render_png=$out/$2.png
    render_scene=$tmp/$3
    shift 3
    if [ ! -x "$render_bin" ]; then
        echo "images.sh: $render_bin is missing" >&2
        exit 1
    fi
    "$render_bin" -q -t 2 -o "$render_png" "$@" "$render_scene" 2>/dev/null
    echo "  $render_png"
}

scenes 01_raycast watertight_mesh degenerate_input
scenes 03_soft_shadows far_from_origin

# Far from the origin: float breaks at 1e4 (contact shadows shrink) and
# 1e5 (shadows gone, light leaks); double at 1e7 is the unit box.
for t in 1e3 1e4 1e5; do
    render build/float/03_soft_shadows/render far_${t}_float far_$t-float-far_$t.scene -W 128 -H 128
done
render build/03_soft_shadows/render far_1e7_double far_1e7-double-far_1e7.scene -W 128 -H 128

# Stage 01 before and after its fixes: the pixel-aligned closed mesh
# (Moller-Trumbore lets rays through shared edges: red or black dots) and
# the zero-area triangles along pixel rows (red dots: they are hit).
before_after() {
    name=$1
    scene=$2
    shift 2
    render build/01_raycast/render "${name}_before" "$scene" "$@"
    if [ -n "$fixed" ]; then
        render "$fixed/01_raycast/render" "${name}_after" "$scene" "$@"
    fi
}
before_after watertight watertight_render-double-watertight.scene
before_after degenerate degenerate_repeated_vertex-double-shapes.scene
before_after up_huge camera_up_huge-double-camera.scene -W 96 -H 96
render build/01_raycast/render up_huge_reference camera_up_huge-double-camera_ref.scene -W 96 -H 96
