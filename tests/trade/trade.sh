#!/usr/bin/env bash
# trade.sh - the speed/accuracy sweep of `make trade`: renders every reference
# scene through every built stage over that stage's quality knobs, and writes
# one CSV row per render: its time and rays (from --stats) and its error
# against two references (imgcmp).  report.sh turns the CSV into plots and
# docs/trade/README.md.
#
#   tests/trade/trade.sh            run the sweep (QUICK=1: the reduced one)
#   tests/trade/trade.sh --plan     print the runs it would make, one per line
#   tests/trade/trade.sh --header   print the CSV header
#   tests/trade/trade.sh --stages   print the stages it would sweep
#   tests/trade/trade.sh --rerun ID...  render plan rows ID... again, print their CSV rows
#
# Environment (the Makefile sets them): QUICK (0|1), BUILDROOT (where the
# stages were built, default build/), TRADE_OUT (default docs/trade, or
# build/trade/quick with QUICK=1), TRADE_STAGES (a subset of the stages).
#
# Conventions:
#   - Every render uses -t 2 (threads) and one image size: 256 x 256, the
#     references' size (QUICK: 64 x 64, against the references shrunk 4 x 4
#     by pfmbox, which is exact for box-filtered pixels).
#   - Renders run one after another, never in parallel, for stable times.
#   - Seeds 1, 2, ...: where a render is random (area lights, sampled
#     pixels, paths) several seeds; deterministic ones (stages 01-02, a
#     point light without pixel sampling) run once.  The same seeds give the
#     same images, so every column but the times (and efficiency, which
#     divides by a time) is reproduced exactly by a second sweep.
#   - The stage's own reference: tests/reference/<scene>_direct.pfm for the
#     direct-light stages (01-06) where it exists (the specular scene has
#     none), <scene>_gi.pfm for 07.  own_is_limit says whether the stage can
#     converge to it (01 has no shadows; 01-02 treat an area light as a point).
#   - Mesh scenes for the BVH question (mesh_N: a Cornell box holding a sphere of N
#     triangles, point light) are generated into the work directory; they
#     have no reference, so their error columns are empty.
set -euo pipefail
cd "$(dirname "$0")/../.."

