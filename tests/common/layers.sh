#!/bin/sh
# layers.sh [LIBCOMMON] - common/ has no circles: no file of common/ calls,
# through others, back into itself, and no header includes itself through
# others.  The files are layers, data below and dispatch above (image.c
# below the encoders below image_write.c; scene_lexer.c, scene_fields.c and
# scene_store.c below the builders below scene.c; the glTF steps below
# gltf_shim.cc).
#
#   calls     file A -> file B when A's object uses a symbol B's object
#             defines (nm on LIBCOMMON, by default the newest
#             build/**/common/libcommon.a; built with make when none is)
#   includes  file A -> header B when A has #include "B" and B is in common/
#
# Prints one line per graph ("ok   layers/calls: N files, N edges, no
# cycle", or FAIL with the cycle's files) and "N passed, N failed, N
# skipped".  Exit status: 0 both acyclic, 1 a cycle or no library.
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
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
        END { for (i = 1; i <= n; i++) if (sym[i] in def) print user[i], def[sym[i]] }' |
        cycles calls
    count $?
else
    echo "FAIL layers/calls: no library to read ($lib; nm is binutils')"
    count 1
fi

for f in "$root"/common/*.c "$root"/common/*.cc "$root"/common/*.h; do
    sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$f" | while read -r inc; do
        [ -f "$root/common/$inc" ] && echo "$(basename "$f") $inc"
    done
done | cycles includes
count $?

echo "$passed passed, $failed failed, 0 skipped"
[ "$failed" -eq 0 ]
