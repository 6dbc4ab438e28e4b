#!/bin/sh
# check-layout.sh - the project's top level holds what its layout names
# (README.md, "Layout"): Makefile, README.md, stages/, common/, scenes/,
# tests/, docs/, and dot-files (.ci/, .devcontainer/, .gitignore, ...).  A
# render written into the root by a test or a hand and committed by
# accident (a 4x4 cornell_diffuse_area.png stood there for a day) fails
# here.  Reads the files git tracks; outside a git checkout (a copy, a
# handout), what the directory holds, build/ left out.  Part `layout` of
# make test; one result line, then "N passed, N failed, N skipped".
# Exit status: 0 as named, 1 not.
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    entries=$(git ls-files | cut -d/ -f1 | sort -u)
else
    entries=$(ls -A | grep -vx build)
fi
stray=$(echo "$entries" | grep -v '^\.' | grep -vxE 'Makefile|README\.md|stages|common|scenes|tests|docs' || :)
if [ -z "$stray" ]; then
    echo "ok   layout/top-level: Makefile, README.md, stages, common, scenes, tests, docs and dot-files"
    echo "1 passed, 0 failed, 0 skipped"
else
    echo "FAIL layout/top-level: not in the layout: $(echo "$stray" | tr '\n' ' ')"
    echo "0 passed, 1 failed, 0 skipped"
    exit 1
fi
