#!/bin/sh
# test-runner.sh - tests of the test runner itself (make test, make test
# STAGE=NN, tests/Makefile, harness/run-tests.sh, harness/test-all.sh, the
# flags stamps), in a temporary copy of the project: the build files, the
# common core, the harness and support library, stage 01 and a one-file
# stage 02 (so that only one real stage is built), and small planted tests.
# The copy builds without the optional libraries (TINYGLTF=0 OPENEXR=0) to
# stay quick.  It is removed on every path out.
#
# Prints one line per check and "N passed, N failed, N skipped" last.
# Under SANITIZE=1 (make sanitize) it skips: it tests the runner, not the
# renderer, and make test runs it.
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)

passed=0
failed=0
skipped=0
ok() { passed=$((passed + 1)); echo "ok   runner/$1"; }
fail() {
    failed=$((failed + 1))
    echo "FAIL runner/$1"
    shift
    for detail in "$@"; do printf '%s\n' "$detail" | tail -n 25 | sed 's/^/    /'; done
}
finish() {
    echo "$passed passed, $failed failed, $skipped skipped"
    [ "$failed" -eq 0 ]
    exit
}

if [ "${SANITIZE:-0}" = 1 ]; then
    skipped=1
    echo "skip runner: the runner's tests run in make test, not make sanitize"
    finish
fi

T=$(mktemp -d "${TMPDIR:-/tmp}/test-runner.XXXXXX") || exit 2
trap 'rm -rf "$T"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM HUP
trap 'exit 141' PIPE
C=$T/tree

# ---- the copy ------------------------------------------------------------
mkdir -p "$C/stages" "$C/tests/common" "$C/tests/stage" "$C/stages/02_fake"
cp "$root/Makefile" "$C/"
mkdir -p "$C/scenes/models"
cp "$root/scenes/models/models.mk" "$C/scenes/models/"
cp -R "$root/common" "$C/common"
cp -R "$root/stages/01_raycast" "$C/stages/"
cp "$root"/stages/course.[ch] "$C/stages/"
cp "$root/tests/Makefile" "$C/tests/"
cp -R "$root/tests/lib" "$root/tests/harness" "$C/tests/"
: >"$C/tests/harness/parts"

# Stage 02: one file that answers --version like a stage does.
printf 'SRCS = main.c\ninclude ../../common/stage.mk\n' >"$C/stages/02_fake/Makefile"
cat >"$C/stages/02_fake/main.c" <<'EOF'
#include <stdio.h>

#include "vec3.h"

int
main(void)
{
    printf("render (%s) stagelight test, %s precision\n", STAGE_NAME,
        sizeof(real) == sizeof(float) ? "float" : "double");
    return 0;
}
EOF

cat >"$C/tests/common/test_ok.c" <<'EOF'
#include "check.h"

TEST(one) { CHECK(1 + 1 == 2); }

TEST_MAIN(TEST_ENTRY(one))
EOF
# Applies to every stage: runs the stage's render (which checks it is the
# stage's own).
cat >"$C/tests/stage/01_ok.c" <<'EOF'
#include "check.h"
#include "testlib.h"

TEST(render_answers)
{
    const char *argv[] = {test_render_binary(), "--version", NULL};
    CHECK(argv[0] != NULL && test_run(argv, NULL, 0) == 0);
}

TEST(arithmetic) { CHECK(2 * 3 == 6); }

TEST_MAIN(TEST_ENTRY(render_answers), TEST_ENTRY(arithmetic))
EOF

# What env removes for a make in the copy: the -j, variant and STAGE of
# the make that runs these tests (make exports its command-line variables,
# REAL=float among them, to the recipes' environment).
CLEAN_ENV="-u MAKEFLAGS -u MAKELEVEL -u MFLAGS -u STAGE -u OUT -u LAB -u REAL -u SANITIZE
    -u WERROR -u CFLAGS -u CPPFLAGS -u LDFLAGS -u LDLIBS -u SKIP_PARTS"

