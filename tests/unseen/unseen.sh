#!/bin/sh
# unseen.sh - every stage on random scenes nobody tuned it to (make unseen).
#
#   unseen.sh [options]
#
# For each seed, tests/unseen/random_scene.py draws a scene twice: at a
# random scale (10^-3 to 10^3) far from the origin, and the same scene at
# scale 1 around it (--unit).  Then:
#   1. every stage renders the scaled scene (SPP / 8 samples): exit status
#      0, every pixel finite and >= 0;
#   2. every stage renders it again with 1 and with 2 threads: the same
#      bytes (the image must not depend on the thread count);
#   3. the last stage's image of the scaled scene beside its image of the
#      unit one: the relative difference of their means (radiance does not
#      depend on the units), printed;
#   4. with Mitsuba 3 (build/mitsuba-venv, as for make bench): a reference
#      of the unit scene (REF_SPP samples, scalar_rgb), and compare's verdict
#      on two renders (SPP samples, seeds 1 and 2) of each stage from
#      07_pathtrace on (the physically based ones) against it.
# Exit status 1 when a check of 1 or 2 fails (a crash, a NaN, an image that
# depends on the threads).  3 and 4 are printed and counted, not failed on:
# compare calls correct work biased with probability up to 0.01 a run, and
# Mitsuba's reference has noise of its own and, in single precision, errors
# of its own at small scales (docs/unseen.md).  The references are kept in
# build/unseen/ under the scene's checksum and REF_SPP.
#
# Options:
#   --count N     scenes (default 12)
#   --first SEED  the first seed (default 1)
#   --spp N       samples per pixel of the renders judged (default 256)
#   --ref-spp N   Mitsuba's samples per pixel (default 32768: 64 times the
#                 two renders' together)
#   --no-mitsuba  skip 4
#   --help
# Exit status: 0 checked, 1 a check failed or a tool is missing, 2 usage.
set -eu

PROG=unseen.sh
LAB_DIR=$(cd "$(dirname "$0")/../lab" && pwd)
. "$LAB_DIR/lablib.sh"
root=$(cd "$LAB_DIR/../.." && pwd)

count=12
first=1
spp=256
ref_spp=32768
mitsuba=1
parse_options '--count count=VALUE --first first=VALUE --spp spp=VALUE --ref-spp ref_spp=VALUE
    --no-mitsuba mitsuba=0' "$@"
shift "$po_used"
[ $# -eq 0 ] || usage_error "unexpected argument: $1"
for n in "$count" "$first" "$spp" "$ref_spp"; do
    case $n in '' | *[!0-9]*) usage_error "expected a whole number, got '$n'" ;; esac
done
[ "$spp" -ge 8 ] || usage_error "--spp must be at least 8, got $spp"

# The stages and tools to run (BUILDROOT: another build, e.g. build/sanitize/).
build=${BUILDROOT:-$root/build/}
compare=${build}tools/compare
python=$root/build/mitsuba-venv/bin/python
command -v python3 >/dev/null 2>&1 || die "python3 is needed (random_scene.py)"
[ -x "$compare" ] || die "no $compare: run make first"
stages=$(stage_list "$root")
for stage in $stages; do
    [ -x "$build$stage/render" ] || die "no $build$stage/render: run make first"
done
last=$(echo "$stages" | tail -n 1)
if [ "$mitsuba" = 1 ] && ! "$python" -c 'import mitsuba' 2>/dev/null; then
    echo "unseen: Mitsuba 3 is not in build/mitsuba-venv (see tests/bench/pathtrace_bench.sh): no reference renders"
    mitsuba=0