QUICK=${QUICK:-0}
BUILD=${BUILDROOT:-build/}
BUILD=${BUILD#"$PWD"/}
BUILD=${BUILD%/}/
if [ "$QUICK" = 1 ]; then
    MODE=quick
    OUT=${TRADE_OUT:-${BUILD}trade/quick}
else
    MODE=full
    OUT=${TRADE_OUT:-docs/trade}
fi
OUT=${OUT#"$PWD"/}
WORK=${BUILD}trade/work-$MODE
IMGCMP=${BUILD}tools/imgcmp
PFMBOX=${BUILD}trade/bin/pfmbox
THREADS=2
REF_DIR=tests/reference
SCENES="cornell_diffuse_point cornell_diffuse_area cornell_specular_area"

if [ "$MODE" = quick ]; then
    WIDTH=64
    MESH_WIDTH=32
else
    WIDTH=256
    MESH_WIDTH=64
fi

# ---- the sweep plan ------------------------------------------------------
#
# One line per run, tab-separated:
#   id stage scene knobs family value seed default pair
# knobs is the readable knob set ("spp=64 nee=off rr=on", "adaptive=4:12");
# family names the curve the run belongs to (the knobs but the swept one),
# value the swept knob's value; default is 1 for the stage's default knobs;
# pair is the id of a run whose image must be identical (bvh=off against
# bvh=on), else 0.

stages() {
    if [ -n "${TRADE_STAGES:-}" ]; then
        echo "$TRADE_STAGES"
        return
    fi
    local d s list=""
    for d in stages/[0-9][0-9]_*; do
        s=${d#stages/}
        if [ -x "$BUILD$s/render" ]; then list="$list $s"; fi
    done
    echo $list
}

# The stage's --help, to see which knobs it has.
declare -A HELP
has() { # has STAGE OPTION
    [[ ${HELP[$1]} == *"$2"* ]]
}

# The kind of sweep a stage gets, by the most advanced knob it has.
stage_class() {
    if has "$1" --no-nee; then
        echo pathtrace
    elif has "$1" --aa; then
        echo supersample
    elif has "$1" --max-depth; then
        echo whitted
    elif has "$1" --shadow-samples; then
        echo soft
    else
        echo fixed
    fi
}

PLAN_ID=0
LAST_ID=0
emit() { # emit STAGE SCENE KNOBS FAMILY VALUE SEED DEFAULT [PAIR]
    PLAN_ID=$((PLAN_ID + 1))
    LAST_ID=$PLAN_ID
    printf '%d\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$PLAN_ID" "$1" "$2" "$3" "$4" "$5" "$6" "$7" "${8:-0}"
}

# emit_seeds N STAGE SCENE KNOBS FAMILY VALUE DEFAULT: seeds 1..N; a stage
# with --no-bvh also renders the default knobs without its BVH, paired with
# the same seed's run to check the images are identical.
emit_seeds() {
    local n=$1 seed
    shift
    for seed in $(seq 1 "$n"); do
        emit "$1" "$2" "$3" "$4" "$5" "$seed" "$6"
    done
}

bvh_pairs() { # bvh_pairs N STAGE SCENE KNOBS: default knobs with and without BVH
    local n=$1 seed on forced="" default=1
    # A stage that skips the tree on small scenes (--brute-force-max) is
    # made to build it, so that bvh=on is the tree on every scene.
    if has "$2" --brute-force-max; then
        forced=" brute=0"
        default=0
    fi
    for seed in $(seq 1 "$n"); do
        emit "$2" "$3" "$4$forced" "bvh=on" 1 "$seed" "$default"
        on=$LAST_ID
        emit "$2" "$3" "$4 bvh=off" "bvh=off" 0 "$seed" 0 "$on"
    done
}

area_scene() { [ "$1" != cornell_diffuse_point ]; }

# Knob values of the full and the quick sweep.
if [ "$MODE" = quick ]; then
    SEEDS=2
    SHADOW_SOFT="1 4 16"
    SHADOW_WHITTED="1 16"
    ADAPTIVE_K="4"
    ADAPTIVE_T="16"
    ADAPTIVE_T_WHITTED="16"
    DEPTH_WHITTED="1 2 8"
    AA_SPP="1 4 16"
    AA_SPP_ADAPTIVE="4 16"
    AA_SPP_SHADOW16="4"
    PT_SPP="1 4 16"
    PT_SPP_MAIN_EXTRA="64"
    PT_DEPTH="2"
    PT_RR_DEPTH="2 5"
    PT_RR_THRESHOLD="0.4 1"
    MESH_B="1 3 9 28" # 0, 24, 288, 3,024 triangles
    MESH_BRUTE_MAX=1000
else
    SEEDS=3
    SHADOW_SOFT="1 2 4 8 16 32 64 128 256"
    SHADOW_WHITTED="1 4 16 64 256"
    ADAPTIVE_K="2 4 8"
    ADAPTIVE_T="8 16 32 64 128"
    ADAPTIVE_T_WHITTED="16 64 256" # budgets of SHADOW_WHITTED, to compare with
    DEPTH_WHITTED="1 2 3 4 6 8 16"
    AA_SPP="1 4 16 64"
    AA_SPP_ADAPTIVE="4 16 64"
    AA_SPP_SHADOW16="1 4 16"
    PT_SPP="1 4 16 64"
    PT_SPP_MAIN_EXTRA="256"
    PT_DEPTH="1 2 3 4 8"
    PT_RR_DEPTH="2 3 4 5 6 8"
    PT_RR_THRESHOLD="0.2 0.3 0.4 0.5 0.7 1"
    MESH_B="1 2 3 5 9 16 28 50 88 158 280" # 0 (the box alone), 8 ... 312,480 triangles
    MESH_BRUTE_MAX=31000 # brute force grows as pixels x triangles: capped
fi

# Seeds for a path-traced spp: cheap ones get more (5, 3, 2 in the full sweep).
pt_seeds() {
    if [ "$MODE" = quick ]; then
        echo "$SEEDS"
    elif [ "$1" -le 16 ]; then
        echo 5
    elif [ "$1" -le 64 ]; then
        echo 3
    else
        echo 2
    fi
}

plan_fixed() { # 01, 02: no knobs, deterministic
    local sc
    for sc in $SCENES; do
        emit "$1" "$sc" default default 0 1 1
    done
}

plan_soft() { # 03: shadow samples, adaptive probes
    local st=$1 sc n k t
    for sc in $SCENES; do
        if ! area_scene "$sc"; then
            emit "$st" "$sc" default default 0 1 1 # the knobs only sample area lights
            continue
        fi
        for n in $SHADOW_SOFT; do
            emit_seeds "$SEEDS" "$st" "$sc" "shadow=$n" shadow "$n" "$([ "$n" = 16 ] && echo 1 || echo 0)"
        done
        for k in $ADAPTIVE_K; do
            for t in $ADAPTIVE_T; do
                [ "$t" -gt "$k" ] || continue
                emit_seeds "$SEEDS" "$st" "$sc" "adaptive=$k:$((t - k))" "adaptive=$k" "$t" 0
            done
        done
    done
}

plan_whitted() { # 04, 05: + max depth (specular scene), + BVH on/off (05)
    local st=$1 sc n k t d dk bvh=0
    if has "$st" --no-bvh; then bvh=1; fi
    for sc in $SCENES; do
        dk=""
        if [ "$sc" = cornell_specular_area ]; then dk=" depth=8"; fi
        if ! area_scene "$sc"; then
            emit "$st" "$sc" default default 0 1 1
            if [ $bvh = 1 ]; then bvh_pairs 1 "$st" "$sc" default; fi
            continue
        fi
        for n in $SHADOW_WHITTED; do
            emit_seeds "$SEEDS" "$st" "$sc" "shadow=$n$dk" shadow "$n" "$([ "$n" = 16 ] && echo 1 || echo 0)"
        done
        for k in 4; do
            for t in $ADAPTIVE_T_WHITTED; do
                emit_seeds "$SEEDS" "$st" "$sc" "adaptive=$k:$((t - k))$dk" "adaptive=$k" "$t" 0
            done
        done
        if [ -n "$dk" ]; then
            for d in $DEPTH_WHITTED; do
                emit_seeds "$SEEDS" "$st" "$sc" "shadow=16 depth=$d" depth "$d" "$([ "$d" = 8 ] && echo 1 || echo 0)"
            done
        fi
        if [ $bvh = 1 ]; then bvh_pairs "$SEEDS" "$st" "$sc" "shadow=16$dk"; fi
    done
}

plan_supersample() { # 06: spp x AA pattern (x shadow samples on area lights)
    local st=$1 sc n aa sh seeds bvh=0
    if has "$st" --no-bvh; then bvh=1; fi
    for sc in $SCENES; do
        sh=" shadow=1"
        area_scene "$sc" || sh=""
        for aa in grid jitter adaptive $(has "$st" sobol && echo sobol); do
            seeds=$SEEDS
            if [ $aa = grid ] && [ -z "$sh" ]; then seeds=1; fi # nothing random is left
            for n in $([ $aa = adaptive ] && echo "$AA_SPP_ADAPTIVE" || echo "$AA_SPP"); do
                emit_seeds "$seeds" "$st" "$sc" "spp=$n aa=$aa$sh" "aa=$aa$sh" "$n" \
                    "$([ -z "$sh" ] && [ $aa = jitter ] && [ "$n" = 4 ] && echo 1 || echo 0)"
            done
        done
        if [ -n "$sh" ]; then
            for n in $AA_SPP_SHADOW16; do
                emit_seeds "$SEEDS" "$st" "$sc" "spp=$n aa=jitter shadow=16" "aa=jitter shadow=16" "$n" \
                    "$([ "$n" = 4 ] && echo 1 || echo 0)"
            done
        fi
        if [ $bvh = 1 ]; then bvh_pairs 1 "$st" "$sc" "spp=4 aa=jitter${sh:+ shadow=16}"; fi
    done
}

plan_pathtrace() { # 07: spp x NEE on/off x RR on/off; the other levers; max depth
    local st=$1 sc n nee rr d l bvh=0
    if has "$st" --no-bvh; then bvh=1; fi
    for sc in $SCENES; do
        for nee in on off; do
            # --no-nee changes only area lights: a point light is always sampled.
            [ $nee = off ] && ! area_scene "$sc" && continue
            for rr in on off; do
                for n in $PT_SPP; do
                    emit_seeds "$(pt_seeds "$n")" "$st" "$sc" "spp=$n nee=$nee rr=$rr" "nee=$nee rr=$rr" "$n" 0
                done
                if [ $nee = on ] && [ $rr = on ]; then
                    for n in $PT_SPP_MAIN_EXTRA; do
                        emit_seeds "$(pt_seeds "$n")" "$st" "$sc" "spp=$n nee=on rr=on" "nee=on rr=on" "$n" 0
                    done
                fi
            done
        done
        if has "$st" --sampler; then
            # The Sobol sampler is the default: against the independent one.
            for n in $PT_SPP $PT_SPP_MAIN_EXTRA; do
                emit_seeds "$(pt_seeds "$n")" "$st" "$sc" "spp=$n nee=on rr=on sampler=independent aa=jitter" \
                    "nee=on rr=on sampler=independent aa=jitter" "$n" 0
            done
        fi
        if has "$st" --no-mis && area_scene "$sc"; then
            for n in $PT_SPP $PT_SPP_MAIN_EXTRA; do
                emit_seeds "$(pt_seeds "$n")" "$st" "$sc" "spp=$n nee=on rr=on mis=off" "nee=on rr=on mis=off" "$n" 0
            done
        fi
        if has "$st" --light-sampling && area_scene "$sc"; then
            for l in solid-angle auto; do
                for n in $PT_SPP $PT_SPP_MAIN_EXTRA; do
                    emit_seeds "$(pt_seeds "$n")" "$st" "$sc" "spp=$n nee=on rr=on light=$l" \
                        "nee=on rr=on light=$l" "$n" 0
                done
            done
        fi
        if has "$st" --rr-depth; then
            # Where roulette starts, with each sampler: stratified early
            # bounces make a late start pay more (docs/stages/07_pathtrace.md).
            for d in $PT_RR_DEPTH; do
                emit_seeds "$SEEDS" "$st" "$sc" "spp=16 nee=on rr=on rrdepth=$d" "rr start (spp=16)" "$d" 0
                if has "$st" --sampler; then
                    emit_seeds "$SEEDS" "$st" "$sc" "spp=16 nee=on rr=on rrdepth=$d sampler=independent aa=jitter" \
                        "rr start independent (spp=16)" "$d" 0
                fi
            done
        fi
        if has "$st" --rr-threshold; then
            for d in $PT_RR_THRESHOLD; do
                emit_seeds "$SEEDS" "$st" "$sc" "spp=16 nee=on rr=on rrthreshold=$d" \
                    "rr threshold (spp=16)" "$d" 0
            done
        fi
        for d in $PT_DEPTH; do
            emit_seeds "$SEEDS" "$st" "$sc" "spp=16 nee=on rr=on depth=$d" "depth (spp=16)" "$d" 0
        done
        if [ $bvh = 1 ]; then bvh_pairs 1 "$st" "$sc" "spp=64 nee=on rr=on"; fi
    done
}

plan_mesh() { # the first stage with a BVH: time against triangle count
    local st=$1 b n rep on
    for b in $MESH_B; do
        n=$(mesh_triangles "$b")
        for rep in $(seq 1 "$(mesh_repeats "$n")"); do
            emit "$st" "mesh_$n" "bvh=on" "bvh=on" "$n" "$rep" 0
            on=$LAST_ID
            if [ "$n" -le "$MESH_BRUTE_MAX" ]; then
                emit "$st" "mesh_$n" "bvh=off" "bvh=off" "$n" "$rep" 0 "$on"
            fi
        done
    done
}

# A UV sphere of B bands and 2B segments has 4 B (B - 1) triangles.
mesh_triangles() { echo $((4 * $1 * ($1 - 1))); }

# Repeats of a mesh render, for its median time: more where a render takes
# milliseconds and the noise of starting threads weighs most.
mesh_repeats() {
    if [ "$MODE" = quick ]; then
        echo 1
    elif [ "$1" -le 1000 ]; then
        echo 5
    else
        echo 3
    fi
}

plan() {
    local st class mesh_done=0
    for st in $(stages); do
        HELP[$st]=$("$BUILD$st/render" --help 2>&1 || true)
        class=$(stage_class "$st")
        "plan_$class" "$st"
        if [ $mesh_done = 0 ] && has "$st" --no-bvh; then
            plan_mesh "$st"
            mesh_done=1
        fi
    done
}

# Fix the default flag of 07's 64 spp runs, which plan_pathtrace emits from
# PT_SPP (full sweep) without knowing they are the default.
fix_defaults() {
    awk -F'\t' 'BEGIN { OFS = "\t" }
        $4 == "spp=64 nee=on rr=on" && $5 == "nee=on rr=on" { $8 = 1 }
        { print }'
}

# ---- running -------------------------------------------------------------

# Command-line options of a knob set.
knob_args() {
    local k args=""
    for k in $1; do
        case $k in
        default | bvh=on | nee=on | rr=on) ;;
        shadow=*) args="$args --shadow-samples ${k#*=}" ;;
        adaptive=*) args="$args --adaptive $(echo "${k#*=}" | tr : ,)" ;;
        depth=*) args="$args --max-depth ${k#*=}" ;;
        spp=*) args="$args --spp ${k#*=}" ;;
        aa=*) args="$args --aa ${k#*=}" ;;
        bvh=off) args="$args --no-bvh" ;;
        brute=*) args="$args --brute-force-max ${k#*=}" ;;
        sampler=*) args="$args --sampler ${k#*=}" ;;
        rrdepth=*) args="$args --rr-depth ${k#*=}" ;;
        rrthreshold=*) args="$args --rr-threshold ${k#*=}" ;;
        mis=off) args="$args --no-mis" ;;
        light=*) args="$args --light-sampling ${k#*=}" ;;
        nee=off) args="$args --no-nee" ;;
        rr=off) args="$args --no-rr" ;;
        *)
            echo "trade.sh: unknown knob '$k'" >&2
            exit 1
            ;;
        esac
    done
    echo "$args"
}

