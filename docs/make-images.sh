#!/bin/sh
# docs/make-images.sh - render the images of the lesson pages (docs/stages/)
# into docs/images/, with the stages themselves.
#
#   docs/make-images.sh            every stage's images
#   docs/make-images.sh 03 07      only those stages' images
#
# Needs the stages built (`make`). The one single-precision image of stage 02
# needs `make REAL=float`, and the mesh scene of stage 05 the test tools
# (`make -C tests tools`); the script runs those when they are missing.
# Environment: THREADS (default 2; the images do not depend on it), BUILD
# (default build), IMAGES (default docs/images). An image that needs what
# an optional library (tinygltf, OpenEXR) brings, in a build without it, is
# skipped with a note, and the rest are rendered. Every render uses the default seed, so the same tree gives
# the same images, bit for bit. Takes about two and a half minutes on two
# busy cores, most of it stage 07.
set -eu

root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
build=${BUILD:-build}
threads=${THREADS:-2}
out=${IMAGES:-docs/images}
tmp=$(mktemp -d)
skipped=0
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' HUP INT PIPE TERM
mkdir -p "$out"

# render STAGE NAME [OPTIONS...] SCENE: one image, docs/images/NAME.png.
# Warnings about features a stage does not model are expected (the pages
# show those simplifications); they go to a log shown only on failure.
render() {
    stage=$1
    name=$2
    shift 2
    bin=$build/$stage/render
    if [ ! -x "$bin" ]; then
        echo "make-images.sh: $bin is missing; run make first" >&2
        exit 1
    fi
    if ! "$bin" -q -t "$threads" -o "$out/$name.png" "$@" 2>"$tmp/log"; then
        # What an optional library left out of this build cannot be
        # rendered: say so, and render the rest.
        if grep -q 'no glTF support\|built without OpenEXR' "$tmp/log"; then
            echo "  skipped $out/$name.png: $(grep -o 'no glTF support[^;]*\|built without OpenEXR' "$tmp/log" | head -n 1) (see make config)"
            skipped=$((skipped + 1))
            return 0
        fi
        cat "$tmp/log" >&2
        echo "make-images.sh: $stage failed on $name" >&2
        exit 1
    fi
    echo "  $out/$name.png"
}

# The grazing-light scene of 02_shadows.md: a plane tilted off the axes, lit
# by a point light 10 degrees above it, with three spheres resting on it
# (radii 0.3, 0.06, 0.02). Every length is multiplied by the scale s and the
# light's intensity by s^2, so the picture is the same at every scale.
grazing_scene() {
    awk -v s="$1" '
    function norm(v,   l) { l = sqrt(v[1]^2 + v[2]^2 + v[3]^2); v[1] /= l; v[2] /= l; v[3] /= l }
    function pt(a, b, c,   i, r) {
        r = ""
        for (i = 1; i <= 3; i++) r = r sprintf(" %.17g", s * (a * t1[i] + b * n[i] + c * t2[i]))
        return r
    }
    BEGIN {
        n[1] = 0.3; n[2] = 1; n[3] = 0.2; norm(n)
        q[1] = 0.2; q[2] = 0.1; q[3] = 1
        t1[1] = n[2] * q[3] - n[3] * q[2]; t1[2] = n[3] * q[1] - n[1] * q[3]; t1[3] = n[1] * q[2] - n[2] * q[1]
        norm(t1)
        t2[1] = t1[2] * n[3] - t1[3] * n[2]; t2[2] = t1[3] * n[1] - t1[1] * n[3]; t2[3] = t1[1] * n[2] - t1[2] * n[1]
        el = 10 * atan2(0, -1) / 180
        printf "# a tilted plane lit at a grazing 10 degrees, scale %s\n", s
        printf "camera origin%s target%s up %.17g %.17g %.17g fov 40\n", pt(0.2, 3.4, 1.9), pt(0.2, 0, -0.1), n[1], n[2], n[3]
        printf "image width 192 height 192\n"
        printf "ambient color 0.04 0.04 0.04\n"
        printf "material plane diffuse albedo 0.6 0.6 0.6\n"
        printf "material ball diffuse albedo 0.7 0.25 0.2\n"
        printf "quad corner%s edge1%s edge2%s material plane\n", pt(-4, 0, -4), pt(8, 0, 0), pt(0, 0, 8)
        printf "sphere center%s radius %.17g material ball\n", pt(-0.9, 0.3, -0.4), 0.3 * s
        printf "sphere center%s radius %.17g material ball\n", pt(-0.2, 0.06, 0.8), 0.06 * s
        printf "sphere center%s radius %.17g material ball\n", pt(0.1, 0.02, -0.9), 0.02 * s
        i = 900 * s * s
        printf "point_light position%s intensity %.17g %.17g %.17g\n", pt(-10 * cos(el), 10 * sin(el), -1), i, i, 0.92 * i
    }' >"$tmp/grazing_$1.scene"
    echo "$tmp/grazing_$1.scene"
}

# The checkered floor of 06_supersample.md, running to the horizon.
checker_scene() {
    cat >"$tmp/checker.scene" <<'EOF'
# a checkered floor running to the horizon: aliasing
camera origin 0 1 0 target 0 0.35 -10 up 0 1 0 fov 35
image width 320 height 160
material floor checker albedo 0.9 0.9 0.9 albedo2 0.05 0.05 0.05 size 0.5
quad corner -400 0 -400 edge1 0 0 800 edge2 800 0 0 material floor
point_light position 0 50 0 intensity 6000 6000 6000
EOF
    echo "$tmp/checker.scene"
}

