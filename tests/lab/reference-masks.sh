#!/bin/sh
# reference-masks.sh - the feature masks of the reference scenes.
#
#   reference-masks.sh [--help] [--check]     (make reference-masks)
#
# For each scene of the references in tests/reference/ (NAME_direct.pfm
# and NAME_gi.pfm are renders of scenes/NAME.scene), writes
# tests/reference/NAME.feature.pfm: stage 07's `--aov feature` pass of the
# scene at the reference's size (docs/aov.md).  make grade breaks a lab's
# error down by these regions (compare --regions).  The label depends on
# the scene alone, not on the stage's sampling, so the masks are
# reproducible: --check renders them again and fails when one differs
# from the stored file (build/07_pathtrace/render must be built).
# Exit status: 0 written (or, --check, all equal), 1 a render failed or a
# mask differs, 2 usage.
set -eu

PROG=reference-masks.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

check=0
case ${1:-} in
    -h | --help) show_help "$0"; exit 0 ;;
    --check) check=1; shift ;;
esac
[ $# -eq 0 ] || usage_error "unexpected argument: $1"
root=$(cd "$LAB_DIR/../.." && pwd)
render=${BUILDROOT:-$root/build/}07_pathtrace/render
[ -x "$render" ] || die "no $render: build stage 07 first (make 07_pathtrace)"
refs=$root/tests/reference
work=$(mktemp -d "${TMPDIR:-/tmp}/masks.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM

status=0
for scene in $(ls "$refs" | sed -n -e 's/_direct\.pfm$//p' -e 's/_gi\.pfm$//p' | sort -u); do
    size=$(head -c 64 "$refs/$(ls "$refs" | grep "^${scene}_" | head -n 1)" | sed -n 2p)
    set -- $size
    "$render" -q -s 1 -t 1 -W "$1" -H "$2" --aov feature -o "$work/$scene.pfm" \
        "$root/scenes/$scene.scene" || die "stage 07 could not render scenes/$scene.scene"
    if [ "$check" -eq 1 ]; then
        if cmp -s "$work/$scene.feature.pfm" "$refs/$scene.feature.pfm"; then
            echo "ok   $scene.feature.pfm"
        else
            echo "FAIL $scene.feature.pfm differs from what stage 07 writes now (make reference-masks)"
            status=1
        fi
    else
        mv "$work/$scene.feature.pfm" "$refs/$scene.feature.pfm"
        echo "wrote tests/reference/$scene.feature.pfm"
    fi
done
exit "$status"
