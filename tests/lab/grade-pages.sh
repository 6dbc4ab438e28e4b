#!/bin/sh
# grade-pages.sh - a compare report page for each reference render of a lab.
#
#   grade-pages.sh [--help] [--spp N|auto|paired] [--max-spp N] [--records FILE]
#                  [--paired-only NAME] HANDOUT STAGE OUT
#
# HANDOUT is a built lab handout (grade.sh's copy), STAGE its stage
# (05_bvh).  For every Mitsuba reference the stage's tests compare with
# (tests/reference/), renders the scene with the handout's render at the
# reference's size, runs build/tools/compare with --html, and writes
# OUT/NAME.html (the render, the reference, the error map, the numbers and
# the verdict; how to read it: the handout's LAB.md, "Reading the report
# pages").  Prints for each page its verdict, what its tests can find
# (compare's power line, pages with block tests), its regions and its
# path.
# Paired pages (every lab, scored; lablib.sh's paired_scenes): the
# student's render with the options and seed of the solution's render that
# the handout carries (tests/reference/solution/, make-lab.sh), compared
# with it pixel by pixel (build/tools/paired: per 16x16 block, the
# difference against a 1% minimum effect); where the student's code draws
# its random numbers as the solution's does, the two share their paths and
# a bias shows at once (labs 01-02 are deterministic: any difference over
# 1% of a block); where not, the comparison is as of two independent
# renders, and says "unpaired".  --records FILE: one line a paired page, "NAME ok" or
# "NAME FAIL MESSAGE" (grade.sh scores them).  --paired-only NAME: only
# the paired page NAME (check-one.sh, make check TEST=pages/NAME_paired).
# By default (no --spp) the Mitsuba pages of labs 06-08 are one render of
# 16 spp (the paired page's), a look at the image and its error map, not a
# verdict to score.
# --spp auto (make grade SPP=auto): for each noise-tested
# page, as many samples per pixel as its test needs to find a 2% bias in 9
# of 10 32x32 windows 9 times in 10 (compare's power line on a pilot of two
# renders of GRADE_DEFAULT_SPP, with seeds of their own, not judged), at
# least the pilot's and at most --max-spp (default GRADE_MAX_SPP).
# --spp N: N for each render of the noise-tested pages (make grade LAB=dir
# SPP=N), quicker, and finding less (docs/calibration/README.md).
#
# What is compared, as the stage's own tests do it:
#   stages 02-05  cornell_diffuse_point_direct: one render, the reference's
#                 smooth pixels only (no anti-aliasing before stage 06, so
#                 edges differ by design), relMSE limit 1e-5
#   stages 03-05  cornell_diffuse_area_direct: one render with 64 shadow
#                 samples, smooth pixels, relMSE limit 5e-5
#   stage 06      cornell_diffuse_point_direct: two renders of --spp samples with
#                 different seeds, block tests (noise or bias)
#   stages 07-08  the three *_gi references: two renders of --spp samples each,
#                 block tests
# The pages with block tests share the family level 0.01 (lablib.sh's
# page_alpha): one run of make grade on correct work says "biased" on any
# page with probability at most 0.01, as make calibrate-compare measures
# (docs/calibration/README.md).
# Each page's verdict is followed by its error region by region (compare
# --regions with the reference scene's feature mask, tests/reference/
# NAME.feature.pfm, docs/aov.md): a line per region, the biased ones first,
# each with one of its pixels and the command that replays it
# (render --pixel X,Y --trace -, with the options of the render compared).
# Exit status: 0 pages written (whatever their verdicts), 1 a render or a
# page failed, 2 usage.
set -eu

PROG=grade-pages.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

