#!/bin/sh
# image-hashes.sh - the SHA-256 of every stage's image of every scene of
# scenes/, rendered small (make image-hashes): for a change that must not
# move a pixel (issue 52's restructuring of common/), run it before and
# after and compare.  One line per stage and scene, sorted:
#   STAGE SCENE SHA256        (or "exit N" in place of the hash when the
#                              render fails, e.g. a glTF scene in a build
#                              without tinygltf: a failure must stay one)
# Each render: -W WIDTH (default 16), -s 1, -t 2 (a stage's image does not
# depend on its thread count), the stage's defaults otherwise, PFM.
#
#   image-hashes.sh [--width N] [--stages "01 05"] [--build DIR] [--out FILE] [--compare FILE]
#   image-hashes.sh --self-test
#
# --stages LIST   only these stages (default: every one)
# --build DIR     the build whose renders to hash, under the project (default
#                 build; build/native for make NATIVE=1, whose images must
#                 be the plain build's: CI compares the two)
# --out FILE      write the lines to FILE (default: standard output)
# --compare FILE  compare with FILE, an earlier run's lines: print each
#                 line that differs, exit 1 when one does
# --self-test     check the tool itself on stage 01 at 4 pixels (make test's
#                 part `hashes`): two runs agree, and a changed hash is found
# Run from anywhere after make.  Exit status: 0 done (and the same), 1 a
# difference or a stage not built, 2 usage.
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
width=16
build=build
out=
compare=
stages=
self_test=0
while [ $# -gt 0 ]; do
    case $1 in
        --width) width=${2:?--width needs a number}; shift 2 ;;
        --out) out=${2:?--out needs a file}; shift 2 ;;
        --compare) compare=${2:?--compare needs a file}; shift 2 ;;
        --stages) stages=${2:?--stages needs a list}; shift 2 ;;
        --build) build=${2:?--build needs a directory}; shift 2 ;;
        --self-test) self_test=1; shift ;;
        -h | --help) sed -n '2,/^set -eu/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
        *) echo "image-hashes.sh: unexpected argument: $1" >&2; exit 2 ;;
    esac
done
case $width in '' | *[!0-9]*) echo "image-hashes.sh: --width must be a whole number" >&2; exit 2 ;; esac
[ -z "$compare" ] || [ -f "$compare" ] || { echo "image-hashes.sh: $compare: no such file" >&2; exit 2; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sl-hashes.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' HUP INT PIPE TERM

if [ "$self_test" -eq 1 ]; then
    # Two runs agree; a doctored line is reported and fails the comparison.
    pass=0
    fail=0
    check() {
        if [ "$1" -eq 0 ]; then
            echo "ok   hashes/$2"
            pass=$((pass + 1))
        else
            echo "FAIL hashes/$2"
            fail=$((fail + 1))
        fi
    }
    st=0
    "$0" --stages 01 --width 4 --out "$tmp/a" || st=$?
    [ "$st" -eq 0 ] && grep -q ' [0-9a-f]\{64\}$' "$tmp/a" && st=0 || st=1
    check "$st" "a run of stage 01 hashes its images"
    st=0
    "$0" --stages 01 --width 4 --compare "$tmp/a" >"$tmp/same" || st=$?
    check "$st" "a second run is the same: $(cat "$tmp/same")"
    sed '1s/ [0-9a-f]*$/ 0000/' "$tmp/a" >"$tmp/b"
    st=0
    "$0" --stages 01 --width 4 --compare "$tmp/b" >"$tmp/diff" || st=$?
    [ "$st" -eq 1 ] && grep -q '^before: .* 0000$' "$tmp/diff" && st=0 || st=1
    check "$st" "a changed image is named and fails the comparison"
    echo "$pass passed, $fail failed, 0 skipped"
    [ "$fail" -eq 0 ]
    exit
fi

for dir in "$root"/stages/[0-9][0-9]_*; do
    stage=$(basename "$dir")
    if [ -n "$stages" ]; then
        case " $stages " in *" ${stage%%_*} "* | *" $stage "*) ;; *) continue ;; esac
    fi
    bin=$root/$build/$stage/render
    [ -x "$bin" ] || { echo "image-hashes.sh: $bin: not built (make)" >&2; exit 1; }
    for scene in "$root"/scenes/*.scene "$root"/scenes/*.gltf; do
        [ -f "$scene" ] || continue
        status=0
        "$bin" -q -W "$width" -s 1 -t 2 -o "$tmp/image.pfm" "$scene" >/dev/null 2>&1 </dev/null || status=$?
        if [ "$status" -eq 0 ]; then
            hash=$(sha256sum "$tmp/image.pfm" | cut -d' ' -f1)
        else
            hash="exit $status"
        fi
        rm -f "$tmp/image.pfm"
        echo "$stage $(basename "$scene") $hash"
    done
done | sort >"$tmp/lines"

if [ -n "$out" ]; then
    cp "$tmp/lines" "$out"
elif [ -z "$compare" ]; then
    cat "$tmp/lines"
fi
if [ -n "$compare" ]; then
    if diff "$compare" "$tmp/lines" >"$tmp/diff"; then
        echo "image-hashes.sh: $(wc -l <"$tmp/lines" | tr -d ' ') images, all as in $compare"
    else
        grep '^[<>]' "$tmp/diff" | sed 's/^</before:/; s/^>/after: /'
        exit 1
    fi
fi