# mk ARGS... - make in the copy, with a clean command line; output in
# $T/out, status in st.
mk() {
    st=0
    # shellcheck disable=SC2086 # CLEAN_ENV is a list of options
    (cd "$C" && env $CLEAN_ENV make --no-print-directory TINYGLTF=0 OPENEXR=0 "$@") \
        >"$T/out" 2>"$T/err" || st=$?
}

# said - everything the last make printed; last - its last line of output.
said() { cat "$T/out" "$T/err"; }
last() { tail -n 1 "$T/out"; }

# row NAME - the totals line of part NAME in the last output (seconds cut).
row() {
    grep -E "^$1 +[0-9]+ passed" "$T/out" | sed 's/, [0-9]* s$//'
}

# renders - checksums of every build/NN_*/render of the copy.
renders() {
    (cd "$C" && for r in build/[0-9][0-9]_*/render; do
        [ -f "$r" ] && cksum "$r"
    done)
}

# ---- a clean build, and the baseline run -----------------------------------
mk -j2
if [ "$st" -ne 0 ]; then
    fail copy-builds "make in the copy exited $st" "$(said)"
    finish
fi
renders >"$T/clean.sum"
mk test
base01=$(row 01_raycast)
base02=$(row 02_fake)
if [ "$st" -eq 0 ] && [ -n "$base01" ] && [ -n "$base02" ] &&
    last | grep -Eq '^[0-9]+ passed, 0 failed, 0 skipped in [0-9]+ s$'; then
    ok baseline
else
    fail baseline "exit $st" "$(said)"
fi

# ---- make test STAGE=NN: that stage only, nothing else built ---------------
rm -rf "$C/build"
mk test STAGE=02
if [ "$st" -eq 0 ] && [ "$(last | cut -d' ' -f1-6)" = "2 passed, 0 failed, 0 skipped" ] &&
    [ -z "$(row 01_raycast)" ] && [ -z "$(row common)" ]; then
    ok stage-only
else
    fail stage-only "exit $st; expected stage 02's 2 tests alone" "$(said)"
fi
built=$(cd "$C/build" && find . -name '*.o' -o -name render | grep -Ev '^\./(float/)?(02_fake|common|tests)/' | head)
if [ -z "$built" ] && [ ! -d "$C/build/02" ]; then
    ok stage-builds-only-its-own
else
    fail stage-builds-only-its-own "built outside stage 02's directories:" "$built"
fi
mk test STAGE=02_fake
if [ "$st" -eq 0 ] && last | grep -q '^2 passed, 0 failed'; then
    ok stage-by-name
else
    fail stage-by-name "exit $st" "$(said)"
fi
mk test STAGE=99
if [ "$st" -eq 2 ] && said | grep -q "^make test: unknown stage '99'" && said | grep -q '01_raycast' &&
    said | grep -q '02_fake'; then
    ok unknown-stage
else
    fail unknown-stage "exit $st (expected 2 and the list of stages)" "$(said)"
fi
# The message names the command that was typed.
mk sanitize STAGE=99
if [ "$st" -eq 2 ] && said | grep -q "^make sanitize: unknown stage '99'"; then
    ok unknown-stage-names-sanitize
else
    fail unknown-stage-names-sanitize "exit $st (expected 2, 'make sanitize: unknown stage')" "$(said)"
fi

# ---- no variable of the caller moves a stage's build -------------------------
mk test STAGE=02 OUT=elsewhere LAB=x
mk STAGE=02 OUT=elsewhere LAB=x
renders >"$T/after.sum"
if [ "$st" -eq 0 ] && [ ! -d "$C/build/02" ] && [ ! -e "$C/elsewhere" ] &&
    cmp -s "$T/clean.sum" "$T/after.sum"; then
    ok no-redirect
else
    fail no-redirect "exit $st; renders after make test STAGE=02 and make STAGE=02 OUT=elsewhere:" \
        "$(diff "$T/clean.sum" "$T/after.sum")" "$(ls "$C/build")"
fi

