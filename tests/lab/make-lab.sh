#!/bin/sh
# make-lab.sh - write the lab handout of one stage.
#
#   make-lab.sh [options] STAGE OUT          (make lab STAGE=05 OUT=path)
#
# STAGE is a stage number (05) or name (05_bvh).  OUT becomes a
# self-contained, buildable copy of the project for that lab:
#   stages/NN_name/  the stage, each LAB NN region replaced by its stub
#                    (earlier labs' regions keep their code, without markers)
#   stages/course.*  the course's table, which every stage links (every
#                    file beside the stages is copied)
#   common/          the common core
#   tests/           the harness and the stage tests that apply to stage NN
#                    (the autograder), reference images, test scenes
#   scenes/          the scenes
#   Makefile         make (build), make test (the autograder), make check
#                    TEST=PROGRAM/NAME (one test)
#   .devcontainer/   the project's development container (VS Code,
#                    Codespaces): Debian and the packages CI installs
#   .github/         GitHub Classroom's autograding: the workflow and the
#                    test list, one entry per test of the lab with its points
#                    (tests/course/classroom.sh; controls, from
#                    tests/course/controls/NN_name, get 0 points)
#   LAB.md           the "Lab" section of docs/stages/NN_name.md, the places
#                    to write code, and the tests
# The marker format is in tests/lab/README.md.  OUT must not exist, be
# empty, or hold an earlier handout, which is updated in place: files that
# did not change keep their dates, so rebuilding it is quick.  An earlier
# handout someone changed (a file edited, added or removed since make-lab.sh
# wrote it, as its list .stagelight-handout records; build/ aside) is a
# student's work: it is refused (exit 2, naming the files) unless --force,
# which first moves it aside to OUT.old-DATE and says so.
#
# Options:
#   --force      move a changed handout aside instead of refusing
#   --discard-changes  overwrite a changed handout (for check-labs.sh, which
#                puts the solution into its own handouts and back)
#   --solution   keep the solution and all markers (an instructor's copy)
#   --strict     warnings (no Lab section, no LAB NN region, a missing
#                linked file) are errors
#   --quiet      print nothing on success
#   --root DIR   the project (default: the one this script belongs to)
#   --help       this text
# Exit status: 0 written, 1 error, 2 usage or a changed handout refused.
set -eu

PROG=make-lab.sh
LAB_DIR=$(cd "$(dirname "$0")" && pwd)
. "$LAB_DIR/lablib.sh"

root=$(cd "$LAB_DIR/../.." && pwd)
solution=0
force=0
discard=0
strict=0
quiet=0
parse_options '--solution solution=1 --force force=1 --discard-changes discard=1 --strict strict=1
    --quiet quiet=1 --root root=DIR' "$@"
