#!/bin/sh
# collect-seeds.sh ROOT OUT - copy the glTF and PFM files of the tree (the
# models of scenes/, the fixtures of tests/) into OUT/glb, OUT/gltf, OUT/pfm
# as extra seeds for make fuzz.  Files over 64 KiB are left out: libFuzzer's
# input length follows its largest seed, and small inputs run faster.
root=$1
out=$2
mkdir -p "$out/glb" "$out/gltf" "$out/pfm"
for ext in glb gltf pfm; do
    find "$root/scenes" "$root/tests" -name "*.$ext" -type f -size -65k \
        ! -path "$root/tests/fuzz/*" 2>/dev/null |
        while read -r f; do
            cp "$f" "$out/$ext/$(echo "${f#$root/}" | tr / _)"
        done
done