# ---- flags stamps: changed flags rebuild, and back ---------------------------
mk CFLAGS=-O0
renders >"$T/o0.sum"
mk
renders >"$T/back.sum"
if ! cmp -s "$T/clean.sum" "$T/o0.sum" && cmp -s "$T/clean.sum" "$T/back.sum"; then
    ok flags-stamp
else
    fail flags-stamp "the renders did not change with CFLAGS=-O0, or did not come back" \
        "$(cat "$T/clean.sum" "$T/o0.sum" "$T/back.sum")"
fi

# ---- a stage's tests refuse another stage's render ---------------------------
cp "$C/build/01_raycast/render" "$C/build/02_fake/render"
mk test STAGE=02
if [ "$st" -ne 0 ] && grep -q '^FAIL 02_fake/01_ok' "$T/out" &&
    grep -q 'is not the double-precision render of stage 02_fake' "$T/out"; then
    ok foreign-render
else
    fail foreign-render "exit $st" "$(said)"
fi
rm -f "$C/build/02_fake/render"

# ---- a test that does not compile --------------------------------------------
printf 'this is not C;\n' >"$C/tests/stage/02_broken.c"
mk test
if [ "$st" -ne 0 ] && grep -q '^FAIL 02_fake/02_broken: did not build' "$T/out" &&
    grep -q '02_broken\.c:1' "$T/out" && [ "$(row 01_raycast)" = "$base01" ] &&
    last | grep -q ', 1 failed'; then
    ok broken-test
else
    fail broken-test "exit $st; stage 01 before: $base01" "$(said)"
fi
mk test STAGE=02
if [ "$st" -ne 0 ] && grep -q '^FAIL 02_fake/02_broken: did not build' "$T/out" &&
    grep -q '02_broken\.c:1' "$T/out"; then
    ok broken-test-stage
else
    fail broken-test-stage "exit $st" "$(said)"
fi
rm -f "$C/tests/stage/02_broken.c"

# ---- a stage whose render does not build --------------------------------------
cp "$C/stages/02_fake/main.c" "$T/main.c"
printf 'int broken(void) { return undeclared; }\n' >>"$C/stages/02_fake/main.c"
mk test STAGE=02
if [ "$st" -ne 0 ] && grep -q '^FAIL 02_fake/render: did not build' "$T/out" &&
    grep -q '^FAIL 02_fake/01_ok: not run' "$T/out"; then
    ok broken-stage
else
    fail broken-stage "exit $st" "$(said)"
fi
cp "$T/main.c" "$C/stages/02_fake/main.c"

# ---- crash, no summary, time-out ---------------------------------------------
cat >"$C/tests/stage/02_crash.c" <<'EOF'
#include <stdio.h>

int
main(void)
{
    volatile int *volatile nowhere = NULL;
    printf("before the crash\n");
    fflush(stdout);
    return *nowhere;
}
EOF
printf '#include <stdio.h>\nint main(void) { puts("nothing to report"); return 0; }\n' \
    >"$C/tests/stage/02_silent.c"
printf '#include <unistd.h>\nint main(void) { sleep(60); return 0; }\n' >"$C/tests/stage/02_hang.c"
TEST_TIMEOUT=2
export TEST_TIMEOUT
mk test STAGE=02
unset TEST_TIMEOUT
if [ "$st" -ne 0 ] && grep -q '^FAIL 02_fake/02_crash: crashed' "$T/out" &&
    grep -q '^FAIL 02_fake/02_silent: exit 0, no result line' "$T/out" &&
    grep -q '^FAIL 02_fake/02_hang: timed out' "$T/out" &&
    last | grep -q '^2 passed, 3 failed'; then
    ok crash-silent-hang
else
    fail crash-silent-hang "exit $st" "$(said)"
fi
rm -f "$C/tests/stage/02_crash.c" "$C/tests/stage/02_silent.c" "$C/tests/stage/02_hang.c"

# ---- an interrupted run leaves nothing in TMPDIR ------------------------------
# A test that has written to its temporary directory is running when the
# whole run is stopped (SIGTERM to its process group, as a terminal's Ctrl-C
# reaches every process of the job).
cat >"$C/tests/stage/02_hang.c" <<'EOF'
#include <stdio.h>
#include <unistd.h>

