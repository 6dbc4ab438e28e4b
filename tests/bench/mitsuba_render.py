#!/usr/bin/env python3
"""mitsuba_render.py - render a stagelight scene file with Mitsuba 3, timed.

    mitsuba_render.py VARIANT SCENE SPP SEED THREADS OUT.pfm [BATCHES]

Translates the statements the bench scenes use (camera with its near
plane, image, material diffuse/mirror/glass, quad, sphere, area_light,
point_light, sphere_light, triangle, mesh: a .glb's nodes with their
transforms and materials, then the statement's own) into a Mitsuba scene
as tests/reference/SCENES.md defines it (Mitsuba's `path` integrator, unbounded depth, Russian roulette from depth
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


def triangle_mesh(v, bsdf, normals=None, emitter=None):
    """A Mitsuba mesh of the triangles (v[3i], v[3i+1], v[3i+2]): smooth-shaded
    by the corners' normals where given (as the stages shade a mesh with
    normals), flat otherwise; an area emitter on the front (counter-
    clockwise) side when given."""
    v = np.asarray(v, dtype=np.float32)
    props = mi.Properties()
    props["bsdf"] = mi.load_dict(bsdf)
    if emitter is not None:  # a shape's emitter is given when it is made
        props["emitter"] = mi.load_dict({"type": "area", "radiance": rgb(emitter)})
    mesh = mi.Mesh("triangles", len(v), len(v) // 3, props, has_vertex_normals=normals is not None)
    params = mi.traverse(mesh)
    # The buffers' own types, built from flat arrays: the same code serves
    # the scalar and the LLVM variants.
    params["vertex_positions"] = type(params["vertex_positions"])(v.ravel())
    params["faces"] = type(params["faces"])(np.arange(len(v), dtype=np.uint32))
    if normals is not None:
        n = np.asarray(normals, dtype=np.float32)
        params["vertex_normals"] = type(params["vertex_normals"])(n.ravel())
    params.update()
    return mesh


def rotation(axis, degrees):
    """The matrix of a rotation by `degrees` about `axis`, counter-clockwise
    when the axis points at the viewer (Rodrigues' formula)."""
    k = np.array(axis, dtype=np.float64)
    k = k / np.linalg.norm(k)
    a = np.radians(degrees)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.identity(3) + np.sin(a) * cross + (1 - np.cos(a)) * cross @ cross


def numbers_after(words, key):
    """The numbers that follow `key` on a statement, up to the next word."""
    out = []
    for w in words[words.index(key) + 1:]:
        try:
            out.append(float(w))
        except ValueError:
            break
    return out


def statement_transform(words):
    """The 4x4 matrix of a mesh statement's scale, then rotate, then
    translate (docs/scene-format.md)."""
    m = np.identity(4)
    if "scale" in words:
        sc = numbers_after(words, "scale")
        m = np.diag((sc * 3 if len(sc) == 1 else sc[:3]) + [1.0]) @ m
    if "rotate" in words:
        r = floats(words, "rotate", 4)
        rot = np.identity(4)
        rot[:3, :3] = rotation(r[:3], r[3])
        m = rot @ m
    if "translate" in words:
        t = np.identity(4)
        t[:3, 3] = floats(words, "translate")
        m = t @ m
    return m


def node_matrix(node):
    """A glTF node's local transform: its matrix (column-major), or T R S
    (rotation a unit quaternion x y z w)."""
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
    t = np.identity(4)
    t[:3, 3] = node.get("translation", [0, 0, 0])
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    r = np.identity(4)
    r[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    sc = np.diag(list(node.get("scale", [1, 1, 1])) + [1.0])
    return t @ r @ sc


def gltf_material(gltf, index):
    """(bsdf, emitted radiance or None, both sides emit) of a glTF material
    as the stages map it (docs/scene-format.md, "Materials from the file");
    a texture is not translated (the stages use its mean colour)."""
    if index is None:
        return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb([1, 1, 1])}}, None, False
    m = gltf["materials"][index]
    pbr = m.get("pbrMetallicRoughness", {})
    ext = m.get("extensions", {})
    for slot in ("baseColorTexture", "emissiveTexture"):
        if slot in pbr or slot in m:
            fail("material '%s': %s is not translated" % (m.get("name", index), slot))
    base = pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]
    strength = ext.get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
    emit = [c * strength for c in m.get("emissiveFactor", [0, 0, 0])]
    if max(emit) > 0:
        black = {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb([0, 0, 0])}}
        return black, emit, bool(m.get("doubleSided", False))
    transmission = ext.get("KHR_materials_transmission", {}).get("transmissionFactor", 0)
    if transmission > 0:
        ior = ext.get("KHR_materials_ior", {}).get("ior", 1.5)
        return {"type": "dielectric", "int_ior": ior, "ext_ior": 1.0}, None, False
    if pbr.get("metallicFactor", 1.0) >= 0.5 and pbr.get("roughnessFactor", 1.0) < 0.5:
        return {"type": "twosided", "bsdf": {"type": "conductor", "material": "none",
                                             "specular_reflectance": rgb(base)}}, None, False
    return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb(base)}}, None, False


