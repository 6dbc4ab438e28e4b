#!/usr/bin/env bash
# check-trade.sh [--no-rerun] [DIR] - check the outputs of `make trade`.
#
# DIR defaults to build/trade/quick (what `make trade QUICK=1` writes; CI
# runs this after it); `tests/trade/check-trade.sh docs/trade` checks the
# committed full sweep.  Checks:
#   - trade.csv: the header of trade.sh, one row per run of the sweep's plan
#     (regenerated now from the built stages: a stage added since the sweep
#     makes the results stale), every row well formed (numbers where numbers
#     belong, 2 threads, errors present exactly where references exist);
#   - sweep.txt holds one command line per row;
#   - every SVG is well formed XML (xmllint when installed, otherwise a tag
#     balance check in awk), and the summary and per-stage plots exist;
#   - README.md holds the cheapest-setting table (one line per stage and
#     reference scene) and the five answers;
#   - no output holds an absolute path of this machine;
#   - reproducibility: a few random settings rendered again give the same
#     rays and errors, to the last digit (skipped with --no-rerun or when the
#     stages are not built);
#   - the box downsampler's unit tests (when built).
# Prints "ok"/"FAIL" per check, then "N passed, N failed, N skipped".
set -uo pipefail
cd "$(dirname "$0")/../.."

RERUN=1
if [ "${1:-}" = --no-rerun ]; then
    RERUN=0
    shift
