#!/bin/sh
# check-functions.sh - the function tests name every catalogued student bug.
#
#   check-functions.sh [--lab NN] [--verbose] [--help]     (part of make test)
#
# For each lab with a bug catalogue (tests/lab/bugs/NN_name.bugs: a plausible
# misunderstanding per line, the file and sed script that plant it, and the
# LAB function it lives in), plants each bug in a copy of the stage
# (lablib.sh's plant_stage), builds the function test programs that apply
# to the stage (tests/stage/*_lab_functions.c: every lab's up to this one)
# against the copy, runs them, and checks that
#   - a test of this lab's program fails, and one whose name starts with the
#     catalogued function (the grade names the function);
#   - no earlier lab's function test fails (the bug is never reported as a
#     regression of code the student did not write).
# The correct stage's function tests must all pass first.
# --lab NN: only that lab's catalogue.  --verbose: each failing test's
# first message.
# Cost: one stage copy built and a few small programs compiled per bug,
# about 3 s each.
# Prints one result line per check and "N passed, N failed, N skipped".
# Exit status: 0 every check passed, 1 a check failed, 2 usage.
set -eu

PROG=check-functions.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

only=
verbose=0
parse_options '--lab only=VALUE --verbose verbose=1' "$@"
shift "$po_used"
[ $# -eq 0 ] || usage_error "unexpected argument: $1"
root=$(cd "$LAB_DIR/../.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/functions.XXXXXX")
trap 'rm -rf "$work"' EXIT
trap 'exit 1' HUP INT PIPE TERM
plain_make -C "$root" all >"$work/log" 2>&1 ||
    die "the project does not build: $(tail -n 5 "$work/log")"
plain_make -s -C "$root/tests" flags >"$work/flags" 2>"$work/log" ||
    die "cannot read the test flags: $(tail -n 5 "$work/log")"
compile=$(sed -n 1p "$work/flags")
support=$(sed -n 2p "$work/flags")
libs=$(sed -n 3p "$work/flags")

passed=0
failed=0
pass() {
    echo "ok   functions/$1"
    passed=$((passed + 1))
}
fail() {
    echo "FAIL functions/$1: $2"
    failed=$((failed + 1))
}

# build_and_run TREE STAGE OUT - build the function test programs of STAGE
# (in TREE, built) and run them; OUT/results gets "PROGRAM STATUS TEST" a
# line, OUT/PROGRAM.log each program's output.  False when one does not build.
build_and_run() {
    br_tree=$1
    br_stage=$2
    br_out=$3
    mkdir -p "$br_out"
    : >"$br_out/results"
    rm -f "$br_out/libstage.a"
    ar rcs "$br_out/libstage.a" $(ls "$br_tree/build/$br_stage"/*.o | grep -v '/main\.o$')
    for br_src in $("$root/tests/harness/select-tests.sh" "${br_stage%%_*}" "$root"/tests/stage/*_lab_functions.c); do
        br_name=$(basename "$br_src" .c)
        eval "$compile -I\"$br_tree/stages/$br_stage\" -DSTAGE_NAME=\\\"$br_stage\\\" -o \"$br_out/$br_name\" \
            \"$br_src\" $support \"$br_out/libstage.a\" $libs" >"$br_out/$br_name.build.log" 2>&1 || {
            echo "$br_name did-not-compile -" >>"$br_out/results"
            continue
        }
        # One process a TEST(): a crash (an assertion on a NaN) fails its
        # own test only, as grade.sh counts a crashed program's tests.
        : >"$br_out/$br_name.log"
        for br_test in $(test_names "$br_src"); do
            br_status=FAIL
            br_log=$br_out/$br_name.$br_test.log
            # ("|| :" after the program keeps the subshell from becoming it, so
            # that the subshell, whose output is the log, reports a crash.)
            (cd "$root/tests" && "$root/tests/harness/with-timeout.sh" 60 "$br_out/$br_name" "$br_test" || :) >"$br_log" 2>&1 </dev/null
            if grep -q "^ok   $br_test\$" "$br_log" && grep -q "^1 passed, 0 failed" "$br_log"; then
                br_status=ok
            fi
            cat "$br_log" >>"$br_out/$br_name.log"
            echo "$br_name $br_status $br_test" >>"$br_out/results"
        done
    done
}

for bugs in "$LAB_DIR"/bugs/*.bugs; do
    stage=$(basename "$bugs" .bugs)
    nn=${stage%%_*}
    [ -z "$only" ] || [ "$only" = "$nn" ] || [ "$only" = "$stage" ] || continue
    [ -d "$root/stages/$stage" ] || { fail "$stage" "no stage $stage for $bugs"; continue; }

    # The correct stage first: every function test passes.
    build_and_run "$root" "$stage" "$work/$stage-correct"
    bad=$(awk '$2 != "ok"' "$work/$stage-correct/results")
    if [ -z "$bad" ] && awk -v nn="$nn" 'substr($1, 1, 2) == nn { found = 1 } END { exit !found }' "$work/$stage-correct/results"; then
        pass "$stage/correct"
    else
        fail "$stage/correct" "the correct stage fails: $(echo "$bad" | tr '\n' ';')"
    fi

    tab=$(printf '\t')
    grep -v '^#' "$bugs" | grep -v '^[[:space:]]*$' | while IFS=$tab read -r name file function script what; do
        out=$work/$stage-$name
        if ! plant_stage "$root" "$work/tree" "$stage" "$file" -e "$script" >"$work/log" 2>&1; then
            fail "$stage/$name" "could not plant it: $(tail -n 3 "$work/log" | tr '\n' ' ')"
            continue
        fi
        build_and_run "$work/tree" "$stage" "$out"
        # This lab's programs: NN_lab_functions and NN-MM_lab_functions.
        lab_failed=$(awk -v nn="$nn" 'substr($1, 1, 2) == nn && $2 != "ok" { print $3 }' "$out/results")
        named=$(echo "$lab_failed" | grep "^$function" | head -n 1 || true)
        earlier=$(awk -v nn="$nn" 'substr($1, 1, 2) != nn && $2 != "ok" { print $1 "/" $3 }' "$out/results")
        if [ "$verbose" -eq 1 ] && [ -n "$lab_failed" ]; then
            echo "     $name: failed: $(echo "$lab_failed" | tr '\n' ' ')"
            cat "$out/$nn"*_lab_functions.log | grep -m 1 "check failed" | cut -c 1-300 | sed 's/^/       /'
        fi
        if [ -z "$lab_failed" ]; then
            fail "$stage/$name" "no function test fails ($what)"
        elif [ -z "$named" ]; then
            fail "$stage/$name" "$function is not named: failed $(echo "$lab_failed" | tr '\n' ' ')"
        elif [ -n "$earlier" ]; then
            fail "$stage/$name" "blamed on an earlier lab: $(echo "$earlier" | tr '\n' ' ')"
        else
            pass "$stage/$name ($named)"
        fi
    done >"$work/lines"
    cat "$work/lines"
    passed=$((passed + $(grep -c '^ok' "$work/lines" || true)))
    failed=$((failed + $(grep -c '^FAIL' "$work/lines" || true)))
done
echo "$passed passed, $failed failed, 0 skipped"
[ "$failed" -eq 0 ]
