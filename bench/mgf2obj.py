#!/usr/bin/env python3
"""Converts the subset of MGF (the Materials and Geometry Format of RenderPark and
rpkCpp) that their test scenes use into OBJ + MTL for rad-mesh, so bench/ can run the chain
on the same geometry as rpkCpp's Galerkin radiosity (bench/corridor).

Handled: c (cxy chromaticity), m (c, rd, ed; rs, ts and sides are ignored: radiosity is
diffuse), v (p, n), o (groups), f, xf (-t, -rx, -ry, -rz, -s, -a arrays, nested), sph, cyl,
torus (tessellated with QCDIVS divisions a quarter circle, as rpk's -nqcdivs). Colours become
linear sRGB from CIE xy at the reflectance's luminance; emission (lm/m^2) is divided by
EMISSION_SCALE into W/m^2-like units (only ratios matter to the comparison).
Usage: bench/mgf2obj.py SCENE.mgf OUT.obj [--qcdivs 18]"""
import math
import sys

EMISSION_SCALE = 1000.0


def xy_to_rgb(x, y, luminance):
    """Linear sRGB of CIE xy at `luminance`, scaled so that the equal-energy white (1/3,
    1/3) is grey: MGF's neutral is E, not D65."""
    rgb = xyz_to_rgb(x, y, luminance)
    white = xyz_to_rgb(1 / 3, 1 / 3, 1.0)
    return tuple(c / w for c, w in zip(rgb, white))


def xyz_to_rgb(x, y, luminance):
    if y <= 0:
        return (luminance,) * 3
    X, Z = x * luminance / y, (1 - x - y) * luminance / y
    Y = luminance
    r = 3.2406 * X - 1.5372 * Y - 0.4986 * Z
    g = -0.9689 * X + 1.8758 * Y + 0.0415 * Z
    b = 0.0557 * X - 0.2040 * Y + 1.0570 * Z
    return tuple(max(0.0, c) for c in (r, g, b))


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def identity():
    return [[float(i == j) for j in range(4)] for i in range(4)]


def rotation(axis, degrees):
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    m = identity()
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m[i][i], m[i][j], m[j][i], m[j][j] = c, -s, s, c
    return m


def parse_transform(args):
    """The transforms of one xf line: a list of (count, matrix) steps. A step of count 0 is
    applied once; an array step (-a N) repeats its matrix 0..N-1 times."""
    steps, current, count, k = [], identity(), 0, 0
    def flush():
        nonlocal current, count
        steps.append((count, current))
        current, count = identity(), 0
    while k < len(args):
        a = args[k]
        if a == "-t":
            m = identity()
            for i in range(3):
                m[i][3] = float(args[k + 1 + i])
            current, k = matmul(m, current), k + 4
        elif a in ("-rx", "-ry", "-rz"):
            current, k = matmul(rotation("xyz".index(a[2]), float(args[k + 1])), current), k + 2
        elif a == "-s":
            s = float(args[k + 1])
            m = identity()
            for i in range(3):
                m[i][i] = s
            current, k = matmul(m, current), k + 2
        elif a == "-a":
            flush()
            count, k = int(args[k + 1]), k + 2
        else:
            sys.exit(f"mgf2obj: transform {a} is not handled")
    flush()
    return steps


def expand(steps):
    """Every instance matrix of one xf line's steps (later steps apply after earlier ones)."""
    out = [identity()]
    for count, m in steps:
        if count == 0:
            out = [matmul(m, o) for o in out]
            continue
        powers, p = [], identity()
        for _ in range(count):
            powers.append(p)
            p = matmul(m, p)
        out = [matmul(q, o) for o in out for q in powers]
    return out


def apply(m, p, w=1.0):
    return tuple(sum(m[i][j] * c for j, c in enumerate((*p, w))) for i in range(3))


