#!/bin/sh
# pathtrace_bench.sh - how fast the last stage (stages/ in order: today
# 09_fast_rays) converges on the bench scenes, beside Mitsuba 3
# when it can be had; it names the stage it runs.
#
# For each scene, the stage with its defaults (the Sobol sampler, MIS, the
# light picker, roulette threshold 0.4, no tree on small scenes) and with each of its
# refinements turned back to stage 07's way: the independent sampler
# (--sampler independent), no MIS (--no-mis), emitting triangles picked by
# area, not power (--no-light-pick), roulette's threshold 1 (--rr-threshold 1),
# the tree on every scene (--brute-force-max 0), and all at once (stage
# 07's path tracer): spp x relMSE
# against Mitsuba's converged reference (a constant for an unbiased
# estimator: relMSE falls as 1/spp), seconds per spp at 256x256 on 2
# threads, and from the two the time to reach the scene's target relMSE
# (1e-3; 1e-2 for the caustics of cornell_specular_area).  bunny_cornell,
# the scene library's bunny in the box, has no reference in the repository:
# Mitsuba LLVM renders one the first time (4096 spp in 16 batches, about 2
# minutes; kept in build/bench-references/), and without Mitsuba it is timed
# only.
# Mitsuba 3 (`path` integrator, independent
# sampler; variants llvm_ad_rgb and scalar_rgb) renders the same scenes
# (tests/bench/mitsuba_render.py translates them: sphere lights, meshes with
# their files' node transforms and materials; a scene it cannot translate
# is timed without Mitsuba, and the line says why), interleaved with ours:
# each round renders every renderer once, ROUNDS rounds (default 3), each
# with its own seed.  A row gives the medians over the rounds, and each
# ratio (a renderer's time to the target over ours, wall-clock and
# processor) as the median of the rounds' ratios, with their range: a
# ratio is taken within one round, where both saw the same load.  The
# processor time (all threads) is the steadier figure on a loaded machine;
# on a quiet one, wall-clock x 2 threads is about the processor time.
# References: the repository's Mitsuba renders (tests/reference/; a scene
# written to match one, cornell_gltf_area, uses it).  A scene without one
# gets two, once, kept in build/bench-references/: Mitsuba LLVM's (4096
# spp) and the stage's own (SELF_SPP, 1024 spp); each renderer is then
# timed to its own converged image (so the time measures noise alone), and
# the two converged images' mean brightness is compared: where they differ
# by more than 2% (smallpt: tests/bench/README.md says why), the line says
# so, and the times are not to the same answer.  Without Mitsuba the stage's own reference serves alone.
# Last, cornell_diffuse_area is rendered by the stage at the spp predicted
# for relMSE 1e-3 (rounded up to whole passes of 16), to check the
# prediction.
#
# Mitsuba is looked for in build/mitsuba-venv (make it with
#   python3 -m venv build/mitsuba-venv
#   build/mitsuba-venv/bin/pip install mitsuba numpy
# ); its LLVM variant needs an LLVM shared library of version 16 or later
# (Debian: apt-get install libllvm19), found in /usr/lib or given by
# DRJIT_LIBLLVM_PATH.  Without Mitsuba the script says so and prints
# the stage alone.
#
# Times, so never part of `make test`.  Run from the project root after
# `make`:  sh tests/bench/pathtrace_bench.sh   (SPP, ROUNDS, SCENES to
# change the defaults 32, 3 and the six scenes: the three boxes, the bunny
# box, smallpt, where MIS pays, and cornell_gltf_area, where the light
# picker does).
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
stage=$(cd "$root/stages" && ls -d [0-9][0-9]_* | tail -n 1)
render=${BUILDROOT:-$root/build/}$stage/render
imgcmp=$root/build/tools/imgcmp
python=$root/build/mitsuba-venv/bin/python
spp=${SPP:-32}
rounds=${ROUNDS:-3}
scenes=${SCENES:-cornell_diffuse_area cornell_specular_area cornell_diffuse_point bunny_cornell smallpt cornell_gltf_area}
work=$(mktemp -d "${TMPDIR:-/tmp}/pathtrace-bench.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT TERM
trap 'exit 1' HUP PIPE

[ -x "$render" ] && [ -x "$imgcmp" ] || {
    echo "pathtrace_bench.sh: run make first" >&2
    exit 2
}

# stat FILE KEY: a number from a --stats JSON file.
stat() {
    sed -n "s/.*\"$2\": \([-0-9.e+]*\).*/\1/p" "$1" | head -n 1
}

# scene_file SCENE: the scene's file (bunny_cornell: the Stanford bunny,
# 69,451 triangles, in the Cornell box of cornell_diffuse_area).
scene_file() {
    echo "$root/scenes/$1.scene"
}

# reference SCENE [RENDERER]: the converged GI image a render of SCENE by
# RENDERER (stagelight*, mitsuba_*) is measured against: the repository's
# Mitsuba reference (tests/reference/; cornell_gltf_area is written to
# match cornell_diffuse_area's), else the renderer's own converged image
# (build/bench-references/: SCENE_mitsuba_gi.pfm, SCENE_self_gi.pfm);
# nothing when there is none.
reference() {
    case $1 in cornell_gltf_area) set -- cornell_diffuse_area "${2:-}" ;; esac
    if [ -f "$root/tests/reference/${1}_gi.pfm" ]; then
        echo "$root/tests/reference/${1}_gi.pfm"
        return
    fi
    case ${2:-stagelight} in
    mitsuba*) f=$root/build/bench-references/${1}_mitsuba_gi.pfm ;;
    *) f=$root/build/bench-references/${1}_self_gi.pfm ;;
    esac
    [ ! -f "$f" ] || echo "$f"
}

