#!/bin/sh
# autograder.sh - the Gradescope autograder of one lab.
#
#   autograder.sh [options] STAGE OUT         (make autograder STAGE=05 OUT=dir)
#
# Writes OUT/autograder.zip, the file Gradescope's "Configure Autograder"
# takes, and OUT/autograder/, the same files unpacked:
#   setup.sh        Gradescope runs it once, as root, to build the image:
#                   installs the packages of .devcontainer/packages (the
#                   list CI installs; a name the image's distribution lacks
#                   is skipped with a warning) and builds the handout
#   run_autograder  Gradescope runs it for each submission: takes the
#                   student's stages/NN_name/ from /autograder/submission (a
#                   repository or a zip of the handout, with or without a
#                   top folder; or the stage's files alone), puts it into a
#                   fresh copy of the untouched handout, grades it as make
#                   grade does (grade.sh with the project's tests, controls
#                   unscored) and writes /autograder/results/results.json
#                   (results.awk).  AUTOGRADER_ROOT moves /autograder (tests)
#   handout/        the untouched handout of the lab (no solution in it)
#   controls        the lab's controls (tests/course/controls/NN_name; found
#                   by running the untouched handout where there is none)
#   tools/          the grading scripts: tests/lab/grade.sh and what it uses
#   lab-total       the points: the lab's tests less its controls
# The assignment's total in Gradescope: one point per scored test, printed
# at the end (make grade's lab_total).
#
# Options:
#   --timeout SEC  time limit of one test program (default 300)
#   --spp N|auto|paired  the report pages (grade.sh --spp; default paired,
#                  as make grade's: the scored paired pages and the Mitsuba
#                  pages at 16 spp, seconds a page; auto: the calibrated
#                  Mitsuba pages too, about 12 processor minutes for lab 07;
#                  N: their samples; tests/course/README.md)
#   --root DIR     the project (default: this script's)
#   --help
# Exit status: 0 written, 1 error, 2 usage.
set -eu

PROG=autograder.sh
COURSE_DIR=$(cd "$(dirname "$0")" && pwd)
LAB_DIR=$COURSE_DIR/../lab
. "$LAB_DIR/lablib.sh"

root=$(cd "$COURSE_DIR/../.." && pwd)
limit=300
spp=paired
parse_options '--timeout limit=VALUE --spp spp=VALUE --root root=DIR' "$@"
shift "$po_used"
[ $# -eq 2 ] || usage_error "expected STAGE and OUT, got $# argument(s)"
case $limit in '' | *[!0-9]*) usage_error "--timeout needs a number of seconds, got '$limit'" ;; esac
check_spp "$spp" auto
stage=$(resolve_stage "$root" "$1")
out=$2
command -v python3 >/dev/null 2>&1 || die "python3 is needed to write the zip (it is in .devcontainer/packages)"

mkdir -p "$out" || die "cannot write $out"
out=$(abs_dir "$out")
dest=$out/autograder
# (An earlier autograder's handout is updated in place, its build kept:
# make grade-class builds it once and reruns rebuild nothing.)
[ ! -d "$dest/handout" ] || [ "$(handout_stage "$dest/handout")" = "$stage" ] || rm -rf "$dest/handout"
rm -rf "$dest/tools" "$dest/controls" "$dest/setup.sh" "$dest/run_autograder" "$dest/lab-total" "$out/autograder.zip"
mkdir -p "$dest/tools/tests/lab" "$dest/tools/tests/harness" "$dest/tools/tests/course"

"$LAB_DIR/make-lab.sh" --quiet --discard-changes --root "$root" "$stage" "$dest/handout" ||
    die "could not write the handout of $stage"
for f in grade.sh grade.awk lablib.sh grade-pages.sh; do
    cp "$LAB_DIR/$f" "$dest/tools/tests/lab/"
done
cp "$root/tests/harness/with-timeout.sh" "$dest/tools/tests/harness/"
cp "$COURSE_DIR/results.awk" "$COURSE_DIR/relocate-deps.sh" "$dest/tools/tests/course/"
if [ -f "$root/tests/course/controls/$stage" ]; then
    cp "$root/tests/course/controls/$stage" "$dest/controls"
else
    echo "$PROG: no tests/course/controls/$stage: finding the controls in the untouched handout"
    "$LAB_DIR/grade.sh" --no-pages --root "$root" --timeout "$limit" --save-controls "$dest/controls" \
        "$dest/handout" >"$out/controls.log" 2>&1 || die "could not grade the untouched handout (log: $out/controls.log)"
    rm -rf "$dest/handout/build" "$dest/handout/grade"
fi
sed -e "s/@STAGE@/$stage/g" "$COURSE_DIR/setup.sh.in" >"$dest/setup.sh"
sed -e "s/@STAGE@/$stage/g" -e "s/@TIMEOUT@/$limit/g" -e "s/@SPP@/$spp/g" "$COURSE_DIR/run_autograder.in" >"$dest/run_autograder"
chmod +x "$dest/setup.sh" "$dest/run_autograder"

# The zip: setup.sh and run_autograder at its top, as Gradescope wants them
# (python3's zipfile keeps the files' modes); no build.
(cd "$dest" && python3 - "$out/autograder.zip.tmp" <<'PY'
import os, sys, zipfile
with zipfile.ZipFile(sys.argv[1], "w", zipfile.ZIP_DEFLATED) as z:
    for top, dirs, files in os.walk("."):
        if top == "./handout":
            dirs[:] = [d for d in dirs if d not in ("build", "grade")]
        dirs.sort()
        for f in sorted(files):
            path = os.path.join(top, f)[2:]
            z.write(path, path)
PY
) || die "could not write $out/autograder.zip"
mv "$out/autograder.zip.tmp" "$out/autograder.zip"
# The points: the lab's tests less its controls, and its paired pages
# (scored tests of the lab too; grade-class.sh reads the total).
total=0
for src in $(handout_tests "$dest/handout"); do
    [ "$(test_from "$src")" = "${stage%%_*}" ] || continue
    for t in $(test_names "$src"); do
        grep -qx "$(basename "$src" .c) $t" "$dest/controls" || total=$((total + 1))
    done
done
for scene in $(paired_scenes "${stage%%_*}"); do
    [ ! -f "$dest/handout/tests/reference/solution/$scene.pfm" ] || total=$((total + 1))
done
echo "$total" >"$dest/lab-total"
echo "$PROG: wrote $out/autograder.zip (lab ${stage%%_*}, $stage): upload it in Gradescope's Configure Autograder;"
echo "$PROG: the assignment is worth $total point(s), one per scored test ($(wc -l <"$dest/controls" | tr -d ' ') control(s) not scored)"
