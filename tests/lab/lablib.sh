# lablib.sh - shell functions shared by the lab tools (tests/lab/*.sh).
# Sourced, not run.  The caller sets PROG (its name for messages) and
# LAB_DIR (this directory) first.  POSIX sh: no `local`, so each function's
# variables carry its own prefix.

die() {
    printf '%s: error: %s\n' "$PROG" "$*" >&2
    exit 1
}

warn() {
    printf '%s: warning: %s\n' "$PROG" "$*" >&2
}

usage_error() {
    printf '%s: %s\n' "$PROG" "$*" >&2
    printf "Try '%s --help'.\n" "$PROG" >&2
    exit 2
}

# An awk function for programs that rewrite paths: replace(s, from, to) is
# s with every occurrence of the string from replaced by to, literally (no
# regular expression: paths hold dots and more).  Prepend it to a program:
# awk "$AWK_REPLACE"'{ print replace($0, a, b) }'.
AWK_REPLACE='
function replace(s, from, to,    i, out) {
    out = ""
    while ((i = index(s, from)) > 0) {
        out = out substr(s, 1, i - 1) to
        s = substr(s, i + length(from))
    }
    return out s
}
'

# show_help SCRIPT - print the script's header comment (its help).
show_help() {
    awk 'NR == 1 { next } /^#/ { sub(/^# ?/, ""); print; next } { exit }' "$1"
}

# parse_options SPEC ARG... - the options of a lab script's command line.
# SPEC pairs each option with what it does, as words: `--force force=1`
# sets force to 1 (any word but VALUE and DIR), `--jobs jobs=VALUE` sets
# jobs to the argument that follows, `--root root=DIR` sets root to that
# argument, a directory, made absolute.  -h and --help print the script's
# help and exit 0; an option SPEC does not name, or one without its value,
# is a usage error (exit 2).  Parsing stops at the first argument that is
# not an option, or after `--`; po_used is then the number of arguments
# read, for the caller's `shift "$po_used"`.
parse_options() {
    po_spec=$1
    shift
    po_used=0
    while [ $# -gt 0 ]; do
        case $1 in
            -h | --help) show_help "$0"; exit 0 ;;
            --) po_used=$((po_used + 1)); return 0 ;;
            -*) ;;
            *) return 0 ;;
        esac
        po_action=
        po_key=
        for po_w in $po_spec; do
            if [ -z "$po_key" ]; then
                po_key=$po_w
                continue
            fi
            [ "$po_key" = "$1" ] && po_action=$po_w
            po_key=
        done
        [ -n "$po_action" ] || usage_error "unknown option: $1"
        po_n=2
        case ${po_action#*=} in
            VALUE) [ $# -ge 2 ] || usage_error "$1 needs a value"; po_value=$2 ;;
            DIR) [ $# -ge 2 ] || usage_error "$1 needs a directory"; po_value=$(abs_dir "$2") || exit 1 ;;
            *) po_value=${po_action#*=}; po_n=1 ;;
        esac
        eval "${po_action%%=*}=\$po_value"
        shift "$po_n"
        po_used=$((po_used + po_n))
    done
}

# abs_dir DIR - DIR as an absolute path (DIR must exist).
abs_dir() {
    (cd "$1" 2>/dev/null && pwd) || die "no such directory: $1"
}

# stage_list ROOT - the stage directories (NN_name), in order.
stage_list() {
    for sl_d in "$1"/stages/[0-9][0-9]_*; do
        [ -d "$sl_d" ] && basename "$sl_d"
    done
    return 0
}

# resolve_stage ROOT ARG - the stage named by ARG (5, 05 or 05_bvh).
resolve_stage() {
    rs_arg=$2
    case $rs_arg in
        [0-9]) rs_arg=0$rs_arg ;;
    esac
    case $rs_arg in
        [0-9][0-9]) ;;
        [0-9][0-9]_*) rs_arg=${rs_arg%%_*} ;;
        *) die "not a stage: '$2' (give its number, e.g. 05, or its name, e.g. 05_bvh)" ;;
    esac
    rs_found=
    for rs_d in "$1"/stages/"$rs_arg"_*; do
        [ -d "$rs_d" ] || continue
        [ -z "$rs_found" ] || die "two stages numbered $rs_arg in $1/stages"
        rs_found=$(basename "$rs_d")
    done
    [ -n "$rs_found" ] || die "no stage $rs_arg in stages/ (there are: $(stage_list "$1" | tr '\n' ' '))"
    case $2 in
        [0-9][0-9]_*) [ "$2" = "$rs_found" ] || die "no stage $2 (stage $rs_arg is $rs_found)" ;;
    esac
    echo "$rs_found"
}