#include "testlib.h"

int
main(void)
{
    test_write_file(test_tmp_path("work.txt"), "partial");
    puts("started");
    fflush(stdout);
    sleep(60);
    return 0;
}
EOF
# setsid (util-linux) starts the run in a process group of its own, the
# group a terminal signals; without it (macOS) the check is skipped.
if command -v setsid >/dev/null 2>&1; then
    mkdir -p "$T/tmp"
    log=$C/build/tests/logs/02_fake-02_hang.log
    rm -f "$log"
    # shellcheck disable=SC2086 # CLEAN_ENV is a list of options
    (cd "$C" && exec env $CLEAN_ENV TMPDIR="$T/tmp" \
        setsid make --no-print-directory TINYGLTF=0 OPENEXR=0 test STAGE=02) >"$T/out" 2>"$T/err" &
    job=$!
    # Up to 300 s for the copy to build stage 02 (double and float) and its
    # tests on a loaded machine; the loop ends as soon as the test has started.
    i=0
    while [ "$i" -lt 3000 ] && ! grep -qs started "$log"; do
        sleep 0.1
        i=$((i + 1))
    done
    kill -TERM -- "-$job" 2>/dev/null
    st=0
    wait "$job" || st=$?
    left=$(ls -A "$T/tmp")
    if grep -qs started "$log" && [ "$st" -ne 0 ] && [ -z "$left" ]; then
        ok interrupted-run-cleans-up
    else
        fail interrupted-run-cleans-up "exit $st; left in TMPDIR: $left" "$(said)"
    fi
else
    skipped=$((skipped + 1))
    echo "skip runner/interrupted-run-cleans-up: no setsid here to start the run in a process group"
fi
rm -f "$C/tests/stage/02_hang.c"

# ---- parts: no result line, a lost exit status, leftovers in TMPDIR -----------
cat >"$C/tests/harness/parts" <<'EOF'
quiet   every  echo "no summary here"
lying   every  echo "1 passed, 0 failed, 0 skipped"; exit 1
leaky   every  mktemp "$TMPDIR/leftover.XXXXXX" >/dev/null; echo "1 passed, 0 failed, 0 skipped"
plainly plain  echo "2 passed, 0 failed, 0 skipped"
EOF
mk test
if [ "$st" -ne 0 ] && grep -q '^FAIL quiet: exit 0, no result line' "$T/out" &&
    grep -q '^FAIL lying: exit 1 with no failure counted' "$T/out" &&
    grep -q '^FAIL tmpdir: the run left 1 file' "$T/out" && grep -q 'leftover\.' "$T/out" &&
    [ "$(row plainly)" = "plainly                  2 passed, 0 failed, 0 skipped" ] &&
    [ "$(row 01_raycast)" = "$base01" ] && [ "$(row 02_fake)" = "$base02" ]; then
    ok parts
else
    fail parts "exit $st" "$(said)"
fi
# A part SKIP_PARTS names is skipped, counted and named.
mk test SKIP_PARTS="quiet plainly"
if grep -q '^skip plainly: SKIP_PARTS names it' "$T/out" && grep -q '^skip quiet: SKIP_PARTS names it' "$T/out" &&
    [ "$(row plainly)" = "plainly                  0 passed, 0 failed, 1 skipped" ] &&
    grep -q '^FAIL lying' "$T/out" && ! grep -q '^FAIL quiet' "$T/out"; then
    ok skip-parts
else
    fail skip-parts "exit $st" "$(said)"
fi
# A part of the plain build only is skipped, counted and named, in a variant.
mk REAL=float test
if grep -q '^skip plainly: the same in every build' "$T/out" &&
    [ "$(row plainly)" = "plainly                  0 passed, 0 failed, 1 skipped" ] &&
    grep -q '^FAIL lying' "$T/out"; then
    ok plain-parts-skip-in-variants
else
    fail plain-parts-skip-in-variants "exit $st" "$(said)"
fi
: >"$C/tests/harness/parts"

finish
