#!/bin/sh
# test-lab-tools.sh - tests of the lab tools themselves, on fixtures.
#
#   test-lab-tools.sh [--keep]
#
# markers.awk on fixtures/sample.c.in (golden files) and on one bad input
# per error; labdoc.awk, leaks.awk and diffstat.awk on small inputs; then
# make-lab.sh, make-diffs.sh, check-diffs.sh and make-branches.sh on a
# miniature project written into a temporary directory (nothing is
# compiled: check-labs.sh and grade.sh build real handouts, and run in
# make test and make check-labs); grade-pages.sh on the project's own
# build; lablib.sh's parse_options and grading functions.  Prints one line per test and the closing
# line "N passed, N failed, N skipped".  --keep keeps the temporary
# directory and prints its name.
# Exit status: 0 all passed, 1 a test failed, 2 usage.
set -eu

PROG=test-lab-tools.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

keep=0
case ${1:-} in
    -h | --help) show_help "$0"; exit 0 ;;
    --keep) keep=1 ;;
    '') ;;
    *) usage_error "unknown argument: $1" ;;
esac

FIX=$LAB_DIR/fixtures
T=$(mktemp -d "${TMPDIR:-/tmp}/test-lab-tools.XXXXXX")
if [ "$keep" -eq 1 ]; then
    echo "keeping $T"
else
    trap 'rm -rf "$T"' EXIT
fi
trap 'exit 1' HUP INT PIPE TERM

