#!/bin/sh
# classroom.sh - the GitHub Classroom autograding files of a lab handout.
#
#   classroom.sh HANDOUT CONTROLS          (make-lab.sh runs it)
#
# HANDOUT is a handout being written (make-lab.sh's), CONTROLS the lab's
# controls ("PROGRAM TEST" lines, tests/course/controls/NN_name; "-": none
# known).  Writes, for every TEST() of the lab's own tests, in the order of
# its sources, and every paired page of the lab (pages/PAGE_paired):
#   .github/classroom/autograding.json   the test list of GitHub Classroom's
#       autograding action: {"tests": [{"name", "setup", "run", "input",
#       "output", "comparison", "timeout" (minutes), "points"}]}
#   .github/workflows/classroom.yml      the workflow GitHub Classroom runs on
#       every push: a Debian container with the packages of
#       .devcontainer/packages, the build, then one command-grader step per
#       test (test-name, command, timeout, max-score) and the reporter,
#       whose runners are the steps' ids
# Each test runs as `make check TEST=PROGRAM/NAME` (the handout's Makefile,
# tests/lab/check-one.sh: counted as make grade counts it, a statistical
# test's failure at the second seed too) and scores 1 point when it passes; a control (it passes without the
# student's work: make grade lists it unscored) is listed with 0 points.  So
# the points total is make grade's lab_total, and a student's points its
# lab_passed.
set -eu

PROG=classroom.sh
COURSE_DIR=$(cd "$(dirname "$0")" && pwd)
LAB_DIR=$COURSE_DIR/../lab
. "$LAB_DIR/lablib.sh"

case ${1:-} in -h | --help) show_help "$0"; exit 0 ;; esac
[ $# -eq 2 ] || usage_error "expected HANDOUT CONTROLS, got $# argument(s)"
dir=$1
controls=$2
[ "$controls" = - ] && controls=/dev/null
stage=$(handout_stage "$dir") || die "$dir: expected exactly one stage in stages/"
nn=${stage%%_*}

# The lab's tests, "PROGRAM TEST POINTS" a line.
for src in $(handout_tests "$dir"); do
    [ "$(test_from "$src")" = "$nn" ] || continue
    test_names "$src" | sed "s/^/$(basename "$src" .c) /"
done | awk -v controls="$controls" '
    BEGIN { while ((getline l < controls) > 0) { split(l, w, " "); c[w[1] " " w[2]] = 1 } }
    { print $1, $2, (($1 " " $2) in c ? 0 : 1) }' >"$dir/.classroom-tests"
# ... and its paired pages (scored as make grade scores them), where the
# handout carries the solution's render.
for scene in $(paired_scenes "$nn"); do
    [ ! -f "$dir/tests/reference/solution/$scene.pfm" ] ||
        echo "pages $(paired_page_name "$nn" "$scene")_paired 1" >>"$dir/.classroom-tests"
done

mkdir -p "$dir/.github/classroom" "$dir/.github/workflows"
awk '
    BEGIN { print "{"; print "  \"tests\": [" }
    NR > 1 { print "    }," }
    {
        print "    {"
        printf "      \"name\": \"%s/%s\",\n", $1, $2
        print "      \"setup\": \"make -s\","
        printf "      \"run\": \"make -s check TEST=%s/%s\",\n", $1, $2
        print "      \"input\": \"\","
        print "      \"output\": \"\","
        print "      \"comparison\": \"included\","
        print "      \"timeout\": 10,"
        printf "      \"points\": %d\n", $3
    }
    END { if (NR > 0) print "    }"; print "  ]"; print "}" }' "$dir/.classroom-tests" >"$dir/.github/classroom/autograding.json"

{
    cat <<YAML
# GitHub Classroom autograding of lab $nn ($stage), written by stagelight's
# make lab (tests/course/classroom.sh): one step per test of the lab, 1 point
# each; a control (it passes without your work) is listed with 0 points.
# Run one test yourself: make check TEST=PROGRAM/NAME
name: Autograding Tests
'on':
- push
- repository_dispatch
- workflow_dispatch
permissions:
  checks: write
  actions: read
  contents: read
jobs:
  run-autograding-tests:
    runs-on: ubuntu-latest
    container: debian:bookworm
    if: github.actor != 'github-classroom[bot]'
    steps:
    - name: Checkout code
      uses: actions/checkout@v4
    - name: Install the packages of .devcontainer/packages
      run: apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \$(sed 's/#.*//' .devcontainer/packages) >/dev/null
    - name: Build
      run: make -j2
YAML
    awk '{
        printf "    - name: %s/%s\n", $1, $2
        printf "      id: t%d\n", NR
        print "      uses: classroom-resources/autograding-command-grader@v1"
        print "      with:"
        printf "        test-name: %s/%s\n", $1, $2
        printf "        command: make -s check TEST=%s/%s\n", $1, $2
        print "        timeout: 10"
        printf "        max-score: %d\n", $3
    }' "$dir/.classroom-tests"
    echo "    - name: Autograding Reporter"
    echo "      uses: classroom-resources/autograding-grading-reporter@v1"
    echo "      env:"
    awk '{ printf "        T%d_RESULTS: \"${{steps.t%d.outputs.result}}\"\n", NR, NR }' "$dir/.classroom-tests"
    echo "      with:"
    printf '        runners: %s\n' "$(awk '{ printf "%st%d", (NR > 1 ? "," : ""), NR }' "$dir/.classroom-tests")"
} >"$dir/.github/workflows/classroom.yml"
rm -f "$dir/.classroom-tests"
