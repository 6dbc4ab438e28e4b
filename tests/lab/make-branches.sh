#!/bin/sh
# make-branches.sh - export the stages as a small git repository (make branches).
#
#   make-branches.sh [options] OUT          (make branches OUT=path)
#
# OUT becomes a new git repository whose branch main has one commit per
# stage, in order.  The tree of the commit of stage NN is
#   src/        stage NN's files (stages/NN_name/)
#   common/     the common core (the same in every commit)
#   course/     stages/course.[ch], the course's table (the same in every commit)
#   README.md   what this repository is (the same in every commit)
# so that `git diff stage-04 stage-05`, `git log -p`, `git show stage-05`
# and any diff viewer show exactly one stage's change.  Each commit is
# tagged stage-NN, and has a branch feature/NN_name (the stage's commit,
# whose parent is the previous stage: compare it with that stage's tag).
# Commit dates are the project's last commit date (or now, outside git),
# so the same sources give the same commit ids.  The repository's user.name
# and user.email are set in OUT/.git/config only.
#
# Options:
#   --force      replace OUT if it is an earlier export
#   --root DIR   the project (default: the one this script belongs to)
#   --help
# Exit status: 0 written, 1 error, 2 usage.
set -eu

PROG=make-branches.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

root=$(cd "$LAB_DIR/../.." && pwd)
force=0
parse_options '--force force=1 --root root=DIR' "$@"
shift "$po_used"
[ $# -eq 1 ] || usage_error "expected OUT, got $# argument(s)"
[ -n "$1" ] || usage_error "OUT is empty"
out=$1
command -v git >/dev/null 2>&1 || die "git is needed"

if [ -e "$out" ]; then
    if [ -f "$out/.git/stagelight-export" ] && [ "$force" -eq 1 ]; then
        rm -rf "$out"
    elif [ -f "$out/.git/stagelight-export" ]; then
        die "$out holds an earlier export; --force (make branches FORCE=1) replaces it"
    elif [ -d "$out" ] && [ -z "$(ls -A "$out")" ]; then
        :
    else
        die "$out exists and is not an empty directory"
    fi
fi

stages=$(stage_list "$root")
[ -n "$stages" ] || die "no stages in $root/stages"

# The idea of a stage, from the table in README.md ("| `05_bvh` | idea |").
stage_idea() {
    awk -F '|' -v s="\`$1\`" '{ c = $2; gsub(/^ +| +$/, "", c) }
        c == s { i = $3; gsub(/^ +| +$/, "", i); print i; exit }' "$root/README.md" 2>/dev/null || true
}

date=
if git -C "$root" rev-parse --verify -q HEAD >/dev/null 2>&1; then
    date=$(git -C "$root" log -1 --format=%cI)
fi
[ -n "$date" ] || date=$(date -u +%Y-%m-%dT%H:%M:%SZ)

mkdir -p "$out"
g() {
    HOME=$out/.git XDG_CONFIG_HOME=$out/.git GIT_CONFIG_NOSYSTEM=1 \
        GIT_AUTHOR_DATE=$date GIT_COMMITTER_DATE=$date git -C "$out" "$@"
}
g init -q
g symbolic-ref HEAD refs/heads/main
g config user.name "stagelight export"
g config user.email "stagelight-export@example.invalid"
g config commit.gpgsign false
g config tag.gpgsign false
g config core.autocrlf false
echo "written by stagelight's tests/lab/make-branches.sh" >"$out/.git/stagelight-export"

readme() {
    cat <<'EOF'
# stagelight, one commit per stage

This repository is generated from the stagelight project by `make branches`:
each commit of `main` is one stage, tagged `stage-NN`; `src/` holds that
stage's sources and `common/` the common core the stages share.  So

    git log --oneline                  # the stages
    git diff stage-04 stage-05         # what stage 05 adds: one idea
    git show stage-05 --stat
    git diff stage-04 feature/05_bvh   # the same, as a branch for diff viewers

show one stage's change and nothing else.  It is for reading: to build and
test a stage, use the stagelight project itself (`make`, `make test`).
EOF
}

for s in $stages; do
    nn=${s%%_*}
    find "$out" -mindepth 1 -maxdepth 1 ! -name .git -exec rm -rf {} +
    readme >"$out/README.md"
    copy_files "$root/common" "$out/common"
    copy_files "$root/stages/$s" "$out/src"
    for f in "$root"/stages/*; do
        [ ! -f "$f" ] || { mkdir -p "$out/course" && cp "$f" "$out/course/"; }
    done
    g add -A
    idea=$(stage_idea "$s")
    g commit -q --no-verify --allow-empty -m "Stage $s${idea:+: $idea}" \
        -m "The tree of stagelight's stages/$s in src/, with the common core."
    g tag "stage-$nn"
    g branch "feature/$s"
done
g gc -q --auto 2>/dev/null || true
echo "$PROG: wrote $out: branch main with $(echo "$stages" | wc -w | tr -d ' ') commits, tags stage-NN, branches feature/NN_name"