passed=0
failed=0
ok() {
    passed=$((passed + 1))
    echo "ok   lab-tools/$1"
}
fail() {
    failed=$((failed + 1))
    echo "FAIL lab-tools/$1"
    if [ $# -gt 1 ]; then
        shift
        printf '%s\n' "$@" | sed 's/^/        /' | head -n 20
    fi
}
# check NAME COMMAND... - ok when the command succeeds.
check() {
    ck_name=$1
    shift
    if "$@" >"$T/out" 2>&1; then ok "$ck_name"; else fail "$ck_name" "$(cat "$T/out")"; fi
}
# same NAME EXPECTED-FILE ACTUAL-FILE
same() {
    if diff "$2" "$3" >"$T/diff" 2>&1; then ok "$1"; else fail "$1" "$(cat "$T/diff")"; fi
}
markers() {
    awk -f "$LAB_DIR/markers.awk" "$@"
}

# --- markers.awk ---------------------------------------------------------
test_markers() {
    cd "$FIX"
    markers -v mode=handout -v lab=02 -v stage=02 -v docref=docs/stages/02_b.md sample.c.in >"$T/h02" 2>&1 || true
    same markers/handout-02 sample.handout-02.c "$T/h02"
    markers -v mode=handout -v lab=01 -v stage=02 -v docref=docs/stages/01_a.md sample.c.in >"$T/h01" 2>&1 || true
    same markers/handout-01 sample.handout-01.c "$T/h01"
    markers -v mode=regions sample.c.in >"$T/regions" 2>&1 || true
    same markers/regions sample.regions "$T/regions"
    check markers/lint-ok markers -v mode=lint -v stage=02 sample.c.in
    # inside + outside = every line but the marker comments, and the stub
    markers -v mode=inside -v lab=02 sample.c.in | cut -f 3 >"$T/in"
    if grep -q 'shadow_rays_of' "$T/in" && grep -q 'sin2_t(cos_i, eta);' "$T/in" &&
        ! grep -q 'x + x' "$T/in"; then
        ok markers/inside
    else
        fail markers/inside "$(cat "$T/in")"
    fi
    markers -v mode=outside -v lab=02 sample.c.in | cut -f 3 >"$T/outside"
    if grep -q 'return x + x;' "$T/outside" && grep -q '^return true;$' "$T/outside" &&
        ! grep -q 'shadow_rays_of' "$T/outside" && ! grep -q 'LAB [0-9]' "$T/outside"; then
        ok markers/outside
    else
        fail markers/outside "$(cat "$T/outside")"
    fi
    # The stub store: sample.c.in with its LAB 02 marker comments replaced
    # by the one-line markers of stubs/02_b.stubs (in order) must give the
    # same handout.
    mkdir -p "$T/02_b"
    awk 'NR == FNR { if ($0 ~ /^sample\.c: /) name[++n] = substr($0, 11); next }
        skip { skip = index($0, "*/") == 0; next }
        /^[ \t]*\/\* LAB 02:/ {
            match($0, /^[ \t]*/)
            print substr($0, 1, RLENGTH) name[++i]
            skip = index($0, "*/") == 0
            next
        }
        { print }' stubs/02_b.stubs sample.c.in >"$T/02_b/sample.c"
    cd "$T"
    markers -v mode=handout -v lab=02 -v stage=02 -v docref=docs/stages/02_b.md -v stubs="$FIX/stubs" \
        02_b/sample.c >"$T/s02" 2>&1 || true
    same markers/store-handout "$FIX/sample.handout-02.c" "$T/s02"
    check markers/store-lint-ok markers -v mode=lint -v stubs="$FIX/stubs" 02_b/sample.c
    markers -v mode=outside -v lab=02 -v stubs="$FIX/stubs" 02_b/sample.c | cut -f 3 >"$T/s-outside"
    if grep -q '^return true;$' "$T/s-outside" && ! grep -q 'shadow_rays_of' "$T/s-outside"; then
        ok markers/store-outside
    else
        fail markers/store-outside "$(cat "$T/s-outside")"
    fi
    cd "$T"
}

# bad_store NAME EXPECTED-MESSAGE - markers.awk lint of 02_b/bad.c (stdin)
# with the store 02_b.stubs ($T/stubs, written by the caller) must fail.
bad_store() {
    mkdir -p "$T/02_b"
    cat >"$T/02_b/bad.c"
    bs_status=0
    (cd "$T" && markers -v mode=lint -v stubs=stubs 02_b/bad.c) >"$T/bad.out" 2>&1 || bs_status=$?
    if [ "$bs_status" -eq 1 ] && grep -q "$2" "$T/bad.out"; then
        ok "markers/error/$1"
    else
        fail "markers/error/$1" "exit $bs_status, expected '$2':" "$(cat "$T/bad.out")"
    fi
}

test_store_errors() {
    mkdir -p "$T/stubs"
    printf '%s\n' 'bad.c: /* LAB 02: one */' '/* LAB 02: the hint' ' * stub: return 0; */' >"$T/stubs/02_b.stubs"
    bad_store store-inline-marker 'a marker over several lines' <<'EOF'
/* LAB 02: one */
int x;
/* END LAB */
/* LAB 01: an earlier lab
 * stub: return 1; */
int y;
/* END LAB */
EOF
    bad_store store-no-entry "no entry 'bad.c: /\\* LAB 02: two \\*/'" <<'EOF'
/* LAB 02: one */
int x;
/* END LAB */
/* LAB 02: two */
int y;
/* END LAB */
EOF
    bad_store store-unused-entry 'no marker in 02_b/bad.c uses this entry' <<'EOF'
int x;
EOF
    printf '%s\n' 'bad.c: /* LAB 02: one */' 'int x;' >"$T/stubs/02_b.stubs"
    bad_store store-bad-entry "starts with its marker comment" <<'EOF'
/* LAB 02: one */
int x;
/* END LAB */
EOF
}

# bad NAME EXPECTED-MESSAGE - markers.awk lint on stdin must fail with it.
bad() {
    cat >"$T/bad.c"
    bd_status=0
    markers -v mode=lint -v stage=02 "$T/bad.c" >"$T/bad.out" 2>&1 || bd_status=$?
    if [ "$bd_status" -eq 1 ] && grep -q "$2" "$T/bad.out"; then
        ok "markers/error/$1"
    else
        fail "markers/error/$1" "exit $bd_status, expected '$2':" "$(cat "$T/bad.out")"
    fi
}

test_marker_errors() {
    bad end-without-open 'without an open LAB region' <<'EOF'
int x;
/* END LAB */
EOF
    bad region-not-closed 'never closed with /\* END LAB \*/' <<'EOF'
/* LAB 02: hint */
int x;
EOF
    bad comment-not-closed 'never closed with \*/' <<'EOF'
/* LAB 02: hint
 * stub: return 0;
int x;
EOF
    bad nested 'LAB region inside LAB 02' <<'EOF'
/* LAB 02: hint */
/* LAB 02: again */
int x;
/* END LAB */
EOF
    bad label-above-stage 'a stage holds only its own and earlier labs' <<'EOF'
/* LAB 03: from the future */
int x;
/* END LAB */
EOF
    bad one-digit-label 'malformed LAB marker' <<'EOF'
/* LAB 2: hint */
int x;
/* END LAB */
EOF
    bad not-alone 'malformed LAB marker' <<'EOF'
int y; /* LAB 02: hint */
EOF
    bad end-label-mismatch 'closes LAB 02' <<'EOF'
/* LAB 02: hint */
int x;
/* END LAB 01 */
EOF
    bad empty-region 'empty LAB 02 region' <<'EOF'
/* LAB 02: hint */

/* END LAB */
EOF
    bad stub-on-first-line "'stub:' must begin a comment line" <<'EOF'
/* LAB 02: hint stub: return 0; */
int x;
/* END LAB */
EOF
    bad no-leader "must start with ' \* '" <<'EOF'
/* LAB 02: hint
   stub: return 0; */
int x;
/* END LAB */
EOF
    bad no-hint 'needs a hint' <<'EOF'
/* LAB 02: */
int x;
/* END LAB */
EOF
    bad text-after-close 'text after the \*/' <<'EOF'
/* LAB 02: hint */ int y;
int x;
/* END LAB */
EOF
}

# --- labdoc.awk, leaks.awk, diffstat.awk ----------------------------------
test_labdoc() {
    cat >"$T/page.md" <<'EOF'
# Stage 02: b

The lesson.

## Lab

### Goals

See [stage 01](01_a.md#camera), ![the image](../images/ref.png "ref") and
[the site](https://example.org/x.md).

```sh
## not a heading
```

## After the lab

Not in the section.
EOF
    cat >"$T/labdoc.expected" <<'EOF'
## Goals

See stage 01 (stagelight's `docs/stages/01_a.md`), ![the image](docs/images/ref.png "ref") and
[the site](https://example.org/x.md).

```sh
## not a heading
```
EOF
    : >"$T/assets"
    awk -v dir=docs/stages -v assets="$T/assets" -f "$LAB_DIR/labdoc.awk" "$T/page.md" >"$T/labdoc.out" 2>&1 || true
    same labdoc/section "$T/labdoc.expected" "$T/labdoc.out"
    echo docs/images/ref.png >"$T/assets.expected"
    same labdoc/assets "$T/assets.expected" "$T/assets"
    printf '# Title\n\n## Not lab\n' >"$T/nolab.md"
    ld_status=0
    awk -v dir=docs/stages -v assets="$T/assets" -f "$LAB_DIR/labdoc.awk" "$T/nolab.md" >/dev/null || ld_status=$?
    if [ "$ld_status" -eq 3 ]; then ok labdoc/no-section; else fail labdoc/no-section "exit $ld_status, expected 3"; fi
}

test_leaks() {
    printf 'int shared_line_of_both_kinds = 1;\n' >"$T/known.c"
    printf 'f\t1\t    int shared_line_of_both_kinds = 1;\nf\t2\t    return !world_occluded(w, shadow, t_max, st);\nf\t3\t    return false;\n' >"$T/inside"
    printf 'int shared_line_of_both_kinds = 1;\nreturn false;\n' >"$T/clean.c"
    printf 'x\n  return   !world_occluded(w, shadow, t_max, st);\n' >"$T/leaky.c"
    check leaks/clean awk -f "$LAB_DIR/leaks.awk" pass=known "$T/known.c" pass=solution "$T/inside" \
        pass=handout "$T/clean.c"
    lk_status=0
    awk -f "$LAB_DIR/leaks.awk" pass=known "$T/known.c" pass=solution "$T/inside" \
        pass=handout "$T/leaky.c" >"$T/leaks.out" || lk_status=$?
    if [ "$lk_status" -eq 1 ] && grep -q 'leaky.c:2: return !world_occluded' "$T/leaks.out"; then
        ok leaks/found
    else
        fail leaks/found "exit $lk_status" "$(cat "$T/leaks.out")"
    fi
}

test_diffstat() {
    mkdir -p "$T/ds/01_a" "$T/ds/02_b"
    printf 'a\nb\nc\n' >"$T/ds/01_a/x.c"
    printf 'a\n/* LAB 02: h */\nB\n/* END LAB */\nc\n' >"$T/ds/02_b/x.c"
    printf 'new\n' >"$T/ds/02_b/y.c"
    (cd "$T/ds" && git diff --no-index --no-prefix 01_a 02_b >"$T/ds.diff") || true
    (cd "$T/ds" && markers -v mode=regions 02_b/x.c >"$T/ds.regions")
    set -- $(awk -v lab=02 -f "$LAB_DIR/diffstat.awk" pass=regions "$T/ds.regions" pass=diff "$T/ds.diff")
    # 2 files, 1 new, 0 deleted, 4 added (3 in x.c, 1 in y.c), 1 removed, 3 in the region
    if [ "$*" = "2 1 0 4 1 3" ]; then ok diffstat/counts; else fail diffstat/counts "got: $*" "$(cat "$T/ds.diff")"; fi
}

# --- the scripts, on a miniature project ----------------------------------
mini_project() {
    M=$T/mini
    mkdir -p "$M/stages/01_a" "$M/stages/02_b" "$M/common" "$M/tests/stage" "$M/tests/common" \
        "$M/tests/harness" "$M/tests/lib" "$M/tests/reference" "$M/scenes" "$M/docs/stages" "$M/docs/images"
    cp "$LAB_DIR/../harness/select-tests.sh" "$M/tests/harness/select-tests.sh"
    printf 'SRCS = main.c\n' >"$M/stages/01_a/Makefile"
    printf '/* the first\n * stage */\nint main(void) { return 0; }\n' >"$M/stages/01_a/main.c"
    printf 'SRCS = main.c\n' >"$M/stages/02_b/Makefile"
    cat >"$M/stages/02_b/main.c" <<'EOF'
static int
answer(void)
{
    /* LAB 02: compute the answer (docs/stages/02_b.md#lab)
     * stub: return 0; */
    return six_times_seven_is_the_answer();
    /* END LAB */
}

int main(void) { return answer(); }
EOF
    printf '/* common */\n' >"$M/common/x.h"
    printf 'all:\n' >"$M/tests/Makefile"
    printf '/* harness */\n' >"$M/tests/lib/check.h"
    for f in 01_a 02_b 01-01_only 02-03_range 03_future; do
        printf 'TEST(one) {}\nTEST(two) {}\n' >"$M/tests/stage/$f.c"
    done
    printf 'int main(void) { return 0; }\n' >"$M/tests/common/test_x.c"
    printf 'ref\n' >"$M/tests/reference/r.pfm"
    printf 'camera\n' >"$M/scenes/s.scene"
    printf 'PNG\n' >"$M/docs/images/ref.png"
    printf '# Stage 01: a\n\nAll of it: [01_a.diff](../diffs/01_a.diff).\n' >"$M/docs/stages/01_a.md"
    cat >"$M/docs/stages/02_b.md" <<'EOF'
# Stage 02: the answer

Diff: [02_b.diff](../diffs/02_b.diff).

## Lab

Compute the answer. ![reference](../images/ref.png)

## More
EOF
    cat >"$M/README.md" <<'EOF'
| stage | the idea |
|---|---|
| `01_a` | nothing yet |
| `02_b` | the answer |
EOF
}

# reading-time.sh counts the lesson's words, comment words (a comment
# line's "*" not one) and code lines of stage 01, then of each diff, the
# lines it removes included (their comments as words, not code lines);
# its last column counts what a diff adds alone.
test_reading_time() {
    check reading-time/runs "$LAB_DIR/reading-time.sh" --root "$M"
    if grep -qF '| 01_a: lesson page and code | 11 | 1 | 0 | 0 | 0 |' "$T/out" &&
        grep -qF '| 01_a → 02_b: the diff | 14 | 7 | 1 | 1 | 1 |' "$T/out"; then
        ok reading-time/counts
    else
        fail reading-time/counts "$(cat "$T/out")"
    fi
    # A diff that removes 40 code lines and adds 10: 5 minutes read whole
    # (10 at the slow pace), 1 for the added lines alone.
    R=$T/rt
    mkdir -p "$R/stages/01_a" "$R/stages/02_b"
    seq 40 | sed 's/.*/int a&;/' >"$R/stages/01_a/x.c"
    seq 10 | sed 's/.*/int b&;/' >"$R/stages/02_b/x.c"
    check reading-time/runs-removal "$LAB_DIR/reading-time.sh" --root "$R"
    if grep -qF '| 01_a → 02_b: the diff | 0 | 50 | 5 | 10 | 1 |' "$T/out"; then
        ok reading-time/added-alone
    else
        fail reading-time/added-alone "$(cat "$T/out")"
    fi
}

test_make_lab() {
    H=$T/handout
    check make-lab/writes "$LAB_DIR/make-lab.sh" --strict --quiet --root "$M" 02 "$H"
    (cd "$H" && find . -type f | sed 's|^\./||' | LC_ALL=C sort) >"$T/files"
    cat >"$T/files.expected" <<'EOF'
.github/classroom/autograding.json
.github/workflows/classroom.yml
.gitignore
.stagelight-handout
LAB.md
Makefile
common/x.h
docs/images/ref.png
scenes/s.scene
stages/02_b/Makefile
stages/02_b/main.c
tests/Makefile
tests/harness/select-tests.sh
tests/lab/check-one.sh
tests/lab/grade-pages.sh
tests/lab/grade.awk
tests/lab/grade.sh
tests/lab/lablib.sh
tests/lib/check.h
tests/reference/r.pfm
tests/stage/01_a.c
tests/stage/02-03_range.c
tests/stage/02_b.c
EOF
    same make-lab/files "$T/files.expected" "$T/files"
    if grep -q '^    return 0;$' "$H/stages/02_b/main.c" && ! grep -q six_times "$H/stages/02_b/main.c" &&
        grep -q 'LAB 02: compute the answer (LAB.md)' "$H/stages/02_b/main.c"; then
        ok make-lab/stubbed
    else
        fail make-lab/stubbed "$(cat "$H/stages/02_b/main.c")"
    fi
    if grep -q '^# Lab 02: the answer$' "$H/LAB.md" && grep -q '^Compute the answer' "$H/LAB.md" &&
        grep -q '](docs/images/ref.png)' "$H/LAB.md" &&
        grep -q '`stages/02_b/main.c`, line 4: compute the answer (LAB.md)' "$H/LAB.md" &&
        grep -q '`tests/stage/02-03_range.c`' "$H/LAB.md" && ! grep -q '^## More' "$H/LAB.md" &&
        grep -q '^## Is my image right? Reading the report pages' "$H/LAB.md" &&
        grep -q 'build/02_b/render -W 256' "$H/LAB.md"; then
        ok make-lab/lab-md
    else
        fail make-lab/lab-md "$(cat "$H/LAB.md")"
    fi
    if head -n 1 "$H/Makefile" | grep -q '^# stagelight lab handout: lab 02 (02_b)'; then
        ok make-lab/makefile
    else
        fail make-lab/makefile "$(head -n 3 "$H/Makefile")"
    fi
    # Again: unchanged files keep their dates; a changed one is replaced.
    mkdir -p "$H/build/x"
    touch "$H/build/x/keep"
    sleep 1
    touch "$T/stamp"
    sleep 1
    printf '/* common, changed */\n' >"$M/common/x.h"
    "$LAB_DIR/make-lab.sh" --quiet --root "$M" 02_b "$H" >/dev/null 2>&1 || true
    newer=$(cd "$H" && find . -type f -newer "$T/stamp" | sed 's|^\./||' | LC_ALL=C sort | tr '\n' ' ')
    if [ "$newer" = ".stagelight-handout common/x.h " ] && [ -f "$H/build/x/keep" ]; then
        ok make-lab/update-in-place
    else
        fail make-lab/update-in-place "newer files: $newer"
    fi
    # A student's work in the handout (an edit, a new file, a removed one)
    # is refused, naming the files; --force moves it aside, and says where.
    printf '/* mine */\n' >>"$H/stages/02_b/main.c"
    printf 'notes\n' >"$H/mynotes.txt"
    rm "$H/LAB.md"
    expect_exit make-lab/refuses-changes 2 'stages/02_b/main.c' "$LAB_DIR/make-lab.sh" --root "$M" 02 "$H"
    if grep -q '^    mynotes.txt$' "$T/ee.out" && grep -q '^    LAB.md$' "$T/ee.out" &&
        grep -q mine "$H/stages/02_b/main.c" && [ -f "$H/mynotes.txt" ]; then
        ok make-lab/refusal-keeps-work
    else
        fail make-lab/refusal-keeps-work "$(cat "$T/ee.out")"
    fi
    "$LAB_DIR/make-lab.sh" --force --root "$M" 02 "$H" >"$T/force.out" 2>&1 || true
    aside=$(sed -n 's/.*moved it to //p' "$T/force.out")
    if [ -n "$aside" ] && grep -q mine "$aside/stages/02_b/main.c" && [ -f "$aside/mynotes.txt" ] &&
        [ -f "$H/LAB.md" ] && [ ! -e "$H/mynotes.txt" ] && ! grep -q mine "$H/stages/02_b/main.c"; then
        ok make-lab/force-moves-aside
    else
        fail make-lab/force-moves-aside "$(cat "$T/force.out")"
    fi
    check make-lab/unchanged-again "$LAB_DIR/make-lab.sh" --quiet --root "$M" 02 "$H"
    # make grade's report pages (grade/*.html) are not the student's edits.
    mkdir -p "$H/grade"
    printf '<!DOCTYPE html>\n' >"$H/grade/lab.html"
    check make-lab/grade-pages-are-not-edits "$LAB_DIR/make-lab.sh" --quiet --root "$M" 02 "$H"
    check make-lab/solution "$LAB_DIR/make-lab.sh" --solution --quiet --root "$M" 02 "$T/solution"
    if grep -q six_times "$T/solution/stages/02_b/main.c"; then ok make-lab/solution-kept; else fail make-lab/solution-kept; fi
    # Errors: exit 1 with a message; usage: exit 2.
    mkdir -p "$T/notempty"
    touch "$T/notempty/precious"
    expect_exit make-lab/refuses-other-dir 1 'holds no handout' "$LAB_DIR/make-lab.sh" --root "$M" 02 "$T/notempty"
    expect_exit make-lab/unknown-stage 1 'no stage 09' "$LAB_DIR/make-lab.sh" --root "$M" 09 "$T/h9"
    expect_exit make-lab/usage 2 'expected STAGE and OUT' "$LAB_DIR/make-lab.sh" --root "$M" 02
    expect_exit make-lab/strict-no-region 1 'no LAB 01 region' "$LAB_DIR/make-lab.sh" --strict --root "$M" 01 "$T/h1"
}

# expect_exit NAME STATUS MESSAGE COMMAND...
expect_exit() {
    ee_name=$1
    ee_want=$2
    ee_msg=$3
    shift 3
    ee_status=0
    "$@" >"$T/ee.out" 2>&1 || ee_status=$?
    if [ "$ee_status" -eq "$ee_want" ] && grep -q "$ee_msg" "$T/ee.out"; then
        ok "$ee_name"
    else
        fail "$ee_name" "exit $ee_status (expected $ee_want), expected '$ee_msg':" "$(cat "$T/ee.out")"
    fi
}

test_diffs() {
    check make-diffs/writes "$LAB_DIR/make-diffs.sh" --quiet --root "$M"
    if [ -f "$M/docs/diffs/02_b.diff" ] && grep -q '^+++ 02_b/main.c$' "$M/docs/diffs/02_b.diff" &&
        ! grep -q '^index ' "$M/docs/diffs/02_b.diff"; then
        ok make-diffs/diff
    else
        fail make-diffs/diff "$(cat "$M/docs/diffs/02_b.diff" 2>&1)"
    fi
    if grep -q '^| \[02_b\](stages/02_b.md) | 01_a | \[02_b.diff\](diffs/02_b.diff) | 1 | 10 | 3 | 4 |$' "$M/docs/README.md" &&
        grep -q '^| \[01_a\](stages/01_a.md) | (none) | \[01_a.diff\](diffs/01_a.diff) | 2 (2 new) | 4 | 0 | 0 |$' "$M/docs/README.md"; then
        ok make-diffs/table
    else
        fail make-diffs/table "$(cat "$M/docs/README.md")"
    fi
    cp "$M/docs/diffs/02_b.diff" "$T/first.diff"
    cp "$M/docs/README.md" "$T/first.md"
    "$LAB_DIR/make-diffs.sh" --quiet --root "$M" >/dev/null 2>&1 || true
    if cmp -s "$T/first.diff" "$M/docs/diffs/02_b.diff" && cmp -s "$T/first.md" "$M/docs/README.md"; then
        ok make-diffs/reproducible
    else
        fail make-diffs/reproducible
    fi
    check check-diffs/current "$LAB_DIR/check-diffs.sh" --root "$M"
    if tail -n 1 "$T/out" | grep -q '^[0-9]* passed, 0 failed, 0 skipped$'; then
        ok check-diffs/closing-line
    else
        fail check-diffs/closing-line "$(tail -n 1 "$T/out")"
    fi
    printf '/* more */\n' >>"$M/stages/02_b/main.c"
    expect_exit check-diffs/stale 1 'FAIL diffs/02_b.diff: stale' "$LAB_DIR/check-diffs.sh" --root "$M"
    "$LAB_DIR/make-diffs.sh" --quiet --root "$M" >/dev/null 2>&1 || true
    check check-diffs/fixed "$LAB_DIR/check-diffs.sh" --root "$M"
    # A reader that leaves early (| head): SIGPIPE ends the script through
    # its trap, which removes its temporary directory.
    mkdir -p "$T/piped"
    TMPDIR=$T/piped "$LAB_DIR/check-diffs.sh" --root "$M" 2>/dev/null | head -n 0
    if [ -z "$(ls -A "$T/piped")" ]; then
        ok check-diffs/sigpipe-cleans-up
    else
        fail check-diffs/sigpipe-cleans-up "$(ls -A "$T/piped")"
    fi
}

test_branches() {
    B=$T/branches
    check make-branches/writes "$LAB_DIR/make-branches.sh" --root "$M" "$B"
    if [ "$(git -C "$B" tag | tr '\n' ' ')" = "stage-01 stage-02 " ] &&
        git -C "$B" rev-parse -q --verify feature/02_b >/dev/null &&
        [ "$(git -C "$B" rev-list --count main)" = 2 ] &&
        [ "$(git -C "$B" log -1 --format=%s stage-02)" = "Stage 02_b: the answer" ]; then
        ok make-branches/tags
    else
        fail make-branches/tags "$(git -C "$B" log --oneline --decorate 2>&1)"
    fi
    git -C "$B" diff stage-01 stage-02 --numstat >"$T/numstat"
    # 1 file: 10 lines of 02_b's main.c and the line test_diffs added, for
    # 01_a's 3
    if [ "$(awk '{ a += $1; r += $2; n++ } END { print n, a, r }' "$T/numstat")" = "1 11 3" ]; then
        ok make-branches/diff
    else
        fail make-branches/diff "$(cat "$T/numstat")"
    fi
    expect_exit make-branches/refuses 1 'earlier export' "$LAB_DIR/make-branches.sh" --root "$M" "$B"
    check make-branches/force "$LAB_DIR/make-branches.sh" --force --root "$M" "$B"
}

# grade-pages.sh on the project's own build (make test builds it first):
# a page per reference render of labs 03 (one render, relMSE limit) and 06
# (two renders, block tests, of the samples --spp asks for, as its header
# line says, and what they can find: compare's power line), each one file
# with its images embedded.
test_grade_pages() {
    root=$(cd "$LAB_DIR/../.." && pwd)
    expect_exit grade-pages/spp-must-be-positive 2 "spp needs a positive number, auto or paired, got '0'" \
        "$LAB_DIR/grade-pages.sh" --spp 0 "$root" 06_supersample "$T/pages/none"
    for gp_stage in 03_soft_shadows 06_supersample; do
        if [ ! -x "$root/build/$gp_stage/render" ]; then
            fail "grade-pages/$gp_stage" "no $root/build/$gp_stage/render: run make first"
            continue
        fi
        if ! "$LAB_DIR/grade-pages.sh" --spp 16 "$root" "$gp_stage" "$T/pages/$gp_stage" >"$T/out" 2>&1; then
            fail "grade-pages/$gp_stage" "$(cat "$T/out")"
            continue
        fi
        gp_want=2
        gp_verdict="within the limit"
        if [ "$gp_stage" = 06_supersample ]; then
            gp_want=1
            gp_verdict="consistent with the reference"
        fi
        gp_pages=$(ls "$T/pages/$gp_stage"/*.html 2>/dev/null | wc -l)
        gp_images=$(cat "$T/pages/$gp_stage"/*.html 2>/dev/null | grep -o 'src="data:image/png;base64,' | wc -l)
        # Its lines name the handout's files as the handout names them
        # (grade.sh grades a temporary copy, gone when the grade is read).
        if [ "$gp_pages" -eq "$gp_want" ] && [ "$gp_images" -eq $((5 * gp_want)) ] &&
            [ "$(grep -c "$gp_verdict" "$T/out")" -eq "$gp_want" ] &&
            grep -q "feature pass tests/reference/" "$T/out" &&
            { [ "$gp_stage" != 06_supersample ] ||
                { grep -q "two renders of 16 spp" "$T/out" &&
                    grep -q "; measured: docs/calibration/README.md)$" "$T/out" &&
                    grep -q "^        power: a bias that brightens or darkens a 32x32 window by" "$T/out"; }; } &&
            ! grep -q -e "$root/tests/reference" -e "grade-pages\." "$T/out"; then
            ok "grade-pages/$gp_stage"
        else
            fail "grade-pages/$gp_stage" "$gp_pages pages, $gp_images images" "$(cat "$T/out")"
        fi
    done
    # No --spp (make grade's default): the Mitsuba page, one render of 16
    # spp without a verdict (a look, the paired page's render), and the
    # paired page, which the project (no solution renders in
    # tests/reference/solution/: not a handout) cannot judge, and says so,
    # recording nothing.
    : >"$T/paired-records"
    if "$LAB_DIR/grade-pages.sh" --records "$T/paired-records" "$root" 06_supersample "$T/pages/default" >"$T/out" 2>&1 &&
        grep -q "(each page below: one render of 16 spp, the paired page's, a look" "$T/out" &&
        grep -q "^    cornell_diffuse_point_direct: not tested for bias" "$T/out" &&
        grep -q "^    cornell_diffuse_point_direct, paired: the handout has no solution render of cornell_diffuse_point" "$T/out" &&
        [ ! -s "$T/paired-records" ]; then
        ok grade-pages/paired-by-default
    else
        fail grade-pages/paired-by-default "$(cat "$T/out")"
    fi
    # --spp auto: a pilot of two 64-spp renders, whose power line already
    # finds 2% on lab 06's page, so its renders keep the pilot's spp.
    if "$LAB_DIR/grade-pages.sh" --spp auto "$root" 06_supersample "$T/pages/auto" >"$T/out" 2>&1 &&
        grep -q "two renders of the spp its pilot asks for" "$T/out" &&
        grep -q "1 grade in 100 by design; measured: docs/calibration/auto-256/README.md)$" "$T/out" &&
        [ -f "$root/docs/calibration/auto-256/README.md" ] &&
        grep -q "^    cornell_diffuse_point_direct: 64 spp a render (its pilot, two renders of 64 spp: finds 2% in 9 windows of 10 already)$" "$T/out" &&
        grep -q "^    cornell_diffuse_point_direct: consistent with the reference" "$T/out" &&
        [ "$(ls "$T/pages/auto"/*.html | wc -l)" -eq 1 ]; then
        ok grade-pages/spp-auto
    else
        fail grade-pages/spp-auto "$(cat "$T/out")"
    fi
    expect_exit grade-pages/spp-auto-or-number 2 "spp needs a positive number, auto or paired, got 'x'" \
        "$LAB_DIR/grade-pages.sh" --spp x "$root" 06_supersample "$T/pages/none"
}

# handout_build (lablib.sh) leaves no program of an earlier build standing
# in for one that does not build now, and relinks none that is up to
# date: a handout of two C "programs" and a "render", built, then broken
# in one program's source, then in the stage.
test_handout_build() {
    hb=$T/hb
    mkdir -p "$hb/stages/01_x" "$hb/tests/stage"
    printf 'int main(void) { return 0; }\n' >"$hb/stages/01_x/render.c"
    printf 'int main(void) { return 0; }\n' >"$hb/tests/stage/01_one.c"
    printf 'int main(void) { return 0; }\n' >"$hb/tests/stage/01_two.c"
    printf 'all: build/01_x/render\nbuild/01_x/render: stages/01_x/render.c\n\t@mkdir -p $(@D)\n\t$(CC) -o $@ $<\n' \
        >"$hb/Makefile"
    printf '%s/build/tests/01_x/%%: stage/%%.c\n\t@mkdir -p $(@D)\n\t$(CC) -o $@ $<\n' "$(cd "$hb" && pwd -P)" \
        >"$hb/tests/Makefile"
    hb_progs() { ls "$hb/build/01_x/render" "$hb/build/tests/01_x/01_one" "$hb/build/tests/01_x/01_two" 2>/dev/null | wc -l; }
    if handout_build "$hb" "$T/hb.log" all && [ "$(hb_progs)" -eq 3 ]; then
        touch -d '2000-01-01' "$hb/build/tests/01_x/01_two"
        touch -d '1999-01-01' "$hb/tests/stage/01_two.c"
        echo 'broken' >>"$hb/tests/stage/01_one.c"
        touch -d '2001-01-01' "$hb/build/tests/01_x/01_two" # up to date: not relinked
        if ! handout_build "$hb" "$T/hb.log" all && [ ! -e "$hb/build/tests/01_x/01_one" ] &&
            [ "$(stat -c %Y "$hb/build/tests/01_x/01_two")" = "$(date -d '2001-01-01' +%s)" ] &&
            [ -e "$hb/build/01_x/render" ]; then
            ok handout-build/a-program-that-does-not-build-goes
        else
            fail handout-build/a-program-that-does-not-build-goes "$(ls -l "$hb/build/tests/01_x")" "$(cat "$T/hb.log")"
        fi
        # A default grade's build leaves out the FULL=1-only programs.
        printf '/*\n * Grading: make grade FULL=1 only (slow)\n */\nint main(void) { return 0; }\n' \
            >"$hb/tests/stage/01_slow.c"
        handout_build "$hb" "$T/hb.log" default || :
        hb_default=0
        [ ! -e "$hb/build/tests/01_x/01_slow" ] || hb_default=1
        handout_build "$hb" "$T/hb.log" all || :
        if [ "$hb_default" -eq 0 ] && [ -e "$hb/build/tests/01_x/01_slow" ]; then
            ok handout-build/a-default-grade-builds-no-full-only-program
        else
            fail handout-build/a-default-grade-builds-no-full-only-program "$(ls -l "$hb/build/tests/01_x")"
        fi
        echo 'broken' >>"$hb/stages/01_x/render.c"
        if ! handout_build "$hb" "$T/hb.log" all && [ "$(hb_progs)" -eq 0 ]; then
            ok handout-build/a-stage-that-does-not-build-takes-every-program
        else
            fail handout-build/a-stage-that-does-not-build-takes-every-program "$(ls -lR "$hb/build")"
        fi
    else
        fail handout-build/builds "$(cat "$T/hb.log")"
    fi
}

# The paired page's second look (grade-pages.sh, lablib.sh's
# PAIRED_SECOND_SEED): a handout whose render copies a prepared image for
# each seed, against the solution's renders of seeds 1 and 2 (two seeds of
# lab 06's stage).  A bias at both seeds fails, naming both; a bias at the
# first seed only passes, saying the first look was chance; a handout
# without the second seed's render keeps the first look's verdict.
test_second_look() {
    root=$(cd "$LAB_DIR/../.." && pwd)
    sl=$T/second-look
    mkdir -p "$sl/build/06_supersample" "$sl/build/tools" "$sl/scenes" "$sl/tests/reference/solution/seed2" "$sl/img"
    cp "$root/build/tools/paired" "$sl/build/tools/" || { fail grade-pages/second-look "no paired tool (make first)"; return; }
    cp "$root/scenes/cornell_diffuse_point.scene" "$sl/scenes/"
    printf 'tools:\n\t@:\n' >"$sl/tests/Makefile"
    for sl_seed in 1 2; do
        "$root/build/06_supersample/render" -q -W 256 -H 256 --spp 4 --seed "$sl_seed" -o "$sl/img/sol$sl_seed.pfm" \
            "$root/scenes/cornell_diffuse_point.scene" >/dev/null 2>&1 ||
            { fail grade-pages/second-look "no render of lab 06 (make first)"; return; }
        "$root/build/tools/imgedit" --scale 1.05 "$sl/img/sol$sl_seed.pfm" "$sl/img/biased$sl_seed.pfm" >/dev/null
    done
    cp "$sl/img/sol1.pfm" "$sl/tests/reference/solution/cornell_diffuse_point.pfm"
    cp "$sl/img/sol2.pfm" "$sl/tests/reference/solution/seed2/cornell_diffuse_point.pfm"
    # The student's "render": the image named in $sl/student.SEED for --seed SEED.
    cat >"$sl/build/06_supersample/render" <<'SCRIPT'
#!/bin/sh
seed= out=
while [ $# -gt 0 ]; do
    case $1 in --seed) seed=$2; shift ;; -o) out=$2; shift ;; esac
    shift
done
cp "$(cat "$(dirname "$0")/../../student.$seed")" "$out"
SCRIPT
    chmod +x "$sl/build/06_supersample/render"
    # sl_case NAME IMAGE1 IMAGE2 WANT_RECORD WANT_LINE
    sl_case() {
        echo "$sl/img/$2.pfm" >"$sl/student.1"
        echo "$sl/img/$3.pfm" >"$sl/student.2"
        : >"$T/sl-records"
        "$LAB_DIR/grade-pages.sh" --records "$T/sl-records" --paired-only cornell_diffuse_point_direct \
            "$sl" 06_supersample "$T/sl-pages" >"$T/sl-out" 2>&1 || :
        if grep -q "^cornell_diffuse_point_direct $4" "$T/sl-records" && grep -q "$5" "$T/sl-out"; then
            ok "grade-pages/second-look-$1"
        else
            fail "grade-pages/second-look-$1" "$(cat "$T/sl-records" "$T/sl-out")"
        fi
    }
    sl_case bias-at-both biased1 biased2 "FAIL biased at both seeds (1 and 2)" "second look (--seed 2): .*biased"
    sl_case chance-at-the-first biased1 sol2 ok "consistent at the second seed: the first look's blocks were chance"
    sl_case correct sol1 biased2 ok "paired with the solution's render"
    if grep -q "second look" "$T/sl-out"; then fail grade-pages/second-look-only-after-a-bias "$(cat "$T/sl-out")"; else ok grade-pages/second-look-only-after-a-bias; fi
    rm -r "$sl/tests/reference/solution/seed2"
    sl_case without-its-render biased1 sol2 FAIL "biased"
}

# spp_for_power (lablib.sh) on compare's own power lines: two renders of 1
# spp of lab 06, which need many times their samples to find 2% (the spp
# those ask for, a whole number of passes of 16, at most MAX), and
# lines written as compare writes its other two cases.
test_spp_for_power() {
    root=$(cd "$LAB_DIR/../.." && pwd)
    sp_render=$root/build/06_supersample/render
    sp_scene=$root/scenes/cornell_diffuse_point.scene
    sp_ref=$root/tests/reference/cornell_diffuse_point_direct.pfm
    for sp_i in 1 2; do
        "$sp_render" -q -W 256 -H 256 --spp 1 --seed "$sp_i" -o "$T/sp.$sp_i.pfm" "$sp_scene" >/dev/null 2>&1 ||
            { fail spp-for-power "no render of lab 06 (run make first)"; return; }
    done
    "$root/build/tools/compare" -q "$T/sp.1.pfm" "$T/sp.2.pfm" "$sp_ref" >"$T/sp.out" 2>&1 || true
    sp_times=$(grep -o "about [0-9.]* times these renders' samples" "$T/sp.out" | awk '{ print $2 }')
    sp_want=$(awk -v t="$sp_times" 'BEGIN { n = 16 * int((t + 15) / 16); print (n > 4096 ? 4096 : n) }')
    if [ -n "$sp_times" ] && spp_for_power "$T/sp.out" 1 4096 && [ "$sfp_spp" = "$sp_want" ] &&
        [ "$sfp_says" = "2% in 9 windows of 10 needs $sp_times times their samples" ]; then
        ok spp-for-power/compare-line
    else
        fail spp-for-power/compare-line "times '$sp_times', want $sp_want, got '${sfp_spp:-}' ('${sfp_says:-}')" "$(cat "$T/sp.out")"
    fi
    sp_ok=1
    while IFS='|' read -r sp_line sp_base sp_max sp_spp sp_says; do
        printf 'verdict\npower: %s\n' "$sp_line" >"$T/sp.line"
        if ! spp_for_power "$T/sp.line" "$sp_base" "$sp_max" || [ "$sfp_spp" != "$sp_spp" ] || [ "$sfp_says" != "$sp_says" ]; then
            fail spp-for-power/cases "$sp_line: want $sp_spp ($sp_says), got ${sfp_spp:-} (${sfp_says:-})"
            sp_ok=0
        fi
    done <<'EOF_CASES'
a bias ...; 2.0% is found so in 9 windows of 10 already|64|4096|64|finds 2% in 9 windows of 10 already
a bias ...; to find 2.0% so in 9 windows of 10: about 2.1 times these renders' samples (--spp, or more renders with other --seed values)|64|4096|144|2% in 9 windows of 10 needs 2.1 times their samples
a bias ...; to find 2.0% so in 9 windows of 10: about 1400 times these renders' samples (--spp, or more renders with other --seed values)|64|4096|4096|2% in 9 windows of 10 needs 1400 times their samples; at most 4096
a bias ...; 2.0% in 9 windows of 10 is hidden by the reference's own noise|64|512|512|2% in 9 windows of 10 is hidden by the reference's own noise; at most 512
EOF_CASES
    printf 'consistent\n' >"$T/sp.line"
    if spp_for_power "$T/sp.line" 64 4096; then
        fail spp-for-power/cases "a verdict without a power line gave ${sfp_spp:-}"
        sp_ok=0
    fi
    [ "$sp_ok" = 0 ] || ok spp-for-power/cases
}

# make docs-images in a build without glTF: the mesh image is skipped with
# a note and the others are rendered (a stand-in render that answers as
# such a build does for a scene with a mesh).
test_docs_images() {
    di_root=$(cd "$LAB_DIR/../.." && pwd)
    if [ ! -x "$di_root/build/05_bvh/render" ] || [ ! -x "$di_root/build/tools/gen_meshes" ]; then
        fail docs-images/skips-what-needs-a-missing-library "build the project first (make)"
        return 0
    fi
    mkdir -p "$T/nogltf/05_bvh"
    ln -s "$di_root/build/tools" "$T/nogltf/tools"
    cat >"$T/nogltf/05_bvh/render" <<EOF
#!/bin/sh
for a in "\$@"; do
    if [ -f "\$a" ] && grep -q '^mesh ' "\$a"; then
        echo "\$a:1:1: error: cannot load mesh: this build has no glTF support: install libtinygltf-dev and rebuild" >&2
        exit 1
    fi
done
exec "$di_root/build/05_bvh/render" "\$@"
EOF
    chmod +x "$T/nogltf/05_bvh/render"
    di_status=0
    BUILD=$T/nogltf IMAGES=$T/images "$di_root/docs/make-images.sh" 05 >"$T/di.out" 2>&1 || di_status=$?
    if [ "$di_status" -eq 0 ] && grep -q 'skipped .*05_bvh_terrain.png: no glTF support' "$T/di.out" &&
        [ -f "$T/images/05_bvh_showcase.png" ] && [ ! -e "$T/images/05_bvh_terrain.png" ]; then
        ok docs-images/skips-what-needs-a-missing-library
    else
        fail docs-images/skips-what-needs-a-missing-library "exit $di_status" "$(cat "$T/di.out")"
    fi
}

# check-limits.sh on the mini project (its diffs written by test_diffs), then
# on a doctored table and on files grown past the limits.
test_limits() {
    check check-limits/within "$LAB_DIR/check-limits.sh" --root "$M"
    sed -E 's/^(\| \[02_b\].*\|) [0-9]+ \| [0-9]+ \| [0-9]+ \|$/\1 440 | 11 | 251 |/' \
        "$M/docs/README.md" >"$T/limits.md"
    expect_exit check-limits/diff-over 1 'FAIL limits/diff 02_b: 451 changed lines' \
        "$LAB_DIR/check-limits.sh" --root "$M" --table "$T/limits.md"
    expect_exit check-limits/lab-over 1 'FAIL limits/lab 02_b: 251 lines in LAB regions' \
        "$LAB_DIR/check-limits.sh" --root "$M" --table "$T/limits.md"
    sed -E 's/^(\| \[02_b\].*\|) [0-9]+ \| [0-9]+ \| [0-9]+ \|$/\1 440 | 10 | 250 |/' \
        "$M/docs/README.md" >"$T/limits.md"
    check check-limits/at-the-limits "$LAB_DIR/check-limits.sh" --root "$M" --table "$T/limits.md"
    awk 'BEGIN { for (i = 0; i < 501; i++) print "/* line */" }' >"$M/stages/02_b/long.h"
    expect_exit check-limits/source-over 1 'FAIL limits/source: stages/02_b/long.h has 501 lines' \
        "$LAB_DIR/check-limits.sh" --root "$M"
    mv "$M/stages/02_b/long.h" "$M/docs/stages/03_c.md"
    expect_exit check-limits/lesson-over 1 'FAIL limits/lesson: docs/stages/03_c.md has 501 lines' \
        "$LAB_DIR/check-limits.sh" --root "$M"
    rm "$M/docs/stages/03_c.md"
    expect_exit check-limits/no-table 1 'no diff table' \
        "$LAB_DIR/check-limits.sh" --root "$M" --table /dev/null
}

test_help() {
    # make help has a line for every target of the top-level Makefile.
    hp_root=$(cd "$LAB_DIR/../.." && pwd)
    make -s --no-print-directory -C "$hp_root" help >"$T/make-help" 2>&1 || true
    hp_missing=
    for hp_t in $(sed -n 's/^\.PHONY: *//p' "$hp_root/Makefile" | tr ' ' '\n' | grep -v '^\$'); do
        grep -q "^make $hp_t\( \|$\)" "$T/make-help" || hp_missing="$hp_missing $hp_t"
    done
    # ... and for the knobs a user types with them.
    for hp_k in STAGE=NN REAL=float WERROR=1; do
        grep -q "$hp_k" "$T/make-help" || hp_missing="$hp_missing $hp_k"
    done
    if [ -z "$hp_missing" ] && [ -s "$T/make-help" ]; then
        ok help/make-help
    else
        fail help/make-help "no line for:$hp_missing" "$(cat "$T/make-help")"
    fi
    for hp_s in make-lab grade grade-pages make-diffs check-diffs check-labs check-limits make-branches test-lab-tools; do
        if "$LAB_DIR/$hp_s.sh" --help 2>&1 | head -n 1 | grep -q "^$hp_s.sh - "; then
            ok "help/$hp_s"
        else
            fail "help/$hp_s" "$("$LAB_DIR/$hp_s.sh" --help 2>&1 | head -n 3)"
        fi
    done
}

# --- options: parse_options (lablib.sh) ------------------------------------
# po SPEC ARG... - what the variables and the rest hold after parsing, as
# one line, or the usage error and its exit status.
po() {
    (
        po_spec=$1
        shift
        flag=0 value=- dir=-
        parse_options "$po_spec" "$@" 2>&1
        shift "$po_used"
        echo "flag=$flag value=$value dir=$dir rest=$*"
    ) 2>&1 || echo "exit $?"
}
test_options() {
    op_spec='--flag flag=yes --value value=VALUE --dir dir=DIR'
    mkdir -p "$T/opt dir"
    op_dir=$(cd "$T/opt dir" && pwd)
    # Each case: its name|the expected lines|the arguments.
    for op_case in \
        "all-kinds|flag=yes value=a b dir=$op_dir rest=x --flag|--flag --value 'a b' --dir '$T/opt dir' x --flag" \
        "double-dash|flag=0 value=--flag dir=- rest=--flag|--value --flag -- --flag" \
        "none|flag=0 value=- dir=- rest=|" \
        "unknown|$PROG: unknown option: --bogus|Try '$PROG --help'.|exit 2|--flag --bogus" \
        "no-value|$PROG: --value needs a value|Try '$PROG --help'.|exit 2|--value" \
        "no-dir|$PROG: --dir needs a directory|Try '$PROG --help'.|exit 2|--dir" \
        "missing-dir|$PROG: error: no such directory: $T/none|exit 1|--dir '$T/none'"; do
        op_name=${op_case%%|*}
        op_want=${op_case#*|}
        op_want=${op_want%|*}
        eval "set -- ${op_case##*|}"
        op_got=$(po "$op_spec" "$@" | tr '\n' '|')
        if [ "$op_got" = "$op_want|" ]; then
            ok "options/$op_name"
        else
            fail "options/$op_name" "got:  $op_got" "want: $op_want|"
        fi
    done
}

# --- grading: test_statuses (lablib.sh) and grade.awk ----------------------
# A TEST() that passes in the untouched handout is a control: listed, not
# scored (a handout with only stubs must score 0%, the solution 100%).
test_grade_score() {
    printf 'TEST(a) {}\nTEST(b) {}\nTEST(c) {}\nTEST(d) {}\n' >"$T/05_x.c"
    printf 'ok   a\nsome check: FAIL this line is not a result\nFAIL b\nskip c\n3 passed, 1 failed, 1 skipped\n' >"$T/05_x.log"
    test_statuses "$T/05_x.c" "$T/05_x.log" - >"$T/st" 2>&1
    printf 'a ok\nb FAIL\nc skip\nd FAIL\n' >"$T/st.expected"
    same grade/statuses "$T/st.expected" "$T/st"
    test_statuses "$T/05_x.c" "$T/05_x.log" crashed >"$T/st" 2>&1
    printf 'a FAIL\nb FAIL\nc FAIL\nd FAIL\n' >"$T/st.expected"
    same grade/statuses-crashed "$T/st.expected" "$T/st"
    test_statuses "$T/05_x.c" "$T/05_x.log" exit-1 | tail -n 1 >"$T/st" 2>&1
    printf '(exit-1) FAIL\n' >"$T/st.expected"
    same grade/statuses-exit "$T/st.expected" "$T/st"

    # Lab 05: 05_x has the controls a and b; 05-06_y none; 01_z is earlier.
    # gr RECORDS... - grade.awk's GRADE line and control line for records.
    gr() {
        printf '%s\n' "$@" | tr '|' '\t' >"$T/records"
        awk -v nn=05 -v stage=05_x -v build=ok -v controls=known -f "$LAB_DIR/grade.awk" "$T/records" >"$T/report"
        { grep '^GRADE ' "$T/report"; grep '^    controls' "$T/report" | sed 's/^ *//'; } | tr '\n' '|'
    }
    # Untouched: the controls pass, everything else fails: 0%.
    got=$(gr 'C|05_x|a' 'C|05_x|b' 'P|05|05_x|-' 'T|05|05_x|a|ok' 'T|05|05_x|b|ok' 'T|05|05_x|c|FAIL' \
        'P|05|05-06_y|-' 'T|05|05-06_y|e|FAIL' 'P|01|01_z|-' 'T|01|01_z|a|ok' 'T|01|01_z|b|ok')
    want='GRADE lab=05_x score=0.0 lab_passed=0 lab_total=2 controls=2 earlier_passed=2 earlier_total=2 regressions=0 build=ok|controls (pass without your work, not scored): 05_x/a, 05_x/b|'
    if [ "$got" = "$want" ]; then ok grade/untouched-scores-0; else fail grade/untouched-scores-0 "got:  $got" "want: $want"; fi
    # The solution: everything passes: 100%, the controls still not scored.
    got=$(gr 'C|05_x|a' 'C|05_x|b' 'P|05|05_x|-' 'T|05|05_x|a|ok' 'T|05|05_x|b|ok' 'T|05|05_x|c|ok' \
        'P|05|05-06_y|-' 'T|05|05-06_y|e|ok' 'T|05|05-06_y|f|skip' 'P|01|01_z|-' 'T|01|01_z|a|ok' 'T|01|01_z|b|ok')
    want='GRADE lab=05_x score=100.0 lab_passed=2 lab_total=2 controls=2 earlier_passed=2 earlier_total=2 regressions=0 build=ok|controls (pass without your work, not scored): 05_x/a, 05_x/b|'
    if [ "$got" = "$want" ]; then ok grade/solution-scores-100; else fail grade/solution-scores-100 "got:  $got" "want: $want"; fi
    # Half done, a control broken, an earlier test of the same name as a
    # control (not a control: controls are the lab's), a crashed program.
    # The three regressions (two controls, one earlier test) count as failed
    # tests of the lab: 1 of 2 + 3 = 20%.
    got=$(gr 'C|05_x|a' 'C|05_x|b' 'C|05-06_y|e' 'P|05|05_x|-' 'T|05|05_x|a|FAIL' 'T|05|05_x|b|ok' 'T|05|05_x|c|ok' \
        'P|05|05-06_y|crashed' 'T|05|05-06_y|e|FAIL' 'T|05|05-06_y|f|FAIL' 'P|01|01_z|-' 'T|01|01_z|a|FAIL' 'T|01|01_z|b|ok')
    want='GRADE lab=05_x score=20.0 lab_passed=1 lab_total=2 controls=3 earlier_passed=1 earlier_total=2 regressions=3 build=ok|controls (pass without your work, not scored): 05_x/a (fails now), 05_x/b, 05-06_y/e (fails now)|'
    if [ "$got" = "$want" ] && grep -q '^score: 20.0% (1 of 2 tests of lab 05; 3 control(s) not scored); earlier stages: 1 of 2 (3 regression(s), each counted as a failed test of lab 05: your code is the code that changed)$' "$T/report" &&
        grep -q '^    05-06_y  *0/1    crashed failed: f$' "$T/report"; then
        ok grade/controls-not-scored
    else
        fail grade/controls-not-scored "got:  $got" "want: $want" "$(cat "$T/report")"
    fi
    # check-labs' "earlier" detail: the earlier groups' failing programs,
    # not the lab's own (05_x and 05-06_y fail above too).
    earlier_failures "$T/report" | sed 's/  */ /g' >"$T/earlier"
    printf ' 01_z 1/2 failed: a\n' >"$T/earlier.expected"
    same grade/earlier-failures "$T/earlier.expected" "$T/earlier"
    # Every test of the lab passes but a control fails: below 100% (a bug
    # that only a control catches is scored).
    got=$(gr 'C|05_x|a' 'P|05|05_x|-' 'T|05|05_x|a|FAIL' 'T|05|05_x|b|ok' 'T|05|05_x|c|ok')
    case $got in
        'GRADE lab=05_x score=66.7 lab_passed=2 lab_total=2 controls=1 earlier_passed=0 earlier_total=0 regressions=1 build=ok|'*) ok grade/a-failing-control-costs-points ;;
        *) fail grade/a-failing-control-costs-points "$got" ;;
    esac
    # A program that only a full grade runs: listed as not run, counted
    # nowhere (the score is the tests that ran).
    got=$(gr 'S|05|05_slow' 'P|05|05_x|-' 'T|05|05_x|a|ok')
    if [ "$got" = 'GRADE lab=05_x score=100.0 lab_passed=1 lab_total=1 controls=0 earlier_passed=0 earlier_total=0 regressions=0 build=ok|controls: none (every test of this lab fails without your work)|' ] &&
        grep -q '^not run (slow; their bugs are the function tests.* make grade FULL=1 runs them): 05_slow$' "$T/report"; then
        ok grade/full-only-programs-listed-not-run
    else
        fail grade/full-only-programs-listed-not-run "$got" "$(cat "$T/report")"
    fi
    # The function tests' list: each TEST() of the lab's NN_lab_functions
    # with its status, and a failing one's first message under it.
    printf '%s\n' 'P|05|05_lab_functions|-' 'T|05|05_lab_functions|bvh_intersect_x|FAIL' \
        'M|05|05_lab_functions|bvh_intersect_x|bvh_intersect (3 primitives): wrong hit' \
        'T|05|05_lab_functions|build_subtree_y|ok' | tr '|' '\t' >"$T/records"
    awk -v nn=05 -v stage=05_x -v build=ok -v controls=known -f "$LAB_DIR/grade.awk" "$T/records" |
        sed -n '/^your functions/,/^$/p' >"$T/functions"
    printf '%s\n' 'your functions (each test named for the LAB function it tests):' '    FAIL bvh_intersect_x' \
        '         bvh_intersect (3 primitives): wrong hit' '    ok   build_subtree_y' '' >"$T/functions.expected"
    same grade/functions-listed-with-messages "$T/functions.expected" "$T/functions"
    got=$(gr 'P|05|05_x|-' 'T|05|05_x|a|ok')
    case $got in
        *'controls: none'*'|') ok grade/no-controls ;;
        *) fail grade/no-controls "$got" ;;
    esac
}

# --- controls: handout_controls (lablib.sh) ---------------------------------
# A program that crashes or times out as a whole is run again one TEST() at
# a time: which tests pass untouched must not depend on the machine's load
# or on a slow sibling test.  The "program" is a script: run whole, it
# prints "ok   a" and dies without a result line; run with a TEST()'s
# name, a passes, b fails, c hangs past the limit (1 s).
test_controls() {
    ct=$T/controls-handout
    mkdir -p "$ct/stages/05_x" "$ct/tests/stage" "$ct/build/tests/05_x"
    printf 'TEST(a) {}\nTEST(b) {}\nTEST(c) {}\n' >"$ct/tests/stage/05_x.c"
    printf 'TEST(z) {}\n' >"$ct/tests/stage/01_z.c"
    cat >"$ct/build/tests/05_x/05_x" <<'EOF2'
#!/bin/sh
case ${1:-} in
    '') echo 'ok   a'; kill -s SEGV $$ ;;
    a) printf 'ok   a\n1 passed, 0 failed, 0 skipped\n' ;;
    b) printf 'FAIL b\n0 passed, 1 failed, 0 skipped\n'; exit 1 ;;
    c) exec sleep 5 ;;
