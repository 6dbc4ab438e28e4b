#!/bin/sh
# test-slurm.sh - make grade-class and make farm-render under a real Slurm,
# started here for this machine alone (CI runs it: .ci/run).
#
#   test-slurm.sh [--help]
#
# Skipped, with the reason, where Slurm (slurm-wlm: slurmctld, slurmd,
# sbatch) or MUNGE (munge) is not installed, or without root (slurmd runs
# the tasks as their users).  Otherwise, in a temporary directory: a munge
# key and munged on a socket of its own, a generated slurm.conf (one node,
# localhost, this machine's processors, ports of its own, state and logs in
# the directory), slurmctld and slurmd; every daemon stopped by its pid at
# the end and the directory removed (TMPDIR left as it was).
#   class       grade-class --scheduler slurm on six submissions of lab 02
#               (the untouched handout, the solution, three planted bugs,
#               one that does not compile) as one job array; one task is
#               cancelled while it runs; then the collect step (a rerun)
#               grades that one only and the CSV has the six rows: 0% for
#               the untouched handout, 100% for the solution, between for
#               each bug, build=failed with its reason for the one that does
#               not compile, and the rows graded before the cancel kept;
#               the autograder renders its report pages with make grade's
#               default samples (--spp auto)
#   results     the results.json that run_autograder wrote for the
#               untouched handout, the solution and a bug: Gradescope's
#               fields (results-check.py), scores 0, full and partial
#   farm        farm-render over 4 tasks (64 spp of cornell_diffuse_area,
#               256x256, stage 07's independent sampler): the merged image's stats
#               (64 spp from 4 inputs) and compare's verdict with one render
#               of 64 spp, against the Mitsuba reference: consistent
# Needs the project built (make).  Prints one line per check and
# "N passed, N failed, N skipped".
set -u
COURSE_DIR=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$COURSE_DIR/../.." && pwd)
case ${1:-} in -h | --help) awk 'NR == 1 { next } /^#/ { sub(/^# ?/, ""); print; next } { exit }' "$0"; exit 0 ;; esac

CHECKS=slurm
. "$COURSE_DIR/checklib.sh"
skip_all() {
    for c in class results farm; do skip "$c: $1"; done
    finish
}

for p in slurmctld slurmd sbatch squeue scancel sinfo munged; do
    command -v "$p" >/dev/null 2>&1 || [ -x "/usr/sbin/$p" ] || skip_all "no $p here (apt-get install slurm-wlm munge)"
done
[ "$(id -u)" = 0 ] || skip_all "not root: slurmd runs the tasks as their users"
command -v python3 >/dev/null 2>&1 || skip_all "no python3 to read results.json"
for f in "$root/build/02_shadows/render" "$root/build/07_pathtrace/render" "$root/build/tools/merge" "$root/build/tools/compare"; do
    [ -x "$f" ] || skip_all "the project is not built (no $f): make first"
done
PATH=$PATH:/usr/sbin:/sbin