# test_from FILE - the first stage a stage test applies to: 05 for
# 05_bvh.c and for 05-06_speed.c (tests/harness/select-tests.sh).
test_from() {
    tf_b=$(basename "$1")
    tf_b=${tf_b%%_*}
    echo "${tf_b%-*}"
}

# copy_files SRC DEST - copy SRC's regular files into DEST, recursively,
# without hidden files and editor or patch leftovers.
copy_files() {
    mkdir -p "$2"
    (cd "$1" && find . \( -name '.?*' -prune \) -o -type f ! -name '*~' ! -name '*.o' \
        ! -name '*.orig' ! -name '*.rej' ! -name '*.swp' -print) |
        while IFS= read -r cf_f; do
            cf_f=${cf_f#./}
            case $cf_f in
                */*) mkdir -p "$2/${cf_f%/*}" ;;
            esac
            cp "$1/$cf_f" "$2/$cf_f"
        done
}

# is_handout DIR - whether DIR holds a handout written by make-lab.sh.
is_handout() {
    [ -f "$1/Makefile" ] && head -n 1 "$1/Makefile" | grep -q '^# stagelight lab handout'
}

# handout_stage DIR - the stage directory name in a handout.
handout_stage() {
    set -- "$1"/stages/[0-9][0-9]_*
    [ $# -eq 1 ] && [ -d "$1" ] || return 1
    basename "$1"
}

# full_only SRC - whether a stage test program runs only in a full grade
# (make grade FULL=1, grade.sh --full): its header says so, with why, in a
# line " * Grading: make grade FULL=1 only (...)".
full_only() {
    grep -q '^ \* Grading: make grade FULL=1 only' "$1"
}

# handout_tests DIR - the handout's stage test sources (tests/stage/*.c).
handout_tests() {
    for ht_f in "$1"/tests/stage/*.c; do
        [ -f "$ht_f" ] && echo "$ht_f"
    done
    return 0
}

# The make the lab tools run inside handouts: a clean command line, so the
# -j or variables of an enclosing make do not leak in, and the default
# build variant (build/, whose paths the tools know), whatever REAL= or
# SANITIZE= the environment holds.
lab_make() {
    MAKEFLAGS= MAKELEVEL= MFLAGS= ${MAKE:-make} --no-print-directory REAL=double SANITIZE=0 "$@"
}

# handout_build DIR LOG all|default|lab [VAR=value...] - build a handout's
# stage and its test programs: all, those a default grade runs (not the
# FULL=1-only ones), or only the lab's own (make -k: as many as compile).
# Output goes to LOG; the status is make's.
handout_build() {
    hb_dir=$1
    hb_log=$2
    hb_which=$3
    shift 3
    hb_stage=$(handout_stage "$hb_dir") || die "$hb_dir: no stage in stages/"
    # (make prints absolute paths, from its physical working directory.)
    hb_abs=$(cd "$hb_dir" && pwd -P)
    hb_progs=
    for hb_src in $(handout_tests "$hb_dir"); do
        if [ "$hb_which" = lab ] && [ "$(test_from "$hb_src")" != "${hb_stage%%_*}" ]; then
            continue
        fi
        if [ "$hb_which" = default ] && full_only "$hb_src"; then
            continue
        fi
        hb_progs="$hb_progs $hb_abs/build/tests/$hb_stage/$(basename "$hb_src" .c)"
    done
    hb_status=0
    # No program of an earlier build may stand in for one that does not
    # build now: where a compile fails, make -k leaves the old program in
    # place.  When the stage does not build, the render and every program
    # (they link the stage's objects) go; else make -n names the programs
    # still out of date, and those go.  The rest stand: relinking all 45 of
    # lab 08 cost 4.5 processor seconds a grade.
    if ! lab_make -C "$hb_dir" "$@" all >"$hb_log" 2>&1; then
        rm -f "$hb_abs/build/$hb_stage/render" $hb_progs
        return 2
    fi
    [ -n "$hb_progs" ] || return 0
    lab_make -k -C "$hb_dir/tests" "$@" STAGE="$hb_stage" $hb_progs >>"$hb_log" 2>&1 || hb_status=$?
    for hb_p in $(lab_make -n -k -C "$hb_dir/tests" "$@" STAGE="$hb_stage" $hb_progs 2>/dev/null |
        awk '{ for (i = 1; i < NF; i++) if ($i == "-o") print $(i + 1) }'); do
        case "$hb_progs " in
            *" $hb_p "*) rm -f "$hb_p" ;;
        esac
    done
    return $hb_status
}

# build_warnings LOG - the compiler's and linker's warnings in a build log.
build_warnings() {
    grep -E 'warning:' "$1" | grep -Ev '^g?make(\[[0-9]+\])?: ' || true
}

# build_errors LOG - the compiler's and linker's errors and warnings.
build_errors() {
    grep -E '(error|warning):|undefined reference' "$1" | grep -Ev '^g?make(\[[0-9]+\])?: ' || true
}

# run_handout_test DIR SRC LOG TIMEOUT [TEST...] - run the test program built
# from SRC (tests/stage/NAME.c), or only the named TEST()s of it, and print
# "passed failed skipped status note".
# A program that crashes, times out or prints no result line counts every
# TEST() of its source as failed; one that prints a result line but exits
# non-zero counts one more failure (as tests/harness/run-tests.sh does).
run_handout_test() {
    rt_dir=$1
    rt_src=$2
    rt_log=$3
    rt_limit=$4
    rt_stage=$(handout_stage "$rt_dir")
    rt_prog=$rt_dir/build/tests/$rt_stage/$(basename "$rt_src" .c)
    shift 4
    rt_count=$#
    [ "$rt_count" -gt 0 ] || rt_count=$(grep -c '^TEST(' "$rt_src" || true)
    if [ ! -x "$rt_prog" ]; then
        echo "did not compile" >"$rt_log"
        echo "0 $rt_count 0 - did-not-compile"
        return 0
    fi
    rt_timeout=
    if [ "$rt_limit" -gt 0 ] 2>/dev/null; then
        # timeout(1), or a shell watchdog where it is absent
        rt_timeout="$LAB_DIR/../harness/with-timeout.sh $rt_limit"
    fi
    rt_status=0
    (cd "$rt_dir/tests" &&
        RENDER=$rt_dir/build/$rt_stage/render STAGE=$rt_stage ROOT=$rt_dir \
            $rt_timeout "$rt_prog" "$@") >"$rt_log" 2>&1 </dev/null || rt_status=$?
    rt_line=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$rt_log" | tail -n 1)
    if [ -z "$rt_line" ]; then
        rt_note=crashed
        [ -n "$rt_timeout" ] && [ "$rt_status" -eq 124 ] && rt_note=timed-out
        echo "0 $rt_count 0 $rt_status $rt_note"
        return 0
    fi
    echo "$rt_line" | awk -v st="$rt_status" '{
        p = $1; f = $3; s = ($5 == "" ? 0 : $5)
        note = "-"
        if (st != 0 && f == 0) { if (p > 0) p--; f = 1; note = "exit-" st }
        print p, f, s, st, note
    }'
}

# wilson K N - "P LO HI": the rate K/N and its Wilson 95% interval (Wilson,
# JASA 22, 1927), as fractions.
wilson() {
    awk -v k="$1" -v n="$2" 'BEGIN {
        z = 1.959964; p = k / n
        c = (p + z * z / (2 * n)) / (1 + z * z / n)
        h = z / (1 + z * z / n) * sqrt(p * (1 - p) / n + z * z / (4 * n * n))
        lo = c - h; hi = c + h; if (lo < 0 || k == 0) lo = 0; if (hi > 1 || k == n) hi = 1
        printf "%.6f %.6f %.6f\n", p, lo, hi }'
}

# plant_rect SET SIZE: "X,Y,32,32", the square where calibration set SET
# plants a bias into a SIZE x SIZE image: point SET + 1 of Roberts' R2
# sequence (additive recurrence with the plastic number, 2018), so that any
# number of sets spreads its squares evenly over the image.  (awk's rand()
# right after srand(seed) is nearly linear in the seed in mawk: seeding per
# set put the first sets' squares in one band.)
plant_rect() {
    awk -v i="$1" -v n="$2" 'BEGIN { w = (n < 32 ? n : 32)
        u = 0.5 + 0.7548776662466927 * (i + 1); v = 0.5 + 0.5698402909980532 * (i + 1)
        u -= int(u); v -= int(v)
        printf "%d,%d,%d,%d", int(u * (n - w + 1)), int(v * (n - w + 1)), w, w }'
}

# The second seed of a grade.  A statistical test (its program takes its
# seeds from PATHCHECK_SEED: tests/lib/pathcheck.h) that fails is run again
# on its own at this seed, and fails the grade only when it fails again.
# Each such test fails correct work at about its level (0.01 or less) at a
# seed nobody chose, and a lab's grade runs dozens of them (its own and
# every earlier stage's), so one chance failure somewhere would hit several
# percent of correct submissions; failing the same test at two seeds is a
# chance of about 0.01^2 a test.  A bug fails at both (the bug catalogue,
# check-functions.sh, is checked with the same rule).  Fixed, so that a
# grade gives the same score every time.
GRADE_SECOND_SEED=9000001

# is_statistical SRC - whether a test program takes PATHCHECK_SEED.
is_statistical() {
    grep -q 'pathcheck_seed(' "$1"
}

# one_test_passed LOG TEST - whether LOG, a run of the one TEST(), passed.
one_test_passed() {
    grep -q "^ok   $2\$" "$1" && grep -q '^1 passed, 0 failed' "$1"
}

# second_seed SRC SEED LOGS RUNNER... - "TEST STATUS" lines in, the same
# out, but a statistical program's (SRC's) failing TEST() is run again on
# its own with PATHCHECK_SEED=SEED (the grade's: GRADE_SECOND_SEED) by
# `RUNNER... LOG TEST`, which writes the run's output to LOG (here
# LOGS.TEST.second.log), and "TEST ok second" is its line when it passes
# there.  grade.sh, check-functions.sh and calibrate/grades.sh all count a
# failure so, each with its own way of running a program.
second_seed() {
    sd_src=$1
    sd_seed=$2
    sd_logs=$3
    shift 3
    while read -r sd_test sd_status; do
        if [ "$sd_status" = FAIL ] && is_statistical "$sd_src" && grep -q "^TEST($sd_test)" "$sd_src"; then
            PATHCHECK_SEED=$sd_seed "$@" "$sd_logs.$sd_test.second.log" "$sd_test"
            if one_test_passed "$sd_logs.$sd_test.second.log" "$sd_test"; then
                echo "$sd_test ok second"
                continue
            fi
        fi
        echo "$sd_test $sd_status"
    done
}

# test_names SRC - the names of the TEST()s defined in a test source.
test_names() {
    sed -n 's/^TEST(\([A-Za-z_][A-Za-z0-9_]*\)).*/\1/p' "$1"
}

# test_statuses SRC LOG NOTE - "TEST STATUS" (ok, FAIL or skip) for every
# TEST() of SRC, from the "ok NAME", "FAIL NAME" and "skip NAME" lines of
# the program's LOG; NOTE is run_handout_test's note.  A program that did
# not compile, crashed or timed out fails every TEST(), as does a TEST()
# the log does not mention; a program whose tests passed but that exited
# non-zero (note exit-N) has one more failed line, "(exit-N) FAIL", as
# run_handout_test counts it.
test_statuses() {
    ts_log=$2
    case $3 in
        did-not-compile | crashed | timed-out) ts_log=/dev/null ;;
    esac
    test_names "$1" | awk -v note="$3" -v logf="$ts_log" '
        BEGIN {
            while ((getline l < logf) > 0)
                if (split(l, w, " ") == 2 && (w[1] == "ok" || w[1] == "FAIL" || w[1] == "skip")) st[w[2]] = w[1]
        }
        { print $1, ($1 in st ? st[$1] : "FAIL") }
        END { if (note ~ /^exit-/) print "(" note ")", "FAIL" }'
}