shift "$po_used"
[ $# -eq 2 ] || usage_error "expected STAGE and OUT, got $# argument(s)"
[ -n "$2" ] || usage_error "OUT is empty"

stage=$(resolve_stage "$root" "$1")
nn=${stage%%_*}
out=$2
page=docs/stages/$stage.md
tmp=
trap 'if [ -n "$tmp" ]; then rm -rf "$tmp" "$tmp.list" "$tmp.now"; fi' EXIT
trap 'exit 1' HUP INT PIPE TERM

# A warning, or under --strict an error.
problem() {
    if [ "$strict" -eq 1 ]; then die "$*"; fi
    warn "$*"
}

check_out() {
    if [ -e "$out" ] && [ ! -d "$out" ]; then
        die "$out exists and is not a directory"
    fi
    if [ -d "$out" ] && [ -n "$(ls -A "$out")" ] && ! is_handout "$out"; then
        die "$out is not empty and holds no handout; refusing to write into it"
    fi
    return 0
}

# The stage, stubbed: LAB NN regions become hint + TODO + stub; beside it
# the course's table (stages/course.[ch]), which every stage links.
write_stage() {
    ws_src=$root/stages/$stage
    ws_dest=$tmp/stages/$stage
    copy_files "$ws_src" "$ws_dest"
    for ws_f in "$root"/stages/*; do
        [ ! -f "$ws_f" ] || cp "$ws_f" "$tmp/stages/"
    done
    [ "$solution" -eq 1 ] && return 0
    for ws_f in "$ws_dest"/*.c "$ws_dest"/*.h; do
        [ -f "$ws_f" ] || continue
        ws_name=$(basename "$ws_f")
        (cd "$root" && awk -v mode=handout -v lab="$nn" -v stage="$nn" \
            -v docref="docs/stages/$stage.md" -v stubs="$LAB_DIR/stubs" -f "$LAB_DIR/markers.awk" \
            "stages/$stage/$ws_name") >"$ws_f" ||
            die "stages/$stage/$ws_name: bad LAB markers (see above)"
    done
}

# The tests: the harness, support code and data, and the stage tests that
# apply to this stage.  Left out: the unit tests of common/, the lab tools,
# the trade-off measurements (tests/trade/) and the other stage tests; of
# the lab tools only the grading scripts (the handout's make grade).
write_tests() {
    wt_t=$root/tests
    mkdir -p "$tmp/tests/stage"
    for wt_f in "$wt_t"/*; do
        wt_b=$(basename "$wt_f")
        if [ -f "$wt_f" ]; then
            case $wt_b in
                *~ | *.o | *.orig | *.rej) ;;
                *) cp "$wt_f" "$tmp/tests/$wt_b" ;;
            esac
        elif [ -d "$wt_f" ]; then
            case $wt_b in
                stage | common | lab | trade) ;;
                *) copy_files "$wt_f" "$tmp/tests/$wt_b" ;;
            esac
        fi
    done
    for wt_f in $(cd "$wt_t" && sh ./harness/select-tests.sh "$nn" stage/*.c); do
        cp "$wt_t/$wt_f" "$tmp/tests/$wt_f"
    done
    # The grading scripts, for the handout's own make grade.
    mkdir -p "$tmp/tests/lab"
    for wt_f in grade.sh grade.awk grade-pages.sh lablib.sh check-one.sh; do
        cp "$LAB_DIR/$wt_f" "$tmp/tests/lab/$wt_f"
    done
}

# The solution's renders of the paired pages' scenes (lablib.sh's
# paired_scenes and paired_options: every lab), with the project's own
# build of the stage, into tests/reference/solution/: make grade renders
# the student's stage the same way and compares the two pixel by pixel
# (grade-pages.sh).  Images only: the handout never holds the solution's
# code.  Without a build of the stage, none (the paired pages then say
# that they judge nothing).
write_solution_renders() {
    ws_render=$root/build/$stage/render
    ws_scenes=$(paired_scenes "$nn")
    [ -n "$ws_scenes" ] && [ -x "$ws_render" ] || return 0
    mkdir -p "$tmp/tests/reference/solution"
    echo "The solution of $stage rendered by make-lab.sh (tests/lab/make-lab.sh), one image a scene:" \
        >"$tmp/tests/reference/solution/README"
    for ws_scene in $ws_scenes; do
        ws_options="$(paired_options "$nn" "$ws_scene") --seed $PAIRED_SEED"
        paired_render "$ws_render" "$nn" "$root/scenes/$ws_scene.scene" "$PAIRED_SEED" \
            "$tmp/tests/reference/solution/$ws_scene.pfm" >/dev/null ||
            die "the solution's render of $ws_scene failed"
        echo "    render -W 256 -H 256 $ws_options scenes/$ws_scene.scene" >>"$tmp/tests/reference/solution/README"
    done
    # The second look's renders (lablib.sh's PAIRED_SECOND_SEED).
    if paired_second_look "$nn"; then
        mkdir -p "$tmp/tests/reference/solution/seed$PAIRED_SECOND_SEED"
        for ws_scene in $ws_scenes; do
            paired_render "$ws_render" "$nn" "$root/scenes/$ws_scene.scene" "$PAIRED_SECOND_SEED" \
                "$tmp/tests/reference/solution/seed$PAIRED_SECOND_SEED/$ws_scene.pfm" >/dev/null ||
                die "the solution's render of $ws_scene at seed $PAIRED_SECOND_SEED failed"
        done
        echo "and seed$PAIRED_SECOND_SEED/: the same with --seed $PAIRED_SECOND_SEED, for a second look where the first finds a bias." \
            >>"$tmp/tests/reference/solution/README"
    fi
    {
        echo "make grade renders your stage the same way and compares the two pixel by pixel"
        echo "(LAB.md, \"Reading the report pages\")."
    } >>"$tmp/tests/reference/solution/README"
}

write_makefile() {
    sed -e "s/@STAGE@/$stage/g" -e "s/@NN@/$nn/g" "$LAB_DIR/handout.mk.in" >"$tmp/Makefile"
    printf '/build/\n' >"$tmp/.gitignore"
}

# The development container, and GitHub Classroom's autograding files.
write_course_files() {
    if [ -d "$root/.devcontainer" ]; then
        copy_files "$root/.devcontainer" "$tmp/.devcontainer"
    fi
    wc_controls=$root/tests/course/controls/$stage
    [ -f "$wc_controls" ] || wc_controls=-
    "$LAB_DIR/../course/classroom.sh" "$tmp" "$wc_controls" || die "could not write the autograding workflow"
}

# The Lab section of the stage's docs page, its linked files copied.
lab_section() {
    ls_assets=$tmp/.assets
    : >"$ls_assets"
    if [ ! -f "$root/$page" ]; then
        problem "$page does not exist: LAB.md has no lab description"
        return 0
    fi
    ls_status=0
    (cd "$root" && awk -v dir="$(dirname "$page")" -v assets="$ls_assets" \
        -f "$LAB_DIR/labdoc.awk" "$page") >"$tmp/.section" || ls_status=$?
    if [ "$ls_status" -eq 3 ]; then
        problem "$page has no '## Lab' section: LAB.md has no lab description"
        return 0
    fi
    [ "$ls_status" -eq 0 ] || die "could not read $page"
    cat "$tmp/.section"
    echo
    for ls_a in $(sort -u "$ls_assets"); do
        if [ -f "$root/$ls_a" ]; then
            mkdir -p "$tmp/$(dirname "$ls_a")"
            cp "$root/$ls_a" "$tmp/$ls_a"
        else
            problem "$page links to $ls_a, which does not exist"
        fi
    done
}

# The page's first "# " heading, else the stage name.
page_title() {
    pt_t=
    if [ -f "$root/$page" ]; then
        pt_t=$(awk '/^# / { sub(/^# +/, ""); sub(/^[Ss]tage [0-9]+[:.] */, ""); sub(/^[0-9][0-9]_[A-Za-z0-9_]*[:.] */, ""); print; exit }' "$root/$page")
    fi
    echo "${pt_t:-$stage}"
}