scene_file() {
    case $1 in
    mesh_*) echo "$WORK/scenes/$1.scene" ;;
    *) echo "scenes/$1.scene" ;;
    esac
}

# A Cornell box (the walls of the reference scenes, no spheres, the point
# light) holding a UV sphere of B bands as triangle statements.
write_mesh_scene() { # write_mesh_scene B FILE
    {
        echo "# Generated by tests/trade/trade.sh: the Cornell box of"
        echo "# cornell_diffuse_point.scene with its two spheres replaced by one UV"
        echo "# sphere (radius 0.5 at (0, 0.5, 0)) of $(mesh_triangles "$1") triangles."
        grep -E '^(camera|image|material|quad|point_light) ' scenes/cornell_diffuse_point.scene
        awk -v B="$1" 'BEGIN {
            pi = atan2(0, -1); S = 2 * B
            for (i = 0; i <= B; i++) for (j = 0; j <= S; j++) {
                th = pi * i / B; ph = 2 * pi * j / S
                P[i, j] = sprintf("%.6f %.6f %.6f", 0.5 * sin(th) * cos(ph),
                                  0.5 + 0.5 * cos(th), 0.5 * sin(th) * sin(ph))
            }
            for (i = 0; i < B; i++) for (j = 0; j < S; j++) {
                if (i > 0) print "triangle v0 " P[i, j] " v1 " P[i + 1, j] " v2 " P[i, j + 1] " material white"
                if (i < B - 1) print "triangle v0 " P[i, j + 1] " v1 " P[i + 1, j] " v2 " P[i + 1, j + 1] " material white"
            }
        }'
    } >"$2.tmp"
    mv "$2.tmp" "$2"
}