# Short names: a Unix socket's path (Chromium's, in a test the gradings
# run) must stay under 108 bytes.
T=$(mktemp -d "${TMPDIR:-/tmp}/ts.XXXXXX") || exit 2
chmod 755 "$T"
pids=
stop_daemons() {
    for p in $pids; do kill -TERM "$p" 2>/dev/null; done
    for p in $pids; do
        i=0
        while kill -0 "$p" 2>/dev/null && [ "$i" -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
        kill -KILL "$p" 2>/dev/null
    done
    pids=
}
trap 'stop_daemons; rm -rf "$T"' EXIT
trap 'exit 1' HUP INT PIPE TERM

# ---- MUNGE and Slurm, for localhost ---------------------------------------------
mkdir -p "$T/munge" "$T/state" "$T/spool" "$T/log" "$T/t"
chmod 700 "$T/munge"
dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$T/munge/munge.key"
munged --force --key-file="$T/munge/munge.key" --socket="$T/munge/socket" --pid-file="$T/munge/pid" \
    --seed-file="$T/munge/seed" --log-file="$T/log/munged.log" >"$T/log/munged.out" 2>&1
i=0
while [ ! -s "$T/munge/pid" ] && [ "$i" -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
[ -s "$T/munge/pid" ] || { fail class "munged did not start" "$(cat "$T/log/munged.out" "$T/log/munged.log" 2>/dev/null)"; finish; }
pids=$(cat "$T/munge/pid")
cpus=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
mem=$(awk '/^MemTotal:/ { print int($2 / 1024 / 2) }' /proc/meminfo 2>/dev/null || echo 2048)
port=$((20000 + $$ % 20000))
cat >"$T/slurm.conf" <<CONF
# A one-node Slurm for tests/course/test-slurm.sh (generated).
ClusterName=stagelight-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$T/munge/socket
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
ReturnToService=2
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1
KillWait=5
InactiveLimit=0
MinJobAge=300
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
SLURM_CONF=$T/slurm.conf
export SLURM_CONF
slurmctld -D -i -f "$T/slurm.conf" >"$T/log/slurmctld.out" 2>&1 &
pids="$pids $!"
slurmd -D -N localhost -f "$T/slurm.conf" >"$T/log/slurmd.out" 2>&1 &
pids="$pids $!"
i=0
until sinfo -h -o '%T' 2>/dev/null | grep -q '^idle'; do
    i=$((i + 1))
    if [ "$i" -gt 300 ]; then
        fail class "Slurm did not come up in 30 s" "$(sinfo 2>&1)" "$(tail -n 20 "$T/log/slurmctld.log" "$T/log/slurmd.log" 2>&1)"
        finish
    fi
    sleep 0.1
done
export TMPDIR="$T/t"

# ---- six submissions of lab 02 ----------------------------------------------------------
S=$T/subs
"$root/tests/lab/make-lab.sh" --quiet --root "$root" 02 "$S/untouched" >/dev/null || { fail class "make-lab.sh 02 failed"; finish; }
rm -rf "$S/untouched/.github"  # (a student's clone: its files, any of them)
mkdir -p "$S/solution/stages"
cp -R "$root/stages/02_shadows" "$S/solution/stages/"
# plant NAME FILE SED-SCRIPT - a copy of the solution with one change (which must change the file).
plant() {
    mkdir -p "$S/$1/stages"
    cp -R "$root/stages/02_shadows" "$S/$1/stages/"
    sed -e "$3" "$root/stages/02_shadows/$2" >"$S/$1/stages/02_shadows/$2"
    cmp -s "$root/stages/02_shadows/$2" "$S/$1/stages/02_shadows/$2" && fail class "the bug $1 changed nothing in $2"
    return 0
}
plant bug-acne geometry.c 's|real offset = 2 \* h->error;|real offset = 0;|'
plant bug-leak geometry.c 's|^\( *\)ray r = spawn_ray(h, vec3_normalize(vec3_sub(to, h->p)));|&\n\1r.o = vec3_madd(r.o, r.d, (real)0.2);|'
plant bug-notrace light.c '/inspect_shadow_ray(w, shadow, t_max, clear, st);/d'
mkdir -p "$S/broken"
cp "$root"/stages/02_shadows/* "$S/broken/"  # the stage's files alone, one of them broken
printf 'this is not C;\n' >>"$S/broken/light.c"

# ---- class: the job array, a task cancelled, the collect ---------------------------------
O=$T/class
start=$(date +%s)
"$COURSE_DIR/grade-class.sh" --root "$root" --out "$O" --scheduler slurm --timeout 300 \
    --sbatch "--cpus-per-task=1 --mem=512M --time=30" "$S" >"$T/class1.log" 2>&1 &
gc=$!
# Cancel the first task seen running, after it has run 5 s.
victim=
i=0
while [ -z "$victim" ] && [ "$i" -lt 3000 ] && kill -0 "$gc" 2>/dev/null; do
    victim=$(squeue -h -t RUNNING -o '%i %M' 2>/dev/null | awk '{ n = split($2, t, ":"); if (t[n] + 60 * t[n - 1] >= 5) { print $1; exit } }')
    [ -n "$victim" ] || sleep 0.2
    i=$((i + 1))
done
[ -n "$victim" ] && scancel "$victim"
wait "$gc"
st1=$?
cp "$O/grades.csv" "$T/grades1.csv" 2>/dev/null
cp "$O/lab-key.files" "$T/lab-key1" 2>/dev/null
cat "$O"/students/*/result >"$T/results1" 2>/dev/null
"$COURSE_DIR/grade-class.sh" --root "$root" --out "$O" --scheduler slurm --timeout 300 \
    --sbatch "--cpus-per-task=1 --mem=512M --time=30" "$S" >"$T/class2.log" 2>&1
st2=$?
secs=$(($(date +%s) - start))
row() { grep "^$1," "$O/grades.csv"; }
field() { row "$1" | cut -d, -f"$2"; }
why=
[ -n "$victim" ] || why="$why no task was seen running to cancel;"
[ "$st1" -ne 0 ] && grep -q 'not-graded' "$T/grades1.csv" 2>/dev/null || why="$why the first run (exit $st1) did not report the cancelled task as not graded;"
grep -q '1 to grade' "$T/class2.log" ||
    why="$why the collect did not grade just the cancelled one: $(grep 'to grade' "$T/class2.log"); the lab's files changed: $(diff "$T/lab-key1" "$O/lab-key.files"); the rows' keys were: $(cut -f 1,2 "$T/results1"), now: $(cat "$O"/students/*/result | cut -f 1,2);"
[ "$st2" -eq 0 ] || why="$why the collect exited $st2;"
grep -q -- '--spp paired ' "$O/autograder/run_autograder" ||
    why="$why the autograder's report pages are not make grade's default (--spp paired);"
[ "$(grep -c . "$O/grades.csv")" -eq 7 ] || why="$why $(grep -c . "$O/grades.csv") lines in the CSV, not 7;"
[ "$(field untouched 2)" = 0.0 ] || why="$why untouched scores '$(field untouched 2)';"
[ "$(field solution 2)" = 100.0 ] || why="$why the solution scores '$(field solution 2)';"
for b in bug-acne bug-leak bug-notrace; do
    awk -v s="$(field "$b" 2)" 'BEGIN { exit !(s > 0 && s < 100) }' || why="$why $b scores '$(field "$b" 2)', not partial;"
done
[ "$(field broken 5)" = failed ] && [ "$(field broken 2)" = 0.0 ] && row broken | grep -q 'build failed: light.c' ||
    why="$why the broken one: $(row broken);"
# The rows graded before the cancel are those of the collect.
kept=$(awk -F, 'NR > 1 && $5 != "not-graded" { print }' "$T/grades1.csv" 2>/dev/null | while IFS= read -r l; do
    grep -qxF "$l" "$O/grades.csv" || echo "lost: $l"; done)
[ -z "$kept" ] || why="$why $kept;"
grep -q '<h2>Tests most failed</h2>' "$O/index.html" && grep -q 'href="students/solution/report.txt"' "$O/index.html" ||
    why="$why index.html;"
if [ -z "$why" ]; then
    ok "class: 6 rows under Slurm (a cancelled task regraded alone by the collect) in $secs s"
else
    fail class "$why" "$(cat "$O/grades.csv" 2>/dev/null)" "$(cat "$T/class1.log" "$T/class2.log")"
fi
sed 's/^/    /' "$O/grades.csv" | cut -c1-150

# ---- results: Gradescope's results.json of three of them ------------------------------------
why=
for c in "untouched 0" "solution full" "bug-notrace -"; do
    set -- $c
    f=$O/students/$1/results/results.json
    if [ "$2" = - ]; then
        r=$(python3 "$COURSE_DIR/results-check.py" "$f") &&
            echo "$r" | awk '{ exit !($2 > 0 && $2 < $3) }' || why="$why $1: $r (not partial);"
    else
        r=$(python3 "$COURSE_DIR/results-check.py" "$f" "$2") || why="$why $1: $r;"
    fi
done
if [ -z "$why" ]; then ok "results: the untouched, solution and bug results.json have Gradescope's fields, scores 0, full, partial"; else fail results "$why"; fi

# ---- farm: 4 tasks against one render ----------------------------------------------------
F=$T/farm
scene=$root/scenes/cornell_diffuse_area.scene
opts="-W 256 -H 256"
start=$(date +%s)
"$COURSE_DIR/farm-render.sh" --root "$root" --out "$F" --options "$opts" \
    --sbatch "--cpus-per-task=1 --mem=512M --time=30" "$scene" 64 4 >"$T/farm.log" 2>&1
st=$?
"$root/build/07_pathtrace/render" -q --spp 64 --seed 1000 $opts -o "$T/single.pfm" "$scene" >"$T/single.log" 2>&1
verdict=$("$root/build/tools/compare" -q "$F/image.pfm" "$T/single.pfm" "$root/tests/reference/cornell_diffuse_area_gi.pfm" 2>&1)
cst=$?
secs=$(($(date +%s) - start))
if [ "$st" -eq 0 ] && [ "$cst" -eq 0 ] && echo "$verdict" | grep -q '^consistent' &&
    grep -q '"spp": *64[,} ]' "$F/image.json" && grep -q '"inputs": *4[,} ]' "$F/image.json" &&
    [ "$(ls "$F"/part-*.json | wc -l)" -eq 4 ]; then
    ok "farm: 4 Slurm tasks merged to 64 spp, consistent with one render of 64 spp ($secs s)"
else
    fail farm "farm-render exit $st, compare exit $cst: $verdict" "$(cat "$T/farm.log")" "$(cat "$F/image.json" 2>/dev/null)"
fi

stop_daemons
finish
