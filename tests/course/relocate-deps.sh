#!/bin/sh
# relocate-deps.sh FROM TO - point the dependency files (*.d, which the
# compiler writes with -MMD) under TO/build at TO.
#
# A handout built at FROM and copied to TO (cp -Rp, as run_autograder copies
# the image's handout for each submission) still names FROM in its .d files,
# the objects' own paths included: make then finds no rule for TO's objects
# but the pattern rule's, so an object depends on its .c file and on no
# header, and a header the submission changed (lab 08's lowdisc.h, which
# the test programs include) recompiles nothing.  FROM is replaced where it
# starts a path (FROM/), as typed and as its physical path (pwd -P), by TO's
# physical path; the replacement is literal (lablib.sh's AWK_REPLACE).
# Exit status: 0 done (also when there is no build), 1 error, 2 usage.
set -eu
PROG=relocate-deps.sh
LAB_DIR=$(cd "$(dirname "$0")/../lab" && pwd) # the autograder's tools keep this layout
. "$LAB_DIR/lablib.sh"
case ${1:-} in -h | --help) show_help "$0"; exit 0 ;; esac
[ $# -eq 2 ] || usage_error "usage: relocate-deps.sh FROM TO"
[ -d "$2" ] || die "no directory $2"
to=$(cd "$2" && pwd -P)
from_physical=$(cd "$1" 2>/dev/null && pwd -P || echo "$1")
[ -d "$to/build" ] || exit 0
find "$to/build" -name '*.d' -type f | while IFS= read -r d; do
    FROM_A="$1/" FROM_B="$from_physical/" TO="$to/" awk "$AWK_REPLACE"'
        { line = replace($0, ENVIRON["FROM_A"], ENVIRON["TO"])
          if (ENVIRON["FROM_B"] != ENVIRON["FROM_A"]) line = replace(line, ENVIRON["FROM_B"], ENVIRON["TO"])
          print line }' "$d" >"$d.tmp"
    mv "$d.tmp" "$d"
done