# relmse IMAGE SCENE RENDERER: relMSE of IMAGE against the reference of
# SCENE for RENDERER (-1 when there is none).
relmse() {
    ref=$(reference "$2" "$3")
    if [ -z "$ref" ]; then
        echo -1
        return
    fi
    "$imgcmp" --csv "$1" "$ref" |
        awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "relmse") c = i }
                 NR == 2 { print $c }'
}

# mean_ratio A.pfm B.pfm: mean brightness of A over B's (the channels' means summed).
mean_ratio() {
    "$imgcmp" --csv "$1" "$2" |
        awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i }
                 NR == 2 { a = $col["mean_r"] + $col["mean_g"] + $col["mean_b"]
                           b = $col["ref_mean_r"] + $col["ref_mean_g"] + $col["ref_mean_b"]
                           printf "%.4f", a / b }'
}

# target SCENE: the relMSE the scene is timed to.
target() {
    case $1 in
    cornell_specular_area) echo 1e-2 ;;
    *) echo 1e-3 ;;
    esac
}

# ours SCENE SPP SEED [OPTION...]: "wall_seconds cpu_seconds relmse" of one
# render by the stage.
ours() {
    scene=$1 spp_=$2 seed=$3
    shift 3
    "$render" -q -t 2 --spp "$spp_" --seed "$seed" "$@" -o "$work/ours.pfm" --stats "$work/s.json" \
        "$(scene_file "$scene")"
    echo "$(stat "$work/s.json" seconds_render) $(stat "$work/s.json" seconds_render_cpu)" \
        "$(relmse "$work/ours.pfm" "$scene" stagelight)"
}

# mitsuba VARIANT SCENE SPP SEED: the same for Mitsuba (nothing if it fails).
mitsuba() {
    out=$("$python" "$root/tests/bench/mitsuba_render.py" "$1" "$(scene_file "$2")" \
        "$3" "$4" 2 "$work/mi.pfm" 2>"$work/mi.err") || {
        echo "  (mitsuba $1 failed: $(tail -n 1 "$work/mi.err"))" >&2
        return 0
    }
    echo "$out" | awk '{ printf "%s %s ", $2, $4 }'
    relmse "$work/mi.pfm" "$2" "mitsuba_$1"
}

# A build without tinygltf (make config) loads no mesh: a scene that needs
# one (the bunny box) is left out, and said so.
if "$render" --version | grep -q 'glTF: no'; then
    kept=
    for scene in $scenes; do
        if "$render" -q -t 1 -W 1 -H 1 --spp 1 -o "$work/probe.pfm" "$(scene_file "$scene")" \
            2>"$work/probe.err"; then
            kept="$kept $scene"
        elif grep -q 'no glTF support' "$work/probe.err"; then
            echo "$scene: left out: this build has no glTF support (apt-get install libtinygltf-dev)"
        else
            cat "$work/probe.err" >&2
            exit 1
        fi
    done
    scenes=$kept
fi

# Mitsuba's variants that work here.
variants=""
if [ -x "$python" ] && "$python" -c 'import mitsuba, numpy' 2>/dev/null; then
    if [ -z "${DRJIT_LIBLLVM_PATH:-}" ]; then
        # The newest LLVM of 16 or later (15's x86 back end failed on
        # Dr.Jit 1.5's kernels here; 14 is refused).
        best=15
        for lib in /usr/lib/*/libLLVM*.so* /usr/lib/llvm-*/lib/libLLVM*.so*; do
            [ -f "$lib" ] || continue
            v=$(echo "$lib" | sed -n 's/.*[Ll][Ll][Vv][Mm][^0-9]*\([0-9][0-9]*\).*/\1/p')
            if [ -n "$v" ] && [ "$v" -gt "$best" ]; then
                best=$v
                DRJIT_LIBLLVM_PATH=$lib
            fi
        done
        export DRJIT_LIBLLVM_PATH
    fi
    for v in llvm_ad_rgb scalar_rgb; do
        if "$python" -c "import mitsuba as mi; mi.set_variant('$v')" 2>/dev/null; then
            variants="$variants $v"
        fi
    done
