#!/bin/sh
# grade-class.sh - grade every submission of a class: one CSV, one HTML page.
#
#   grade-class.sh [options] SUBMISSIONS     (make grade-class SUBMISSIONS=dir)
#
# SUBMISSIONS holds one directory per student, named after the student,
# each a student's handout (a clone of its repository) or the stage's files
# alone.  Each is graded by the lab's Gradescope autograder (make
# autograder, written into OUT/autograder/ and built once): its
# run_autograder grades as make grade does, the student's stages/NN_name/
# in a fresh copy of the untouched handout, with the project's tests, the
# lab's controls listed and not scored (tests/course/controls/NN_name), so
# a class's grades and results.json are Gradescope's.
# Writes into OUT:
#   grades.csv    one row per student: student, score (%), lab_passed,
#                 lab_total, build (ok, tests-partly, failed, not-graded),
#                 seconds, reason (why a submission lost everything or could
#                 not be graded: its build failed, a test program hung or
#                 crashed, a regression, the task died), then one column per
#                 test of the lab: ok, FAIL or skip (a control's column is
#                 named "PROGRAM/TEST (control)")
#   index.html    the class at a glance: the histogram of the scores, the
#                 tests most failed, and per student the score, the reason
#                 and links to the report and its compare pages
#   students/NAME/  results/results.json (Gradescope's), report.txt (make
#                 grade's report), pages/ (its compare report pages), keep/
#                 (what the grading read), result (the row, written last)
# Nothing is lost when a grading dies: a student's result is written last,
# under a key of the submission's files and of the lab, and a rerun grades
# only the students without a result for their files as they are now (so
# a rerun after a killed task, or after a student resubmits, collects what
# finished and grades the rest).
#
# Schedulers:
#   local   (default) --jobs submissions at a time on this machine
#   slurm   one Slurm job array (sbatch --array, one task per submission to
#           grade) with the resources of --sbatch (default: 1 CPU, 2 GB,
#           60 minutes per task), waited for with sbatch --wait, then
#           collected; OUT and the project must be on a file system the
#           nodes share
#
# Options:
#   --stage STAGE      the lab (default: the stage found in the submissions)
#   --out DIR          where the results go (default: build/grade-class)
#   --scheduler local|slurm
#   --jobs N           local: submissions graded at once (default: the
#                      number of processors)
#   --sbatch "OPTIONS" slurm: sbatch's resource options (default
#                      "--cpus-per-task=1 --mem=2G --time=60")
#   --timeout SEC      time limit of one test program (default 300); a whole
#                      grading is stopped after 10 times that
#   --spp N|auto|paired  the report pages (autograder.sh --spp; default its
#                      default, paired)
#   --root DIR         the project (default: this script's)
#   --task N           (internal) grade the Nth submission of OUT/tasks
#   --help
# Exit status: 0 every submission has a row with a grade, 1 some could not be
# graded (rerun to grade them) or an error, 2 usage.
set -eu

PROG=grade-class.sh
COURSE_DIR=$(cd "$(dirname "$0")" && pwd)
LAB_DIR=$COURSE_DIR/../lab
. "$LAB_DIR/lablib.sh"

root=$(cd "$COURSE_DIR/../.." && pwd)
stage=
out=
scheduler=local
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
sbatch_options="--cpus-per-task=1 --mem=2G --time=60"
limit=300
spp=
task=
parse_options '--stage stage=VALUE --out out=VALUE --scheduler scheduler=VALUE --jobs jobs=VALUE
    --sbatch sbatch_options=VALUE --timeout limit=VALUE --spp spp=VALUE --root root=DIR --task task=VALUE' "$@"
shift "$po_used"
[ $# -eq 1 ] || usage_error "expected one directory of submissions, got $# argument(s)"
case $scheduler in local | slurm) ;; *) usage_error "--scheduler is local or slurm, got '$scheduler'" ;; esac
case $jobs in '' | *[!0-9]* | 0) usage_error "--jobs needs a positive number, got '$jobs'" ;; esac
case $limit in '' | *[!0-9]*) usage_error "--timeout needs a number of seconds, got '$limit'" ;; esac
[ -z "$spp" ] || check_spp "$spp" auto
subs=$(abs_dir "$1")
[ -n "$out" ] || out=$root/build/grade-class
mkdir -p "$out/students" || die "cannot write $out"
out=$(abs_dir "$out")

# files_key DIR - a checksum of DIR's files (names and contents).
files_key() {
    (cd "$1" && find . -path ./build -prune -o -type f -print | LC_ALL=C sort |
        while IFS= read -r fk_f; do cksum "$fk_f"; done) | cksum | awk '{ print $1 "-" $2 }'
}