spp=paired
max_spp=$GRADE_MAX_SPP
records=
only=
parse_options '--spp spp=VALUE --max-spp max_spp=VALUE --records records=VALUE --paired-only only=VALUE' "$@"
shift "$po_used"
[ "$spp" = paired ] || check_spp "$spp" auto
check_spp "$max_spp"
[ $# -eq 3 ] || usage_error "expected HANDOUT STAGE OUT, got $# argument(s)"
dir=$(abs_dir "$1")
stage=$2
out=$3
nn=${stage%%_*}
render=$dir/build/$stage/render
compare=$dir/build/tools/compare
refs=$dir/tests/reference
[ -x "$render" ] || die "no render program in $dir/build/$stage (the stage did not build)"
lab_make -C "$dir/tests" tools >/dev/null 2>&1 || die "the tools of $dir/tests/tools do not build"
mkdir -p "$out"
work=$(mktemp -d "${TMPDIR:-/tmp}/grade-pages.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM

failed=0
# The handout may be grade.sh's temporary copy, gone when the grade is read:
# its files are named as the student's handout names them.
handout_paths() {
    awk -v refs="$refs/" -v work="$work/" "$AWK_REPLACE"'
        { print replace(replace($0, refs, "tests/reference/"), work, "") }'
}

# renders NAME SCENE COUNT FIRST_SEED "RENDER OPTIONS": COUNT renders of
# scenes/SCENE.scene, seeds FIRST_SEED on, as $work/NAME.I.pfm; their paths
# in rd_inputs.  False (the error printed, failed set) when one fails.
renders() {
    rd_inputs=
    rd_i=1
    while [ "$rd_i" -le "$3" ]; do
        # shellcheck disable=SC2086 # the options are words
        if ! "$render" -q -W 256 -H 256 $5 --seed "$(($4 + rd_i - 1))" -o "$work/$1.$rd_i.pfm" \
            "$dir/scenes/$2.scene" >"$work/render.log" 2>&1; then
            echo "    $1: the render failed:"
            sed -n '1,5s/^/        /p' "$work/render.log"
            failed=1
            return 1
        fi
        rd_inputs="$rd_inputs $work/$1.$rd_i.pfm"
        rd_i=$((rd_i + 1))
    done
    # What the first render was made with, for paired_page to reuse it.
    echo "$5 --seed $4" >"$work/$1.options"
}

# page_spp NAME SCENE: the samples per pixel of the renders of noise-tested
# page NAME, into pg_spp: --spp's, or with --spp auto, from its pilot
# (compare's power line, at the page's alpha from noise_pages, says how
# many times the pilot's samples find 2% in 9 windows of 10; the
# reference's own noise may hide it at any spp).
# False when the pilot could not render or be compared.
page_spp() {
    pg_spp=$spp
    [ "$spp" != paired ] || pg_spp=$PAIRED_SPP
    [ "$spp" = auto ] || return 0
    renders "$1.pilot" "$2" 2 1001 "--spp $GRADE_DEFAULT_SPP" || return 1
    # shellcheck disable=SC2086
    "$compare" -q --alpha "$alpha" $rd_inputs "$refs/$1.pfm" >"$work/pilot" 2>&1 || [ $? -eq 1 ] || {
        echo "    $1: compare failed on the pilot: $(handout_paths <"$work/pilot")"
        failed=1
        return 1
    }
    spp_for_power "$work/pilot" "$GRADE_DEFAULT_SPP" "$max_spp" || {
        echo "    $1: no power line in compare's verdict on the pilot: $(head -n 1 "$work/pilot")"
        failed=1
        return 1
    }
    pg_spp=$sfp_spp
    echo "    $1: $pg_spp spp a render (its pilot, two renders of $GRADE_DEFAULT_SPP spp: $sfp_says)"
}

# page NAME SCENE RENDERS "RENDER OPTIONS" [COMPARE OPTIONS...]
page() {
    pg_name=$1
    pg_base=$2
    pg_options=$4
    renders "$1" "$2" "$3" 1 "$4" || return 0
    pg_inputs=$rd_inputs
    shift 4
    pg_status=0
    pg_regions=
    [ -f "$refs/$pg_base.feature.pfm" ] && pg_regions="--regions $refs/$pg_base.feature.pfm"
    # shellcheck disable=SC2086
    "$compare" -q --title "lab $nn: $pg_name" --html "$out/$pg_name.html" $pg_regions "$@" $pg_inputs \
        "$refs/$pg_name.pfm" >"$work/verdict" 2>&1 || pg_status=$?
    if [ "$pg_status" -ge 2 ]; then
        echo "    $pg_name: compare failed: $(handout_paths <"$work/verdict")"
        failed=1
    else
        echo "    $pg_name: $(head -n 1 "$work/verdict")"
        # The regions' lines; a pixel's replay uses the first render's options.
        handout_paths <"$work/verdict" | sed -e '1d' -e 's/^regions    /regions: /' \
            -e "s|--trace - SCENE|--trace - -W 256 -H 256 $pg_options --seed 1 scenes/$pg_base.scene|" \
            -e 's/^/        /'
        echo "        $out/$pg_name.html"
    fi
}

# paired_page NAME SCENE: the student's render of SCENE with the options
# and seed of the solution's render in the handout (lablib.sh's
# paired_options; tests/reference/solution/, make-lab.sh), judged by
# build/tools/paired against it: the pixel-by-pixel differences, per 16x16
# block, against a 1% minimum effect.  A look page's first render serves
# when it was made so.  Scored: its verdict goes to the records (--records:
# "NAME ok|FAIL MESSAGE").  Without the solution's render, says so and
# judges nothing.
paired_page() {
    pp_solution=$refs/solution/$2.pfm
    if [ ! -f "$pp_solution" ]; then
        echo "    $1, paired: the handout has no solution render of $2 (make-lab.sh renders it with the project's build): not judged"
        return 0
    fi
    pp_status=0
    pp_options="$(paired_options "$nn" "$2") --seed $PAIRED_SEED"
    pp_student=$work/$1.paired.pfm
    if [ -f "$work/$1.1.pfm" ] && [ "$(cat "$work/$1.options")" = "$pp_options" ]; then
        pp_student=$work/$1.1.pfm
    fi
    if [ ! -f "$pp_student" ] &&
        ! paired_render "$render" "$nn" "$dir/scenes/$2.scene" "$PAIRED_SEED" "$pp_student" >"$work/render.log"; then
        echo "    $1, paired: the render failed:"
        sed -n '1,5s/^/        /p' "$work/render.log"
        pp_status=1
        echo "the render failed: $(head -n 1 "$work/render.log")" >"$work/paired.out"
    else
        "$dir/build/tools/paired" "$pp_student" "$pp_solution" >"$work/paired.out" 2>&1 || pp_status=$?
        echo "    $1, paired with the solution's render ($pp_options): $(tail -n 1 "$work/paired.out" | sed 's/^paired: //')"
        sed '$d' "$work/paired.out" | sed -n '1,3s/^  /        /p'
        [ "$pp_status" -ne 1 ] || second_look "$1" "$2"
    fi
    [ "$pp_status" -le 1 ] || failed=1
    if [ -n "$records" ]; then
        if [ "$pp_status" -eq 0 ]; then
            echo "$1 ok" >>"$records"
        else
            echo "$1 FAIL $(head -n 1 "$work/paired.out" | sed 's/^ *//')" >>"$records"
        fi
    fi
}

# second_look NAME SCENE - the paired page NAME found a bias at the first
# seed: judged again at PAIRED_SECOND_SEED against the solution's render of
# that seed (lablib.sh), it fails (pp_status 1, paired.out the second
# look's words) only when the bias is there too.  Without that render (a
# handout written before it), the first look stands.
second_look() {
    sl_solution=$refs/solution/seed$PAIRED_SECOND_SEED/$2.pfm
    [ -f "$sl_solution" ] || return 0
    sl_student=$work/$1.second.pfm
    if ! paired_render "$render" "$nn" "$dir/scenes/$2.scene" "$PAIRED_SECOND_SEED" "$sl_student" >"$work/render.log"; then
        echo "        second look: the render failed: $(head -n 1 "$work/render.log")"
        echo "the render at the second seed failed: $(head -n 1 "$work/render.log")" >"$work/paired.out"
        return 0
    fi
    pp_status=0
    "$dir/build/tools/paired" "$sl_student" "$sl_solution" >"$work/paired2.out" 2>&1 || pp_status=$?
    echo "        second look (--seed $PAIRED_SECOND_SEED): $(tail -n 1 "$work/paired2.out" | sed 's/^paired: //')"
    case $pp_status in
        0) echo "        consistent at the second seed: the first look's blocks were chance (a bias repeats at every seed)" ;;
        1) sed '$d' "$work/paired2.out" | sed -n '1,3s/^  /        /p'
           { echo "biased at both seeds ($PAIRED_SEED and $PAIRED_SECOND_SEED): $(head -n 1 "$work/paired2.out" | sed 's/^ *//')"; } >"$work/paired.out" ;;
        *) cp "$work/paired2.out" "$work/paired.out" ;;
    esac
}

