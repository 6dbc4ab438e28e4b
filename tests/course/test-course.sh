#!/bin/sh
# test-course.sh - the course tools' own tests that run nothing heavy (part
# of make test; tests/course/test-slurm.sh grades and renders for real).
#
#   test-course.sh [--help]
#
#   packages       .ci/run, the devcontainer's Dockerfile and the autograder's
#                  setup.sh install the one list, .devcontainer/packages, and
#                  nothing else; devcontainer.json is valid JSON naming that
#                  Dockerfile
#   controls       each stage's list of controls names tests of its lab
#                  (controls.sh --check; a stage without one is named)
#   classroom      a handout of stage 02 (make-lab.sh) holds .devcontainer/
#                  (the project's), and GitHub Classroom's files: the test
#                  list is valid JSON with one entry per test of the lab,
#                  1 point each and 0 for a control; the workflow has one
#                  command-grader step per entry, with the same points, and
#                  the reporter names every step
#   results-json   results.awk on a fixture grading (a failing, a passing, a
#                  control's and a crashed program's tests, an earlier
#                  stage's, a report page; quotes, backslashes, tabs and a
#                  control character in the logs) writes JSON with
#                  Gradescope's fields and types (results-check.py), the
#                  score of the report
#   results-nobuild  the same for a stage that does not build: a failing
#                  "build" entry with the compiler's error, score 0
#   class-summary  class.awk on fixture results: the CSV's header and rows
#                  (a comma in a reason quoted), the HTML's histogram, most
#                  failed test and links
#   spp-option     autograder.sh and grade-class.sh take --spp N|auto for
#                  the report pages and refuse anything else before they
#                  write a thing (test-slurm.sh checks the default, auto)
#   timeout        with-timeout.sh's shell watchdog (WITH_TIMEOUT=posix, as
#                  without timeout(1)): 124 for a command past its limit,
#                  the command's own status otherwise, nothing left behind
#   relocated-deps a tiny project built with -MMD (its objects and .d files
#                  under build/, named by absolute path, as the project's
#                  are) and copied elsewhere, as run_autograder copies the
#                  image's handout: with relocate-deps.sh, a header changed
#                  in the copy recompiles the object that includes it; the
#                  same copy without it keeps the stale object (the check
#                  that the fixture shows the bug)
# Prints one line per check and "N passed, N failed, N skipped".
set -u
COURSE_DIR=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$COURSE_DIR/../.." && pwd)
case ${1:-} in -h | --help) awk 'NR == 1 { next } /^#/ { sub(/^# ?/, ""); print; next } { exit }' "$0"; exit 0 ;; esac

CHECKS=course
. "$COURSE_DIR/checklib.sh"
T=$(mktemp -d "${TMPDIR:-/tmp}/test-course.XXXXXX") || exit 2
trap 'rm -rf "$T"' EXIT
trap 'exit 1' HUP INT PIPE TERM
F=$COURSE_DIR/fixtures

# json_check FILE PYTHON - run PYTHON (a check of the JSON in FILE, loaded
# as d) with python3; prints what it says; status 3 when python3 is absent.
json_check() {
    command -v python3 >/dev/null 2>&1 || return 3
    python3 -c "import json, sys
d = json.load(open(sys.argv[1]))
$2" "$1" 2>&1
}

# ---- packages -----------------------------------------------------------------
list=$root/.devcontainer/packages
names=$(sed 's/#.*//' "$list" | tr -s ' \t' '\n\n' | grep -v '^$' | LC_ALL=C sort)
why=
grep -q "apt-get install .*\$(sed 's/#.\*//' .devcontainer/packages)" "$root/.ci/run" ||
    why="$why .ci/run does not install \$(sed 's/#.*//' .devcontainer/packages);"
[ "$(grep -c 'apt-get install' "$root/.ci/run")" -eq 1 ] || why="$why .ci/run has another apt-get install;"
grep -q '^COPY packages ' "$root/.devcontainer/Dockerfile" &&
    grep -q "\$(sed 's/#.\*//' /tmp/stagelight-packages)" "$root/.devcontainer/Dockerfile" ||
    why="$why the Dockerfile does not install the list;"
[ "$(grep -c 'apt-get install' "$root/.devcontainer/Dockerfile")" -eq 1 ] || why="$why the Dockerfile has another apt-get install;"
grep -q '^FROM debian:' "$root/.devcontainer/Dockerfile" || why="$why the Dockerfile is not from Debian;"
grep -q "packages=\$(sed 's/#.\*//' handout/.devcontainer/packages)" "$COURSE_DIR/setup.sh.in" ||
    why="$why setup.sh does not install the list;"
