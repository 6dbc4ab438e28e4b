#!/bin/sh
# layers.sh [LIBCOMMON] - common/ is layers: its folders (common/config.mk's
# COMMON_LAYERS, in order: core image gltf scene inspect render app) each
# use only themselves and the folders before them, no file calls or
# includes back into itself through others, nothing but the build files
# sits at common/'s top, no code names a stage, and no file is over 450
# lines.
#
#   calls     file A -> file B when A's object uses a symbol B's object
#             defines (nm on LIBCOMMON, by default the newest
#             build/**/common/libcommon.a; built with make when none is)
#   includes  file A -> header B when A has #include "B" and B is in common/
#
# Prints one line per check ("ok   layers/calls: N files, N edges, no
# cycle"; "ok   layers/folders: ..."; or FAIL with the cycle's files or the
# edge that goes up a layer) and "N passed, N failed, N skipped".
# Exit status: 0 all hold, 1 one does not or no library.
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
trap 'rm -f "${TMPDIR:-/tmp}/layers.$$".*' EXIT
lib=${1:-}
if [ -z "$lib" ]; then
    lib=$(ls -t "$root"/build/common/libcommon.a "$root"/build/*/common/libcommon.a 2>/dev/null | head -n 1)
fi
if [ -z "$lib" ]; then
    ${MAKE:-make} --no-print-directory -C "$root/common" >/dev/null 2>&1
    lib=$root/build/common/libcommon.a
fi

# cycles NAME: reads "A B" edges; prints the ok or FAIL line.
cycles() {
    awk -v name="$1" '
        $1 != $2 { if (!(($1, $2) in seen)) { seen[$1, $2] = 1; n_out[$1]++; out[$1, n_out[$1]] = $2; edges++ }
                   node[$1] = 1; node[$2] = 1 }
        # Depth-first search, iterative: colour 1 on the stack, 2 done.
        function visit(start,    top, v, i, w, k, path) {
            top = 1; stack[1] = start; next_i[1] = 1; colour[start] = 1
            while (top > 0) {
                v = stack[top]; i = next_i[top]
                if (i > n_out[v]) { colour[v] = 2; top--; continue }
                next_i[top] = i + 1; w = out[v, i]
                if (colour[w] == 1) {
                    path = w
                    for (k = top; k >= 1 && stack[k] != w; k--) path = stack[k] " -> " path
                    return w " -> " path
                }
                if (colour[w] == 0) { top++; stack[top] = w; next_i[top] = 1; colour[w] = 1 }
            }
            return ""
        }
        END {
            files = 0
            for (v in node) { files++; colour[v] = 0 }
            for (v in node) {
                if (colour[v] == 0 && (c = visit(v)) != "") {
                    print "FAIL layers/" name ": a cycle: " c
                    exit 1
                }
            }
            printf "ok   layers/%s: %d files, %d edges, no cycle\n", name, files, edges
        }'
}

passed=0
failed=0
count() {
    if [ "$1" -eq 0 ]; then passed=$((passed + 1)); else failed=$((failed + 1)); fi
}

if [ -f "$lib" ] && nm -A "$lib" >/dev/null 2>&1; then
    # "lib.a:file.o:ADDR T sym" or "lib.a:file.o: U sym"
    nm -A "$lib" 2>/dev/null | awk '
        { k = split($1, at, ":"); f = at[k - 1]; sub(/\.o$/, "", f) }
        NF == 3 && $2 ~ /^[TDRBC]$/ { def[$3] = f }
        NF == 3 && $2 == "U" { n++; user[n] = f; sym[n] = $3 }
        END { for (i = 1; i <= n; i++) if (sym[i] in def) print user[i], def[sym[i]] }' \
        >"${TMPDIR:-/tmp}/layers.$$.calls"
    cycles calls <"${TMPDIR:-/tmp}/layers.$$.calls"
    count $?
else
    echo "FAIL layers/calls: no library to read ($lib; nm is binutils')"
    count 1
fi

layers=$(sed -n 's/^COMMON_LAYERS := //p' "$root/common/config.mk")
# folder_of NAME: the layer folder that holds common/*/NAME ("" if none).
folder_of() {
    for fo_d in $layers; do
        [ -f "$root/common/$fo_d/$1" ] && { echo "$fo_d"; return; }
    done
}
# The include edges, "A B" by file name.
for d in $layers; do
    for f in "$root/common/$d"/*; do
        sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f" | while read -r inc; do
            [ -n "$(folder_of "$inc")" ] && echo "$(basename "$f") $inc"
        done
    done
done >"${TMPDIR:-/tmp}/layers.$$.includes"
cycles includes <"${TMPDIR:-/tmp}/layers.$$.includes"
count $?

# Every edge, calls and includes, goes to the same folder or one before it.
{
    cat "${TMPDIR:-/tmp}/layers.$$.includes"
    [ ! -f "${TMPDIR:-/tmp}/layers.$$.calls" ] || cat "${TMPDIR:-/tmp}/layers.$$.calls"
} | awk -v layers="$layers" -v files="$(for d in $layers; do for f in "$root/common/$d"/*; do
        printf '%s %s\n' "$(basename "$f")" "$d"; done; done)" '
    BEGIN {
        n = split(layers, l, " "); for (i = 1; i <= n; i++) rank[l[i]] = i
        m = split(files, fl, "\n"); for (i = 1; i <= m; i++) { split(fl[i], w, " "); dir[w[1]] = w[2] }
    }
    {
        a = dir[$1]; b = dir[$2]
        if (a == "" || b == "") { a = a == "" ? dir[$1 ".c"] dir[$1 ".cc"] : a; b = b == "" ? dir[$2 ".c"] dir[$2 ".cc"] : b }
        edges++
        if (rank[b] > rank[a]) { printf "FAIL layers/folders: %s/%s -> %s/%s: %s is below %s\n", a, $1, b, $2, a, b; bad = 1 }
    }
    END { if (!bad) printf "ok   layers/folders: %d folders, %d edges, none up a layer\n", n, edges; exit bad }'
count $?

# Nothing at common/'s top but its build files (and the browser build).
top=$(cd "$root/common" && ls | grep -v -x -e Makefile -e config.mk -e stage.mk -e web $(for d in $layers; do printf -- '-e %s ' "$d"; done) | tr '\n' ' ')
if [ -z "$top" ]; then
    echo "ok   layers/top: common/ holds its build files and $(echo "$layers" | wc -w) layer folders"
    count 0
else
    echo "FAIL layers/top: files at common/'s top, outside its layers: $top"
    count 1
fi

# common/ knows no stage: no string of its code (comments aside) names one;
# the course's table, which does, is stages/course.c.
named=$(for d in $layers; do for f in "$root/common/$d"/*.c "$root/common/$d"/*.h "$root/common/$d"/*.cc; do
    [ -f "$f" ] || continue
    case $f in *.cc) lang=c++ ;; *) lang=c ;; esac
    if gcc -fpreprocessed -dD -E -P -x "$lang" "$f" 2>/dev/null | grep -qE '"[0-9][0-9]_[a-z]'; then
        printf '%s/%s ' "$d" "$(basename "$f")"
    fi
done; done)
if [ -z "$named" ]; then
    echo "ok   layers/stages: no code of common/ names a stage"
    count 0
else
    echo "FAIL layers/stages: code that names a stage (the course's table is stages/course.c): $named"
    count 1
fi

# docs/architecture.md's sizes of the layers are true: "N files, M lines"
# per folder, files exactly, lines within 5% (a small edit does not void
# them, a new file or a real change in size does).
sizes=$(for d in $layers; do
    files=$(ls "$root/common/$d" | wc -l)
    lines=$(cat "$root/common/$d"/* | wc -l)
    row=$(grep -F "| \`common/$d/\` | " "$root/docs/architecture.md" | head -n 1)
    echo "$row" | awk -v d="$d" -v f="$files" -v l="$lines" -F'|' '{
        size = $3; gsub(/,/, "", size)
        if (split(size, w, " ") < 4 || w[1] != f || (w[3] - l) > 0.05 * l || (l - w[3]) > 0.05 * l)
            printf "common/%s/ is %d files, %d lines, not \"%s\" ", d, f, l, $3
    }'
done)
if [ -z "$sizes" ]; then
    echo "ok   layers/sizes-documented: docs/architecture.md gives each layer's files and lines"
    count 0
else
    echo "FAIL layers/sizes-documented: update docs/architecture.md: $sizes"
    count 1
fi

# No file of a layer over 450 lines: a file is read in one sitting.
long=$(for d in $layers; do wc -l "$root/common/$d"/* | awk -v d="$d" '$2 != "total" && $1 > 450 {
    n = split($2, p, "/"); printf "%s/%s (%d lines) ", d, p[n], $1 }'; done)
if [ -z "$long" ]; then
    echo "ok   layers/size: no file of common/'s layers over 450 lines"
    count 0
else
    echo "FAIL layers/size: over 450 lines: $long"
    count 1
fi

echo "$passed passed, $failed failed, 0 skipped"
[ "$failed" -eq 0 ]
