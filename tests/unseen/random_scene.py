#!/usr/bin/env python3
"""random_scene.py - a random scene nobody tuned the renderer to.

    random_scene.py SEED [--unit]

Writes to standard output a scene file drawn from SEED (the same seed, the
same scene): a box of side 2 with some of its walls (rays escape through
the missing ones), 1-4 spheres and 0-3 triangles of four random materials
(diffuse, mirror, glass with an index from 1.05 to 2.5 or a bubble of
0.7), 1-2 area lights 0.01 and 0.03 under the ceiling (facing down,
facing the ceiling so that their light reaches the room only round their
edges, or tilted),
half the time a point light, a camera at a random place with a vertical
field of view of 15-110 degrees, and an image of one of seven shapes
(1x40 and 40x1 among them).  Only the statements that
tests/bench/mitsuba_render.py translates are used, so Mitsuba 3 can
render the same scene.

The whole scene is then scaled by 10^u (u uniform in [-3, 3]) and moved
up to 50 scene sizes from the origin; --unit leaves it at scale 1 around
the origin, the same scene otherwise (every other random draw is the
same), so that a render of each can be compared (radiance does not depend
on the units; a point light's intensity, W/sr, is scaled with the square
of the scale so that the irradiance it gives is unchanged).
"""
import random
import sys


def vec(v):
    return " ".join("%.9g" % x for x in v)


def scene(seed, unit):
    rng = random.Random(seed)
    scale = 10 ** rng.uniform(-3, 3)
    offset = [rng.uniform(-50, 50) * scale for _ in range(3)]
    if unit:
        scale, offset = 1.0, [0.0, 0.0, 0.0]

    def point(p):
        return [offset[i] + scale * p[i] for i in range(3)]

    def edge(e):
        return [scale * x for x in e]

    lines = []
    shapes = [(1, 40), (40, 1), (7, 53), (48, 27), (33, 33), (64, 16), (20, 45)]
    width, height = rng.choice(shapes)
    fov = rng.uniform(15, 110)
    lines.append("image width %d height %d" % (width, height))
    names = ["m0", "m1", "m2", "m3"]
    for name in names:
        kind = rng.random()
        if kind < 0.55:
            lines.append("material %s diffuse albedo %s" % (name, vec([rng.uniform(0, 0.95) for _ in range(3)])))
        elif kind < 0.75:
            lines.append("material %s mirror reflectance %s" % (name, vec([rng.uniform(0.2, 1) for _ in range(3)])))
        else:
            ior = rng.choice([rng.uniform(1.05, 2.5), rng.uniform(1.05, 2.5), 0.7])
            lines.append("material %s glass ior %.4g" % (name, ior))
    lines.append("material wall diffuse albedo %s" % vec([rng.uniform(0.3, 0.9)] * 3))

    # The floor always; the ceiling and three walls each with probability 0.6.
    walls = [([-1, 0, -1], [2, 0, 0], [0, 0, 2]), ([-1, 2, -1], [0, 0, 2], [2, 0, 0]),
             ([-1, 0, -1], [0, 2, 0], [2, 0, 0]), ([-1, 0, -1], [0, 0, 2], [0, 2, 0]),
             ([1, 0, -1], [0, 2, 0], [0, 0, 2])]
    for i, (corner, e1, e2) in enumerate(walls):
        if i == 0 or rng.random() < 0.6:
            material = "wall" if rng.random() < 0.6 else rng.choice(names)
            lines.append("quad corner %s edge1 %s edge2 %s material %s"
                         % (vec(point(corner)), vec(edge(e1)), vec(edge(e2)), material))
    for _ in range(rng.randint(1, 4)):
        centre = [rng.uniform(-0.7, 0.7), rng.uniform(0.1, 1.5), rng.uniform(-0.7, 0.7)]
        lines.append("sphere center %s radius %.9g material %s"
                     % (vec(point(centre)), scale * rng.uniform(0.05, 0.45), rng.choice(names)))
    # The translator takes triangles of one material.
    triangle_material = rng.choice(names)
    for _ in range(rng.randint(0, 3)):
        c = [rng.uniform(-0.8, 0.8), rng.uniform(0.1, 1.6), rng.uniform(-0.8, 0.8)]
        v = [point([c[j] + rng.uniform(-0.5, 0.5) for j in range(3)]) for _ in range(3)]
        lines.append("triangle v0 %s v1 %s v2 %s material %s"
                     % (vec(v[0]), vec(v[1]), vec(v[2]), triangle_material))
    for i in range(rng.randint(1, 2)):
        a, b = rng.uniform(0.1, 0.8), rng.uniform(0.1, 0.8)
        # The second lamp 0.02 lower: two lamps in one plane could overlap,
        # and which one a ray meets there would be decided by rounding.
        corner = [rng.uniform(-0.9, 0.9 - a), 1.99 - 0.02 * i, rng.uniform(-0.9, 0.9 - b)]
        e1, e2 = [a, 0, 0], [0, 0, b]
        if rng.random() < 0.3:
            e1, e2 = e2, e1  # facing the ceiling, 0.01 above it
        if rng.random() < 0.3:
            # Tilted.  After the swap this makes a parallelogram with
            # nearly parallel edges (seed 31): kept, the format's lamps are
            # parallelograms and Mitsuba's translator takes them.
            e1 = [a, rng.uniform(-0.3, 0.3), 0]
        radiance = [rng.uniform(1, 30) for _ in range(3)]
        lines.append("area_light corner %s edge1 %s edge2 %s radiance %s"
                     % (vec(point(corner)), vec(edge(e1)), vec(edge(e2)), vec(radiance)))
    if rng.random() < 0.5:
        p = [rng.uniform(-0.8, 0.8), rng.uniform(0.3, 1.9), rng.uniform(-0.8, 0.8)]
        intensity = [scale * scale * rng.uniform(0.2, 5) for _ in range(3)]
        lines.append("point_light position %s intensity %s" % (vec(point(p)), vec(intensity)))
    origin = [rng.uniform(-0.9, 0.9), rng.uniform(0.2, 1.8), rng.uniform(1.5, 4.0)]
    target = [rng.uniform(-0.3, 0.3), rng.uniform(0.3, 1.3), rng.uniform(-0.3, 0.3)]
    up = rng.choice([[0, 1, 0], [0.3, 1, 0], [0, 1, 0.2]])
    lines.insert(0, "camera origin %s target %s up %s fov %.4g"
                 % (vec(point(origin)), vec(point(target)), vec(up), fov))
    head = "# random_scene.py %d%s: scale %.3g\n" % (seed, " --unit" if unit else "", scale)
    return head + "\n".join(lines) + "\n"


def main(argv):
    args = [a for a in argv[1:] if a != "--unit"]
    if len(args) != 1 or not args[0].isdigit():
        sys.stderr.write("usage: random_scene.py SEED [--unit]\n")
        return 2
    sys.stdout.write(scene(int(args[0]), "--unit" in argv[1:]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