for p in slurm-wlm munge clang; do
    echo "$names" | grep -qx "$p" || why="$why $p is not in the list;"
done
r=$(json_check "$root/.devcontainer/devcontainer.json" 'assert d["build"]["dockerfile"] == "Dockerfile", d; print("ok")')
case $? in
    0) ;;
    3) skip "packages-json: no python3 to read devcontainer.json" ;;
    *) why="$why devcontainer.json: $r;" ;;
esac
if [ -z "$why" ]; then
    ok "packages: .ci/run, the Dockerfile and setup.sh install .devcontainer/packages ($(echo "$names" | wc -l | tr -d ' ') packages)"
else
    fail packages "$why"
fi

# ---- controls -------------------------------------------------------------------
if out=$("$COURSE_DIR/controls.sh" --check 2>&1); then
    ok "controls: $(echo "$out" | grep -c '^ok') stage(s) have their list$(echo "$out" | sed -n 's/^skip controls\/\([^:]*\):.*/, not yet \1/p' | tr -d '\n')"
else
    fail controls "$out"
fi

# ---- classroom ------------------------------------------------------------------
if "$root/tests/lab/make-lab.sh" --quiet 02 "$T/lab" >"$T/make-lab.log" 2>&1; then
    h=$T/lab
    n_lab=0
    n_ctl=0
    for src in "$h"/tests/stage/02_*.c "$h"/tests/stage/02-*.c; do
        [ -f "$src" ] || continue
        for t in $(sed -n 's/^TEST(\([A-Za-z0-9_]*\)).*/\1/p' "$src"); do
            if grep -qx "$(basename "$src" .c) $t" "$root/tests/course/controls/02_shadows"; then
                n_ctl=$((n_ctl + 1))
            else
                n_lab=$((n_lab + 1))
            fi
        done
    done
    # The paired pages, scored steps too (pages/NAME_paired).
    for pfm in "$h"/tests/reference/solution/*.pfm; do
        [ -f "$pfm" ] && n_lab=$((n_lab + 1))
    done
    why=
    diff -r "$root/.devcontainer" "$h/.devcontainer" >/dev/null || why="$why the handout's .devcontainer is not the project's;"
    r=$(json_check "$h/.github/classroom/autograding.json" "
t = d['tests']
assert len(t) == $n_lab + $n_ctl, len(t)
assert sum(x['points'] for x in t) == $n_lab, [x['points'] for x in t]
for x in t:
    assert set(x) == {'name', 'setup', 'run', 'input', 'output', 'comparison', 'timeout', 'points'}, x
    assert x['run'] == 'make -s check TEST=' + x['name'], x
print('ok')")
    [ $? -eq 3 ] || [ "$r" = ok ] || why="$why autograding.json: $r;"
    wf=$h/.github/workflows/classroom.yml
    steps=$(grep -c 'uses: classroom-resources/autograding-command-grader@v1' "$wf")
    points=$(awk '/max-score:/ { s += $2 } END { print s + 0 }' "$wf")
    runners=$(sed -n 's/^ *runners: //p' "$wf" | tr ',' '\n' | grep -c .)
    envs=$(grep -c '_RESULTS: "${{steps\.t[0-9]*\.outputs\.result}}"' "$wf")
    [ "$steps" -eq $((n_lab + n_ctl)) ] || why="$why the workflow has $steps grader steps, not $((n_lab + n_ctl));"
    [ "$points" -eq "$n_lab" ] || why="$why the workflow's points are $points, not $n_lab;"
    [ "$runners" -eq "$steps" ] && [ "$envs" -eq "$steps" ] || why="$why the reporter names $runners runners and $envs results;"
    grep -q 'apt-get install .*\.devcontainer/packages' "$wf" || why="$why the workflow does not install .devcontainer/packages;"
    if command -v python3 >/dev/null 2>&1 && python3 -c 'import yaml' 2>/dev/null; then
        python3 -c 'import sys, yaml; yaml.safe_load(open(sys.argv[1]))' "$wf" 2>"$T/yaml" || why="$why the workflow is not YAML: $(cat "$T/yaml");"
    fi
    if [ -z "$why" ]; then
        ok "classroom: $steps tests in the workflow and the list, $n_lab point(s), $n_ctl control(s) at 0"
    else
        fail classroom "$why"
    fi
else
    fail classroom "make-lab.sh failed:" "$(cat "$T/make-lab.log")"
fi

# ---- results-json ---------------------------------------------------------------
# (from the project's top: the report names its page from there)
(cd "$root" && awk -v report="$F/report.txt" -v keep="$F/keep" -v secs=7 -f "$COURSE_DIR/results.awk" "$F/keep/tests") \
    >"$T/results.json" 2>"$T/results.err"
r=$(python3 "$COURSE_DIR/results-check.py" "$T/results.json" 1 >/dev/null 2>&1 || python3 "$COURSE_DIR/results-check.py" "$T/results.json" 1
json_check "$T/results.json" "
n = {t['name']: t for t in d['tests']}
assert d['score'] == 1 and d['execution_time'] == 7, d['score']
assert n['02_shadows/a_passing_test']['score'] == 1 and n['02_shadows/a_failing_test']['status'] == 'failed'
assert 'say \"no\" \\\\ \\t\\x01' in n['02_shadows/a_failing_test']['output'], repr(n['02_shadows/a_failing_test']['output'])
assert n['02_spawn/crashes']['max_score'] == 1 and 'crashed' in n['02_spawn/crashes']['output']
c = [t for t in d['tests'] if t['name'].startswith('02_shadows/a_control')][0]
assert c['max_score'] == 0 and c['status'] == 'passed'
e = [t for t in d['tests'] if t['name'].startswith('earlier stage 01: 01_camera')][0]
assert e['max_score'] == 0 and e['status'] == 'failed' and 'centre_ray' in e['output'], e
p = [t for t in d['tests'] if t['name'].startswith('report page: ')][0]
assert p['output_format'] == 'html' and 'umbra' in p['output'] and '<title>page</title>' in p['output'], p
assert p['status'] == 'failed'
print('ok')")
case $? in
    3) skip "results-json: no python3 to read the JSON" ;;
    *) if [ "$r" = ok ] && [ ! -s "$T/results.err" ]; then ok "results-json: Gradescope's fields, score 1 of 3"; else fail results-json "$r" "$(cat "$T/results.err")" "$(head -c 3000 "$T/results.json")"; fi ;;
esac
mkdir -p "$T/nobuild"
printf 'render.c:3:1: error: expected ; before }\nmake: *** [x] Error 1\n' >"$T/nobuild/build.log"
printf 'lab\t02\t02_shadows\ta_failing_test\tFAIL\tdid-not-compile\n' >"$T/nobuild/tests"
printf 'GRADE lab=02_shadows score=0.0 lab_passed=0 lab_total=1 controls=0 earlier_passed=0 earlier_total=0 build=failed\n' >"$T/nobuild/report.txt"
awk -v report="$T/nobuild/report.txt" -v keep="$T/nobuild" -v secs=1 -f "$COURSE_DIR/results.awk" "$T/nobuild/tests" >"$T/nobuild.json"
r=$(python3 "$COURSE_DIR/results-check.py" "$T/nobuild.json" 0 >/dev/null 2>&1 || python3 "$COURSE_DIR/results-check.py" "$T/nobuild.json" 0
json_check "$T/nobuild.json" "
b = d['tests'][0]
assert b['name'] == 'build' and b['status'] == 'failed' and 'render.c:3:1: error' in b['output'], b
assert d['score'] == 0 and d['tests'][1]['status'] == 'failed' and 'does not build' in d['tests'][1]['output']
print('ok')")
case $? in
    3) skip "results-nobuild: no python3 to read the JSON" ;;
    *) if [ "$r" = ok ]; then ok "results-nobuild: a failing build entry with the compiler's error"; else fail results-nobuild "$r"; fi ;;
esac

# ---- class-summary ----------------------------------------------------------------
mkdir -p "$T/class"
awk -v lab=02_shadows -v csv="$T/class/grades.csv" -v html="$T/class/index.html" -v pages="$F/class-pages" \
    -f "$COURSE_DIR/class.awk" "$F/class-tests" "$F/class-results"
why=
head -n 1 "$T/class/grades.csv" | grep -qx 'student,score,lab_passed,lab_total,build,seconds,reason,02_shadows/a,02_shadows/b,02_shadows/c (control)' ||
    why="$why header: $(head -n 1 "$T/class/grades.csv");"
[ "$(wc -l <"$T/class/grades.csv" | tr -d ' ')" -eq 4 ] || why="$why not 3 rows;"
grep -qx 'ann,100.0,2,2,ok,40,,ok,ok,ok' "$T/class/grades.csv" || why="$why ann's row;"
grep -qx 'bob,0.0,0,2,failed,12,"build failed: render.c:3: error: expected x, got y",FAIL,FAIL,FAIL' "$T/class/grades.csv" || why="$why bob's row;"
grep -qx 'cyd,,,2,not-graded,,not graded: its task ended,,,' "$T/class/grades.csv" || why="$why cyd's row;"
grep -q '<td>0-9%</td><td class="n">1</td>' "$T/class/index.html" || why="$why no 0-9% bin of 1;"
grep -q '<td>90-100%</td><td class="n">1</td>' "$T/class/index.html" || why="$why no 90-100% bin of 1;"
grep -q '<tr><td>02_shadows/a</td><td class="n">1 of 2</td></tr>' "$T/class/index.html" || why="$why most failed;"
grep -q 'href="students/ann/pages/cornell.html"' "$T/class/index.html" || why="$why no link to ann's page;"
if [ -z "$why" ]; then ok "class-summary: the CSV's rows, the histogram, the tests most failed, the links"; else fail class-summary "$why" "$(cat "$T/class/grades.csv")"; fi

# ---- spp-option ----------------------------------------------------------------------
why=
for c in autograder.sh grade-class.sh; do
    case $c in autograder.sh) args="02 $T/spp-out" ;; *) args=$T/spp-subs ;; esac
    st=0
    # shellcheck disable=SC2086 # the arguments are words
    "$COURSE_DIR/$c" --spp 0x $args >"$T/spp.log" 2>&1 || st=$?
    [ "$st" -eq 2 ] && grep -q "spp needs a positive number, auto or paired, got '0x'" "$T/spp.log" ||
        why="$why $c --spp 0x: exit $st, $(cat "$T/spp.log");"
done
[ ! -e "$T/spp-out" ] || why="$why autograder.sh wrote $T/spp-out before refusing;"
grep -q -- '--spp @SPP@ ' "$COURSE_DIR/run_autograder.in" || why="$why run_autograder does not pass --spp to grade.sh;"
if [ -z "$why" ]; then ok "spp-option: --spp N|auto checked before anything is written, passed on to grade.sh"; else fail spp-option "$why"; fi

# ---- timeout -------------------------------------------------------------------------
W=$root/tests/harness/with-timeout.sh
mkdir -p "$T/tmp"
st=0; TMPDIR=$T/tmp WITH_TIMEOUT=posix "$W" 1 sleep 20 2>/dev/null || st=$?
st2=0; TMPDIR=$T/tmp WITH_TIMEOUT=posix "$W" 20 sh -c 'exit 3' || st2=$?
st3=0; TMPDIR=$T/tmp WITH_TIMEOUT=posix "$W" 20 true || st3=$?
if [ "$st" -eq 124 ] && [ "$st2" -eq 3 ] && [ "$st3" -eq 0 ] && [ -z "$(ls -A "$T/tmp")" ]; then
    ok "timeout: the shell watchdog stops a command at its limit (124), else passes its status on"
else
    fail timeout "statuses $st $st2 $st3 (expected 124 3 0); left: $(ls -A "$T/tmp")"
fi

# ---- relocated-deps -------------------------------------------------------------------
# value_after_header_change RELOCATE: build the project in $T/deps/image,
# copy it (cp -Rp), set the copy's header to 2, relocate its .d files when
# RELOCATE is 1, make the copy; prints what the copy's program prints.
value_after_header_change() {
    rm -rf "$T/deps"
    mkdir -p "$T/deps/image"
    img=$(cd "$T/deps/image" && pwd -P)
    printf '#define VALUE 1\n' >"$img/value.h"
    printf '#include <stdio.h>\n#include "value.h"\nint main(void) { printf("%%d\\n", VALUE); return 0; }\n' >"$img/main.c"
    printf 'ROOT := $(abspath .)\nbuild/main: $(ROOT)/build/main.o\n\t$(CC) -o $@ $<\n$(ROOT)/build/%%.o: %%.c\n\tmkdir -p $(@D) && $(CC) -MMD -MP -I$(ROOT) -c -o $@ $<\n-include $(ROOT)/build/main.d\n' >"$img/Makefile"
    make -s -C "$img" >/dev/null 2>&1 || return 1
    sleep 1 # the copy's header must be newer than the image's object
    cp -Rp "$img" "$T/deps/copy"
    printf '#define VALUE 2\n' >"$T/deps/copy/value.h"
    if [ "$1" = 1 ]; then sh "$COURSE_DIR/relocate-deps.sh" "$img" "$T/deps/copy" || return 1; fi
    make -s -C "$T/deps/copy" >/dev/null 2>&1 && "$T/deps/copy/build/main"
}
with=$(value_after_header_change 1)
without=$(value_after_header_change 0)
if [ "$with" = 2 ] && [ "$without" = 1 ]; then
    ok "relocated-deps: the copy's changed header recompiles its includer (stale without relocate-deps.sh)"
else
    fail relocated-deps "with relocate-deps.sh the copy printed '$with' (want 2), without '$without' (want 1: the fixture no longer shows the bug)"
fi

finish