# The references at the sweep's image size: tests/reference itself at its
# own size, else shrunk by pfmbox into the work directory.
reference() { # reference SCENE KIND -> path, or nothing if there is none
    local src="$REF_DIR/${1}_$2.pfm" size f dst
    [ -f "$src" ] || return 0
    size=$(head -n 2 "$src" | tail -n 1)
    set -- "$1" "$2" $size
    if [ "$3" = "$WIDTH" ]; then
        echo "$src"
        return
    fi
    f=$(($3 / WIDTH))
    if [ $((f * WIDTH)) -ne "$3" ] || [ $(($4 % f)) -ne 0 ]; then
        echo "trade.sh: image width $WIDTH does not divide the reference size $3x$4" >&2
        exit 1
    fi
    dst="$WORK/ref/${1}_$2.pfm"
    if [ ! -f "$dst" ] || [ "$src" -nt "$dst" ]; then
        mkdir -p "$WORK/ref"
        "$PFMBOX" "$f" "$src" "$dst"
    fi
    echo "$dst"
}

# Which reference a stage converges to: "REF LIMIT" (REF empty: none).
own_reference() { # own_reference STAGE SCENE
    local num=${1%%_*}
    num=$((10#$num))
    case $2 in
    mesh_*) echo " " ;;
    *)
        if [ "$num" -ge 7 ]; then
            echo "gi 1"
        elif [ ! -f "$REF_DIR/${2}_direct.pfm" ]; then
            echo " "
        elif [ "$num" -ge 3 ] || { [ "$num" -ge 2 ] && ! area_scene "$2"; }; then
            echo "direct 1"
        else
            echo "direct 0"
        fi
        ;;
    esac
}