esac
EOF2
    chmod +x "$ct/build/tests/05_x/05_x"
    handout_controls "$ct" "$T/controls-logs" 1 >"$T/controls" 2>/dev/null
    printf '05_x a ok\n05_x b FAIL\n05_x c FAIL\n' >"$T/controls.expected"
    same controls/crashed-program-rerun-per-test "$T/controls.expected" "$T/controls"
}

# --- the second seed: second_seed (lablib.sh) and grade.awk's R records -----
# A statistical program's failing TEST() is run again at GRADE_SECOND_SEED:
# a chance failure (a passes there) counts as passed and is named in the
# report; a bug (b fails there too) stays failed; a deterministic
# program's failure is not run again.
test_second_seed() {
    ss=$T/second-handout
    mkdir -p "$ss/stages/05_x" "$ss/tests/stage" "$ss/build/tests/05_x"
    printf 'TEST(a) {}\nTEST(b) {}\nuint64_t s = pathcheck_seed(1);\n' >"$ss/tests/stage/05_x.c"
    printf 'TEST(a) {}\n' >"$ss/tests/stage/05_det.c"
    cat >"$ss/build/tests/05_x/05_x" <<EOF2
#!/bin/sh
if [ "\${PATHCHECK_SEED:-}" = $GRADE_SECOND_SEED ] && [ "\${1:-}" = a ]; then
    printf 'ok   a\n1 passed, 0 failed, 0 skipped\n'
else
    printf 'FAIL %s\n0 passed, 1 failed, 0 skipped\n' "\${1:-a}"; exit 1
fi
EOF2
    cp "$ss/build/tests/05_x/05_x" "$ss/build/tests/05_x/05_det"
    chmod +x "$ss/build/tests/05_x/05_x" "$ss/build/tests/05_x/05_det"
    # As grade.sh runs one TEST(): run_handout_test in the handout.
    ss_run() { run_handout_test "$ss" "$1" "$2" 5 "$3" >/dev/null; }
    printf 'a FAIL\nb FAIL\n' | second_seed "$ss/tests/stage/05_x.c" "$GRADE_SECOND_SEED" "$T/second" \
        ss_run "$ss/tests/stage/05_x.c" >"$T/second.out" 2>&1
    printf 'a FAIL\n' | second_seed "$ss/tests/stage/05_det.c" "$GRADE_SECOND_SEED" "$T/second-det" \
        ss_run "$ss/tests/stage/05_det.c" >>"$T/second.out" 2>&1
    printf 'a ok second\nb FAIL\na FAIL\n' >"$T/second.expected"
    same grade/second-seed-reruns-statistical-failures "$T/second.expected" "$T/second.out"
    printf '%s\n' 'P|05|05_x|-' 'T|05|05_x|a|ok' 'R|05|05_x|a' 'T|05|05_x|b|FAIL' | tr '|' '\t' >"$T/records"
    awk -v nn=05 -v stage=05_x -v build=ok -v controls=unknown -f "$LAB_DIR/grade.awk" "$T/records" >"$T/report"
    if grep -q '^passed at the second seed (.*): 05_x/a$' "$T/report" && grep -q '^GRADE .* score=50.0 ' "$T/report"; then
        ok grade/second-seed-named-in-the-report
    else
        fail grade/second-seed-named-in-the-report "$(cat "$T/report")"
    fi
}

