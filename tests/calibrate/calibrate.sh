#!/bin/sh
# calibrate.sh - how often each verdict a learner sees says "biased" on
# correct work, and how often it finds a planted bias (make calibrate-compare).
#
#   calibrate.sh [options]
#
# For every reference scene (tests/reference/NAME_gi.pfm, scenes/NAME.scene)
# renders a pool of correct stage-07 renders, SETS independent sets of them
# (seeds never shared between the sets of one verdict), and runs on each
# set the verdicts at their default settings:
#   compare-2     compare R1 R2 REF (block t-tests, alpha 0.01)
#   compare-4     compare R1 R2 R3 R4 REF (the pool's renders four at a
#                 time: the pool holds 4 * SETS renders)
#   regions       compare --regions MASK R1 R2 REF: blocks and regions, one
#                 family (what check-planted's controls and compare --regions run)
#   grade-page    the same at the level of one make grade page (grade-pages.sh:
#                 the family alpha shared by the lab's pages)
#   grade         one run of make grade's pages: every scene's page of set i;
#                 "biased" when any page is
#   control       check-planted's control: regions, and when it flags a
#                 region, again with 4x the spp (two fresh renders)
#   grade-auto    a page of make grade SPP=auto: the set's two renders are
#                 its pilot, whose power line sets the spp (spp_for_power)
#                 of two fresh renders, judged as grade-page; with a 2%
#                 bias planted as below too (not in the default list: a set
#                 costs 35-45 times the others on the point-lit and
#                 specular boxes); each set's outcome is kept in a ledger
#                 (OUT/grade-auto.sets), so that a later run measures only
#                 the sets it lacks and the table counts every set kept
# A verdict is "biased" when compare exits 1.  The same pool, with a bias
# planted into the renders' images (imgedit --scale: 1%, 2% and 5% in a
# 32x32 rectangle spread over the image by plant_rect, 0.5% over the whole image), measures
# how often compare-2 and grade-page find it; and BUG_SETS pairs of renders
# of stage 07 with a bug planted in its code (check-planted's plant_stage):
#   missing-cosine  a shadow ray's estimate without the receiver's cosine
#   light-pdf       the area light's pdf 10% too high (its light 9% dark)
#   leak            shadow rays start 0.05 along their way (past blockers)
# are judged the same way.  Optionally (--seed-offsets N) each statistical
# stage test runs under N values of PATHCHECK_SEED, counting its failures.
#
# Renders are SIZE x SIZE (the references are box-filtered down to it:
# imgedit --downsample, exact for box pixel filters; their META.json
# noise scaled with them; the feature masks rendered at that size).  The
# pool is kept in build/calibrate/ under a key of the render program and
# settings, so a second run with the same build only runs the verdicts.
# Writes OUT/calibration.csv, OUT/calibration.svg (rate of "biased" against
# the planted bias) and the table between the markers of OUT/README.md:
# rates with Wilson 95% intervals, renders, processor seconds.
#
# Options:
#   --size N          image size (default 64; the grade's is 256)
#   --spp N           samples per pixel of one render (default 64: the grade's)
#   --sets N          independent sets per verdict (default 200)
#   --from N          grade-auto: begin at set N (sets N to SETS - 1; the
#                     ledger's other sets still count; default 0)
#   --bug-sets N      pairs per planted code bug and scene (default 20)
#   --scenes LIST     comma-separated reference scenes (default: all)
#   --verdicts LIST   comma-separated (default: all of those above but
#                     grade-auto)
#   --seed-offsets N  run the statistical stage tests N times (default 0)
#   --out DIR         where the table and plot go (default docs/calibration)
#   --append          keep the rows of OUT/calibration.csv for the scenes
#                     this run does not measure (one table from runs of
#                     different scenes, each with its own --sets)
#   --threads N       render threads (default 2)
#   --tools DIR       the compare and imgedit to judge with (default
#                     build/tools; e.g. an older build, on the same pool)
#   --render PROGRAM  the correct stage 07 to render with (default
#                     build/07_pathtrace/render; its pool is kept by its key)
#   --check-plants    only check that each planted bug's change applies to
#                     stage 07's sources as they are now (test-lab-tools)
#   --help
# Exit status: 0 written, 1 a render or a tool failed, 2 usage.
set -eu

