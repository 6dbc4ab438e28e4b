#!/usr/bin/env python3
"""mitsuba_render.py - render a stagelight scene file with Mitsuba 3, timed.

    mitsuba_render.py VARIANT SCENE SPP SEED THREADS OUT.pfm [BATCHES]

Translates the statements the reference scenes use (camera, image,
material diffuse/mirror/glass, quad, sphere, area_light, point_light,
triangle) into a Mitsuba scene as tests/reference/SCENES.md defines it
(Mitsuba's `path` integrator, unbounded depth, Russian roulette from depth
5, the independent sampler, a box filter of one pixel, two-sided surfaces,
one-sided black area lights), renders it once unmeasured (the LLVM variant
compiles its kernels then) and once measured, writes the measured image as
a little-endian PFM (rows bottom to top) and prints "seconds S cpu S".

With BATCHES, a reference image instead: SPP samples in BATCHES renders of
SPP / BATCHES each (seeds SEED, SEED + 1, ...; one render of all the samples
at once would hold them all in memory), averaged, none of them a warm-up;
the times printed are those of all the batches.

Used by tests/bench/pathtrace_bench.sh; not part of make test.
"""
import sys
import time

import drjit as dr
import mitsuba as mi
import numpy as np


def fail(msg):
    sys.stderr.write("mitsuba_render.py: %s\n" % msg)
    sys.exit(1)


def floats(words, key, n=3):
    i = words.index(key)
    return [float(w) for w in words[i + 1:i + 1 + n]]


def word(words, key):
    return words[words.index(key) + 1]


def parallelogram(corner, e1, e2):
    """to_world of Mitsuba's rectangle ([-1,1]^2, normal +z) onto
    corner + s e1 + t e2, s, t in [0, 1], facing cross(e1, e2)."""
    c = np.array(corner)
    a = np.array(e1)
    b = np.array(e2)
    n = np.cross(a, b)
    n = n / np.linalg.norm(n)
    m = np.identity(4)
    m[:3, 0] = a / 2
    m[:3, 1] = b / 2
    m[:3, 2] = n
    m[:3, 3] = c + a / 2 + b / 2
    return mi.ScalarTransform4f(m.tolist())


def rgb(v):
    return {"type": "rgb", "value": v}


def material(words):
    kind = words[2]
    if kind == "diffuse":
        return {"type": "twosided",
                "bsdf": {"type": "diffuse", "reflectance": rgb(floats(words, "albedo"))}}
    if kind == "mirror":
        return {"type": "twosided",
                "bsdf": {"type": "conductor", "material": "none",
                         "specular_reflectance": rgb(floats(words, "reflectance"))}}
    if kind == "glass":
        return {"type": "dielectric", "int_ior": float(word(words, "ior")), "ext_ior": 1.0}
    fail("material kind %s is not translated" % kind)