fi
if [ -z "$variants" ]; then
    echo "Mitsuba 3 is not available (build/mitsuba-venv; see the comment at the top of"
    echo "tests/bench/pathtrace_bench.sh): $stage alone."
else
    echo "Mitsuba 3 $("$python" -c 'import mitsuba; print(mitsuba.__version__)'):$variants" \
        "(LLVM: ${DRJIT_LIBLLVM_PATH:-none})"
fi

# The references the repository lacks: Mitsuba LLVM's, rendered once.  At
# 4096 spp its own relMSE is spp x relMSE / 4096, 0.16 / 4096 = 4e-5 on the
# bunny box, which adds under 2% to any 32-spp render's relMSE there
# (2.5e-3 for stagelight, 4.9e-3 for Mitsuba, measured).
for scene in $scenes; do
    case " $variants " in *" llvm_ad_rgb "*) ;; *) break ;; esac
    [ -z "$(reference "$scene" mitsuba_llvm_ad_rgb)" ] || continue
    mkdir -p "$root/build/bench-references"
    out=$root/build/bench-references/${scene}_mitsuba_gi.pfm
    echo "$scene: no reference; Mitsuba LLVM renders its own (4096 spp) into build/bench-references/"
    if "$python" "$root/tests/bench/mitsuba_render.py" llvm_ad_rgb "$(scene_file "$scene")" \
        4096 7001 2 "$out.tmp.pfm" 16 >/dev/null 2>"$work/mi.err"; then
        mv -f "$out.tmp.pfm" "$out"
    else
        rm -f "$out.tmp.pfm"
        echo "  (failed: $(tail -n 1 "$work/mi.err"))"
    fi
done

# And the stage's own, at SELF_SPP (1024) spp: its renders are measured
# against it (each variant is unbiased; the reference's noise adds spp /
# SELF_SPP of a render's relMSE to every row alike).  It costs about 9
# processor minutes on smallpt (512 x 384), once.
for scene in $scenes; do
    [ -z "$(reference "$scene" stagelight)" ] || continue
    mkdir -p "$root/build/bench-references"
    out=$root/build/bench-references/${scene}_self_gi.pfm
    echo "$scene: no reference; the stage renders its own (${SELF_SPP:-1024} spp, seed 7001)"
    "$render" -q -t 2 --spp "${SELF_SPP:-1024}" --seed 7001 -o "$out.tmp.pfm" \
        "$(scene_file "$scene")" && mv -f "$out.tmp.pfm" "$out"
done

echo "stagelight: $stage (the last stage); 2 threads, $spp spp, $rounds interleaved rounds" \
    "(medians; ratios: the median of the rounds' ratios, their range in brackets);" \
    "load average $(cut -d' ' -f1-3 /proc/loadavg)"