# The statistics the CSV takes from --stats, in this order.
STAT_KEYS="seconds_render seconds_total rays_camera rays_shadow rays_secondary spp width height threads seconds_build prim_tests node_visits penumbra_pixels aa_refined_pixels"

stats_fields() { # stats_fields FILE -> the STAT_KEYS values, comma-separated
    awk -v keys="$STAT_KEYS" '
        { while (match($0, /"[a-z_0-9]+"[ \t]*:[ \t]*[-+0-9.eE]+/)) {
              kv = substr($0, RSTART, RLENGTH); $0 = substr($0, RSTART + RLENGTH)
              k = kv; sub(/^"/, "", k); sub(/".*/, "", k)
              v = kv; sub(/^[^:]*:[ \t]*/, "", v); val[k] = v } }
        END { n = split(keys, K, " ")
              for (i = 1; i <= n; i++) printf "%s%s", (i > 1 ? "," : ""), val[K[i]] }' "$1"
}

metrics_fields() { # metrics_fields RENDER REF -> relmse,rmse,mae,frac5 (empty without REF)
    if [ -z "$2" ]; then
        echo ",,,"
        return
    fi
    local line
    line=$("$IMGCMP" --csv "$1" "$2" | tail -n 1)
    if [ "$(echo "$line" | cut -d, -f2)" != 0 ]; then
        echo "trade.sh: warning: $1: $(echo "$line" | cut -d, -f2) non-finite pixels left out" >&2
        echo "$1" >>"$WORK/nonfinite.txt"
    fi
    echo "$line" | cut -d, -f3-6
}