# grade_task N - grade the Nth line of OUT/tasks ("NAME<TAB>DIR") with the
# autograder's run_autograder (AUTOGRADER_ROOT: OUT/graders/NAME, its
# submission DIR): students/NAME/ gets results/results.json, report.txt,
# pages/, keep/, and, last, the row (result).
grade_task() {
    gt_line=$(sed -n "${1}p" "$out/tasks")
    [ -n "$gt_line" ] || die "no task $1 in $out/tasks"
    gt_name=$(printf '%s\n' "$gt_line" | cut -f 1)
    gt_dir=$(printf '%s\n' "$gt_line" | cut -f 2)
    gt_dest=$out/students/$gt_name
    gt_top=$out/graders/$gt_name
    rm -rf "$gt_dest" "$gt_top"
    mkdir -p "$gt_dest/results" "$gt_top"
    trap 'rm -rf "$gt_top"' EXIT
    trap 'exit 1' HUP INT PIPE TERM
    ln -s "$out/autograder" "$gt_top/source"
    ln -s "$gt_dir" "$gt_top/submission"
    ln -s "$gt_dest/results" "$gt_top/results"
    gt_key=$(cat "$out/lab-key")-$(files_key "$gt_dir")
    gt_start=$(date +%s)
    gt_status=0
    AUTOGRADER_ROOT=$gt_top AUTOGRADER_KEEP=$gt_dest AUTOGRADER_JOBS=1 \
        "$root/tests/harness/with-timeout.sh" $((limit * 10 + 600)) "$out/autograder/run_autograder" \
        >"$gt_dest/run.log" 2>&1 || gt_status=$?
    gt_secs=$(($(date +%s) - gt_start))
    if [ -f "$gt_dest/keep/tests" ]; then
        cp "$gt_dest/keep/tests" "$gt_dest/tests"
    else
        : >"$gt_dest/tests"
    fi
    [ -f "$gt_dest/report.txt" ] || : >"$gt_dest/report.txt"
    awk -v name="$gt_name" -v key="$gt_key" -v secs="$gt_secs" -v status="$gt_status" \
        -v tests="$gt_dest/tests" -v total="$(cat "$out/lab-total")" -v buildlog="$gt_dest/keep/build.log" '
        NR == 1 { first = $0 }
        /^GRADE / { grade = $0 }
        END {
            n = split(grade, w, " ")
            for (i = 2; i <= n; i++) { split(w[i], kv, "="); g[kv[1]] = kv[2] }
            if (grade == "") {
                reason = (status == 124 ? "the grading ran past its time limit" : "the grading stopped (exit " status ")")
                printf "%s\t%s\t0.0\t0\t%s\tfailed\t%d\t%s\n", name, key, total, secs, reason
                exit
            }
            while ((getline l < tests) > 0) {
                split(l, t, "\t")
                if (t[6] == "timed-out" || t[6] == "crashed") bad[t[6] " " t[3]] = 1
                if ((t[1] == "earlier" || t[1] == "control") && t[5] == "FAIL") reg++
            }
            if (g["build"] == "failed") {
                while ((getline l < buildlog) > 0) if (l ~ /error:/) { err = l; break }
                sub(/^.*\//, "", err)
                reason = (err != "" ? "build failed: " err : first)
            } else if (g["build"] == "tests-partly") reason = "some test programs do not compile against the stage"
            for (k in bad) reason = reason (reason != "" ? "; " : "") k
            if (reg && g["build"] != "failed") reason = reason (reason != "" ? "; " : "") reg " regression(s)"
            gsub(/\t/, " ", reason)
            printf "%s\t%s\t%s\t%s\t%s\t%s\t%d\t%s\n", name, key, (g["score"] == "" ? "0.0" : g["score"]),
                g["lab_passed"] + 0, (g["lab_total"] == "" ? total : g["lab_total"]), g["build"], secs, reason
        }' "$gt_dest/report.txt" >"$gt_dest/result.tmp"
    mv "$gt_dest/result.tmp" "$gt_dest/result"
}

if [ -n "$task" ]; then
    grade_task "$task"
    exit 0
fi

# ---- the lab: its stage, untouched handout (built once), controls, key -----
if [ -z "$stage" ]; then
    for d in "$subs"/*/stages/[0-9][0-9]_* "$subs"/*/*/stages/[0-9][0-9]_*; do
        if [ -d "$d" ]; then stage=$(basename "$d"); break; fi
    done
    [ -n "$stage" ] || die "no stages/NN_name/ in the submissions: give the lab with --stage (STAGE=NN)"
fi
stage=$(resolve_stage "$root" "$stage")
echo "$stage" >"$out/stage"
"$COURSE_DIR/autograder.sh" --root "$root" --timeout "$limit" ${spp:+--spp "$spp"} "$stage" "$out" >"$out/autograder.log" 2>&1 ||
    die "could not write the autograder of $stage (log: $out/autograder.log)"
cp "$out/autograder/controls" "$out/controls"
# The common core and the test support built once, for every copy.
handout_build "$out/autograder/handout" "$out/handout-build.log" lab -j"$jobs" ||
    die "the untouched handout does not build (log: $out/handout-build.log)"
cp "$out/autograder/lab-total" "$out/lab-total"
# A result stands for the submission's files under this lab as it is now.
# (lab-key.files: what it sums, to tell why a rerun grades everything again)
{
    (cd "$out/autograder" && find . -path ./handout/build -prune -o -type f -print | LC_ALL=C sort | xargs cksum)
    echo "$limit"
} >"$out/lab-key.files"
cksum <"$out/lab-key.files" | awk '{ print $1 }' >"$out/lab-key"

# ---- the tasks: every submission without a result for its files now --------
: >"$out/tasks"
: >"$out/todo"
n=0
for d in "$subs"/*; do
    [ -d "$d" ] || continue
    name=$(basename "$d")
    case $name in *[!A-Za-z0-9._@+-]*) warn "skipped '$name': a student's name is letters, digits and . _ @ + -"; continue ;; esac
    n=$((n + 1))
    printf '%s\t%s\n' "$name" "$d" >>"$out/tasks"
    key=$(cat "$out/lab-key")-$(files_key "$d")
    if [ "$(cut -f 2 "$out/students/$name/result" 2>/dev/null)" != "$key" ]; then
        echo "$n" >>"$out/todo"
    fi
done
[ "$n" -gt 0 ] || die "no submission directories in $1"
todo=$(wc -l <"$out/todo" | tr -d ' ')
echo "$PROG: lab ${stage%%_*} ($stage): $n submission(s), $((n - todo)) graded already, $todo to grade ($scheduler)"

if [ "$todo" -gt 0 ]; then
    case $scheduler in
        local)
            xargs -I {} -P "$jobs" "$0" --root "$root" --out "$out" --timeout "$limit" --task {} "$subs" <"$out/todo" ||
                warn "some gradings stopped before their result"
            ;;
        slurm)
            command -v sbatch >/dev/null 2>&1 || die "no sbatch here: Slurm's client is not installed (apt-get install slurm-wlm)"
            mkdir -p "$out/slurm"
            cat >"$out/slurm/task.sh" <<TASK
#!/bin/sh
# One task of the job array: the submission of line \$SLURM_ARRAY_TASK_ID of
# $out/tasks (written by grade-class.sh).
exec "$COURSE_DIR/grade-class.sh" --root "$root" --out "$out" --timeout "$limit" --task "\$SLURM_ARRAY_TASK_ID" "$subs"
TASK
            chmod +x "$out/slurm/task.sh"
            array=$(paste -s -d , "$out/todo")
            echo "$PROG: sbatch --array=$array $sbatch_options --wait"
            # shellcheck disable=SC2086 # the resource options are words
            sbatch --array="$array" --job-name="grade-class-${stage%%_*}" $sbatch_options --wait \
                --output="$out/slurm/%A_%a.out" --chdir="$out" "$out/slurm/task.sh" ||
                warn "sbatch reports that some tasks failed (their submissions are collected as not graded)"
            ;;
    esac
fi

# ---- collect: the CSV and the HTML page ------------------------------------
missing=0
: >"$out/results"
: >"$out/results.tests"
: >"$out/results.pages"
while IFS="$(printf '\t')" read -r name dir; do
    r=$out/students/$name/result
    if [ -f "$r" ]; then
        cat "$r" >>"$out/results"
        awk -v name="$name" '{ print name "\t" $0 }' "$out/students/$name/tests" >>"$out/results.tests"
        for p in "$out/students/$name/pages"/*.html; do
            if [ -f "$p" ]; then printf '%s\t%s\n' "$name" "$(basename "$p" .html)" >>"$out/results.pages"; fi
        done
    else
        missing=$((missing + 1))
        printf '%s\t-\t\t\t%s\tnot-graded\t\tnot graded: its task ended without a result (rerun to grade it)\n' \
            "$name" "$(cat "$out/lab-total")" >>"$out/results"
    fi
done <"$out/tasks"
awk -v lab="$stage" -v csv="$out/grades.csv.tmp" -v html="$out/index.html.tmp" -v pages="$out/results.pages" \
    -f "$COURSE_DIR/class.awk" "$out/results.tests" "$out/results"
mv "$out/grades.csv.tmp" "$out/grades.csv"
mv "$out/index.html.tmp" "$out/index.html"
rm -f "$out/results" "$out/results.tests" "$out/results.pages"
echo "$PROG: wrote $out/grades.csv and $out/index.html ($n student(s)$([ "$missing" -eq 0 ] || echo ", $missing not graded: rerun to grade them"))"
[ "$missing" -eq 0 ]