# handout_controls DIR LOGDIR TIMEOUT - run the lab's own test programs of
# DIR, an untouched handout (built), and print "PROGRAM TEST STATUS" for
# each of their TEST()s.  Those with status ok are the lab's controls: they
# pass without the student's work, so grade.sh shows them and does not
# score them.  The programs' logs go to LOGDIR.
# A program that crashed or timed out is run again one TEST() at a time,
# and each TEST() has the status of its own run: a crash or a time-out
# fails every TEST() of a program, so which tests pass untouched would
# otherwise depend on the load of the machine and on the other tests of
# the program (a stub can make one test slow: lab 05's brute-force
# traversal takes minutes in a cost test; a busy machine then pushed the
# whole program past the limit, no control was found, and the grading run
# that followed, on a quieter machine, scored the control: 6.7% for an
# untouched handout).  A TEST() that crashes or times out on its own
# fails without the student's work: not a control.
handout_controls() {
    hc_stage=$(handout_stage "$1") || die "$1: no stage in stages/"
    mkdir -p "$2"
    for hc_src in $(handout_tests "$1"); do
        [ "$(test_from "$hc_src")" = "${hc_stage%%_*}" ] || continue
        hc_name=$(basename "$hc_src" .c)
        hc_note=$(run_handout_test "$1" "$hc_src" "$2/$hc_name.log" "$3" | awk '{ print $5 }')
        case $hc_note in
            crashed | timed-out)
                for hc_test in $(test_names "$hc_src"); do
                    hc_log=$2/$hc_name.$hc_test.log
                    hc_note=$(run_handout_test "$1" "$hc_src" "$hc_log" "$3" "$hc_test" | awk '{ print $5 }')
                    test_statuses "$hc_src" "$hc_log" "$hc_note" | awk -v t="$hc_test" '$1 == t' |
                        sed "s/^/$hc_name /"
                done
                ;;
            *) test_statuses "$hc_src" "$2/$hc_name.log" "$hc_note" | sed "s/^/$hc_name /" ;;
        esac
    done
}

