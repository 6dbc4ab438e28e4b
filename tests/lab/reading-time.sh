#!/bin/sh
# reading-time.sh - how long a learner needs to read stage 01 (its lesson
# page and its code) and each consecutive diff: an estimate from counts,
# not a stopwatch (docs/reading-time.md says why these rates).
#
#   reading-time.sh [--root DIR] [--help]
#
# Counts, for stage 01: the words of docs/stages/01_*.md outside its fenced
# code blocks, the words of the comments in stages/01_*/*.[ch], and the
# lines of code (not blank, not only a comment); for each later stage NN:
# the same counts over the lines the diff from the previous stage adds
# and over those it removes (`diff -ruN`; what it removes is read too, as
# context: its code as code, its comments as prose).  Minutes at two
# paces: prose at 238 words a minute (the mean silent reading rate of
# non-fiction, Brysbaert 2019) with code at 10 lines a minute (600 lines an
# hour, a first careful read), and a slower one, prose at 200 and code at
# 5 lines a minute (300 an hour, the middle of the 200-400 lines an hour
# that code review studies find effective).  For a diff, a last column
# gives the brisk minutes for what it adds alone: the time of a learner who
# only glances at the lines it removes, having read them in the stage
# before (a lower bound; the brisk column is the upper).  Prints a
# markdown table.
# Exit status: 0, 2 usage.
set -eu

PROG=reading-time.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"
root=$(cd "$LAB_DIR/../.." && pwd)
parse_options '--root root=DIR' "$@"
shift "$po_used"
[ $# -eq 0 ] || usage_error "unexpected argument: $1"

# c_counts - of C text on stdin: "CODE_LINES COMMENT_WORDS".
c_counts() {
    awk '
        # words(s): the words of comment text s (the "*" opening a continuation line not one)
        function words(s,   a) { sub(/^[ \t]*\*+/, "", s); return split(s, a, /[ \t]+/) - (s ~ /^[ \t]/) - (s ~ /[ \t]$/) }
        {
            line = $0
            if (in_comment) {
                if (match(line, /\*\//)) { cw += words(substr(line, 1, RSTART - 1)); line = substr(line, RSTART + 2); in_comment = 0 }
                else { cw += words(line); next }
            }
            while (match(line, /\/\*/)) {
                pre = substr(line, 1, RSTART - 1); rest = substr(line, RSTART + 2)
                if (match(rest, /\*\//)) { cw += words(substr(rest, 1, RSTART - 1)); line = pre substr(rest, RSTART + 2) }
                else { cw += words(rest); line = pre; in_comment = 1 }
            }
            if (match(line, /\/\//)) { cw += words(substr(line, RSTART + 2)); line = substr(line, 1, RSTART - 1) }
            if (line ~ /[^ \t]/) code++
        }
        END { print code + 0, cw + 0 }'
}

# page_words FILE - the words of a markdown page outside its fenced code.
page_words() {
    awk '/^```/ { fenced = !fenced; next } !fenced { n += NF } END { print n + 0 }' "$1"
}

# minutes PROSE_WORDS CODE_LINES PROSE_RATE CODE_RATE
minutes() {
    awk -v w="$1" -v c="$2" -v pr="$3" -v cr="$4" 'BEGIN { printf "%.0f", w / pr + c / cr }'
}

echo "| what | prose words (page + comments) | code lines | minutes (238 wpm, 10 lines/min) | minutes (200 wpm, 5 lines/min) | minutes for the added lines alone (238 wpm, 10 lines/min) |"
echo "|---|--:|--:|--:|--:|--:|"
prev=
for dir in "$root"/stages/[0-9][0-9]_*; do
    name=${dir##*/}
    page=$(ls "$root"/docs/stages/"$name".md 2>/dev/null || true)
    if [ -z "$prev" ]; then
        set -- $(cat "$dir"/*.[ch] | c_counts)
        code=$1
        words=$(($2 + $([ -n "$page" ] && page_words "$page" || echo 0)))
        what="$name: lesson page and code"
        added=
    else
        diff=$(diff -ruN "$prev" "$dir" || true)
        set -- $(printf '%s\n' "$diff" | sed -n 's/^+\([^+]\)/\1/p; s/^+$//p' | c_counts) \
            $(printf '%s\n' "$diff" | sed -n 's/^-\([^-]\)/\1/p; s/^-$//p' | c_counts)
        code=$(($1 + $3))
        words=$(($2 + $4))
        what="${prev##*/} → $name: the diff"
        added=$(minutes "$2" "$1" 238 10)
    fi
    brisk=$(minutes "$words" "$code" 238 10)
    echo "| $what | $words | $code | $brisk | $(minutes "$words" "$code" 200 5) | ${added:-$brisk} |"
    prev=$dir
done
