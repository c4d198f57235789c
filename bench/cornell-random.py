#!/usr/bin/env python3
"""Writes one Cornell-type box drawn at random from a seed (#67 item 2): the box's sides each
within 10% of the published ones; floor and walls each in 1-3 pieces; the lamp flush in a hole
of the ceiling, recessed above one (with four white sides) or hanging below an unbroken ceiling
(0.1 mm below it as the published data has it, or up to 5 cm); the ceiling round a hole in four
strips (as the published data draws it) or eight cells; the two blocks moved, turned and scaled
on the floor (each at least 2 mm from the walls and 1 cm from the other); quads or triangles;
a patch size from 0.015 to 0.04. One group a surface: floor, ceiling, back, left, right,
short_block, tall_block, recess, light (a wall's pieces share its group).

Usage: cornell-random.py SEED OUT.obj   (writes OUT.obj and OUT.mtl; prints, tab-separated,
the max edge and a line describing the variant)."""
import math
import os
import random
import sys

MTL = """newmtl white
Kd 0.725 0.71 0.68
newmtl red
Kd 0.63 0.065 0.05
newmtl green
Kd 0.14 0.45 0.091
newmtl light
Kd 0.78 0.78 0.78
Ke 40 32 20
"""


class Obj:
    """Faces by group, each face its own vertices (rad-mesh welds them)."""

    def __init__(self, triangles):
        self.triangles = triangles
        self.vertices, self.groups = [], []

    def group(self, name, material):
        self.groups.append((name, material, []))

    def quad(self, corners, normal):
        """A planar quad, wound so its front faces along normal."""
        a, b, c = corners[0], corners[1], corners[2]
        u = [b[k] - a[k] for k in range(3)]
        v = [c[k] - a[k] for k in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        if sum(n[k] * normal[k] for k in range(3)) < 0:
            corners = corners[::-1]
        base = len(self.vertices) + 1
        self.vertices.extend(corners)
        faces = self.groups[-1][2]
        if self.triangles:
            faces.append((base, base + 1, base + 2))
            faces.append((base, base + 2, base + 3))
        else:
            faces.append((base, base + 1, base + 2, base + 3))

    def write(self, path, mtl_name):
        with open(path, "w") as out:
            out.write(f"mtllib {mtl_name}\n")
            for v in self.vertices:
                out.write("v %.6f %.6f %.6f\n" % tuple(v))
            for name, material, faces in self.groups:
                out.write(f"o {name}\nusemtl {material}\n")
                for f in faces:
                    out.write("f " + " ".join(map(str, f)) + "\n")


def cuts(rng, lo, hi):
    """1-3 pieces of [lo, hi]: the cut positions, ends included."""
    k = rng.choice([1, 1, 2, 3])
    inner = sorted(rng.uniform(0.15, 0.85) for _ in range(k - 1))
    while any(b - a < 0.1 for a, b in zip(inner, inner[1:])):
        inner = sorted(rng.uniform(0.15, 0.85) for _ in range(k - 1))
    return [lo] + [lo + t * (hi - lo) for t in inner] + [hi]


def wall(obj, rng, point, u_range, v_range, normal):
    """A rectangle point(u, v) over the ranges, cut in strips along u or v at random."""
    if rng.random() < 0.5:
        for u0, u1 in pairs(cuts(rng, *u_range)):
            obj.quad([point(u0, v_range[0]), point(u1, v_range[0]), point(u1, v_range[1]), point(u0, v_range[1])], normal)
    else:
        for v0, v1 in pairs(cuts(rng, *v_range)):
            obj.quad([point(u_range[0], v0), point(u_range[1], v0), point(u_range[1], v1), point(u_range[0], v1)], normal)


def pairs(xs):
    return list(zip(xs, xs[1:]))


def footprint(cx, cz, sx, sz, angle):
    c, s = math.cos(angle), math.sin(angle)
    return [(cx + c * x - s * z, cz + s * x + c * z) for x, z in ((-sx / 2, -sz / 2), (sx / 2, -sz / 2), (sx / 2, sz / 2), (-sx / 2, sz / 2))]


def separation(p, q):
    """A lower bound on the distance between two convex polygons (separating axes)."""
    best = -math.inf
    for poly in (p, q):
        for (x0, z0), (x1, z1) in zip(poly, poly[1:] + poly[:1]):
            nx, nz = z1 - z0, x0 - x1
            length = math.hypot(nx, nz)
            nx, nz = nx / length, nz / length
            pp = [x * nx + z * nz for x, z in p]
            qq = [x * nx + z * nz for x, z in q]
            best = max(best, min(qq) - max(pp), min(pp) - max(qq))
    return best


def place_blocks(rng, width, depth):
    """Two footprints (short, tall) inside the floor, turned and scaled at random."""
    scale = rng.uniform(0.7, 1.3)
    sizes = [(0.167, 0.167), (0.166, 0.166)]
    while True:
        feet = []
        for sx, sz in sizes:
            fx, fz = scale * sx * rng.uniform(0.85, 1.15), scale * sz * rng.uniform(0.85, 1.15)
            angle = math.radians(rng.uniform(0, 90))
            margin = rng.uniform(0.002, 0.01) if rng.random() < 0.25 else rng.uniform(0.01, 0.08)
            r = math.hypot(fx, fz) / 2
            cx, cz = rng.uniform(r, width - r), rng.uniform(r, depth - r)
            foot = footprint(cx, cz, fx, fz, angle)
            xs, zs = [x for x, _ in foot], [z for _, z in foot]
            shift_x = max(0, margin - min(xs)) - max(0, max(xs) - (width - margin))
            shift_z = max(0, margin - min(zs)) - max(0, max(zs) - (depth - margin))
            feet.append([(x + shift_x, z + shift_z) for x, z in foot])
        if separation(feet[0], feet[1]) >= 0.01:
            return scale, feet


def block(obj, foot, height):
    """Top and four sides of a box standing on the floor (no bottom: it touches the floor)."""
    cx, cz = sum(x for x, _ in foot) / 4, sum(z for _, z in foot) / 4
    obj.quad([(x, height, z) for x, z in foot], (0, 1, 0))
    for (x0, z0), (x1, z1) in pairs(foot + foot[:1]):
        out = ((x0 + x1) / 2 - cx, 0, (z0 + z1) / 2 - cz)
        obj.quad([(x0, 0, z0), (x1, 0, z1), (x1, height, z1), (x0, height, z0)], out)


def ceiling_round_hole(obj, rng, width, depth, height, hole):
    """The ceiling with a rectangular hole, in four strips or eight cells."""
    x0, x1, z0, z1 = hole
    down = (0, -1, 0)
    at = lambda x, z: (x, height, z)
    rect = lambda a, b, c, d: obj.quad([at(a, c), at(b, c), at(b, d), at(a, d)], down)
    if rng.random() < 0.5:
        rect(0, width, 0, z0); rect(0, width, z1, depth)
        rect(0, x0, z0, z1); rect(x1, width, z0, z1)
        return "4 strips"
    xs, zs = [0, x0, x1, width], [0, z0, z1, depth]
    for i in range(3):
        for j in range(3):
            if (i, j) != (1, 1):
                rect(xs[i], xs[i + 1], zs[j], zs[j + 1])
    return "8 cells"


def variant(seed):
    rng = random.Random(seed)
    width, height, depth = (0.556 * rng.uniform(0.9, 1.1), 0.5488 * rng.uniform(0.9, 1.1), 0.5592 * rng.uniform(0.9, 1.1))
    obj = Obj(triangles=rng.random() < 0.3)
    obj.group("floor", "white"); wall(obj, rng, lambda u, v: (u, 0, v), (0, width), (0, depth), (0, 1, 0))
    obj.group("back", "white"); wall(obj, rng, lambda u, v: (u, v, depth), (0, width), (0, height), (0, 0, -1))
    obj.group("left", "red"); wall(obj, rng, lambda u, v: (width, v, u), (0, depth), (0, height), (-1, 0, 0))
    obj.group("right", "green"); wall(obj, rng, lambda u, v: (0, v, u), (0, depth), (0, height), (1, 0, 0))
    lamp_x, lamp_z = 0.13 * rng.uniform(0.8, 1.3), 0.105 * rng.uniform(0.8, 1.3)
    cx, cz = width / 2 + rng.uniform(-0.05, 0.05), depth / 2 + rng.uniform(-0.05, 0.05)
    hole = (cx - lamp_x / 2, cx + lamp_x / 2, cz - lamp_z / 2, cz + lamp_z / 2)
    kind = rng.choice(["flush", "recessed", "hanging"])
    obj.group("ceiling", "white")
    if kind == "hanging":
        wall(obj, rng, lambda u, v: (u, height, v), (0, width), (0, depth), (0, -1, 0))
        drop = 0.0001 if rng.random() < 0.3 else rng.uniform(0.002, 0.05)
        lamp_y, detail = height - drop, f"hanging {1000 * drop:.1f} mm below the ceiling"
    else:
        detail = ceiling_round_hole(obj, rng, width, depth, height, hole)
        lamp_y = height
        if kind == "recessed":
            depth_up = rng.uniform(0.005, 0.05)
            lamp_y = height + depth_up
            obj.group("recess", "white")
            x0, x1, z0, z1 = hole
            for (a, b), inward in ((((x0, z0), (x1, z0)), (0, 0, 1)), (((x1, z0), (x1, z1)), (-1, 0, 0)),
                                   (((x1, z1), (x0, z1)), (0, 0, -1)), (((x0, z1), (x0, z0)), (1, 0, 0))):
                obj.quad([(a[0], height, a[1]), (b[0], height, b[1]), (b[0], lamp_y, b[1]), (a[0], lamp_y, a[1])], inward)
            detail += f", {1000 * depth_up:.0f} mm deep"
        else:
            detail += ", flush"
    obj.group("light", "light")
    x0, x1, z0, z1 = hole
    obj.quad([(x0, lamp_y, z0), (x1, lamp_y, z0), (x1, lamp_y, z1), (x0, lamp_y, z1)], (0, -1, 0))
    scale, feet = place_blocks(rng, width, depth)
    heights = (0.165 * scale * rng.uniform(0.8, 1.2), min(0.33 * scale * rng.uniform(0.8, 1.2), 0.7 * height))
    for name, foot, h in zip(("short_block", "tall_block"), feet, heights):
        obj.group(name, "white"); block(obj, foot, h)
    near = min(min(x, width - x, z, depth - z) for foot in feet for x, z in foot)
    max_edge = rng.uniform(0.015, 0.04)
    description = (f"box {width:.3f} x {height:.3f} x {depth:.3f}; lamp {kind} ({detail}); blocks x{scale:.2f}, "
                   f"{1000 * near:.0f} mm from a wall; {'triangles' if obj.triangles else 'quads'}")
    return obj, max_edge, description


def main():
    if len(sys.argv) != 3 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 1)
    seed, out = int(sys.argv[1]), sys.argv[2]
    obj, max_edge, description = variant(seed)
    mtl = os.path.splitext(out)[0] + ".mtl"
    obj.write(out, os.path.basename(mtl))
    with open(mtl, "w") as f:
        f.write(MTL)
    print(f"{max_edge:.4f}\t{description}")


if __name__ == "__main__":
    main()