HEADER="stage,scene,knobs,seed,seconds_render,seconds_total,rays_camera,rays_shadow,rays_secondary,relmse_own,rmse_own,mae_own,frac5_own,relmse_gi,rmse_gi,mae_gi,frac5_gi,efficiency,own_ref,own_is_limit,family,value,default,spp,width,height,threads,seconds_build,prim_tests,node_visits,penumbra_pixels,aa_refined_pixels,triangles,cpu_seconds,attempts"

# The command line of a plan row (relative paths, as run from the root).
row_command() { # row_command RUNDIR ID STAGE SCENE KNOBS SEED
    local w=$WIDTH
    case $4 in mesh_*) w=$MESH_WIDTH ;; esac
    echo "$BUILD$3/render -q -t $THREADS -W $w -H $w --seed $6$(knob_args "$5") --stats $1/$2.json -o $1/$2.pfm $(scene_file "$4")"
}

# Timing hygiene.  The render's CPU seconds (user + system, from bash's
# time) against seconds_render x threads show whether it had the cores to
# itself.  When it visibly had not (more than 1.4 x, for renders of at least
# 0.05 CPU seconds) it is run again, up to RETRIES more times within a total
# of RETRY_BUDGET seconds per sweep, and the fastest attempt's statistics are
# kept: the image is the same every time (same seed), only the time changes.
RETRIES=1
RETRY_BUDGET=60
RETRY_SPENT=0
RETRIED=0

render_timed() { # render_timed OUT CMD... -> OUT.json, OUT.cpu, OUT.pfm; sets ATTEMPTS
    local out=$1 t c best_t="" contended TIMEFORMAT='%U %S'
    shift
    ATTEMPTS=0
    while :; do
        ATTEMPTS=$((ATTEMPTS + 1))
        if ! { time "$@" 2>"$out.err"; } 2>"$out.cpu"; then
            echo >&2
            echo "trade.sh: render failed: $*" >&2
            cat "$out.err" >&2
            return 1
        fi
        t=$(stats_fields "$out.json" | cut -d, -f1)
        c=$(awk '{ print $1 + $2 }' "$out.cpu")
        if [ -z "$best_t" ] || awk -v a="$t" -v b="$best_t" 'BEGIN { exit !(a < b) }'; then
            best_t=$t
            cp "$out.json" "$out.best.json"
            cp "$out.cpu" "$out.best.cpu"
        fi
        contended=$(awk -v t="$t" -v c="$c" -v n="$THREADS" 'BEGIN { x = (c >= 0.05 && t * n > 1.4 * c) ? 1 : 0; print x }')
        if [ "$contended" = 0 ] || [ "$ATTEMPTS" -gt "$RETRIES" ] ||
            awk -v s="$RETRY_SPENT" -v b="$RETRY_BUDGET" 'BEGIN { exit !(s >= b) }'; then
            break
        fi
        RETRY_SPENT=$(awk -v s="$RETRY_SPENT" -v t="$t" 'BEGIN { print s + t }')
        [ "$ATTEMPTS" = 1 ] && RETRIED=$((RETRIED + 1))
    done
    mv "$out.best.json" "$out.json"
    mv "$out.best.cpu" "$out.cpu"
}

