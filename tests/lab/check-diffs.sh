#!/bin/sh
# check-diffs.sh - check that the stage diffs and their table are current
# (part of make test).
#
#   check-diffs.sh [options]
#
# Regenerates docs/diffs/ and the diff table of docs/README.md into a
# temporary directory (make-diffs.sh) and compares.  Checks:
#   NN_name.diff   docs/diffs/NN_name.diff is what make diffs writes now
#   table          docs/README.md holds the current diff table
#   stray          docs/diffs/ holds no diff of a stage that does not exist
#   link           docs/stages/NN_name.md links its diff (../diffs/NN_name.diff)
# One result line per check, like tests/harness/run-tests.sh, and the closing line
# "N passed, N failed, N skipped".  Fix a stale diff with make diffs.
#
# Options:
#   --root DIR   the project (default: the one this script belongs to)
#   --help
# Exit status: 0 every check passed, 1 a check failed, 2 usage.
set -eu

PROG=check-diffs.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

root=$(cd "$LAB_DIR/../.." && pwd)
parse_options '--root root=DIR' "$@"
shift "$po_used"
[ $# -eq 0 ] || usage_error "unexpected argument: $1"

tmp=$(mktemp -d "${TMPDIR:-/tmp}/check-diffs.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' HUP INT PIPE TERM

passed=0
failed=0
skipped=0
result() {
    case $1 in
        ok) passed=$((passed + 1)); printf 'ok   diffs/%s\n' "$2" ;;
        FAIL) failed=$((failed + 1)); printf 'FAIL diffs/%s\n' "$2" ;;
    esac
}

docs=$root/docs
mkdir -p "$tmp/docs"
[ -f "$docs/README.md" ] && cp "$docs/README.md" "$tmp/docs/README.md"
if ! "$LAB_DIR/make-diffs.sh" --quiet --root "$root" --docs "$tmp/docs" 2>"$tmp/err"; then
    result FAIL "make-diffs.sh failed"
    sed 's/^/        /' "$tmp/err"
    echo "$passed passed, $failed failed, $skipped skipped"
    exit 1
fi

for s in $(stage_list "$root"); do
    if [ ! -f "$docs/diffs/$s.diff" ]; then
        result FAIL "$s.diff: missing (run make diffs)"
    elif cmp -s "$tmp/docs/diffs/$s.diff" "$docs/diffs/$s.diff"; then
        result ok "$s.diff: current"
    else
        result FAIL "$s.diff: stale, stages/$s changed since (run make diffs)"
        diff "$docs/diffs/$s.diff" "$tmp/docs/diffs/$s.diff" | head -n 10 | sed 's/^/        /'
    fi
    page=docs/stages/$s.md
    if [ ! -f "$root/$page" ]; then
        result FAIL "$s.diff: link: $page does not exist"
    elif grep -q "\.\./diffs/$s\.diff" "$root/$page"; then
        result ok "$s.diff: link: $page links it"
    else
        result FAIL "$s.diff: link: $page does not link ../diffs/$s.diff"
    fi
done

stray=
for f in "$docs"/diffs/*; do
    [ -e "$f" ] || continue
    [ -e "$tmp/docs/diffs/$(basename "$f")" ] || stray="$stray ${f#"$root"/}"
done
if [ -z "$stray" ]; then
    result ok "stray: no diff of a stage that does not exist"
else
    result FAIL "stray: not written by make diffs:$stray"
fi

if [ -f "$docs/README.md" ] && cmp -s "$tmp/docs/README.md" "$docs/README.md"; then
    result ok "table: docs/README.md holds the current diff table"
else
    result FAIL "table: docs/README.md lacks the current diff table (run make diffs)"
fi

echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