# earlier_failures REPORT - the lines of a grade report (grade.awk) that
# name failing programs of earlier stages: those of its "earlier:" groups
# whose tests did not all pass; the lab's own group is left out (its tests
# fail in an untouched handout, as they must).
earlier_failures() {
    awk '/^earlier: / { earlier = 1; next }
        /^[^ ]/ { earlier = 0 }
        earlier && $1 != "total" && split($2, pt, "/") == 2 && pt[1] != pt[2]' "$1"
}

# handout_differences A B - the files (paths relative to the handouts) that
# differ between handouts A and B or are in one only; build/ and grade/
# (make grade's report pages) aside.
handout_differences() {
    for hd_d in "$1" "$2"; do
        (cd "$hd_d" && find . \( -path ./build -o -path ./grade \) -prune -o -type f -print)
    done | sed 's|^\./||' | LC_ALL=C sort -u | while IFS= read -r hd_f; do
        cmp -s "$1/$hd_f" "$2/$hd_f" 2>/dev/null || echo "$hd_f"
    done
}

# Samples per pixel of each of the two renders of a noise-tested report
# page of make grade (grade-pages.sh --spp, make grade SPP=N): what the
# pages' power to find a bias rests on (docs/calibration/README.md).
# The paired pages (grade-pages.sh), one a scene of paired_scenes NN: the
# student's render of the scene against the solution's render that
# make-lab.sh ships in the handout (tests/reference/solution/SCENE.pfm),
# both with paired_options NN SCENE, -W 256 -H 256 and --seed PAIRED_SEED.
# Every lab but 05 has them: scenes whose pictures the lab's functions make
# (an untouched handout's are wrong: check-labs grades it 0%), rendered as
# the lab's look pages render them, so that those renders serve both.  Lab
# 05's stub traversal is brute force, whose pictures are the solution's
# (a tree must not change the picture): a page would pass without the
# student's work, so its bugs are the function tests' (bvh_intersect
# against brute force on the same rays).
paired_scenes() {
    case $1 in
        01 | 02 | 06) echo cornell_diffuse_point ;;
        03) echo cornell_diffuse_area ;;
        04) echo cornell_specular_area ;;
        07 | 08) echo cornell_diffuse_point cornell_diffuse_area cornell_specular_area ;;
    esac
}
# paired_options NN SCENE - the options of lab NN's paired renders of SCENE.
paired_options() {
    case $1 in
        01 | 02) echo "" ;;
        03 | 04 | 05) case $2 in cornell_diffuse_point) echo "" ;; *) echo "--shadow-samples 64" ;; esac ;;
        *) echo "--spp $PAIRED_SPP" ;;
    esac
}
# paired_page_name NN SCENE - the name of lab NN's paired page of SCENE.
paired_page_name() {
    case $1 in
        01) echo "${2}_unshadowed" ;;
        02 | 03 | 04 | 05 | 06) echo "${2}_direct" ;;
        *) echo "${2}_gi" ;;
    esac
}
PAIRED_SPP=16
PAIRED_SEED=1
# The second look: a paired page that calls the student's render biased at
# PAIRED_SEED judges it again at PAIRED_SECOND_SEED, against the
# solution's render of that seed (make-lab.sh ships both), and fails only
# when it finds the bias there too.  A student who draws as the solution
# does repeats the bias at any seed, so a real bias fails both looks; a
# correct student who draws otherwise (two independent renders, judged at
# level q) fails both with probability q^2 (docs/calibration/README.md:
# that is what bounds the grade's false alarms).  Labs 01-02 draw no
# random numbers: their renders are the same at every seed, one look.
PAIRED_SECOND_SEED=2
paired_second_look() {
    case $1 in 01 | 02) return 1 ;; esac
    return 0
}