# Render one plan row into RUNDIR and print its CSV row; the image is left
# at RUNDIR/ID.pfm.
run_row() { # run_row RUNDIR ID STAGE SCENE KNOBS FAMILY VALUE SEED DEFAULT
    local dir=$1 id=$2 stage=$3 scene=$4 knobs=$5 family=$6 value=$7 seed=$8 default=$9
    local out=$dir/$id own_kind own_limit own_ref="" gi_ref="" tri=0 cmd stats m_own m_gi eff
    read -r own_kind own_limit <<<"$(own_reference "$stage" "$scene")"
    if [ -n "$own_kind" ]; then own_ref=$(reference "$scene" "$own_kind"); fi
    case $scene in mesh_*) tri=${scene#mesh_} ;; *) gi_ref=$(reference "$scene" gi) ;; esac
    cmd=$(row_command "$dir" "$id" "$stage" "$scene" "$knobs" "$seed")
    render_timed "$out" $cmd || return 1
    stats=$(stats_fields "$out.json")
    m_own=$(metrics_fields "$out.pfm" "$own_ref")
    m_gi=$(metrics_fields "$out.pfm" "$gi_ref")
    # efficiency = 1 / (relMSE x seconds_render), relMSE against the own
    # reference where there is one, else against the GI reference.
    eff=$(awk -v a="${m_own%%,*}" -v b="${m_gi%%,*}" -v t="${stats%%,*}" 'BEGIN {
        e = (a != "" ? a : b); if (e != "" && e + 0 > 0 && t + 0 > 0) printf "%.6g", 1 / (e * t) }')
    printf '%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n' \
        "$stage" "$scene" "$knobs" "$seed" "$(echo "$stats" | cut -d, -f1-5)" \
        "$m_own" "$m_gi" "$eff" "$own_kind" "$own_limit" "$family" "$value" "$default" \
        "$(echo "$stats" | cut -d, -f6-)" "$tri" "$(awk '{ printf "%.2f", $1 + $2 }' "$out.cpu")" "$ATTEMPTS"
}

# relMSE of the direct-light reference against the GI one: the least error
# against the truth that a direct-light stage can reach on the scene.
floors() {
    local sc d g
    for sc in $SCENES; do
        d=$(reference "$sc" direct)
        g=$(reference "$sc" gi)
        if [ -n "$d" ] && [ -n "$g" ]; then
            echo "floor_$sc=$("$IMGCMP" --csv "$d" "$g" | tail -n 1 | cut -d, -f3)"
        fi
    done
}

progress() { # progress ID TOTAL STAGE SCENE KNOBS SEED
    if [ -t 2 ]; then
        printf '\r[%d/%d] %-20s %-22s %-34s seed %s ' "$@" >&2
    elif [ "$3" != "${LAST_STAGE:-}" ]; then
        echo "trade.sh: [$1/$2] $3" >&2
        LAST_STAGE=$3
    fi
}