PROG=calibrate.sh
LAB_DIR=$(cd "$(dirname "$0")/../lab" && pwd)
. "$LAB_DIR/lablib.sh"
root=$(cd "$LAB_DIR/../.." && pwd)

size=64
spp=64
sets=200
from=0
bug_sets=20
scenes=
verdicts=compare-2,compare-4,regions,grade-page,grade,control
seed_offsets=0
out=$root/docs/calibration
threads=2
tools=
render=
check_plants=0
append=0
parse_options "--size size=VALUE --spp spp=VALUE --sets sets=VALUE --from from=VALUE --bug-sets bug_sets=VALUE
    --scenes scenes=VALUE --verdicts verdicts=VALUE --seed-offsets seed_offsets=VALUE
    --out out=VALUE --threads threads=VALUE --tools tools=DIR --render render=VALUE
    --check-plants check_plants=1 --append append=1" "$@"
shift "$po_used"
[ $# -eq 0 ] || usage_error "unexpected argument: $1"

# The planted code bugs: bug_plant BUG sets file (in stage 07) and expr
# (the sed expression that plants it).
BUGS="missing-cosine light-pdf leak"
bug_plant() {
    case $1 in
        missing-cosine) file=light.c; expr='s|vec3_scale(light->radiance, cos_surface \* cos_light_area / dist2)|vec3_scale(light->radiance, cos_light_area / dist2)|' ;;
        # The sample's density 1/A is in |edge1 x edge2| = A: 1.1 times the pdf is A / 1.1.
        light-pdf) file=light.c; expr='s|vec3 normal_area = vec3_cross(light->edge1, light->edge2);|vec3 normal_area = vec3_scale(vec3_cross(light->edge1, light->edge2), 1 / (real)1.1);|' ;;
        leak) file=geometry.c; expr='s|^\( *\)ray r = spawn_ray(h, vec3_normalize(vec3_sub(to, h->p)));|&\n\1r.o = vec3_madd(r.o, r.d, (real)0.05);|' ;;
    esac
}
if [ "$check_plants" = 1 ]; then
    for bug in $BUGS; do
        bug_plant "$bug"
        src=$root/stages/07_pathtrace/$file
        ! sed -e "$expr" "$src" | cmp -s - "$src" ||
            die "the planted $bug changes nothing in stages/07_pathtrace/$file (the source changed?)"
    done
    echo "calibrate: the planted bugs ($BUGS) apply to stage 07"
    exit 0
fi
scenes=$(echo "$scenes" | tr ',' ' ')
for n in "$size" "$spp" "$sets" "$from" "$bug_sets" "$seed_offsets" "$threads"; do
    case $n in '' | *[!0-9]*) usage_error "expected a whole number, got '$n'" ;; esac
done
[ "$from" -eq 0 ] || [ "$verdicts" = grade-auto ] || usage_error "--from is for --verdicts grade-auto alone"
[ $((256 % size)) -eq 0 ] || usage_error "--size must divide 256 (the references' size), got $size"

build=$root/build
render=${render:-$build/07_pathtrace/render}
compare=${tools:-$build/tools}/compare
imgedit=${tools:-$build/tools}/imgedit
refs=$root/tests/reference
for tool in "$render" "$compare" "$imgedit"; do
    [ -x "$tool" ] || die "no $tool: run make first"