# image_twin NN - the lab whose stage renders lab NN's images bit for bit,
# at every seed and with every option (status 1 when none): stage 05's tree
# and stage 09's wider one change no picture, since the closest hit (ties
# to the lowest primitive number) is one hit however a tree is built
# (05_bvh holds every tree to brute force on the same rays, exactly).
# make calibrate takes such a lab's statistical verdicts from its twin's
# sets and checks the identity on a tenth of them (grades.sh).
image_twin() {
    case $1 in
        05) echo 04 ;;
        09) echo 08 ;;
        *) return 1 ;;
    esac
}

# paired_render RENDER NN SCENE_FILE SEED OUT [OPTION...] - RENDER's image
# of SCENE_FILE as lab NN's paired page renders it (paired_options, 256 x
# 256) at SEED, into OUT, with the OPTIONs (-t N); its output on standard
# output.  Every paired render is made by this one line: the solution's
# (make-lab.sh), the student's (grade-pages.sh) and the checks'.
paired_render() {
    pr_render=$1
    pr_scene=$3
    pr_seed=$4
    pr_out=$5
    pr_options=$(paired_options "$2" "$(basename "$pr_scene" .scene)")
    shift 5
    # shellcheck disable=SC2086 # the options are words
    "$pr_render" -q -W 256 -H 256 $pr_options --seed "$pr_seed" "$@" -o "$pr_out" "$pr_scene" 2>&1
}