# noise_pages N: the family level of each of the lab's N block-tested pages.
noise_pages() {
    alpha=$(page_alpha "$1")
    if [ "$spp" = paired ]; then
        echo "    (each page below: one render of $PAIRED_SPP spp, the paired page's, a look at the image and its error:"
        echo "    one render cannot tell noise from bias; the paired verdict is the one scored)"
        return 0
    fi
    np_spp="$spp spp"
    np_doc=docs/calibration/README.md
    if [ "$spp" = auto ]; then
        np_spp="the spp its pilot asks for"
        np_doc=docs/calibration/auto-256/README.md
    fi
    echo "    (each page below: two renders of $np_spp, tested at alpha $alpha, so that correct work is called biased on"
    echo "    any of its $1 page(s) in at most 1 grade in 100 by design; measured: $np_doc)"
}

# --paired-only NAME: that paired page alone (make check TEST=pages/NAME_paired).
if [ -n "$only" ]; then
    for scene in $(paired_scenes "$nn"); do
        [ "$(paired_page_name "$nn" "$scene")" != "$only" ] || { paired_page "$only" "$scene"; exit "$failed"; }
    done
    die "lab $nn has no paired page $only (its pages: $(for s in $(paired_scenes "$nn"); do paired_page_name "$nn" "$s"; done | tr '\n' ' '))"