fi
BUILD=${BUILDROOT:-build/}
BUILD=${BUILD#"$PWD"/}
BUILD=${BUILD%/}/
DIR=${1:-${BUILD}trade/quick}
DIR=${DIR#"$PWD"/}
DIR=${DIR%/}

passed=0
failed=0
skipped=0
ok() {
    echo "ok   $1"
    passed=$((passed + 1))
}
fail() {
    echo "FAIL $1${2:+: $2}"
    failed=$((failed + 1))
}
skip() {
    echo "skip $1${2:+: $2}"
    skipped=$((skipped + 1))
}
check() { # check NAME DETAIL-IF-FAILED COMMAND...
    local name=$1 detail=$2
    shift 2
    if "$@"; then ok "$name"; else fail "$name" "$detail"; fi
}

finish() {
    echo "$passed passed, $failed failed, $skipped skipped"
    [ "$failed" -eq 0 ]
    exit $?
}

CSV=$DIR/trade.csv
if [ ! -f "$CSV" ]; then
    fail "trade.csv exists" "no $CSV: run make trade QUICK=1 (writes ${BUILD}trade/quick) or make trade (docs/trade)"
    finish
fi
ok "trade.csv exists"

# ---- the CSV ---------------------------------------------------------------
header=$(tests/trade/trade.sh --header)
check "trade.csv header" "expected: $header" [ "$(head -n 1 "$CSV")" = "$header" ]

mode=$(sed -n 's/^# mode=//p' "$DIR/sweep.txt" 2>/dev/null)
runs=$(sed -n 's/^# runs=//p' "$DIR/sweep.txt" 2>/dev/null)
rows=$(($(wc -l <"$CSV") - 1))
check "trade.csv has the sweep's row count" "$rows rows, sweep.txt says ${runs:-nothing}" [ "$rows" = "$runs" ]

if [ -n "$mode" ]; then
    quick=0
    [ "$mode" = quick ] && quick=1
    swept=$(sed -n 's/^# stages=//p' "$DIR/sweep.txt")
    planned=$(QUICK=$quick BUILDROOT=$BUILD TRADE_STAGES=$swept tests/trade/trade.sh --plan | wc -l)
    check "trade.csv rows = runs of the $mode plan" "$rows rows, the plan has $planned runs" [ "$rows" = "$planned" ]
    now=$(BUILDROOT=$BUILD tests/trade/trade.sh --stages)
    check "the sweep covers the stages built now" "swept: $swept; built now: $now: stale, run make trade again" \
        [ "$swept" = "$now" ]
else
    fail "sweep.txt says which sweep ran" "no '# mode=' line in $DIR/sweep.txt"
fi

commands=$(grep -c '^[^#]' "$DIR/sweep.txt" 2>/dev/null || echo 0)
check "sweep.txt: one command line per row" "$commands commands for $rows rows" [ "$commands" = "$rows" ]

# Every row: field count, numbers, threads, errors where references exist.
bad=$(awk -F, '
    NR == 1 { n = NF; for (i = 1; i <= NF; i++) c[$i] = i; next }
    function isnum(x) { return x ~ /^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$/ }
    function bad(msg) { printf "line %d: %s\n", NR, msg; nbad++ }
    NF != n { bad("expected " n " fields, got " NF); next }
    {
        split("seed seconds_render seconds_total rays_camera rays_shadow rays_secondary spp width height threads triangles cpu_seconds attempts", req, " ")
        for (i in req) if (!isnum($c[req[i]])) bad(req[i] " is not a number: \"" $c[req[i]] "\"")
        if (!($c["seconds_render"] > 0)) bad("seconds_render <= 0")
        if ($c["threads"] != 2) bad("threads " $c["threads"] ", expected 2")
        if ($c["rays_camera"] < $c["width"] * $c["height"]) bad("fewer camera rays than pixels")
        mesh = ($c["scene"] ~ /^mesh_/)
        split("relmse_gi rmse_gi mae_gi frac5_gi", gi, " ")
        split("relmse_own rmse_own mae_own frac5_own", own, " ")
        for (i = 1; i <= 4; i++) {
            if (mesh != ($c[gi[i]] == "")) bad(gi[i] (mesh ? " on a mesh scene" : " missing"))
            if ($c[gi[i]] != "" && !(isnum($c[gi[i]]) && $c[gi[i]] >= 0)) bad(gi[i] " not a number >= 0")
            if (($c["own_ref"] == "") != ($c[own[i]] == "")) bad(own[i] " does not match own_ref")
            if ($c[own[i]] != "" && !(isnum($c[own[i]]) && $c[own[i]] >= 0)) bad(own[i] " not a number >= 0")
        }
        if ($c["frac5_gi"] > 1 || $c["frac5_own"] > 1) bad("frac5 > 1")
        if (!mesh && !(isnum($c["efficiency"]) && $c["efficiency"] > 0)) bad("efficiency missing")
        if ($c["own_ref"] !~ /^(direct|gi|)$/) bad("own_ref " $c["own_ref"])
    }
    END { exit nbad > 0 }' "$CSV" | head -n 5)
check "trade.csv rows well formed" "$bad" [ -z "$bad" ]

# ---- the SVGs --------------------------------------------------------------
svg_ok() { # svg_ok FILE: well-formed XML, an <svg> root
    if command -v xmllint >/dev/null 2>&1; then
        xmllint --noout "$1" 2>/dev/null || return 1
    else
        awk '
            BEGIN { RS = "<"; depth = 0; bad = 0; roots = 0 }
            NR == 1 { if ($0 !~ /^[ \t\r\n]*$/) bad = 1; next }
            /^[?]/ { if ($0 !~ /^[?][^>]*[?]>/) bad = 1; next }
            incomment { if (index($0, "-->")) incomment = 0; next }
            incdata { if (index($0, "]]>")) incdata = 0; next }
            /^!--/ { if (!index($0, "-->")) incomment = 1; next }
            /^!\[CDATA\[/ { if (!index($0, "]]>")) incdata = 1; next }
            /^!DOCTYPE[ \t\r\n]/ { if (roots || !index($0, ">")) bad = 1; next }
            {
                tag = $0; sub(/>.*/, "", tag)
                if (index($0, ">") == 0) { bad = 1; next }
                if (tag ~ /^\//) {
                    name = substr(tag, 2); sub(/[ \t\r\n].*/, "", name)
                    if (depth == 0 || stack[depth] != name) bad = 1
                    else depth--
                } else {
                    name = tag; sub(/[ \t\r\n\/].*/, "", name)
                    if (name !~ /^[A-Za-z_][A-Za-z0-9_.:-]*$/) bad = 1
                    if (depth == 0) roots++
                    if (depth == 0 && name != "svg") bad = 1
                    if (tag !~ /\/$/) stack[++depth] = name
                }
                # Text between tags: no stray "<" (split on it) and quotes balanced in the tag.
                q = tag; n = gsub(/"/, "", q); if (n % 2) bad = 1
            }
            END { exit (bad || depth != 0 || roots != 1) }' "$1" || return 1
    fi
    grep -q '<svg' "$1"
}
nsvg=0
badsvg=""
for f in "$DIR"/*.svg; do
    [ -e "$f" ] || continue
    nsvg=$((nsvg + 1))
    svg_ok "$f" || badsvg="$badsvg ${f##*/}"
done
how=awk
command -v xmllint >/dev/null 2>&1 && how=xmllint
check "$nsvg SVG files well formed ($how)" "malformed:$badsvg" [ -z "$badsvg" -a "$nsvg" -gt 0 ]

missing=""
for want in summary $(awk -F, 'NR > 1 && !s[$1]++ { print $1 }' "$CSV"); do
    [ -f "$DIR/$want.svg" ] || missing="$missing $want.svg"
done
for st in $(awk -F, 'NR > 1 && $1 ~ /^0[67]_/ && !s[$1]++ { print $1 }' "$CSV"); do
    ls "$DIR/${st}_spp_"*.svg >/dev/null 2>&1 || missing="$missing ${st}_spp_*.svg"
done
check "summary and per-stage plots exist" "missing:$missing" [ -z "$missing" ]

# ---- the README ------------------------------------------------------------
README=$DIR/README.md
if [ -f "$README" ]; then
    ok "README.md exists"
    want=$(awk -F, 'NR > 1 && $2 ~ /^cornell_/ && !s[$1, $2]++ { n++ } END { print n + 0 }' "$CSV")
    got=$(awk '/^## Cheapest setting/ { on = 1; next } /^## / { on = 0 } on && /^\| [0-9][0-9]_/ { n++ } END { print n + 0 }' "$README")
    check "README: cheapest-setting table, one line per stage and scene" "$got lines, $want stage/scene pairs" \
        [ "$got" = "$want" -a "$want" -gt 0 ]
    check "README: cheapest-setting table header" "" grep -q '^| stage | scene | against | cheapest setting | relMSE | seconds | rays |$' "$README"
    nq=$(grep -c '^## [1-5]\. ' "$README")
    check "README: the five questions answered" "$nq of 5 sections" [ "$nq" = 5 ]
    links=""
    for f in $(grep -o '([0-9A-Za-z_]*\.svg)' "$README" | tr -d '()' | sort -u); do
        [ -f "$DIR/$f" ] || links="$links $f"
    done
    check "README: every linked plot exists" "missing:$links" [ -z "$links" ]
else
    fail "README.md exists" "no $README"
fi

# ---- no absolute paths of this machine -------------------------------------
abs=$(grep -l -F "$PWD/" "$DIR"/*.csv "$DIR"/*.md "$DIR"/*.svg "$DIR"/sweep.txt 2>/dev/null | tr '\n' ' ')
check "no absolute paths in the outputs" "in: $abs" [ -z "$abs" ]

# ---- reproducibility -------------------------------------------------------
if [ $RERUN = 0 ]; then
    skip "same seeds, same rays and errors" "--no-rerun"
elif [ -z "$mode" ] || [ "$rows" != "${planned:-}" ]; then
    skip "same seeds, same rays and errors" "the sweep's plan cannot be rebuilt"
else
    # Seed 2 of the first random setting of each of the last three stages.
    ids=$(awk -F, 'NR > 1 && $4 == 2 && !s[$1]++ { id[++n] = NR - 1 }
        END { for (i = (n > 3 ? n - 2 : 1); i <= n; i++) printf "%s ", id[i] }' "$CSV")
    if [ -z "$ids" ]; then
        skip "same seeds, same rays and errors" "no random setting in the sweep"
    else
        again=$(QUICK=$quick BUILDROOT=$BUILD TRADE_STAGES=$swept tests/trade/trade.sh --rerun $ids 2>/dev/null)
        diffs=""
        i=0
        for id in $ids; do
            i=$((i + 1))
            a=$(sed -n "$((id + 1))p" "$CSV" | cut -d, -f1-4,7-17)
            b=$(echo "$again" | sed -n "${i}p" | cut -d, -f1-4,7-17)
            [ "$a" = "$b" ] || diffs="$diffs row $id: '$a' now '$b';"
        done
        check "same seeds, same rays and errors (rows $ids rendered again)" "$diffs" [ -z "$diffs" ]
    fi
fi

# ---- the downsampler's unit tests -----------------------------------------
if [ -x "${BUILD}trade/bin/test_boxdown" ]; then
    if PFMBOX=${BUILD}trade/bin/pfmbox "${BUILD}trade/bin/test_boxdown" >"${BUILD}trade/test_boxdown.log" 2>&1; then
        ok "box downsampler unit tests ($(tail -n 1 "${BUILD}trade/test_boxdown.log"))"
    else
        fail "box downsampler unit tests" "see ${BUILD}trade/test_boxdown.log"
    fi
else
    skip "box downsampler unit tests" "not built (make -C tests/trade test)"
fi

finish