GRADE_DEFAULT_SPP=64

# The most samples per pixel --spp auto gives a page's renders (about two
# minutes a render of stage 07 at 256x256 on two cores, at the 2.1 s that
# one of 64 spp took).
GRADE_MAX_SPP=4096

# check_spp N [auto] - usage error unless N (a --spp value) is a positive
# number, or, with a second argument, the word auto or paired (make
# grade's default: the paired pages and a 16-spp look, grade-pages.sh).
check_spp() {
    case $1 in auto | paired) [ $# -gt 1 ] && return 0 ;; esac
    case $1 in '' | 0* | *[!0-9]*) usage_error "--spp needs a positive number${2:+, auto or paired}, got '$1'" ;; esac
}

# spp_for_power FILE SPP MAX - the samples per pixel at which the renders
# FILE judged (compare -q's output on renders of SPP spp: its "power:"
# line) find a 2% bias in 9 windows of 10, 9 times in 10: SPP times the
# factor the line gives, up to a whole pass of 16 samples, at least SPP,
# at most MAX (also when the reference's own noise hides 2% at any spp).
# Sets sfp_spp, and sfp_says to what the line said; false without a line.
spp_for_power() {
    sfp_power=$(sed -n 's/^power: //p' "$1")
    case $sfp_power in
        *" already") sfp_times=1 sfp_says="finds 2% in 9 windows of 10 already" ;;
        *"hidden by the reference's own noise") sfp_times=inf sfp_says="2% in 9 windows of 10 is hidden by the reference's own noise" ;;
        *)
            sfp_times=$(printf '%s\n' "$sfp_power" | sed -n 's/.* about \([0-9.]*\) times these renders.*/\1/p')
            sfp_says="2% in 9 windows of 10 needs $sfp_times times their samples"
            ;;
    esac
    [ -n "$sfp_times" ] || return 1
    sfp_spp=$(awk -v t="$sfp_times" -v base="$2" -v most="$3" 'BEGIN {
        n = t == "inf" ? most : 16 * int((base * t + 15) / 16)
        print (n < base ? base : (n > most ? most : n)) }')
    [ "$sfp_spp" != "$3" ] || [ "$sfp_times" = 1 ] || sfp_says="$sfp_says; at most $3"
}

