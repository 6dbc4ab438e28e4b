#!/usr/bin/env python3
"""make-seeds.py - (re)write the hand-made seed inputs of tests/fuzz/seeds/.

The seeds are small valid inputs, one per feature a harness should reach
quickly: libFuzzer mutates from them.  The files are committed; run this only
to change them.  Formats: docs/robustness.md ("What is fuzzed").
"""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
SEEDS = os.path.join(HERE, "seeds")

# One triangle and one quad (two triangles) in z = 0, with normals +z.
POSITIONS = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
NORMALS = [(0, 0, 1)] * 4
INDICES = [0, 1, 2, 1, 3, 2]


def write(kind, name, data):
    os.makedirs(os.path.join(SEEDS, kind), exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(SEEDS, kind, name), mode) as f:
        f.write(data)


def pad4(b, fill=b"\0"):
    return b + fill * (-len(b) % 4)


def model(index_type, with_normals, node):
    """glTF JSON (without buffer URI) and the one buffer's bytes."""
    fmt = {5121: "B", 5123: "H", 5125: "I"}.get(index_type)
    # Without indices, every three vertices make a triangle.
    points = POSITIONS if fmt else [POSITIONS[i] for i in INDICES]
    pos = b"".join(struct.pack("<3f", *p) for p in points)
    nrm = b"".join(struct.pack("<3f", *NORMALS[0]) for p in points)
    idx = pad4(struct.pack("<%d%s" % (len(INDICES), fmt), *INDICES)) if fmt else b""
    blob = pos + (nrm if with_normals else b"") + idx
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(points), "type": "VEC3",
                  "min": [0, 0, 0], "max": [1, 1, 0]}]
    attributes = {"POSITION": 0}
    if with_normals:
        views.append({"buffer": 0, "byteOffset": len(pos), "byteLength": len(nrm)})
        accessors.append({"bufferView": 1, "componentType": 5126, "count": len(points), "type": "VEC3"})
        attributes["NORMAL"] = 1
    primitive = {"attributes": attributes, "mode": 4}
    if fmt:
        views.append({"buffer": 0, "byteOffset": len(blob) - len(idx),
                      "byteLength": len(INDICES) * struct.calcsize(fmt)})
        accessors.append({"bufferView": len(views) - 1, "componentType": index_type,
                          "count": len(INDICES), "type": "SCALAR"})
        primitive["indices"] = len(accessors) - 1
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [dict(node, mesh=0)],
        "meshes": [{"primitives": [primitive]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob)}],
    }
    return doc, blob


def glb(doc, blob):
    js = pad4(json.dumps(doc, separators=(",", ":")).encode(), b" ")
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(blob), b"BIN\0") + blob
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def main():
    rotate = {"rotation": [0, 0.7071068, 0, 0.7071068], "translation": [1, 2, 3], "scale": [2, 2, 2]}
    matrix = {"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1]}
    write("glb", "tri.glb", glb(*model(5125, True, {})))
    write("glb", "u16_trs.glb", glb(*model(5123, False, rotate)))
    write("glb", "u8_matrix.glb", glb(*model(5121, True, matrix)))
    write("glb", "nonindexed.glb", glb(*model(None, False, {})))

    # .gltf seeds: JSON, then NUL and buffer.bin's bytes (fuzz_gltf.c).
    doc, blob = model(5125, True, rotate)
    doc["buffers"][0]["uri"] = "buffer.bin"
    write("gltf", "external.gltf", json.dumps(doc, indent=1).encode() + b"\0" + blob)
    doc, blob = model(5123, False, matrix)
    doc["buffers"][0]["uri"] = ("data:application/octet-stream;base64,"
                                + base64.b64encode(blob).decode())
    write("gltf", "data_uri.gltf", json.dumps(doc, indent=1))
    doc, blob = model(None, True, {"children": [1]})
    doc["nodes"].append({"mesh": 0, "translation": [0, 1, 0]})
    doc["nodes"][0].pop("mesh")
    doc["buffers"][0]["uri"] = "buffer.bin"
    write("gltf", "children.gltf", json.dumps(doc).encode() + b"\0" + blob)

    # The scene harness names its scene tests/fuzz/seeds/glb/fuzz.scene.
    write("scene", "mesh.scene",
          "image width 32 height 24\ncamera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
          "material white diffuse albedo 0.8 0.8 0.8\n"
          "point_light position 0 4 4 intensity 10 10 10\n"
          "mesh file tri.glb material white scale 2 rotate 0 1 0 30 translate 0 0 -1\n"
          "mesh file \"u16_trs.glb\" material white scale 1 1 -1\n")

    # PFM: colour and greyscale, little- and big-endian (the scale's sign).
    write("pfm", "color_le.pfm", b"PF\n2 2\n-1.0\n" + struct.pack("<12f", *range(12)))
    write("pfm", "color_be.pfm", b"PF\n1 2\n1.0\n" + struct.pack(">6f", 0.5, 1, 2, 3, 4, 1e30))
    write("pfm", "grey_le.pfm", b"Pf\n3 1\n-2.5\n" + struct.pack("<3f", 0.25, 0.5, 0.75))

    # Command lines: the stage as one byte, then the arguments after
    # "render", separated by NUL bytes.  The byte's value modulo the number
    # of stages (8) chooses the stage: the digit '0' + n - 1 for stage n.
    # The harness runs in a directory holding the scene a.scene and the
    # image b.png (fuzz_cli.c).
    for name, stage, args in [
        ("typical", 1, ["-o", "out.png", "-W", "320", "-H", "240", "--spp", "16", "-t", "2",
                        "-q", "a.scene"]),
        ("soft_shadows", 3, ["--shadow-samples", "4", "--stats", "s.json", "a.scene"]),
        ("optics", 4, ["--max-depth", "8", "-o", "x.pfm", "a.scene"]),
        ("bvh", 5, ["--no-bvh", "--adaptive", "4,16", "a.scene"]),
        ("stage_knobs", 6, ["--aa=adaptive", "--aa-threshold", "0.1", "--adaptive", "4,16",
                            "--max-depth=8", "--no-bvh", "--shadow-samples", "4", "s"]),
        ("pathtrace", 7, ["--aa", "grid", "--spp", "4", "--rr-depth", "2", "--no-nee", "--no-rr",
                          "--time", "2.5", "a.scene"]),
        ("variance_reduction", 8, ["--no-mis", "--spp", "5", "--sampler=sobol",
                                   "--rr-threshold", "0.5", "--brute-force-max", "0", "a.scene"]),
        ("long_forms", 2, ["--output=x.pfm", "--width=64", "--seed", "9223372036854775807",
                           "--stats", "s.json", "--strict", "--max-memory", "64", "scene"]),
        ("same_output", 2, ["-o", "b.png", "--stats", "b.png", "a.scene"]),
        ("output_is_scene", 5, ["-o", "b.png", "b.png"]),
        ("no_directory", 6, ["-o", "missing/x.png", "a.scene"]),
        ("unknown_format", 3, ["-o", "x.txt", "a.scene"]),
        ("aov", 8, ["--aov", "depth,normal,id", "--sampler", "independent", "-o", "x.pfm",
                    "a.scene"]),
        ("help", 7, ["--help"]),
        ("version", 1, ["--version"]),
    ]:
        write("cli", name, chr(ord("0") + stage - 1) + "\0".join(args))

if __name__ == "__main__":
    main()
