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
#     catalogued function (the grade names the function); a statistical
#     test counts as failed, as in a grade, only when it fails at the
#     grade's second seed too (lablib.sh, GRADE_SECOND_SEED);
#   - no earlier lab's function test fails (the bug is never reported as a
#     regression of code the student did not write).
# The correct stage's function tests must all pass first.
# --lab NN: only that lab's catalogue.  --verbose: each failing test's
# first message.
# Cost: the correct stages' programs compiled once (-O1), then per bug the
# planted file compiled and the programs that include it, every program
# linked and run: about 1.3 processor s a bug, 70 bugs in 45 s on two
# processors (the catalogues in two queues).
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
# -O1 last: these small programs compile in half the time, and run as fast.
compile="$(sed -n 1p "$work/flags") -O1"
support=$(sed -n 2p "$work/flags")
libs=$(sed -n 3p "$work/flags")

passed=0
failed=0

# run_one PROGRAM LOG [TEST] - a built function test program (one TEST()
# of it), from tests/ as make test runs it, at most 60 s.  ("|| :" keeps
# the subshell from becoming the program, so that a crash is the log's.)
run_one() {
    ro_prog=$1
    ro_log=$2
    shift 2
    (cd "$root/tests" && "$root/tests/harness/with-timeout.sh" 60 "$ro_prog" "$@" || :) >"$ro_log" 2>&1 </dev/null
}