for scene in $scenes; do
    : >"$work/rows"
    for round in $(seq 1 "$rounds"); do
        echo "stagelight $round $(ours "$scene" "$spp" "$round")" >>"$work/rows"
        echo "stagelight_independent $round $(ours "$scene" "$spp" "$round" \
            --sampler independent)" >>"$work/rows"
        echo "stagelight_no_mis $round $(ours "$scene" "$spp" "$round" --no-mis)" >>"$work/rows"
        echo "stagelight_no_light_pick $round $(ours "$scene" "$spp" "$round" --no-light-pick)" \
            >>"$work/rows"
        echo "stagelight_rr_threshold_1 $round $(ours "$scene" "$spp" "$round" --rr-threshold 1)" \
            >>"$work/rows"
        echo "stagelight_tree_always $round $(ours "$scene" "$spp" "$round" --brute-force-max 0)" \
            >>"$work/rows"
        echo "stagelight_as_stage_07 $round $(ours "$scene" "$spp" "$round" --sampler independent \
            --rr-threshold 1 --brute-force-max 0 --no-mis --no-light-pick)" >>"$work/rows"
        for v in $variants; do
            r=$(mitsuba "$v" "$scene" "$spp" "$round")
            [ -z "$r" ] || echo "mitsuba_$v $round $r" >>"$work/rows"
        done
    done
    t=$(target "$scene")
    size="$(stat "$work/s.json" width)x$(stat "$work/s.json" height)"
    own=$(reference "$scene" stagelight)
    case $own in
    "$root"/tests/reference/*) against="against $(basename "$own")" ;;
    "") against="no reference" ;;
    *) against="each renderer against its own converged image" ;;
    esac
    echo
    echo "$scene ($size; time to relMSE $t, $against)"
    awk -v spp="$spp" -v t="$t" '
        # the median of v[1..n], and in lo, hi its least and greatest
        function median(v, n,    i, j, x, s) {
            for (i = 1; i <= n; i++) s[i] = v[i]
            for (i = 2; i <= n; i++) {
                x = s[i]
                for (j = i - 1; j >= 1 && s[j] > x; j--) s[j + 1] = s[j]
                s[j + 1] = x
            }
            lo = s[1]; hi = s[n]
            return n % 2 ? s[(n + 1) / 2] : (s[n / 2] + s[n / 2 + 1]) / 2
        }
        function ratio_cell(v, n,    m) {
            m = median(v, n)
            return sprintf("%.2fx [%.2f-%.2f]", m, lo, hi)
        }
        { r = $1; k = ++n[r]; round[r, k] = $2; w[r, k] = $3; u[r, k] = $4
          c[r] += $5 * spp; if ($5 < 0) noref[r] = 1
          if (!seen[r]++) order[++m] = r }
        END {
            printf "| %-24s | %12s | %9s | %13s | %14s | %19s | %14s | %19s |\n", "renderer",
                "spp x relMSE", "s per spp", "CPU s per spp", "time to " t, "time / ours",
                "CPU s to " t, "CPU / ours"
            print "|---|---:|---:|---:|---:|---:|---:|---:|"
            for (i = 1; i <= m; i++) {
                r = order[i]; cc[r] = noref[r] ? 1 : c[r] / n[r] / t
                for (k = 1; k <= n[r]; k++) {
                    tw[r, round[r, k]] = cc[r] * w[r, k] / spp
                    tc[r, round[r, k]] = cc[r] * u[r, k] / spp
                }
            }
            for (i = 1; i <= m; i++) {
                r = order[i]
                split("", a); split("", b); split("", e); split("", f); split("", g); split("", h)
                for (k = 1; k <= n[r]; k++) {
                    q = round[r, k]
                    a[k] = w[r, k] / spp; b[k] = u[r, k] / spp
                    e[k] = tw[r, q]; f[k] = tc[r, q]
                    g[k] = tw[r, q] / tw["stagelight", q]; h[k] = tc[r, q] / tc["stagelight", q]
                }
                printf "| %-24s | %12s | %9.4f | %13.4f | %14s | %19s | %14s | %19s |\n", r,
                    noref[r] ? "-" : sprintf("%.4f", c[r] / n[r]), median(a, n[r]),
                    median(b, n[r]), noref[r] ? "-" : sprintf("%.2f s", median(e, n[r])),
                    ratio_cell(g, n[r]), noref[r] ? "-" : sprintf("%.2f s", median(f, n[r])),
                    ratio_cell(h, n[r])
                if (r == "mitsuba_llvm_ad_rgb") {
                    for (k = 1; k <= n[r]; k++) h[k] = 1 / h[k]
                    verdict = sprintf("stagelight / Mitsuba LLVM, processor time to relMSE %s: %s", t,
                        ratio_cell(h, n[r]))
                }
            }
            if (verdict != "") print verdict
        }' "$work/rows"
    mine=$root/build/bench-references/${scene}_self_gi.pfm
    theirs=$root/build/bench-references/${scene}_mitsuba_gi.pfm
    case $own in "$root"/tests/reference/*) mine= ;; esac
    if [ -n "$mine" ] && [ -f "$mine" ] && [ -f "$theirs" ]; then
        mr=$(mean_ratio "$theirs" "$mine")
        echo "converged images: Mitsuba's mean brightness differs from the stage's by $(awk -v r="$mr" 'BEGIN {
            printf "%+.1f%%", 100 * (r - 1) }')$(awk -v r="$mr" 'BEGIN {
            if (r > 1.02 || r < 0.98) printf ": they disagree (over 2%%), so the times above are to different answers" }')"
    fi
    if [ "$scene" = cornell_diffuse_area ]; then
        # Rounded up to whole passes of 16 samples: the stage draws its
        # Sobol points pass by pass (passes of the largest divisor of spp
        # up to 16), so a prime spp such as 59 runs passes of one sample,
        # which is the independent sampler in effect (measured: relMSE
        # 2.0e-3 at 59 spp where 1e-3 was predicted).
        predict=$(awk -v spp="$spp" '$1 == "stagelight" { c += $5 * spp; n++ }
            END { p = int(c / n / 1e-3 + 0.999); printf "%d", int((p + 15) / 16) * 16 }' "$work/rows")
    fi
done

if [ -n "${predict:-}" ]; then
    check=$(ours cornell_diffuse_area "$predict" 99)
    echo
    echo "$stage on cornell_diffuse_area at the $predict spp predicted for relMSE 1e-3:" \
        "$(echo "$check" | awk '{ printf "%.2f s (cpu %.2f s), relMSE %.2e", $1, $2, $3 }')"
fi