def triangle_mesh(v, bsdf):
    """A Mitsuba mesh of the triangles (v[3i], v[3i+1], v[3i+2]), flat-shaded."""
    v = np.asarray(v, dtype=np.float32)
    mesh = mi.Mesh("triangles", len(v), len(v) // 3)
    params = mi.traverse(mesh)
    # The buffers' own types, built from flat arrays: the same code serves
    # the scalar and the LLVM variants.
    params["vertex_positions"] = type(params["vertex_positions"])(v.ravel())
    params["faces"] = type(params["faces"])(np.arange(len(v), dtype=np.uint32))
    params.update()
    mesh.set_bsdf(mi.load_dict(bsdf))
    return mesh


def rotation(axis, degrees):
    """The matrix of a rotation by `degrees` about `axis`, counter-clockwise
    when the axis points at the viewer (Rodrigues' formula)."""
    k = np.array(axis, dtype=np.float64)
    k = k / np.linalg.norm(k)
    a = np.radians(degrees)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.identity(3) + np.sin(a) * cross + (1 - np.cos(a)) * cross @ cross


def glb_triangles(words, scene_path):
    """The corners of the triangles of a `mesh file F ... [scale S]
    [rotate AX AY AZ DEG] [translate X Y Z]` statement whose .glb holds one
    mesh at its node's identity transform (the bunny of scenes/models):
    scaled, then rotated, then moved (docs/scene-format.md)."""
    import json
    import os
    import struct
    name = word(words, "file").strip('"')
    if not os.path.isabs(name):
        name = os.path.join(os.path.dirname(scene_path), name)
    data = open(name, "rb").read()
    jlen = struct.unpack("<I", data[12:16])[0]
    gltf = json.loads(data[20:20 + jlen])
    blob = data[20 + jlen + 8:]
    if len(gltf["nodes"]) != 1 or set(gltf["nodes"][0]) - {"mesh", "name"}:
        fail("%s: only one untransformed mesh node is translated" % name)

    def accessor(i, dtype, width):
        a = gltf["accessors"][i]
        view = gltf["bufferViews"][a["bufferView"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        return np.frombuffer(blob, dtype=dtype, count=a["count"] * width,
                             offset=start).reshape(-1, width)

    tris = []
    for prim in gltf["meshes"][gltf["nodes"][0]["mesh"]]["primitives"]:
        pos = accessor(prim["attributes"]["POSITION"], "<f4", 3).astype(np.float64)
        kind = {5121: "<u1", 5123: "<u2", 5125: "<u4"}[
            gltf["accessors"][prim["indices"]]["componentType"]]
        tris.append(pos[accessor(prim["indices"], kind, 1).ravel()])
    v = np.concatenate(tris)
    if "matrix" in words:
        fail("mesh: only scale, rotate and translate are translated")
    if "scale" in words:
        v = v * float(word(words, "scale"))
    if "rotate" in words:
        r = floats(words, "rotate", 4)
        v = v @ rotation(r[:3], r[3]).T
    if "translate" in words:
        v = v + np.array(floats(words, "translate"))
    return v


def load(path, spp, seed):
    scene = {"type": "scene",
             "integrator": {"type": "path", "max_depth": -1, "rr_depth": 5,
                            "hide_emitters": False}}
    materials = {}
    width = height = 256
    camera = None
    n = 0
    tri_v = []
    tri_mat = None
    mesh_v = []
    mesh_mat = []
    with open(path) as f:
        for line in f:
            words = line.split("#", 1)[0].split()
            if not words:
                continue
            st = words[0]
            n += 1
            if st == "camera":
                camera = words
            elif st == "image":
                width = int(word(words, "width"))
                height = int(word(words, "height"))
            elif st == "material":
                materials[words[1]] = material(words)
            elif st == "quad":
                scene["s%d" % n] = {
                    "type": "rectangle",
                    "to_world": parallelogram(floats(words, "corner"), floats(words, "edge1"),
                                              floats(words, "edge2")),
                    "bsdf": materials[word(words, "material")]}
            elif st == "sphere":
                scene["s%d" % n] = {"type": "sphere", "center": floats(words, "center"),
                                    "radius": float(word(words, "radius")),
                                    "bsdf": materials[word(words, "material")]}
            elif st == "area_light":
                scene["s%d" % n] = {
                    "type": "rectangle",
                    "to_world": parallelogram(floats(words, "corner"), floats(words, "edge1"),
                                              floats(words, "edge2")),
                    "bsdf": {"type": "diffuse", "reflectance": rgb([0, 0, 0])},
                    "emitter": {"type": "area", "radiance": rgb(floats(words, "radiance"))}}
            elif st == "point_light":
                scene["s%d" % n] = {"type": "point", "position": floats(words, "position"),
                                    "intensity": rgb(floats(words, "intensity"))}
            elif st == "triangle":
                tri_v.append(floats(words, "v0") + floats(words, "v1") + floats(words, "v2"))
                m = word(words, "material")
                if tri_mat not in (None, m):
                    fail("triangles of more than one material are not translated")
                tri_mat = m
            elif st == "mesh":
                mesh_v.append(glb_triangles(words, path))
                scene["mesh%d" % n] = None
                mesh_mat.append((n, word(words, "material")))
            elif st in ("ambient", "background"):
                continue
            else:
                fail("%s: statement %s is not translated" % (path, st))
    if camera is None:
        fail("no camera")
    for (key, mat), v in zip(mesh_mat, mesh_v):
        scene["mesh%d" % key] = triangle_mesh(v, materials[mat])
    if tri_v:
        scene["triangles"] = triangle_mesh(np.array(tri_v).reshape(-1, 3), materials[tri_mat])
    scene["camera"] = {
        "type": "perspective",
        "fov": float(word(camera, "fov")),
        "fov_axis": "y",
        "to_world": mi.ScalarTransform4f().look_at(origin=floats(camera, "origin"),
                                                   target=floats(camera, "target"),
                                                   up=floats(camera, "up")),
        "sampler": {"type": "independent", "sample_count": spp, "seed": seed},
        "film": {"type": "hdrfilm", "width": width, "height": height,
                 "rfilter": {"type": "box"}, "pixel_format": "rgb"}}
    return mi.load_dict(scene)


def write_pfm(path, img):
    h, w, _ = img.shape
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        f.write(np.ascontiguousarray(np.flipud(img), dtype="<f4").tobytes())


def render(scene, spp, seed):
    """One render, finished, as an array of its RGB."""
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    dr.sync_thread()
    return np.array(img)[:, :, :3].astype(np.float64)


def main():
    if len(sys.argv) not in (7, 8):
        fail("usage: mitsuba_render.py VARIANT SCENE SPP SEED THREADS OUT.pfm [BATCHES]")
    variant, path, spp, seed, threads, out = sys.argv[1:7]
    batches = int(sys.argv[7]) if len(sys.argv) == 8 else 0
    spp, seed = int(spp), int(seed)
    mi.set_variant(variant)
    dr.set_thread_count(int(threads))
    if batches and spp % batches:
        fail("SPP must be a multiple of BATCHES")
    per_render = spp // batches if batches else spp
    scene = load(path, per_render, seed)
    if not batches:
        render(scene, spp, seed + 1000)  # the LLVM variant compiles its kernels here
    start = time.perf_counter()
    cpu_start = time.process_time()
    if batches:
        img = sum(render(scene, per_render, seed + b) for b in range(batches)) / batches
    else:
        img = render(scene, spp, seed)
    seconds = time.perf_counter() - start
    cpu = time.process_time() - cpu_start
    write_pfm(out, img)
    print("seconds %.4f cpu %.4f" % (seconds, cpu))


if __name__ == "__main__":
    main()