# The places to write code, from the stubbed files.
todo_list() {
    (cd "$tmp" && awk -v mode=regions -v stubs="$LAB_DIR/stubs" -f "$LAB_DIR/markers.awk" \
        stages/"$stage"/*.[ch]) |
        awk -F '\t' -v nn="$nn" '$4 == nn { sub(/ \(docs\/stages\/[^)]*\)$/, "", $5); printf "- `%s`, line %d: %s\n", $1, $2, $5 }'
}

# ": WHAT", the first sentence of a test source's header comment
# (" * NAME.c - WHAT. More ..."), its lines joined; empty without one.
header_summary() {
    awk 'NR == 1 { next }
         /^ \*\/|^ \*$|^ \* *-/ && NR > 2 { exit }
         /^ \* / { sub(/^ \* /, ""); text = text (text == "" ? "" : " ") $0; next }
         { exit }
         END {
             if (sub(/^[^ ]+\.c - /, "", text) == 0) exit
             if (match(text, /\. |\.$/)) text = substr(text, 1, RSTART - 1)
             sub(/:$/, "", text)
             printf ": %s", text
         }' "$1"
}

test_list() {
    tl_which=$1
    tl_any=0
    for tl_f in "$tmp"/tests/stage/*.c; do
        [ -f "$tl_f" ] || continue
        tl_from=$(test_from "$tl_f")
        if { [ "$tl_which" = lab ] && [ "$tl_from" = "$nn" ]; } ||
            { [ "$tl_which" = earlier ] && [ "$tl_from" != "$nn" ]; }; then
            # With what its header says it checks, for the lab's own.
            tl_says=
            if [ "$tl_which" = lab ]; then
                tl_says=$(header_summary "$tl_f")
                ! full_only "$tl_f" || tl_says="$tl_says (run by make grade FULL=1 only)"
            fi
            printf -- '- `tests/stage/%s`%s\n' "$(basename "$tl_f")" "$tl_says"
            tl_any=1
        fi
    done
    [ "$tl_any" -eq 1 ] || echo "(none)"
}

write_labmd() {
    wl_todo=$(todo_list)
    if [ -z "$wl_todo" ] && [ "$solution" -eq 0 ]; then
        problem "stages/$stage has no LAB $nn region: the handout is the solution"
    fi
    {
        echo "# Lab $nn: $(page_title)"
        echo
        echo "<!-- Generated by stagelight's tests/lab/make-lab.sh from $page. -->"
        echo
        lab_section
        echo "## Where to write your code"
        echo
        if [ "$solution" -eq 1 ]; then
            echo "This is the instructor's copy: it holds the solution, marked"
            echo "\`/* LAB $nn: ... */\` ... \`/* END LAB */\`."
        else
            echo "Each place is marked \`/* LAB $nn: ... */\` ... \`/* END LAB */\`; between"
            echo "the markers is a stub that only keeps the program compiling."
            echo
            if [ -n "$wl_todo" ]; then echo "$wl_todo"; else echo "(none)"; fi
        fi
        echo
        echo "## Building and testing"
        echo
        echo "    make          # builds build/$stage/render"
        echo "    make test     # the tests; the last line is \"N passed, N failed, N skipped\""
        echo
        echo "The tests of this lab fail until you write it (the table above describes"
        echo "the main ones; each line below begins with what its header says):"
        echo
        test_list lab
        echo
        echo "The other tests check earlier stages' features, which your copy already"
        echo "has: they pass now and must still pass when you are done."
        echo
        test_list earlier
        echo
        sed -e "s/@STAGE@/$stage/g" -e "s/@NN@/$nn/g" "$LAB_DIR/report-pages.md"
    } >"$tmp/LAB.md"
    rm -f "$tmp/.assets" "$tmp/.section"
    # The project's pages LAB.md names (docs/aov.md, docs/inspect.md), so
    # that the handout holds what it cites; never a stage's own page (it
    # would show the lab's solution) nor its diffs.
    for wl_doc in $(grep -o 'docs/[A-Za-z0-9_-]*\.md' "$tmp/LAB.md" | LC_ALL=C sort -u); do
        if [ -f "$root/$wl_doc" ] && [ "$wl_doc" != docs/README.md ]; then
            mkdir -p "$tmp/docs"
            cp "$root/$wl_doc" "$tmp/$wl_doc"
        fi
    done
}

# The list of a handout's files with their checksums (build/, grade/ - make
# grade's report pages, not the student's work - and the list itself left
# out), sorted: "CRC SIZE ./path" lines.
file_list() {
    (cd "$1" && find . \( -path ./build -o -path ./grade \) -prune -o -type f ! -name "$MANIFEST" -print |
        while IFS= read -r fl_f; do cksum "$fl_f"; done) | LC_ALL=C sort
}

# The files of OUT that differ from what make-lab.sh last wrote there (its
# list), or, for a handout written before the list existed, from the fresh
# handout: changed, added or removed, one per line.
changed_files() {
    if [ -f "$out/$MANIFEST" ]; then
        cf_was=$out/$MANIFEST
    else
        cf_was=$tmp/$MANIFEST
    fi
    file_list "$out" >"$tmp.now"
    LC_ALL=C comm -3 "$cf_was" "$tmp.now" |
        sed 's/^[[:space:]]*[0-9]* [0-9]* \.\///' | LC_ALL=C sort -u
    rm -f "$tmp.now"
}

# An earlier handout with changes in it is someone's work: refuse, or with
# --force move it aside first.
protect_changes() {
    [ -d "$out" ] && is_handout "$out" || return 0
    [ "$discard" -eq 1 ] && return 0
    pc_changed=$(changed_files)
    [ -n "$pc_changed" ] || return 0
    if [ "$force" -eq 0 ]; then
        pc_n=$(printf '%s\n' "$pc_changed" | wc -l | tr -d ' ')
        {
            printf '%s: %s holds a handout with changes (%s file(s) edited, added or removed):\n' \
                "$PROG" "$out" "$pc_n"
            printf '%s\n' "$pc_changed" | head -n 20 | sed 's/^/    /'
            [ "$pc_n" -le 20 ] || printf '    ... and %s more\n' $((pc_n - 20))
            printf '%s: refusing to overwrite them; FORCE=1 (make-lab.sh --force) moves %s aside first\n' \
                "$PROG" "$out"
        } >&2
        exit 2
    fi
    pc_aside=$out.old-$(date +%Y%m%d-%H%M%S)
    pc_i=1
    while [ -e "$pc_aside" ]; do
        pc_aside=$out.old-$(date +%Y%m%d-%H%M%S)-$pc_i
        pc_i=$((pc_i + 1))
    done
    mv "$out" "$pc_aside" || die "cannot move $out aside to $pc_aside"
    echo "$PROG: $out had changes; moved it to $pc_aside"
}

# Make OUT's files equal to the fresh handout's, touching only those that
# differ; OUT/build is left alone.
sync_out() {
    mkdir -p "$out"
    (cd "$tmp" && find . -type f) | while IFS= read -r so_f; do
        so_f=${so_f#./}
        if ! cmp -s "$tmp/$so_f" "$out/$so_f"; then
            mkdir -p "$(dirname "$out/$so_f")"
            rm -f "$out/$so_f"
            cp "$tmp/$so_f" "$out/$so_f"
        fi
    done
    (cd "$out" && find . -path ./build -prune -o -type f -print) | while IFS= read -r so_f; do
        so_f=${so_f#./}
        [ -e "$tmp/$so_f" ] || rm -f "$out/$so_f"
    done
    (cd "$out" && find . -path ./build -prune -o -type d -empty -print) | sort -r |
        while IFS= read -r so_d; do
            [ "$so_d" = . ] || rmdir "$out/$so_d"
        done
}

MANIFEST=.stagelight-handout
check_out
tmp=$(mktemp -d "${TMPDIR:-/tmp}/make-lab.XXXXXX")
write_stage
copy_files "$root/common" "$tmp/common"
copy_files "$root/scenes" "$tmp/scenes"
write_tests
write_solution_renders
write_makefile
write_course_files
write_labmd
file_list "$tmp" >"$tmp.list" && mv "$tmp.list" "$tmp/$MANIFEST"
protect_changes
sync_out
if [ "$quiet" -eq 0 ]; then
    kind=handout
    [ "$solution" -eq 1 ] && kind="solution copy"
    echo "$PROG: wrote the $kind of lab $nn ($stage) to $out; see $out/LAB.md"
fi