def gltf_meshes(words, scene_path, materials):
    """The Mitsuba meshes of a `mesh file F [material M] [scale ...] [rotate
    ...] [translate ...]` statement: every primitive of every node of the
    file's scene, through the nodes' transforms (matrix or T R S, parents
    first), then the statement's; the file's materials unless M is given.
    A .glb file only."""
    import json
    import os
    import struct
    name = word(words, "file").strip('"')
    if not os.path.isabs(name):
        name = os.path.join(os.path.dirname(scene_path), name)
    if not name.endswith(".glb"):
        fail("%s: only .glb files are translated" % name)
    data = open(name, "rb").read()
    jlen = struct.unpack("<I", data[12:16])[0]
    gltf = json.loads(data[20:20 + jlen])
    blob = data[20 + jlen + 8:]

    def accessor(i, dtype, width):
        a = gltf["accessors"][i]
        view = gltf["bufferViews"][a["bufferView"]]
        if view.get("byteStride", 0) not in (0, np.dtype(dtype).itemsize * width):
            fail("%s: interleaved buffers are not translated" % name)
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        return np.frombuffer(blob, dtype=dtype, count=a["count"] * width,
                             offset=start).reshape(-1, width)

    outer = statement_transform(words)
    meshes = []

    def visit(index, parent):
        node = gltf["nodes"][index]
        m = parent @ node_matrix(node)
        for child in node.get("children", []):
            visit(child, m)
        if "mesh" not in node:
            return
        linear = m[:3, :3]
        mirrored = np.linalg.det(linear) < 0  # glTF: the front face is then clockwise
        for prim in gltf["meshes"][node["mesh"]]["primitives"]:
            if prim.get("mode", 4) != 4:
                fail("%s: only triangle primitives are translated" % name)
            pos = accessor(prim["attributes"]["POSITION"], "<f4", 3).astype(np.float64)
            if "indices" in prim:
                kind = {5121: "<u1", 5123: "<u2", 5125: "<u4"}[
                    gltf["accessors"][prim["indices"]]["componentType"]]
                idx = accessor(prim["indices"], kind, 1).ravel().astype(np.int64)
            else:
                idx = np.arange(len(pos))
            idx = idx.reshape(-1, 3)
            if mirrored:
                idx = idx[:, [0, 2, 1]]
            idx = idx.ravel()
            v = pos[idx] @ linear.T + m[:3, 3]
            normals = None
            if "NORMAL" in prim["attributes"]:
                n = accessor(prim["attributes"]["NORMAL"], "<f4", 3).astype(np.float64)[idx]
                n = n @ np.linalg.inv(linear)  # the inverse transpose, applied to rows
                normals = n / np.linalg.norm(n, axis=1, keepdims=True)
            if "material" in words:
                bsdf, emit, both = materials[word(words, "material")], None, False
            else:
                bsdf, emit, both = gltf_material(gltf, prim.get("material"))
            meshes.append(triangle_mesh(v, bsdf, normals, emit))
            if both:  # a one-sided emitter a side, the copy turned over
                turned = v.reshape(-1, 3, 3)[:, [0, 2, 1]].reshape(-1, 3)
                meshes.append(triangle_mesh(turned, bsdf, None, emit))

    for root in gltf["scenes"][gltf.get("scene", 0)]["nodes"]:
        visit(root, outer)
    return meshes


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
                for k, mesh in enumerate(gltf_meshes(words, path, materials)):
                    scene["mesh%d_%d" % (n, k)] = mesh
            elif st == "sphere_light":
                # Black on both sides; radiance L leaves its surface outward
                # (docs/scene-format.md): Mitsuba's sphere emits outward.
                scene["s%d" % n] = {
                    "type": "sphere", "center": floats(words, "center"),
                    "radius": float(word(words, "radius")),
                    "bsdf": {"type": "diffuse", "reflectance": rgb([0, 0, 0])},
                    "emitter": {"type": "area", "radiance": rgb(floats(words, "radiance"))}}
            elif st in ("ambient", "background"):
                continue
            else:
                fail("%s: statement %s is not translated" % (path, st))
    if camera is None:
        fail("no camera")
    if tri_v:
        scene["triangles"] = triangle_mesh(np.array(tri_v).reshape(-1, 3), materials[tri_mat])
    scene["camera"] = {
        "type": "perspective",
        "fov": float(word(camera, "fov")),
        "fov_axis": "y",
        # The stages' near plane is measured along the view direction, as
        # Mitsuba's near_clip is.
        "near_clip": float(word(camera, "near")) if "near" in camera else 1e-2,
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
