#!/bin/sh
# farm-render.sh - one render split over the tasks of a Slurm job array.
#
#   farm-render.sh [options] SCENE SPP TASKS   (make farm-render SCENE=... SPP=... TASKS=N)
#
# Renders SCENE with SPP samples per pixel in all, split over TASKS tasks:
# task k (1..TASKS) renders SPP / TASKS samples (the first SPP % TASKS tasks
# one more) with --seed k, an independent estimate of the image, into
# OUT/part-k.pfm and its stats OUT/part-k.json; then build/tools/merge
# weights them by their spp into OUT/image.pfm, with OUT/image.json (the
# merged stats: spp the sum, inputs, variance_dof) and OUT/variance.pfm
# (merge --variance, for compare --variance).  The merged image is the
# render of all SPP samples (README.md, "Rendering on many machines"); the
# parts and their stats files are kept.  A task's part counts as done when
# its image and its stats file (written last, naming its spp and seed) are
# there: a rerun renders only the missing parts, so a task that died costs
# only its own part.
#
# Options:
#   --stage STAGE      the stage that renders (default 07)
#   --out DIR          where the parts and the image go (default
#                      build/farm/SCENE-NAME)
#   --options "OPTS"   more render options, the same for every task (e.g.
#                      "-W 512 -H 512 --sampler independent")
#   --scheduler slurm|local   slurm (default): one job array (sbatch --array
#                      --wait) with the resources of --sbatch; local: the
#                      tasks on this machine, --jobs at a time
#   --sbatch "OPTIONS" sbatch's resource options (default
#                      "--cpus-per-task=1 --mem=1G --time=60"); each task
#                      renders with --threads set to its CPUs
#   --jobs N           local: tasks at once (default: the processors)
#   --root DIR         the project (default: this script's); built already
#   --task K           (internal) render part K
#   --help
# Exit status: 0 merged, 1 a part or the merge failed, 2 usage.
set -eu

PROG=farm-render.sh
COURSE_DIR=$(cd "$(dirname "$0")" && pwd)
LAB_DIR=$COURSE_DIR/../lab
. "$LAB_DIR/lablib.sh"

root=$(cd "$COURSE_DIR/../.." && pwd)
stage=07
out=
options=
scheduler=slurm
sbatch_options="--cpus-per-task=1 --mem=1G --time=60"
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
task=
parse_options '--stage stage=VALUE --out out=VALUE --options options=VALUE --scheduler scheduler=VALUE
    --sbatch sbatch_options=VALUE --jobs jobs=VALUE --root root=DIR --task task=VALUE' "$@"
shift "$po_used"
[ $# -eq 3 ] || usage_error "expected SCENE, SPP and TASKS, got $# argument(s)"
scene=$1
spp=$2
tasks=$3
case $spp in '' | *[!0-9]* | 0*) usage_error "SPP must be a positive number, got '$spp'" ;; esac
case $tasks in '' | *[!0-9]* | 0*) usage_error "TASKS must be a positive number, got '$tasks'" ;; esac
[ "$tasks" -le "$spp" ] || usage_error "$tasks tasks for $spp samples: each task needs one sample at least"
case $scheduler in local | slurm) ;; *) usage_error "--scheduler is slurm or local, got '$scheduler'" ;; esac
case $jobs in '' | *[!0-9]* | 0) usage_error "--jobs needs a positive number, got '$jobs'" ;; esac
[ -f "$scene" ] || die "no such scene: $scene"
scene=$(abs_dir "$(dirname "$scene")")/$(basename "$scene")
stage=$(resolve_stage "$root" "$stage")
render=$root/build/$stage/render
merge=$root/build/tools/merge
[ -x "$render" ] && [ -x "$merge" ] || die "build the project first (make): no $render or $merge"
[ -n "$out" ] || out=$root/build/farm/$(basename "$scene" .scene)
mkdir -p "$out" || die "cannot write $out"
out=$(abs_dir "$out")

# part_spp K - the samples of task K.
part_spp() {
    echo $((spp / tasks + ($1 <= spp % tasks ? 1 : 0)))
}

# part_done K - whether part K is rendered: its stats name its spp and seed.
part_done() {
    [ -f "$out/part-$1.pfm" ] && [ -f "$out/part-$1.json" ] &&
        grep -q "\"spp\": *$(part_spp "$1")[,} ]" "$out/part-$1.json" &&
        grep -q "\"seed\": *$1[,} ]" "$out/part-$1.json"
}