class Converter:
    def __init__(self, qcdivs):
        self.qcdivs = qcdivs
        self.colours, self.materials, self.vertices = {}, {}, {}
        self.material = None
        self.instances = [identity()]  # the transforms in effect: every instance
        self.stack = []
        self.groups = []
        self.out_v, self.faces = [], []  # faces: (group, material, [indices])

    def emit(self, points):
        for m in self.instances:
            start = len(self.out_v)
            self.out_v.extend(apply(m, p) for p in points)
            yield [start + i for i in range(len(points))]

    def face(self, points):
        for indices in self.emit(points):
            self.faces.append(("/".join(self.groups) or "default", self.material, indices))

    def quads(self, grid):
        """Faces of a grid of points rows[i][j], wound as given."""
        for i in range(len(grid) - 1):
            for j in range(len(grid[i]) - 1):
                self.face([grid[i][j], grid[i][j + 1], grid[i + 1][j + 1], grid[i + 1][j]])

    def frame(self, axis):
        n = [c / math.sqrt(sum(x * x for x in axis)) for c in axis]
        a = (1, 0, 0) if abs(n[0]) < 0.9 else (0, 1, 0)
        u = [a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]]
        lu = math.sqrt(sum(x * x for x in u))
        u = [x / lu for x in u]
        v = [n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]]
        return n, u, v

    def cylinder(self, p0, radius, p1):
        n, u, v = self.frame([b - a for a, b in zip(p0, p1)])
        around = 4 * self.qcdivs
        ring = lambda c: [tuple(c[i] + radius * (math.cos(t) * u[i] + math.sin(t) * v[i]) for i in range(3))
                          for t in (2 * math.pi * k / around for k in range(around + 1))]
        self.quads([ring(p0), ring(p1)])  # outward for a positive radius

    def sphere(self, c, radius):
        rows = 2 * self.qcdivs
        around = 4 * self.qcdivs
        grid = []
        for i in range(rows + 1):
            phi = math.pi * i / rows - math.pi / 2
            grid.append([(c[0] + radius * math.cos(phi) * math.cos(t), c[1] + radius * math.cos(phi) * math.sin(t),
                          c[2] + radius * math.sin(phi))
                         for t in (2 * math.pi * k / around for k in range(around + 1))])
        self.quads(grid)

    def torus(self, c, normal, rmin, rmax):
        n, u, v = self.frame(normal)
        mid, tube = (rmin + rmax) / 2, (rmax - rmin) / 2
        around = 4 * self.qcdivs
        grid = []
        for i in range(around + 1):
            t = 2 * math.pi * i / around
            d = [math.cos(t) * u[k] + math.sin(t) * v[k] for k in range(3)]
            grid.append([tuple(c[k] + (mid + tube * math.cos(s)) * d[k] + tube * math.sin(s) * n[k] for k in range(3))
                         for s in (2 * math.pi * j / around for j in range(around + 1))])
        # Tube angle first: wound so that the normals point out of the tube.
        self.quads([list(row) for row in zip(*grid)])

    def run(self, lines):
        """MGF is a stream of entities: c, m and v with "=" open a definition that the
        following cxy, rd, ed, p and n lines fill in (indentation is only for the eye)."""
        colour_name, colour = None, [1 / 3, 1 / 3]
        vertex = None
        for line in lines:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            key = words[0]
            if key == "c":
                if len(words) == 1:
                    colour_name, colour = None, [1 / 3, 1 / 3]
                elif len(words) == 3 and words[2] == "=":
                    colour_name, colour = words[1], [1 / 3, 1 / 3]
                    self.colours[colour_name] = colour
                else:
                    colour_name, colour = words[1], self.colours[words[1]]
            elif key == "cxy":
                colour[:] = [float(words[1]), float(words[2])]
            elif key == "m":
                self.material = words[1] if len(words) > 1 else "default"
                if len(words) == 3 and words[2] == "=" or self.material not in self.materials:
                    self.materials[self.material] = {"rd": (0.0, 0.0, 0.0), "ed": (0.0, 0.0, 0.0)}
            elif key == "rd":
                self.materials[self.material]["rd"] = xy_to_rgb(*colour, float(words[1]))
            elif key == "ed":
                e = float(words[1]) / EMISSION_SCALE
                self.materials[self.material]["ed"] = tuple(c * e for c in xy_to_rgb(*colour, 1.0))
            elif key in ("rs", "ts", "td", "sides", "ir"):
                continue  # specular, transmission, sidedness: not diffuse radiosity
            elif key == "v":
                vertex = self.vertices.setdefault(words[1], [None, None])
                if len(words) == 3 and words[2] == "=":
                    vertex[0] = vertex[1] = None
            elif key == "p":
                vertex[0] = tuple(map(float, words[1:4]))
            elif key == "n":
                vertex[1] = tuple(map(float, words[1:4]))
            elif key == "o":
                if len(words) > 1:
                    self.groups.append(words[1])
                elif self.groups:
                    self.groups.pop()
            elif key == "xf":
                if len(words) == 1:
                    self.instances = self.stack.pop()
                else:
                    self.stack.append(self.instances)
                    # Inner transforms apply first: each instance of this line, then the outer.
                    self.instances = [matmul(outer, inner) for outer in self.instances
                                      for inner in expand(parse_transform(words[1:]))]
            elif key == "f":
                self.face([self.vertices[w][0] for w in words[1:]])
            elif key == "cyl":
                self.cylinder(self.vertices[words[1]][0], float(words[2]), self.vertices[words[3]][0])
            elif key == "sph":
                self.sphere(self.vertices[words[1]][0], float(words[2]))
            elif key == "torus":
                p, n = self.vertices[words[1]]
                self.torus(p, n, float(words[2]), float(words[3]))
            else:
                sys.exit(f"mgf2obj: entity {key} is not handled")

    def write(self, obj_path):
        mtl_path = obj_path.rsplit(".", 1)[0] + ".mtl"
        with open(mtl_path, "w") as mtl:
            for name, m in self.materials.items():
                rd, ed = m["rd"], m["ed"]
                rd = tuple(min(0.999, c) for c in rd)  # a reflectance stays below 1
                mtl.write(f"newmtl {name}\nKd {rd[0]:.6f} {rd[1]:.6f} {rd[2]:.6f}\n")
                if any(ed):
                    mtl.write(f"Ke {ed[0]:.6f} {ed[1]:.6f} {ed[2]:.6f}\n")
        with open(obj_path, "w") as obj:
            obj.write(f"# converted by bench/mgf2obj.py (qcdivs {self.qcdivs})\n")
            obj.write(f"mtllib {mtl_path.rsplit('/', 1)[-1]}\n")
            for p in self.out_v:
                obj.write(f"v {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n")
            group = material = None
            for g, m, indices in self.faces:
                if g != group:
                    obj.write(f"g {g}\n")
                    group = g
                if m != material:
                    obj.write(f"usemtl {m}\n")
                    material = m
                obj.write("f " + " ".join(str(i + 1) for i in indices) + "\n")


def main():
    args = sys.argv[1:]
    qcdivs = 18
    if "--qcdivs" in args:
        i = args.index("--qcdivs")
        qcdivs = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    converter = Converter(qcdivs)
    converter.run(open(args[0]).read().splitlines())
    converter.write(args[1])
    print(f"mgf2obj: {len(converter.out_v)} vertices, {len(converter.faces)} faces, "
          f"{len(converter.materials)} materials", file=sys.stderr)


if __name__ == "__main__":
    main()