fi

# The look pages, against Mitsuba's references.
case $nn in
    01) echo "    none against a reference: stage 01 has no shadows, and every reference has them" ;;
    02 | 03 | 04 | 05)
        page cornell_diffuse_point_direct cornell_diffuse_point 1 "" --mask smooth --max-relmse 1e-5
        ;;
esac
case $nn in
    03 | 04 | 05)
        page cornell_diffuse_area_direct cornell_diffuse_area 1 "--shadow-samples 64" --mask smooth --max-relmse 5e-5
        ;;
    06 | 07 | 08)
        # By default (paired) one render a page, the paired page's own: a
        # look; with SPP=N or auto, two, block-tested.
        pg_renders=2
        [ "$spp" != paired ] || pg_renders=1
        noise_pages "$(paired_scenes "$nn" | wc -w)"
        for scene in $(paired_scenes "$nn"); do
            name=$(paired_page_name "$nn" "$scene")
            page_spp "$name" "$scene" && page "$name" "$scene" "$pg_renders" "--spp $pg_spp" --alpha "$alpha"
        done
        ;;
esac
# The paired pages, against the solution's renders: scored.
for scene in $(paired_scenes "$nn"); do
    paired_page "$(paired_page_name "$nn" "$scene")" "$scene"
done
exit "$failed"