if [ -n "$task" ]; then
    threads=${SLURM_CPUS_PER_TASK:-1}
    # Written to temporary names, renamed when both are there: a task
    # killed half-way leaves no part that looks done.
    rm -f "$out/part-$task.pfm" "$out/part-$task.json"
    # shellcheck disable=SC2086 # the options are words
    "$render" -q --spp "$(part_spp "$task")" --seed "$task" --threads "$threads" $options \
        -o "$out/part-$task.tmp.pfm" --stats "$out/part-$task.tmp.json" "$scene" ||
        die "task $task: the render failed"
    mv "$out/part-$task.tmp.pfm" "$out/part-$task.pfm"
    mv "$out/part-$task.tmp.json" "$out/part-$task.json"
    exit 0
fi

: >"$out/todo"
k=1
while [ "$k" -le "$tasks" ]; do
    part_done "$k" || echo "$k" >>"$out/todo"
    k=$((k + 1))
done
# Parts of an earlier split into more tasks are not this render's.
for p in "$out"/part-*.pfm; do
    [ -f "$p" ] || continue
    n=${p##*/part-}
    n=${n%.pfm}
    case $n in *[!0-9]*) rm -f "$p" ;; *) if [ "$n" -gt "$tasks" ]; then rm -f "$p" "$out/part-$n.json"; fi ;; esac
done
todo=$(wc -l <"$out/todo" | tr -d ' ')
echo "$PROG: $(basename "$scene"), $spp spp over $tasks task(s) ($stage): $((tasks - todo)) part(s) done, $todo to render ($scheduler)"
self="$COURSE_DIR/farm-render.sh --root $root --stage $stage --out $out"
if [ "$todo" -gt 0 ]; then
    case $scheduler in
        local)
            xargs -I {} -P "$jobs" "$COURSE_DIR/farm-render.sh" --root "$root" --stage "$stage" --out "$out" \
                --options "$options" --task {} "$scene" "$spp" "$tasks" <"$out/todo" || true
            ;;
        slurm)
            command -v sbatch >/dev/null 2>&1 || die "no sbatch here: Slurm's client is not installed (apt-get install slurm-wlm)"
            mkdir -p "$out/slurm"
            {
                echo '#!/bin/sh'
                echo "# One task of the job array: part \$SLURM_ARRAY_TASK_ID (written by farm-render.sh)."
                printf 'exec "%s" --root "%s" --stage "%s" --out "%s" --options "%s" --task "$SLURM_ARRAY_TASK_ID" "%s" "%s" "%s"\n' \
                    "$COURSE_DIR/farm-render.sh" "$root" "$stage" "$out" "$options" "$scene" "$spp" "$tasks"
            } >"$out/slurm/task.sh"
            chmod +x "$out/slurm/task.sh"
            array=$(paste -s -d , "$out/todo")
            echo "$PROG: sbatch --array=$array $sbatch_options --wait"
            # shellcheck disable=SC2086 # the resource options are words
            sbatch --array="$array" --job-name=farm-render $sbatch_options --wait \
                --output="$out/slurm/%A_%a.out" --chdir="$out" "$out/slurm/task.sh" || true
            ;;
    esac
fi
missing=
k=1
while [ "$k" -le "$tasks" ]; do
    part_done "$k" || missing="$missing $k"
    k=$((k + 1))
done
if [ -n "$missing" ]; then
    # The first failed Slurm task's own words (a bad --options fails every
    # task alike); local tasks wrote theirs to stderr already.
    k=${missing# }
    k=${k%% *}
    for log in "$out"/slurm/*_"$k".out; do
        [ -s "$log" ] && sed "s|^|$PROG: task $k: |" "$log" | tail -n 5 >&2
    done
    die "part(s)$missing not rendered (their tasks failed or died; rerun to render them)"
fi
k=1
parts=
while [ "$k" -le "$tasks" ]; do
    parts="$parts $out/part-$k.pfm"
    k=$((k + 1))
done
variance=
[ "$tasks" -ge 2 ] && variance="--variance $out/variance.pfm"
# shellcheck disable=SC2086 # the parts are paths without blanks
"$merge" -o "$out/image.pfm" $variance --stats "$out/image.json" $parts || die "merge failed"
rm -f "$out/todo"
echo "$PROG: wrote $out/image.pfm ($spp spp from $tasks part(s); stats $out/image.json$([ -z "$variance" ] || echo ", variance $out/variance.pfm"))"