done
all_scenes=$(ls "$refs" | sed -n 's/_gi\.pfm$//p')
[ -n "$scenes" ] || scenes=$all_scenes
key=$(cat "$render" | cksum | cut -d' ' -f1)
cal=$build/calibrate
pool=$cal/pool-$key-$size-$spp
mkdir -p "$pool" "$out"
work=$(mktemp -d "${TMPDIR:-/tmp}/calibrate.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM
csv=$work/calibration.csv
# The run's own copies of the tools: a rebuild during a long run does not
# mix two versions of the statistics into one table.
cp "$compare" "$imgedit" "$work/"
compare=$work/compare
imgedit=$work/imgedit
echo "verdict,scene,bias,bias_pct,sets,biased,rate,low,high,renders,seconds" >"$csv"

# The family level of one make grade page: the lab's noise-tested pages
# share alpha (grade-pages.sh).
page_alpha=$(page_alpha 3)

# ---- references at the calibration size -------------------------------------
# ref_of SCENE, mask_of SCENE: the reference and feature mask at $size.
ref_of() { echo "$pool/refs/${1}_gi.pfm"; }
mask_of() { echo "$pool/refs/$1.feature.pfm"; }
make_refs() {
    mkdir -p "$pool/refs"
    factor=$((256 / size))
    meta=$pool/refs/META.json
    if [ "$size" -eq 256 ]; then
        # The references themselves (also for runs of other scenes beside this one).
        for scene in $scenes; do
            cp "$refs/${scene}_gi.pfm" "$(ref_of "$scene").tmp" && mv "$(ref_of "$scene").tmp" "$(ref_of "$scene")"
            cp "$refs/$scene.feature.pfm" "$(mask_of "$scene").tmp" && mv "$(mask_of "$scene").tmp" "$(mask_of "$scene")"
        done
        cp "$refs/META.json" "$meta.$$" && mv "$meta.$$" "$meta"
        return 0
    fi
    echo '{ "images": {' >"$meta.tmp"
    sep=
    for scene in $scenes; do
        "$imgedit" --downsample "$factor" "$refs/${scene}_gi.pfm" "$(ref_of "$scene")" ||
            die "cannot downsample $scene's reference"
        "$render" -q -s 1 -t "$threads" -W "$size" -H "$size" --aov feature \
            -o "$work/mask.pfm" "$root/scenes/$scene.scene" >/dev/null ||
            die "stage 07 cannot render $scene's feature pass"
        mv "$work/mask.feature.pfm" "$(mask_of "$scene")"
        # The reference's noise per pixel falls with the pixels averaged.
        rel=$(awk -v s="\"${scene}_gi\"" -v f="$factor" '
            index($0, s) { on = 1 }
            on && /"p90_rel_se_pixel"/ { gsub(/[^0-9.eE+-]/, "", $2); print $2 / f; exit }' FS=: "$refs/META.json")
        batches=$(awk -v s="\"${scene}_gi\"" '
            index($0, s) { on = 1 }
            on && /"batches"/ { gsub(/[^0-9]/, "", $2); print $2; exit }' FS=: "$refs/META.json")
        printf '%s "%s_gi": { "p90_rel_se_pixel": %s, "batches": %s }\n' "$sep" "$scene" "$rel" "$batches" >>"$meta.tmp"
        sep=,
    done
    echo '} }' >>"$meta.tmp"
    mv "$meta.tmp" "$meta"
}

# ---- renders ----------------------------------------------------------------
# render_one PROGRAM SCENE SPP SEED OUT: one render and its processor
# seconds appended to OUT's directory's seconds file.
render_one() {
    "$1" -q -t "$threads" -W "$size" -H "$size" --spp "$3" --seed "$4" --stats "$work/stats.json" \
        -o "$5.tmp.pfm" "$root/scenes/$2.scene" >"$work/render.log" 2>&1 ||
        die "render failed: $1 $2 seed $4: $(head -n 3 "$work/render.log")"
    mv "$5.tmp.pfm" "$5"
    sed -n 's/.*"seconds_render_cpu": *\([0-9.eE+-]*\).*/\1/p' "$work/stats.json" >>"$(dirname "$5")/seconds"
}

# pool_renders PROGRAM DIR SCENE SPP FIRST COUNT: seeds FIRST.. in DIR.
pool_renders() {
    mkdir -p "$2"
    pr_i=0
    while [ "$pr_i" -lt "$6" ]; do
        pr_seed=$(($5 + pr_i))
        [ -f "$2/$pr_seed.pfm" ] || render_one "$1" "$3" "$4" "$pr_seed" "$2/$pr_seed.pfm"
        pr_i=$((pr_i + 1))
    done
}

# seconds_per_render DIR: the mean processor seconds of DIR's renders.
seconds_per_render() {
    [ -f "$1/seconds" ] || { echo 0; return 0; }
    awk '{ s += $1; n++ } END { printf "%.4g", n ? s / n : 0 }' "$1/seconds"
}

# Seeds: set i of k renders uses seeds BASE + k i .. BASE + k i + k - 1;
# far from the tests' seeds (1-10000).
BASE=100000

# ---- tallies ----------------------------------------------------------------
# tally VERDICT SCENE BIAS PCT SETS BIASED RENDERS SECONDS: a CSV row with
# the rate and its Wilson 95% interval (Wilson, JASA 22, 1927).
tally() {
    set -- "$@" $(wilson "$6" "$5")
    printf '%s,%s,%s,%s,%d,%d,%.4f,%.4f,%.4f,%d,%.1f\n' "$1" "$2" "$3" "$4" "$5" "$6" "$9" "${10}" "${11}" "$7" "$8" >>"$csv"
}

has_verdict() {
    case ",$verdicts," in *",$1,"*) return 0 ;; esac
    return 1
}

# judge OUTFILE COMPARE-ARGS...: "1" when compare calls it biased, else "0";
# exit 2 (bad input) stops the run.
judge() {
    jd_out=$1
    shift
    jd_status=0
    "$compare" -q "$@" >"$work/verdict" 2>&1 || jd_status=$?
    [ "$jd_status" -le 1 ] || die "compare failed: $(cat "$work/verdict")"
    echo "$jd_status" >>"$jd_out"
}

# planted SET FACTOR RECT IN...: the inputs scaled, as $work/p.N.pfm.
planted() {
    pl_factor=$2
    pl_rect=$3
    shift 3
    pl_j=1
    for pl_in in "$@"; do
        if [ "$pl_rect" = all ]; then
            "$imgedit" --scale "$pl_factor" "$pl_in" "$work/p.$pl_j.pfm"
        else
            "$imgedit" --scale "$pl_factor" --rect "$pl_rect" "$pl_in" "$work/p.$pl_j.pfm"
        fi
        pl_j=$((pl_j + 1))
    done
}

count1() { awk '$1 == 1 { n++ } END { print n + 0 }' "$1"; }

# ---- grade-auto's ledger ----------------------------------------------------
# A set of grade-auto costs minutes (its renders have thousands of spp), so
# its outcome is kept, one line a set, in OUT/grade-auto.sets:
#   SCENE KEY SET FALSE_ALARM FOUND_2% SPP PROCESSOR_SECONDS
# A run measures only the sets the ledger lacks, and the table counts every
# set the ledger holds under the run's key: a measurement too long for one
# session grows over several.  KEY is a checksum of what decides a set's
# outcome: the sources of stage 07, common/ and compare (tests/tools,
# tests/lib), lablib.sh (spp_for_power, page_alpha), this script (seeds,
# rectangles), the scene, its reference and mask, the size and the spp.
# The lines of another key (measured before the code changed) are not
# counted.  (The compiler is not in the key: CI and a course's machines
# build with Debian's gcc.)
ledger=$out/grade-auto.sets
source_sum=$(cd "$root" && cat stages/07_pathtrace/*.[ch] $(find common -name "*.[ch]" | sort) tests/tools/compare.c \
    tests/lib/*.[ch] tests/lab/lablib.sh tests/calibrate/calibrate.sh | cksum | cut -d' ' -f1)
# ledger_key SCENE
ledger_key() {
    echo "$source_sum-$(cat "$root/scenes/$1.scene" "$refs/${1}_gi.pfm" "$refs/$1.feature.pfm" |
        cksum | cut -d' ' -f1)-$size-$spp"
}
# ledger_has SCENE KEY SET: whether the ledger holds that set.
ledger_has() {
    [ -f "$ledger" ] && awk -v s="$1" -v k="$2" -v i="$3" '
        $1 == s && $2 == k && $3 == i { found = 1 } END { exit !found }' "$ledger"
}

make_refs
echo "calibrate: ${size}x$size, $spp spp, $sets sets per verdict; pool $pool"
grade_tmp=$work/grade
for scene in $scenes; do
    ref=$(ref_of "$scene")
    mask=$(mask_of "$scene")
    dir=$pool/$scene
    need=$((2 * sets))
    # compare-4's sets are four renders each: the pool holds 4 * sets.
    ! has_verdict compare-4 || need=$((4 * sets))
    # grade-auto alone renders the pilots of the sets its ledger lacks, in the loop.
    [ "$verdicts" != grade-auto ] || need=0
    start=$(date +%s)
    pool_renders "$render" "$dir" "$scene" "$spp" "$BASE" "$need"
    sec=$(seconds_per_render "$dir")
    echo "  $scene: $need renders ready ($(($(date +%s) - start)) s now; $sec processor s each)"
    for v in compare-2 regions grade-page control; do
        has_verdict "$v" || continue
        : >"$work/$v"
    done
    : >"$work/compare-4"
    for b in region1 region2 region5 whole0.5; do
        : >"$work/c2.$b"
        : >"$work/gp.$b"
    done
    i=$from
    ctl_renders=0
    lkey=$(ledger_key "$scene")
    while [ "$i" -lt "$sets" ]; do
        r1=$dir/$((BASE + 2 * i)).pfm
        r2=$dir/$((BASE + 2 * i + 1)).pfm
        ! has_verdict compare-2 || judge "$work/compare-2" "$r1" "$r2" "$ref"
        ! has_verdict regions || judge "$work/regions" --regions "$mask" "$r1" "$r2" "$ref"
        if has_verdict grade-page || has_verdict grade; then
            judge "$work/grade-page" --alpha "$page_alpha" --regions "$mask" "$r1" "$r2" "$ref"
            echo "$i $(tail -n 1 "$work/grade-page")" >>"$grade_tmp"
        fi
        if has_verdict control; then
            jd_status=0
            "$compare" -q --regions "$mask" "$r1" "$r2" "$ref" >/dev/null 2>&1 || jd_status=$?
            if [ "$jd_status" -eq 1 ]; then
                # Judged again as check-planted does: 4x the spp.
                for j in 1 2; do
                    [ -f "$dir/ctl/$i.$j.pfm" ] ||
                        { mkdir -p "$dir/ctl"; render_one "$render" "$scene" $((4 * spp)) $((2 * BASE + 2 * i + j)) "$dir/ctl/$i.$j.pfm"; }
                done
                ctl_renders=$((ctl_renders + 2))
                judge "$work/control" --regions "$mask" "$dir/ctl/$i.1.pfm" "$dir/ctl/$i.2.pfm" "$ref"
            else
                echo 0 >>"$work/control"
            fi
        fi
        if has_verdict compare-4 && [ $((4 * i + 3)) -lt "$need" ]; then
            judge "$work/compare-4" "$dir/$((BASE + 4 * i)).pfm" "$dir/$((BASE + 4 * i + 1)).pfm" \
                "$dir/$((BASE + 4 * i + 2)).pfm" "$dir/$((BASE + 4 * i + 3)).pfm" "$ref"
        fi
        rect=$(plant_rect "$i" "$size")
        if has_verdict grade-auto && ! ledger_has "$scene" "$lkey" "$i"; then
            # The pilot is the set's pair; the spp it asks for, a pair of its own.
            pool_renders "$render" "$dir" "$scene" "$spp" $((BASE + 2 * i)) 2
            "$compare" -q --alpha "$page_alpha" "$r1" "$r2" "$ref" >"$work/pilot" 2>&1 || [ $? -eq 1 ] ||
                die "compare failed on a pilot: $(cat "$work/pilot")"
            spp_for_power "$work/pilot" "$spp" "$GRADE_MAX_SPP" || die "no power line: $(cat "$work/pilot")"
            for j in 1 2; do
                a=$dir/auto/$sfp_spp/$((3 * BASE + 2 * i + j)).pfm
                [ -f "$a" ] || { mkdir -p "$dir/auto/$sfp_spp"; render_one "$render" "$scene" "$sfp_spp" $((3 * BASE + 2 * i + j)) "$a"; }
                eval "a$j=\$a"
            done
            : >"$work/ga.set"
            judge "$work/ga.set" --alpha "$page_alpha" --regions "$mask" "$a1" "$a2" "$ref"
            planted "$i" 1.02 "$rect" "$a1" "$a2"
            judge "$work/ga.set" --alpha "$page_alpha" --regions "$mask" "$work/p.1.pfm" "$work/p.2.pfm" "$ref"
            # Processor seconds: the pilot's renders and the two it asked for.
            set_sec=$(awk -v p="$(seconds_per_render "$dir")" -v a="$(seconds_per_render "$dir/auto/$sfp_spp")" \
                'BEGIN { printf "%.1f", 2 * p + 2 * a }')
            echo "$scene $lkey $i $(tr '\n' ' ' <"$work/ga.set")$sfp_spp $set_sec" >>"$ledger"
        fi
        has_verdict compare-2 || has_verdict grade-page || { i=$((i + 1)); continue; }
        for b in region1 region2 region5 whole0.5; do
            case $b in
                region1) planted "$i" 1.01 "$rect" "$r1" "$r2" ;;
                region2) planted "$i" 1.02 "$rect" "$r1" "$r2" ;;
                region5) planted "$i" 1.05 "$rect" "$r1" "$r2" ;;
                whole0.5) planted "$i" 1.005 all "$r1" "$r2" ;;
            esac
            ! has_verdict compare-2 || judge "$work/c2.$b" "$work/p.1.pfm" "$work/p.2.pfm" "$ref"
            ! has_verdict grade-page || judge "$work/gp.$b" --alpha "$page_alpha" --regions "$mask" \
                "$work/p.1.pfm" "$work/p.2.pfm" "$ref"
        done
        i=$((i + 1))
    done
    pair=$(awk -v s="$sec" 'BEGIN { printf "%.4f", 2 * s }')
    tally_pairs() { tally "$1" "$scene" "$2" "$3" "$sets" "$(count1 "$4")" $((2 * sets)) \
        "$(awk -v n="$sets" -v p="$pair" -v x="${5:-0}" 'BEGIN { print n * p + x }')"; }
    ! has_verdict compare-2 || tally_pairs compare-2 none 0 "$work/compare-2"
    ! has_verdict regions || tally_pairs regions none 0 "$work/regions"
    ! has_verdict grade-page || tally_pairs grade-page none 0 "$work/grade-page"
    if has_verdict control; then
        ctl_sec=0
        [ ! -f "$dir/ctl/seconds" ] || ctl_sec=$(awk -v n="$ctl_renders" '{ s += $1; k++ } END { print k ? s / k * n : 0 }' "$dir/ctl/seconds")
        tally control "$scene" none 0 "$sets" "$(count1 "$work/control")" $((2 * sets + ctl_renders)) \
            "$(awk -v n="$sets" -v p="$pair" -v x="$ctl_sec" 'BEGIN { print n * p + x }')"
    fi
    if has_verdict grade-auto; then
        # Every set of the ledger under this key, each once.
        awk -v s="$scene" -v k="$lkey" '$1 == s && $2 == k && !seen[$3]++' "$ledger" >"$work/ga.sets"
        read -r ga_n ga_fa ga_found ga_sec <<EOF_GA
$(awk '{ n++; fa += $4; f += $5; t += $7 } END { print n + 0, fa + 0, f + 0, t + 0 }' "$work/ga.sets")
EOF_GA
        if [ "$ga_n" -gt 0 ]; then
            echo "  $scene: grade-auto: $ga_n sets in the ledger; their spp: $(awk '{ print $6 }' "$work/ga.sets" |
                sort -n | awk '{ v[++n] = $1 } END { print "min " v[1] ", median " v[int((n + 1) / 2)] ", max " v[n] }')"
            tally grade-auto "$scene" none 0 "$ga_n" "$ga_fa" $((4 * ga_n)) "$ga_sec"
            tally grade-auto "$scene" region2 2 "$ga_n" "$ga_found" $((4 * ga_n)) "$ga_sec"
        fi
    fi
    ! has_verdict compare-4 || tally compare-4 "$scene" none 0 "$sets" "$(count1 "$work/compare-4")" \
        $((4 * sets)) "$(awk -v n="$sets" -v p="$pair" 'BEGIN { print 2 * n * p }')"
    for b in region1 region2 region5 whole0.5; do
        pct=$(echo "$b" | sed 's/^[a-z]*//')
        [ "${b#region}" != "$b" ] || pct=
        ! has_verdict compare-2 || tally_pairs compare-2 "$b" "$pct" "$work/c2.$b"
        ! has_verdict grade-page || tally_pairs grade-page "$b" "$pct" "$work/gp.$b"
    done
    echo "  $scene: verdicts done"
done

# One run of make grade: set i of every scene (not measured on some of them).
if has_verdict grade && [ "$(echo $scenes | tr ' ' '\n' | sort)" != "$(echo $all_scenes | tr ' ' '\n' | sort)" ]; then
    echo "  grade: not measured (it takes every reference scene's page; --scenes left some out)"
elif has_verdict grade; then
    n_scenes=$(echo $scenes | wc -w)
    awk -v n="$n_scenes" '{ any[$1] += $2; seen[$1]++ }
        END { for (i in seen) if (seen[i] == n) print (any[i] > 0) }' "$grade_tmp" >"$work/grade.any"
    tally grade all-scenes none 0 "$(wc -l <"$work/grade.any")" "$(count1 "$work/grade.any")" \
        $((2 * sets * n_scenes)) "$(awk -F, '$1 == "grade-page" && $3 == "none" { s += $11 } END { print s + 0 }' "$csv")"
fi

# ---- planted code bugs ------------------------------------------------------
# plant_stage (lablib.sh) builds a copy of stage 07 with one sed applied.
if [ "$bug_sets" -gt 0 ]; then
    for bug in $BUGS; do
        bug_plant "$bug"
        tree=$cal/bug-$bug
        plant_stage "$root" "$tree" 07_pathtrace "$file" -e "$expr" >"$work/plant.log" 2>&1 ||
            die "cannot plant $bug: $(tail -n 5 "$work/plant.log")"
        bug_render=$tree/build/07_pathtrace/render
        bug_key=$(cat "$bug_render" | cksum | cut -d' ' -f1)
        for scene in $scenes; do
            dir=$cal/pool-$bug_key-$size-$spp/$scene
            pool_renders "$bug_render" "$dir" "$scene" "$spp" "$BASE" $((2 * bug_sets))
            : >"$work/b.c2"
            : >"$work/b.gp"
            i=0
            while [ "$i" -lt "$bug_sets" ]; do
                r1=$dir/$((BASE + 2 * i)).pfm
                r2=$dir/$((BASE + 2 * i + 1)).pfm
                judge "$work/b.c2" "$r1" "$r2" "$(ref_of "$scene")"
                judge "$work/b.gp" --alpha "$page_alpha" --regions "$(mask_of "$scene")" "$r1" "$r2" "$(ref_of "$scene")"
                i=$((i + 1))
            done
            bsec=$(awk -v s="$(seconds_per_render "$dir")" -v n="$bug_sets" 'BEGIN { print 2 * n * s }')
            tally compare-2 "$scene" "$bug" "" "$bug_sets" "$(count1 "$work/b.c2")" $((2 * bug_sets)) "$bsec"
            tally grade-page "$scene" "$bug" "" "$bug_sets" "$(count1 "$work/b.gp")" $((2 * bug_sets)) "$bsec"
        done
        echo "  $bug: done"
    done
fi

# ---- the statistical stage tests under other seeds ---------------------------
if [ "$seed_offsets" -gt 0 ]; then
    "$root/tests/calibrate/seed-offsets.sh" "$seed_offsets" >"$work/seeds" || die "the seed-offset runs failed"
    while read -r prog runs fails seconds; do
        tally "test:$prog" - none "" "$runs" "$fails" 0 "$seconds"
    done <"$work/seeds"
fi

if [ "$append" = 1 ] && [ -f "$out/calibration.csv" ]; then
    # The earlier rows of the other scenes first, as their run wrote them.
    awk -F, -v scenes=" $scenes " 'NR == 1 { print; next } index(scenes, " " $2 " ") == 0' \
        "$out/calibration.csv" >"$work/kept.csv"
    sed 1d "$csv" >>"$work/kept.csv"
    mv "$work/kept.csv" "$csv"
fi
cp "$csv" "$out/calibration.csv.tmp"
mv "$out/calibration.csv.tmp" "$out/calibration.csv"
"$build/tools/plotcsv" -x bias_pct -y rate -g verdict,scene -f bias=none\|region1\|region2\|region5 \
    -f verdict=compare-2\|grade-page\|grade-auto --title "How often a verdict says biased (${size}x$size, $spp spp)" \
    --xlabel "bias planted in a 32x32 rectangle (%)" --ylabel "rate of 'biased'" \
    -o "$out/calibration.svg" "$out/calibration.csv" || die "plotcsv failed"
awk -F, -v size="$size" -v spp="$spp" -f "$root/tests/calibrate/table.awk" "$out/calibration.csv" >"$work/table.md"
readme=$out/README.md
[ -f "$readme" ] || die "no $readme (the text around the table)"
awk -v table="$work/table.md" '
    /^<!-- calibrate: table -->$/ { print; while ((getline l < table) > 0) print l; skip = 1; next }
    /^<!-- calibrate: end -->$/ { skip = 0 }
    !skip' "$readme" >"$work/README.md"
mv "$work/README.md" "$readme"
echo "wrote $out/calibration.csv, $out/calibration.svg and the table of $readme"
