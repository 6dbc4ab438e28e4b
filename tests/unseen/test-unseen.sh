#!/bin/sh
# test-unseen.sh - the tests of make unseen's tools (a part of make test).
#
#   test-unseen.sh
#
# random_scene.py draws the same scene from the same seed, and --unit the
# same scene at scale 1; unseen.sh passes the stages on two random scenes
# (without Mitsuba), and fails, naming the stage and the check, when a
# stage's image holds a NaN or depends on the thread count (stand-in
# render programs in a build of their own).
# Prints "N passed, N failed, N skipped"; exit status 1 if a test failed.
set -eu

PROG=test-unseen.sh
LAB_DIR=$(cd "$(dirname "$0")/../lab" && pwd)
. "$LAB_DIR/lablib.sh"
root=$(cd "$LAB_DIR/../.." && pwd)
dir=$root/tests/unseen
case ${1:-} in -h | --help) show_help "$0"; exit 0 ;; esac

T=$(mktemp -d "${TMPDIR:-/tmp}/test-unseen.XXXXXX")
trap 'rm -rf "$T"' EXIT
trap 'exit 1' HUP INT PIPE TERM
CHECKS=unseen
. "$root/tests/course/checklib.sh"
if ! command -v python3 >/dev/null 2>&1; then
    skip "all (python3 is not installed: random_scene.py needs it)"
    finish
fi

# The scene generator.
python3 "$dir/random_scene.py" 7 >"$T/a"
python3 "$dir/random_scene.py" 7 >"$T/b"
python3 "$dir/random_scene.py" 8 >"$T/c"
python3 "$dir/random_scene.py" 7 --unit >"$T/u"
if cmp -s "$T/a" "$T/b" && ! cmp -s "$T/a" "$T/c"; then ok same-seed-same-scene; else fail same-seed-same-scene; fi
# --unit: the same statements and materials, other coordinates.
words() { sed 1d "$1" | tr ' ' '\n' | grep -v '^[-0-9.e+]*$'; }
if [ "$(words "$T/a")" = "$(words "$T/u")" ] && ! cmp -s "$T/a" "$T/u" &&
    grep -q 'scale 1$' "$T/u"; then
    ok unit-is-the-same-scene
else
    fail unit-is-the-same-scene "$(diff "$T/a" "$T/u" | head -n 10)"
fi
status=0
python3 "$dir/random_scene.py" x >/dev/null 2>&1 || status=$?
if [ "$status" -eq 2 ]; then ok generator-usage; else fail generator-usage "exit $status, not 2"; fi

# Every stage on two random scenes, as built.
missing=
for stage in $(stage_list "$root"); do
    [ -x "$root/build/$stage/render" ] || missing="$missing $stage"
done
if [ -n "$missing" ]; then
    skip "every-stage-on-random-scenes (not built:$missing)"
else
    status=0
    "$dir/unseen.sh" --count 2 --first 11 --spp 8 --no-mitsuba >"$T/out" 2>&1 || status=$?
    if [ "$status" -eq 0 ] && [ "$(grep -c 'every stage ok' "$T/out")" -eq 2 ] &&
        grep -q '^unseen: 2 scenes, 0 with a failed check' "$T/out"; then
        ok every-stage-on-random-scenes
    else
        fail every-stage-on-random-scenes "exit $status: $(cat "$T/out")"
    fi
fi

# Stand-in stages: a PFM of 1 x 1 pixel; stage 02 writes a NaN, stage 03 an
# image that depends on -t.
fake=$T/build/
mkdir -p "${fake}tools"
printf '#!/bin/sh\nexit 0\n' >"${fake}tools/compare"
chmod +x "${fake}tools/compare"
for stage in $(stage_list "$root"); do
    mkdir -p "$fake$stage"
    case $stage in
        02_*) value="'\\000\\000\\300\\177'" ;;
        03_*) value='$threads' ;;
        *) value="'\\000\\000\\200\\077'" ;;
    esac
    cat >"$fake$stage/render" <<EOF
#!/bin/sh
out=
threads=2
while [ \$# -gt 0 ]; do
    case \$1 in
        -o) out=\$2; shift ;;
        -t) threads=\$2; shift ;;
    esac
    shift
done
v=$value
case \$v in 1) v='\\000\\000\\200\\077' ;; 2) v='\\000\\000\\000\\100' ;; esac
{ printf 'PF\\n1 1\\n-1.0\\n'; printf "\$v\$v\$v"; } >"\$out"
EOF
    chmod +x "$fake$stage/render"
done
status=0
BUILDROOT=$fake "$dir/unseen.sh" --count 1 --spp 8 --no-mitsuba >"$T/out" 2>&1 || status=$?
if [ "$status" -eq 1 ] && grep -q ' 02:3-values-not-finite-or-negative' "$T/out" &&
    grep -q ' 03:threads-change-the-image' "$T/out" && ! grep -q ' 01:' "$T/out"; then
    ok failures-are-named
else
    fail failures-are-named "exit $status: $(cat "$T/out")"
fi

finish