run_sweep() {
    local plan_file=$WORK/plan.tsv csv=$WORK/trade.csv cmds=$WORK/commands.txt
    rm -rf "$WORK/runs"
    mkdir -p "$WORK/runs" "$WORK/scenes" "$OUT"
    rm -f "$WORK/nonfinite.txt"
    local swept
    swept=$(stages)
    TRADE_STAGES=$swept
    plan | fix_defaults >"$plan_file"
    local total b
    total=$(wc -l <"$plan_file")
    for b in $MESH_B; do
        grep -q "mesh_$(mesh_triangles "$b")" "$plan_file" || continue
        write_mesh_scene "$b" "$WORK/scenes/mesh_$(mesh_triangles "$b").scene"
    done
    # Runs whose image a later run is compared with are kept until then.
    local keep=" $(awk -F'\t' '$9 != 0 { printf "%s ", $9 }' "$plan_file")"
    echo "$HEADER" >"$csv"
    : >"$cmds"
    echo "pair,stage,scene,knobs,seed,relmse" >"$WORK/pairs.csv"
    local t0 load0 t1
    t0=$(date +%s)
    load0=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
    local id stage scene knobs family value seed default pair
    while IFS=$'\t' read -r id stage scene knobs family value seed default pair; do
        progress "$id" "$total" "$stage" "$scene" "$knobs" "$seed"
        row_command "$WORK/runs" "$id" "$stage" "$scene" "$knobs" "$seed" >>"$cmds"
        run_row "$WORK/runs" "$id" "$stage" "$scene" "$knobs" "$family" "$value" "$seed" "$default" >>"$csv"
        if [ "$pair" != 0 ]; then
            printf '%s,%s,%s,%s,%s,%s\n' "$pair" "$stage" "$scene" "$knobs" "$seed" \
                "$("$IMGCMP" --csv "$WORK/runs/$id.pfm" "$WORK/runs/$pair.pfm" | tail -n 1 | cut -d, -f3)" \
                >>"$WORK/pairs.csv"
            rm -f "$WORK/runs/$pair.pfm"
        fi
        [[ $keep == *" $id "* ]] || rm -f "$WORK/runs/$id.pfm"
    done <"$plan_file"
    [ -t 2 ] && echo >&2
    t1=$(date +%s)
    {
        echo "# make trade ($MODE sweep): every render, in order (line k: row k of trade.csv),"
        echo "# run from the project root; outputs in $WORK/runs/, images deleted once compared."
        echo "mode=$MODE"
        echo "runs=$total"
        echo "width=$WIDTH"
        echo "mesh_width=$MESH_WIDTH"
        echo "threads=$THREADS"
        echo "wall_seconds=$((t1 - t0))"
        echo "load_before=$load0"
        echo "load_after=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)"
        echo "cores=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo unknown)"
        echo "cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null)"
        echo "stages=$swept"
        echo "mesh_brute_max=$MESH_BRUTE_MAX"
        echo "nonfinite_runs=$(cat "$WORK/nonfinite.txt" 2>/dev/null | wc -l)"
        echo "retried_runs=$RETRIED"
        echo "retry_seconds=$(printf '%.0f' "$RETRY_SPENT")"
        # Time against CPU time: how much the renders had the cores to themselves.
        awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
            { r += $c["seconds_render"]; w = $c["seconds_render"] * $c["threads"]; u += $c["cpu_seconds"]; wt += w
              if ($c["cpu_seconds"] > 0.05 && w / $c["cpu_seconds"] > 1.5) slow++; n++ }
            END { printf "render_seconds=%.0f\ncpu_seconds=%.0f\nwall_over_cpu=%.2f\ncontended_runs=%d\n",
                         r, u, (u > 0 ? wt / u : 0), slow }' "$csv"
        floors
    } | sed -E "s/^([a-z_]+=)/# \\1/" >"$OUT/sweep.txt.tmp"
    cat "$cmds" >>"$OUT/sweep.txt.tmp"
    cp "$csv" "$OUT/trade.csv.tmp"
    mv "$OUT/trade.csv.tmp" "$OUT/trade.csv"
    mv "$OUT/sweep.txt.tmp" "$OUT/sweep.txt"
    if [ "$(wc -l <"$WORK/pairs.csv")" -gt 1 ]; then
        cp "$WORK/pairs.csv" "$OUT/pairs.csv.tmp"
        mv "$OUT/pairs.csv.tmp" "$OUT/pairs.csv"
    else
        rm -f "$OUT/pairs.csv"
    fi
    echo "trade.sh: $total renders in $((t1 - t0)) s; wrote $OUT/trade.csv" >&2
}

# Render plan rows again (into a scratch directory) and print their CSV
# rows: a second sweep in miniature, for the reproducibility check.
rerun() { # rerun ID...
    local dir=$WORK/rerun plan_file id stage scene knobs family value seed default pair want
    rm -rf "$dir"
    mkdir -p "$dir" "$WORK/scenes"
    plan_file=$dir/plan.tsv
    plan | fix_defaults >"$plan_file"
    for want in "$@"; do
        while IFS=$'\t' read -r id stage scene knobs family value seed default pair; do
            [ "$id" = "$want" ] || continue
            case $scene in
            mesh_*) write_mesh_scene "$(mesh_bands "${scene#mesh_}")" "$WORK/scenes/$scene.scene" ;;
            esac
            run_row "$dir" "$id" "$stage" "$scene" "$knobs" "$family" "$value" "$seed" "$default"
        done <"$plan_file"
    done
    rm -rf "$dir"
}

# The bands B of a sphere of N = 4 B (B - 1) triangles.
mesh_bands() { awk -v n="$1" 'BEGIN { printf "%d", (1 + sqrt(1 + n)) / 2 + 0.5 }'; }

case ${1:-} in
--stages)
    stages
    ;;
--header)
    echo "$HEADER"
    ;;
--plan)
    plan | fix_defaults
    ;;
--rerun)
    shift
    rerun "$@"
    ;;
"")
    run_sweep
    ;;
*)
    echo "usage: trade.sh [--plan | --header | --stages | --rerun ID...]" >&2
    exit 2
    ;;
esac
