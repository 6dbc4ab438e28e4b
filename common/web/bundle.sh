#!/bin/sh
# bundle.sh ROOT WEB STAGE... - the browser page's library (make web): copy
# the scenes of ROOT/scenes, the glTF models they name (mesh file ...) and
# the reference images of ROOT/tests/reference into WEB, and write
# WEB/library.json, which the page reads: the stages, the scenes (each with
# the files it needs and its references) and the scenes left out, with why.
# A scene whose model is not among scenes/ models (the Buddha's, made by
# `make models` into build/: 25 MB, 1.08M triangles, minutes per pass in a
# browser) is left out, with the reason in library.json.
set -eu
root=$1
web=$2
shift 2
mkdir -p "$web/scenes/models" "$web/reference"
tmp=$web/library.json.tmp

# json_list WORD... - the words as a JSON array of strings.
json_list() {
    sep=
    printf '['
    for w in "$@"; do
        printf '%s"%s"' "$sep" "$w"
        sep=', '
    done
    printf ']'
}

{
    printf '{\n  "stages": %s,\n  "scenes": [\n' "$(json_list "$@")"
    sep=
    left=
    for path in "$root"/scenes/*.scene "$root"/scenes/*.gltf; do
        file=${path##*/}
        name=${file%.*}
        # The models: `file` fields of mesh lines, comments stripped.
        models=$(sed 's/#.*//' "$path" | tr -s ' \t' '\n\n' | awk 'prev == "file" { print } { prev = $0 }')
        missing=
        for m in $models; do
            case $m in
                /* | ../* | */../*) missing="$missing $m" ;;
                *) [ -f "$root/scenes/$m" ] || missing="$missing $m" ;;
            esac
        done
        if [ -n "$missing" ]; then
            left="$left $name:$(echo $missing)"
            continue
        fi
        cp "$path" "$web/scenes/$file"
        needs=
        for m in $models; do
            cp "$root/scenes/$m" "$web/scenes/$m"
            needs="$needs scenes/$m"
        done
        refs=
        for r in "$root"/tests/reference/"$name"_*.pfm; do
            [ -f "$r" ] || continue
            cp "$r" "$web/reference/"
            refs="$refs reference/${r##*/}"
        done
        printf '%s    {"name": "%s", "file": "scenes/%s", "needs": %s, "references": %s}' \
            "$sep" "$name" "$file" "$(json_list $needs)" "$(json_list $refs)"
        sep=',
'
    done
    printf '\n  ],\n  "left_out": [\n'
    sep=
    for l in $left; do
        printf '%s    {"name": "%s", "why": "its model %s is made by make models (25 MB, 1.08M triangles): too large to bundle; render it natively"}' \
            "$sep" "${l%%:*}" "${l#*:}"
        sep=',
'
    done
    printf '\n  ]\n}\n'
} >"$tmp"
mv "$tmp" "$web/library.json"