# The terrain scene of 05_bvh.md: 12,280 triangles from the generated test
# meshes (tests/tools/gen_meshes.c), which need `make -C tests tools`.
terrain_scene() {
    gen=$build/tools/gen_meshes
    if [ ! -x "$gen" ] && [ "$build" = build ]; then
        ${MAKE:-make} --no-print-directory -C tests tools >"$tmp/make.log" 2>&1 \
            || { cat "$tmp/make.log" >&2; exit 1; }
    fi
    "$gen" "$tmp" >&2 || exit 1
    cat >"$tmp/terrain.scene" <<'EOF'
# a generated terrain (10,000 triangles), a glass sphere (1,000) and an icosphere (1,280)
camera origin 0 2.2 4.2 target 0 0 0 up 0 1 0 fov 40
image width 320 height 200
background color 0.35 0.45 0.6
material ground diffuse albedo 0.55 0.5 0.4
material ball glass ior 1.5
material red diffuse albedo 0.7 0.1 0.1
mesh file terrain_10k.glb material ground
mesh file sphere_1k.glb material ball scale 0.5 translate 0.3 0.6 0.2
mesh file closed_mesh.glb material red scale 0.35 translate -1 0.5 -0.6
area_light corner -1 4 -1 edge1 2 0 0 edge2 0 0 2 radiance 3 3 2.8
EOF
    echo "$tmp/terrain.scene"
}

showcase=scenes/showcase.scene
point=scenes/cornell_diffuse_point.scene
area=scenes/cornell_diffuse_area.scene
specular=scenes/cornell_specular_area.scene

images_01() {
    render 01_raycast 01_raycast_showcase $showcase
    render 01_raycast 01_raycast_cornell_diffuse_point $point
}

images_02() {
    render 02_shadows 02_shadows_showcase $showcase
    render 02_shadows 02_shadows_cornell_diffuse_point $point
    render 02_shadows 02_shadows_grazing_1e-3 "$(grazing_scene 1e-3)"
    render 02_shadows 02_shadows_grazing_1e4 "$(grazing_scene 1e4)"
    if [ ! -x "$build/float/02_shadows/render" ] && [ "$build" = build ]; then
        echo "  (building the single-precision stage 02: make REAL=float 02_shadows)"
        ${MAKE:-make} --no-print-directory REAL=float 02_shadows >"$tmp/make.log" 2>&1 \
            || { cat "$tmp/make.log" >&2; exit 1; }
    fi
    render float/02_shadows 02_shadows_grazing_1e4_float "$(grazing_scene 1e4)"
}

images_03() {
    render 02_shadows 02_shadows_cornell_diffuse_area $area
    render 03_soft_shadows 03_soft_shadows_showcase $showcase
    render 03_soft_shadows 03_soft_shadows_cornell_diffuse_area_ss1 --shadow-samples 1 $area
    render 03_soft_shadows 03_soft_shadows_cornell_diffuse_area $area
    render 03_soft_shadows 03_soft_shadows_cornell_diffuse_area_ss256 --shadow-samples 256 $area
}

images_04() {
    render 03_soft_shadows 03_soft_shadows_cornell_specular_area $specular
    render 04_reflect_refract 04_reflect_refract_showcase $showcase
    render 04_reflect_refract 04_reflect_refract_cornell_specular_area $specular
    for d in 1 2 3; do
        render 04_reflect_refract 04_reflect_refract_cornell_specular_area_depth$d --max-depth $d $specular
    done
}

images_05() {
    if [ ! -d stages/05_bvh ]; then
        echo "  (no stages/05_bvh in this tree: its images are skipped)"
        return
    fi
    render 05_bvh 05_bvh_showcase $showcase
    render 05_bvh 05_bvh_cornell_specular_area $specular
    render 05_bvh 05_bvh_terrain "$(terrain_scene)"
    render 05_bvh 05_bvh_bunny_cornell scenes/bunny_cornell.scene # the README's mesh
}

images_06() {
    render 06_supersample 06_supersample_showcase --spp 16 $showcase
    render 06_supersample 06_supersample_cornell_diffuse_point --spp 16 $point
    checker=$(checker_scene)
    render 06_supersample 06_supersample_checker_grid1 --aa grid --spp 1 "$checker"
    render 06_supersample 06_supersample_checker_grid16 --aa grid --spp 16 "$checker"
    render 06_supersample 06_supersample_checker_jitter16 --aa jitter --spp 16 "$checker"
}

images_07() {
    render 07_pathtrace 07_pathtrace_showcase --spp 256 $showcase
    cp "$out/07_pathtrace_showcase.png" "$out/showcase_07.png" # the README's picture
    echo "  $out/showcase_07.png"
    render 07_pathtrace 07_pathtrace_cornell_diffuse_point --spp 64 $point
    render 07_pathtrace 07_pathtrace_cornell_diffuse_area --spp 256 $area
    render 07_pathtrace 07_pathtrace_cornell_specular_area --spp 256 $specular
    render 07_pathtrace 07_pathtrace_cornell_diffuse_area_nee16 --spp 16 $area
    render 07_pathtrace 07_pathtrace_cornell_diffuse_area_nonee16 --spp 16 --no-nee $area
}

stages=${*:-01 02 03 04 05 06 07}
for n in $stages; do
    case $n in
    01 | 02 | 03 | 04 | 05 | 06 | 07) ;;
    *)
        echo "usage: docs/make-images.sh [01 02 03 04 05 06 07]" >&2
        exit 2
        ;;
    esac
    echo "stage $n:"
    "images_$n"
done
if [ "$skipped" -gt 0 ]; then
    echo "make-images.sh: $skipped image(s) skipped: this build lacks an optional library (make config)"
fi