# build_and_run TREE STAGE OUT [FILE] - build the function test programs of
# STAGE (in TREE, built) and run them; OUT/results gets "PROGRAM STATUS
# TEST" a line, OUT/PROGRAM.log each program's output.  A program's object
# is compiled once per stage, against the correct stage (the first call,
# without FILE), and linked with each planted copy's objects; it is compiled
# again only when it includes the planted FILE itself (a test of a file's
# static functions) or FILE is a header.
build_and_run() {
    br_tree=$1
    br_stage=$2
    br_out=$3
    br_file=${4:-}
    br_objs=$work/$br_stage-objects
    mkdir -p "$br_out" "$br_objs"
    : >"$br_out/results"
    rm -f "$br_out/libstage.a"
    ar rcs "$br_out/libstage.a" $(ls "$br_tree/build/$br_stage"/*.o | grep -v '/main\.o$')
    for br_src in $("$root/tests/harness/select-tests.sh" "${br_stage%%_*}" "$root"/tests/stage/*_lab_functions.c); do
        br_name=$(basename "$br_src" .c)
        br_obj=$br_objs/$br_name.o
        case $br_file in
            *.h) br_obj=$br_out/$br_name.o ;;
            ?*) ! grep -q "^#include \"$br_file\"" "$br_src" || br_obj=$br_out/$br_name.o ;;
        esac
        if [ ! -f "$br_obj" ]; then
            eval "$compile -I\"$br_tree/stages/$br_stage\" -DSTAGE_NAME=\\\"$br_stage\\\" -c -o \"$br_obj\" \"$br_src\"" \
                >"$br_out/$br_name.build.log" 2>&1 || rm -f "$br_obj"
        fi
        if [ ! -f "$br_obj" ] ||
            ! eval "$compile -o \"$br_out/$br_name\" \"$br_obj\" $support \"$br_out/libstage.a\" $libs" \
                >>"$br_out/$br_name.build.log" 2>&1; then
            for br_test in $(test_names "$br_src"); do
                echo "$br_name did-not-compile $br_test" >>"$br_out/results"
            done
            continue
        fi
        # The program once; if it crashes (an assertion on a NaN), each
        # TEST() again on its own, so that a crash fails only its own test,
        # as grade.sh counts a crashed program's tests.
        br_log=$br_out/$br_name.log
        run_one "$br_out/$br_name" "$br_log"
        # A statistical test that fails is run again at the grade's second
        # seed and counts as failed only when it fails there too, as in
        # grade.sh (lablib.sh, GRADE_SECOND_SEED).
        if grep -Eq '^[0-9]+ passed, [0-9]+ failed' "$br_log"; then
            test_statuses "$br_src" "$br_log" - |
                second_seed "$br_src" "$GRADE_SECOND_SEED" "$br_out/$br_name" run_one "$br_out/$br_name" |
                awk -v name="$br_name" '{ print name, $2, $1 }' >>"$br_out/results"
            continue
        fi
        for br_test in $(test_names "$br_src"); do
            br_status=FAIL
            br_one=$br_out/$br_name.$br_test.log
            run_one "$br_out/$br_name" "$br_one" "$br_test"
            if grep -q "^ok   $br_test\$" "$br_one" && grep -q "^1 passed, 0 failed" "$br_one"; then
                br_status=ok
            fi
            cat "$br_one" >>"$br_log"
            echo "$br_name $br_status $br_test" >>"$br_out/results"
        done
    done
}

# check_lab BUGS - every check of one catalogue, its result lines on
# standard output (the correct stage, then each bug).
check_lab() {
    stage=$(basename "$1" .bugs)
    nn=${stage%%_*}
    tree=$work/tree-$stage
    if [ ! -d "$root/stages/$stage" ]; then
        echo "FAIL functions/$stage: no stage $stage for $1"
        return 0
    fi

    # The correct stage first: every function test passes.
    build_and_run "$root" "$stage" "$work/$stage-correct"
    bad=$(awk '$2 != "ok"' "$work/$stage-correct/results")
    if [ -z "$bad" ] && awk -v nn="$nn" 'substr($1, 1, 2) == nn { found = 1 } END { exit !found }' "$work/$stage-correct/results"; then
        echo "ok   functions/$stage/correct"
    else
        echo "FAIL functions/$stage/correct: the correct stage fails: $(echo "$bad" | tr '\n' ';')"
    fi

    tab=$(printf '\t')
    grep -v '^#' "$1" | grep -v '^[[:space:]]*$' | while IFS=$tab read -r name file function script what; do
        out=$work/$stage-$name
        if ! plant_stage "$root" "$tree" "$stage" "$file" -e "$script" >"$out.plant.log" 2>&1; then
            echo "FAIL functions/$stage/$name: could not plant it: $(tail -n 3 "$out.plant.log" | tr '\n' ' ')"
            continue
        fi
        build_and_run "$tree" "$stage" "$out" "$file"
        # This lab's programs: NN_lab_functions and NN-MM_lab_functions.
        lab_failed=$(awk -v nn="$nn" 'substr($1, 1, 2) == nn && $2 != "ok" { print $3 }' "$out/results")
        named=$(echo "$lab_failed" | grep "^$function" | head -n 1 || true)
        earlier=$(awk -v nn="$nn" 'substr($1, 1, 2) != nn && $2 != "ok" { print $1 "/" $3 }' "$out/results")
        if [ "$verbose" -eq 1 ] && [ -n "$lab_failed" ]; then
            echo "     $name: failed: $(echo "$lab_failed" | tr '\n' ' ')"
            cat "$out/$nn"*_lab_functions.log | grep -m 1 "check failed" | cut -c 1-300 | sed 's/^/       /'
        fi
        if [ -z "$lab_failed" ]; then
            echo "FAIL functions/$stage/$name: no function test fails ($what)"
        elif [ -z "$named" ]; then
            echo "FAIL functions/$stage/$name: $function is not named: failed $(echo "$lab_failed" | tr '\n' ' ')"
        elif [ -n "$earlier" ]; then
            echo "FAIL functions/$stage/$name: blamed on an earlier lab: $(echo "$earlier" | tr '\n' ' ')"
        else
            echo "ok   functions/$stage/$name ($named)"
        fi
    done
}

# The catalogues in two queues, one a processor (every other lab each:
# the later labs, with more programs, split between them).
queue0=
queue1=
i=0
for bugs in "$LAB_DIR"/bugs/*.bugs; do
    stage=$(basename "$bugs" .bugs)
    [ -z "$only" ] || [ "$only" = "${stage%%_*}" ] || [ "$only" = "$stage" ] || continue
    if [ $((i % 2)) -eq 0 ]; then queue0="$queue0 $bugs"; else queue1="$queue1 $bugs"; fi
    i=$((i + 1))
done
[ "$i" -gt 0 ] || die "no bug catalogue matches --lab $only"
for q in 0 1; do
    eval "list=\$queue$q"
    (for bugs in $list; do check_lab "$bugs" >"$work/$(basename "$bugs" .bugs).lines"; done) &
done
wait
for bugs in "$LAB_DIR"/bugs/*.bugs; do
    lines=$work/$(basename "$bugs" .bugs).lines
    [ -f "$lines" ] || continue
    cat "$lines"
    passed=$((passed + $(grep -c '^ok' "$lines" || true)))
    failed=$((failed + $(grep -c '^FAIL' "$lines" || true)))
done
echo "$passed passed, $failed failed, 0 skipped"
[ "$failed" -eq 0 ]
