#!/usr/bin/env bash
# report.sh - turn the sweep's trade.csv into settings.csv, the SVG plots and
# README.md, all in the output directory (docs/trade, or build/trade/quick
# with QUICK=1; TRADE_OUT overrides).  Plots are drawn by plotcsv
# (tests/tools/plotcsv.c) from small CSVs that awk cuts out of settings.csv.
#
#   tests/trade/report.sh
set -euo pipefail
cd "$(dirname "$0")/../.."

QUICK=${QUICK:-0}
BUILD=${BUILDROOT:-build/}
BUILD=${BUILD#"$PWD"/}
BUILD=${BUILD%/}/
if [ "$QUICK" = 1 ]; then
    OUT=${TRADE_OUT:-${BUILD}trade/quick}
    MODE=quick
else
    OUT=${TRADE_OUT:-docs/trade}
    MODE=full
fi
OUT=${OUT#"$PWD"/}
PLOTCSV=${BUILD}tools/plotcsv
TMP=${BUILD}trade/report-$MODE
HERE=tests/trade
CSV=$OUT/trade.csv
SETTINGS=$OUT/settings.csv

if [ ! -f "$CSV" ]; then
    echo "report.sh: no $CSV: run the sweep first (make trade${QUICK:+ QUICK=$QUICK})" >&2
    exit 1
fi
rm -rf "$TMP"
mkdir -p "$TMP"

awk -F, -v timebase="${TRADE_TIME:-render}" -f "$HERE/aggregate.awk" "$CSV" >"$TMP/settings.csv"
mv "$TMP/settings.csv" "$SETTINGS"

# The sweep's image size, for titles.
WIDTH=$(sed -n 's/^# width=//p' "$OUT/sweep.txt" 2>/dev/null || true)
WIDTH=${WIDTH:-256}
SIZE="${WIDTH}x$WIDTH px, 2 threads"

# Remove the plots of an earlier run (a stage may have gone or come).
rm -f "$OUT"/*.svg

PLOTS="" # "file|caption" lines, for the README
plot() { # plot FILE CAPTION -- plotcsv options...
    local file=$1 caption=$2
    shift 3
    if "$PLOTCSV" "$@" -o "$OUT/$file" 2>"$TMP/plot.err"; then
        PLOTS="$PLOTS$file|$caption"$'\n'
    else
        cat "$TMP/plot.err" >&2
        echo "report.sh: plotcsv failed for $file" >&2
        exit 1
    fi
    grep -v '^plotcsv: note:' "$TMP/plot.err" >&2 || true
}

# Rows of settings.csv that an awk condition keeps (the header always).
cut_rows() { # cut_rows CONDITION OUTFILE
    awk -F, "NR == 1 || ($1)" "$SETTINGS" >"$2"
}

rows() { # rows FILE -> data rows in a cut
    echo $(($(wc -l <"$1") - 1))
}

STAGES=$(awk -F, 'NR > 1 && !seen[$1]++ { printf "%s ", $1 }' "$SETTINGS")
CORNELL="cornell_diffuse_point cornell_diffuse_area cornell_specular_area"

# ---- summary: every stage's default curve on cornell_diffuse_area, against GI
cut_rows '$2 == "cornell_diffuse_area" && $6 == 1' "$TMP/summary.csv"
if [ "$(rows "$TMP/summary.csv")" -gt 0 ]; then
    plot summary.svg "Every stage on cornell_diffuse_area: relMSE against the full global-illumination reference vs render seconds; one curve per stage (the knob curve holding its defaults), Pareto front in black." -- \
        -x seconds -y relmse_gi -g stage,family --loglog --pareto \
        --title "cornell_diffuse_area: error against the GI truth vs time ($SIZE)" \
        --xlabel "seconds (render)" --ylabel "relMSE vs GI reference" "$TMP/summary.csv"
fi

# ---- every stage and curve on each scene, against GI
for sc in $CORNELL; do
    cut_rows "\$2 == \"$sc\" && \$3 !~ /^bvh=/" "$TMP/$sc.csv"
    [ "$(rows "$TMP/$sc.csv")" -gt 0 ] || continue
    plot "$sc.svg" "$sc: every stage and knob curve (BVH on/off aside: it changes only the time), relMSE against the GI reference vs render seconds, Pareto front in black." -- \
        -x seconds -y relmse_gi -g stage,family --loglog --pareto --size 960,720 \
        --title "$sc: every stage and knob ($SIZE)" \
        --xlabel "seconds (render)" --ylabel "relMSE vs GI reference" "$TMP/$sc.csv"
done

# ---- one plot per stage, for its docs page: its knob curves on its scene,
# against its own reference (GI where it has none), with the previous
# stage's default curve for comparison.
stage_scene() {
    case $1 in
    01_* | 02_*) echo cornell_diffuse_point ;;
    04_*) echo cornell_specular_area ;;
    *) echo cornell_diffuse_area ;;
    esac
}
prev=""
for st in $STAGES; do
    sc=$(stage_scene "$st")
    # Stages with a BVH get the BVH plot below instead, if there are mesh runs.
    if awk -F, -v s="$st" 'NR > 1 && $1 == s && $2 ~ /^mesh_/ { f = 1 } END { exit !f }' "$SETTINGS"; then
        prev=$st
        continue
    fi
    cut_rows "\$2 == \"$sc\" && \$2 !~ /^mesh_/ && (\$1 == \"$st\" || (\$1 == \"$prev\" && \$6 == 1))" "$TMP/$st.csv"
    if [ "$(rows "$TMP/$st.csv")" -eq 0 ]; then
        prev=$st
        continue
    fi
    # The stage's own reference on this scene: direct, gi or none.
    own=$(awk -F, -v s="$st" 'NR > 1 && $1 == s { print $19; exit }' "$TMP/$st.csv")
    if [ "$own" = direct ]; then
        y=relmse_own
        ylabel="relMSE vs direct-light reference"
        what="against the direct-light reference"
    else
        y=relmse_gi
        ylabel="relMSE vs GI reference"
        what="against the global-illumination reference"
    fi
    with_prev=""
    if [ -n "$prev" ]; then with_prev=", with the default curve of $prev"; fi
    plot "$st.svg" "$st on $sc: relMSE $what vs render seconds, one curve per knob$with_prev; Pareto front in black." -- \
        -x seconds -y "$y" -g stage,family --loglog --pareto \
        --title "$st on $sc ($SIZE)" --xlabel "seconds (render)" --ylabel "$ylabel" "$TMP/$st.csv"
    prev=$st
done

# ---- error against samples per pixel, with the 1/spp line of Monte Carlo
# theory through each plot's first point: 07 (NEE, RR) and 06 (AA patterns).
for st in $STAGES; do
    case $st in 06_* | 07_*) ;; *) continue ;; esac
    for sc in $CORNELL; do
        if [ "${st%%_*}" = 07 ]; then
            cond="\$1 == \"$st\" && \$2 == \"$sc\" && \$3 ~ /^nee=/"
            y=relmse_gi
            ylabel="relMSE vs GI reference"
        else
            [ "$sc" = cornell_specular_area ] && continue # no direct reference
            cond="\$1 == \"$st\" && \$2 == \"$sc\" && \$3 ~ /^aa=/"
            y=relmse_own
            ylabel="relMSE vs direct-light reference"
        fi
        cut_rows "$cond" "$TMP/$st-spp-$sc.csv"
        [ "$(rows "$TMP/$st-spp-$sc.csv")" -gt 1 ] || continue
        # The line passes through the lowest-spp point of the default curve.
        at=$(awk -F, -v y=$y 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
            { if (!n || $c["spp"] + 0 < best || ($c["main"] == 1 && $c["spp"] + 0 == best && !m)) {
                  best = $c["spp"] + 0; at = $c["spp"] "," $c[y]; n = 1; m = ($c["main"] == 1) } }
            END { print at }' "$TMP/$st-spp-$sc.csv")
        plot "${st}_spp_$sc.svg" "$st on $sc: relMSE vs samples per pixel, one curve per setting; dashed: relMSE proportional to 1/spp (Monte Carlo theory)." -- \
            -x spp -y "$y" -g family --loglog --refline -1 --refline-at "$at" --refline-label "1/spp" \
            --title "$st on $sc: error vs spp ($SIZE)" --xlabel "samples per pixel" --ylabel "$ylabel" \
            "$TMP/$st-spp-$sc.csv"
    done
done

# ---- the BVH: time and work per ray against triangle count
mesh_stage=$(awk -F, 'NR > 1 && $2 ~ /^mesh_/ { print $1; exit }' "$SETTINGS")
if [ -n "$mesh_stage" ]; then
    MW=$(sed -n 's/^# mesh_width=//p' "$OUT/sweep.txt" 2>/dev/null || true)
    # x: primitives = the sphere's triangles + the box's 5 quads (the box alone has 0 triangles).
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "triangles") t = i; print $0 ",primitives"; next }
        $2 ~ /^mesh_/ { print $0 "," $t + 5 }' "$SETTINGS" >"$TMP/bvh.csv"
    plot "$mesh_stage.svg" "$mesh_stage: seconds (render + BVH build) against primitive count (a sphere of N triangles in the box's 5 quads), with and without the BVH (--no-bvh: brute force, capped)." -- \
        -x primitives -y seconds_render_build -g family --loglog \
        --title "$mesh_stage: sphere of N triangles in the Cornell box (${MW:-64}x${MW:-64} px, 2 threads)" \
        --xlabel "primitives (triangles + 5 quads)" --ylabel "seconds (render + build)" "$TMP/bvh.csv"
    plot "${mesh_stage}_tests.svg" "$mesh_stage: primitive intersection tests per ray against primitive count, with and without the BVH." -- \
        -x primitives -y prim_tests_per_ray -g family --loglog \
        --title "$mesh_stage: intersection tests per ray" \
        --xlabel "primitives (triangles + 5 quads)" --ylabel "primitive tests per ray" "$TMP/bvh.csv"
fi

# ---- README.md
printf '%s' "$PLOTS" >"$TMP/plots.txt"
awk -F, -v timebase="${TRADE_TIME:-render}" -v mode="$MODE" -v sweep="$OUT/sweep.txt" -v pairs="$OUT/pairs.csv" -v plots="$TMP/plots.txt" \
    -f "$HERE/readme.awk" "$SETTINGS" >"$TMP/README.md"
mv "$TMP/README.md" "$OUT/README.md"
echo "report.sh: wrote $OUT/README.md, $OUT/settings.csv and $(printf '%s' "$PLOTS" | grep -c .) plots" >&2
