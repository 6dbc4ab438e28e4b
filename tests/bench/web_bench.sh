#!/bin/sh
# web_bench.sh - the browser build's rays per second against the native
# build's (make bench; docs/web.md): stage 07 at 128x128 with 16 spp and
# stage 05 (one ray per pixel) at 512x512, on the Cornell box and on the
# bunny box (a BVH of 70k triangles), natively on 1 thread and on
# every core, and the WebAssembly build (build/web/, make web) on 1 and on as
# many workers, each a share of the tiles, as the page runs it
# (web_bench.js, under node: V8, Chromium's engine).  Each configuration
# runs ROUNDS times and its fastest round counts (the machine is shared).
# The ratio is native / browser: how many times slower the browser is per
# thread (the aim is at most 2).  Skipped, with the reason, without
# emscripten or node.  Run from the project root after make.
set -eu
ROUNDS=${ROUNDS:-3}
cores=$(nproc 2>/dev/null || echo 2)
if [ ! -f build/web/index.html ]; then
    if command -v emcc >/dev/null 2>&1; then
        make --no-print-directory web >/dev/null
    else
        echo "web_bench: skipped: no emscripten (apt-get install emscripten) for make web"
        exit 0
    fi
fi
if ! command -v node >/dev/null 2>&1; then
    echo "web_bench: skipped: no node (apt-get install nodejs)"
    exit 0
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sl-webbench.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' HUP INT PIPE TERM

# best CMD... - the largest rays_per_second of ROUNDS runs of CMD (which
# prints JSON with that field, on one line or many).
best() {
    b=0
    i=0
    while [ "$i" -lt "$ROUNDS" ]; do
        r=$("$@" | tr -d '\n ' | sed 's/.*"rays_per_second":\([0-9.e+-]*\).*/\1/')
        b=$(awk -v a="$b" -v r="$r" 'BEGIN { print (r > a ? r : a) }')
        i=$((i + 1))
    done
    echo "$b"
}

printf 'browser build (WebAssembly, node %s) against native, fastest of %d rounds\n' \
    "$(node --version)" "$ROUNDS"
printf '%-16s %-22s %8s %14s %14s %8s\n' stage scene threads "native Mray/s" "browser Mray/s" ratio
for stage in 05_bvh 07_pathtrace; do
    case $stage in
        05_*) args="-W 512" ;;
        *) args="-W 128 --spp 16" ;;
    esac
    for scene in cornell_diffuse_area bunny_cornell; do
        for n in 1 "$cores"; do
            nat=$(best build/$stage/render -q $args -t "$n" --stats - -o "$tmp/n.pfm" scenes/$scene.scene)
            web=$(best node tests/bench/web_bench.js build/web $stage scenes/$scene.scene "$n" $args)
            awk -v s=$stage -v sc=$scene -v n="$n" -v a="$nat" -v b="$web" \
                'BEGIN { printf "%-16s %-22s %8d %14.2f %14.2f %8.2f\n", s, sc, n, a / 1e6, b / 1e6, a / b }'
        done
    done
done