fi
out=$root/build/unseen
mkdir -p "$out"
work=$(mktemp -d "${TMPDIR:-/tmp}/unseen.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM

# pfm_check FILE - "MEAN BAD": the mean of all channels of a PFM image and
# the number of its values that are not finite or are negative.
pfm_check() {
    python3 - "$1" <<'EOF'
import math, struct, sys
data = open(sys.argv[1], "rb").read()
lines = data.split(b"\n", 3)
w, h = map(int, lines[1].split())
scale = float(lines[2])
values = struct.unpack(("<" if scale < 0 else ">") + "%df" % (3 * w * h), lines[3][:12 * w * h])
bad = sum(1 for v in values if not math.isfinite(v) or v < 0)
print("%.17g %d" % (math.fsum(v for v in values if math.isfinite(v)) / len(values), bad))
EOF
}

failures=0
scenes=0
max_scale_diff=0
biased_list=
judged=0
seed=$first
while [ "$seed" -lt $((first + count)) ]; do
    python3 "$root/tests/unseen/random_scene.py" "$seed" >"$work/scaled.scene"
    python3 "$root/tests/unseen/random_scene.py" "$seed" --unit >"$work/unit.scene"
    line="seed $seed ($(sed -n 's/^image width \([0-9]*\) height \([0-9]*\)$/\1x\2/p' "$work/scaled.scene"), $(sed -n '1s/.*: //p' "$work/scaled.scene")):"
    problems=
    for stage in $stages; do
        render=$build$stage/render
        nn=${stage%%_*}
        if ! "$render" -q -t 2 -s $((spp / 8)) "$work/scaled.scene" -o "$work/a.pfm" 2>"$work/err"; then
            problems="$problems $nn:exit($(head -n 1 "$work/err"))"
            continue
        fi
        set -- $(pfm_check "$work/a.pfm")
        [ "$2" -eq 0 ] || problems="$problems $nn:$2-values-not-finite-or-negative"
        "$render" -q -t 1 -s 4 --seed 9 "$work/scaled.scene" -o "$work/t1.pfm" 2>/dev/null || true
        "$render" -q -t 2 -s 4 --seed 9 "$work/scaled.scene" -o "$work/t2.pfm" 2>/dev/null || true
        cmp -s "$work/t1.pfm" "$work/t2.pfm" || problems="$problems $nn:threads-change-the-image"
    done
    if [ -n "$problems" ]; then
        line="$line FAILED:$problems"
        failures=$((failures + 1))
    else
        line="$line every stage ok"
    fi
    # 3: the last stage, the same seed, both scales.
    rm -f "$work/s.pfm" "$work/u.pfm"
    "$build$last/render" -q -t 2 -s $((spp / 8)) --seed 5 "$work/scaled.scene" -o "$work/s.pfm" 2>/dev/null || true
    "$build$last/render" -q -t 2 -s $((spp / 8)) --seed 5 "$work/unit.scene" -o "$work/u.pfm" 2>/dev/null || true
    if [ -f "$work/s.pfm" ] && [ -f "$work/u.pfm" ]; then
        diff=$(python3 -c 'import sys; a, b = float(sys.argv[1]), float(sys.argv[2]); print("%.2g" % (abs(a - b) / b if b > 0 else abs(a - b)))' \
            "$(pfm_check "$work/s.pfm" | cut -d' ' -f1)" "$(pfm_check "$work/u.pfm" | cut -d' ' -f1)")
        max_scale_diff=$(python3 -c 'import sys; print("%.2g" % max(float(sys.argv[1]), float(sys.argv[2])))' "$max_scale_diff" "$diff")
        line="$line; scale $diff"
    else
        line="$line; scale: not rendered"
    fi
    # 4: against Mitsuba.
    if [ "$mitsuba" = 1 ]; then
        ref=$out/$(cksum <"$work/unit.scene" | cut -d' ' -f1)-$ref_spp.pfm
        if [ ! -f "$ref" ]; then
            "$python" "$root/tests/bench/mitsuba_render.py" scalar_rgb "$work/unit.scene" "$ref_spp" 7 2 \
                "$work/ref.pfm" 16 >"$work/mitsuba.log" 2>&1 || die "Mitsuba failed on seed $seed: $(tail -n 1 "$work/mitsuba.log")"
            mv "$work/ref.pfm" "$ref"
        fi
        for stage in $stages; do
            [ "${stage%%_*}" -ge 7 ] || continue
            for s in 1 2; do
                "$build$stage/render" -q -t 2 -s "$spp" --seed "$s" "$work/unit.scene" -o "$work/r$s.pfm" 2>/dev/null
            done
            status=0
            "$compare" "$work/r1.pfm" "$work/r2.pfm" "$ref" >"$work/cmp" 2>&1 || status=$?
            judged=$((judged + 1))
            case $status in
                0) line="$line; ${stage%%_*} consistent" ;;
                1) line="$line; ${stage%%_*} BIASED ($(sed -n 's/^worst *//p' "$work/cmp"))"
                   biased_list="$biased_list $seed/${stage%%_*}" ;;
                *) die "compare failed on seed $seed: $(head -n 1 "$work/cmp")" ;;
            esac
        done
    fi
    echo "$line"
    scenes=$((scenes + 1))
    seed=$((seed + 1))
done

echo "unseen: $scenes scenes, $failures with a failed check (1, 2); the largest relative difference of the means of a scene at its scale and at scale 1: $max_scale_diff"
if [ "$mitsuba" = 1 ]; then
    echo "unseen: against Mitsuba, 'biased' in $(echo $biased_list | wc -w) of $judged verdicts (at alpha 0.01, about $(python3 -c "print('%.1f' % (0.01 * $judged))") by chance):${biased_list:- none}"
fi
[ "$failures" -eq 0 ]