# page_alpha N - the family level of one of N noise-tested report pages of
# make grade (grade-pages.sh): Sidak's 1 - (1 - 0.01)^(1/N), so that one
# run of make grade on correct work says "biased" on any page with
# probability at most 0.01 (docs/calibration/README.md measures it).
page_alpha() {
    awk -v n="$1" 'BEGIN { printf "%.6g\n", 1 - exp(log(1 - 0.01) / n) }'
}

# plain_make ARGS... - make of the project's plain build, whatever variant
# called us (make sanitize or REAL=float pass theirs in MAKEFLAGS and,
# being set on the command line, in the environment: none of them here,
# where planted copies link build/common).
plain_make() {
    env -u SANITIZE -u REAL -u FUZZ -u BUILDROOT -u VARIANT MAKEFLAGS= \
        ${MAKE:-make} --no-print-directory "$@"
}

# plant_stage ROOT TREE STAGE FILE SED-ARGS... - a copy of ROOT's STAGE in
# TREE with a bug planted in FILE (sed SED-ARGS), built into
# TREE/build/STAGE/render against ROOT's common core (built already) and
# the files beside ROOT's stages (linked).
# The copy starts from ROOT's build of the stage, dates kept, so that make
# compiles only the planted file (and what includes it).
# Fails, saying so, when the sed changes nothing (the source moved on);
# make's output goes to standard output.
plant_stage() {
    ps_root=$1
    ps_tree=$2
    ps_stage=$3
    ps_file=$4
    shift 4
    rm -rf "$ps_tree/stages/$ps_stage" "$ps_tree/build/$ps_stage"
    mkdir -p "$ps_tree/stages" "$ps_tree/build"
    [ -e "$ps_tree/common" ] || ln -s "$ps_root/common" "$ps_tree/common"
    [ -e "$ps_tree/build/common" ] || ln -s "$ps_root/build/common" "$ps_tree/build/common"
    cp -Rp "$ps_root/stages/$ps_stage" "$ps_tree/stages/$ps_stage"
    # The files beside the stages (stages/course.[ch], which every stage links).
    for ps_f in "$ps_root"/stages/*; do
        [ ! -f "$ps_f" ] || [ -e "$ps_tree/stages/${ps_f##*/}" ] || ln -s "$ps_f" "$ps_tree/stages/"
    done
    [ ! -d "$ps_root/build/$ps_stage" ] || cp -Rp "$ps_root/build/$ps_stage" "$ps_tree/build/$ps_stage"
    sed "$@" "$ps_root/stages/$ps_stage/$ps_file" >"$ps_tree/stages/$ps_stage/$ps_file"
    if cmp -s "$ps_root/stages/$ps_stage/$ps_file" "$ps_tree/stages/$ps_stage/$ps_file"; then
        echo "the planted change to stages/$ps_stage/$ps_file matches nothing (the source changed?)"
        return 1
    fi
    plain_make -C "$ps_tree/stages/$ps_stage"
}