# make calibrate-compare's planted code bugs (sed expressions on stage 07's
# sources) still change what they name: stage 07 moved on once under them.
test_calibrate_plants() {
    check calibrate/plants-apply sh "$LAB_DIR/../calibrate/calibrate.sh" --check-plants
}

# make calibrate-compare's grade-auto ledger (tiny renders): a second run with more
# --sets measures only the set the ledger lacks and counts both; a line of
# another key (measured before the code changed) is not counted.
test_calibrate_ledger() {
    root=$(cd "$LAB_DIR/../.." && pwd)
    if [ ! -x "$root/build/07_pathtrace/render" ] || [ ! -x "$root/build/tools/plotcsv" ]; then
        fail calibrate/ledger "no $root/build/07_pathtrace/render or build/tools: run make first"
        return
    fi
    cl_out=$T/calibrate
    mkdir -p "$cl_out"
    printf '# calibration\n<!-- calibrate: table -->\n<!-- calibrate: end -->\n' >"$cl_out/README.md"
    cl_ledger=$cl_out/grade-auto.sets
    cl_run() {
        sh "$LAB_DIR/../calibrate/calibrate.sh" --size 32 --spp 4 --threads 1 --verdicts grade-auto \
            --bug-sets 0 --scenes cornell_diffuse_area --out "$cl_out" "$@" >"$T/out" 2>&1
    }
    if ! cl_run --sets 1 || [ "$(wc -l <"$cl_ledger")" -ne 1 ]; then
        fail calibrate/ledger "first run" "$(cat "$T/out")"
        return
    fi
    # Set 0 doctored to a false alarm that was not found: counted as it is
    # only if the second run does not measure it again.
    awk '{ $4 = 1; $5 = 0; print }' "$cl_ledger" >"$T/ledger" && mv "$T/ledger" "$cl_ledger"
    echo "cornell_diffuse_area another-key 1 1 1 16 1.0" >>"$cl_ledger"
    if cl_run --sets 2 && [ "$(wc -l <"$cl_ledger")" -eq 3 ] &&
        grep -q '^grade-auto,cornell_diffuse_area,none,0,2,1,' "$cl_out/calibration.csv" &&
        grep -q '^| grade-auto | cornell_diffuse_area | none | 1 of 2 |' "$cl_out/README.md" &&
        grep -q 'grade-auto: 2 sets in the ledger' "$T/out"; then
        ok calibrate/ledger
    else
        fail calibrate/ledger "$(cat "$T/out")" "$(cat "$cl_ledger")" "$(cat "$cl_out/calibration.csv")"
    fi
    expect_exit calibrate/from-is-grade-auto-alone 2 "is for --verdicts grade-auto alone" \
        sh "$LAB_DIR/../calibrate/calibrate.sh" --from 3
}

test_markers
cd "$T"
test_marker_errors
test_store_errors
test_labdoc
test_leaks
if command -v git >/dev/null 2>&1; then
    test_diffstat
fi
mini_project
test_reading_time
test_make_lab
if command -v git >/dev/null 2>&1; then
    test_diffs
    test_limits
    test_branches
fi
test_options
test_grade_score
test_controls
test_second_seed
test_grade_pages
test_handout_build
test_second_look
test_spp_for_power
test_docs_images
test_help
test_calibrate_plants
test_calibrate_ledger
echo "$passed passed, $failed failed, 0 skipped"
[ "$failed" -eq 0 ]
