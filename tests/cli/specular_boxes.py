"""Scenes with known answers for light through mirrors and glass (tests/cli/direct_specular.sh).

  specular_boxes.py lum-mirror DIR R   the mirror box lit by a 1000 cd isotropic point luminaire
                                   (layout.csv, iso.ies) where its panel was, no emitting
                                   surface; closed.txt: I cos / r^2 from it and R times the same
                                   from its image.
  specular_boxes.py lum-pane DIR 0|1   the pane box lit by that luminaire 0.1 m under the
                                   ceiling's middle; expected.txt as for `pane`, at the angle to
                                   the luminaire.

  specular_boxes.py mirror DIR R   a closed black 2 m box whose x = 0 wall is a mirror of
                                   reflectance R, lit by a 0.4 m ceiling panel off its middle;
                                   writes DIR/box.obj, box.mtl, pts.txt (96 sensors on the floor
                                   and the wall facing the mirror) and closed.txt, the lux at
                                   each: E (F(panel) + R F(its image)) by Lambert's contour
                                   formula, in rad-gather's lux (179 lm/W of white).
  specular_boxes.py pane DIR 0|1   a closed black 2 m box lit by a 0.2 m panel in the ceiling's
                                   middle, with (1) or without (0) a pane of glass of normal
                                   transmittance 0.8 (index 1.52) across it at y = 1.5;
                                   writes DIR/box.obj, box.mtl, pts.txt (6 floor sensors from
                                   under the panel to the wall) and, with 1, expected.txt:
                                   each sensor's transmission by Radiance's glass at its angle
                                   to the panel's centre.
"""
import math
import sys

SIZE = 2.0
E = 10.0  # the panel's exitance, W/m^2


def write_box(folder, extra, materials):
    vertices, faces = [], []

    def quad(a, b, c, d, material):
        i = len(vertices)
        vertices.extend([a, b, c, d])
        faces.append((material, [i + 4, i + 3, i + 2, i + 1]))  # wound to face inward

    s = SIZE
    quad((0, 0, 0), (s, 0, 0), (s, 0, s), (0, 0, s), "black")
    quad((0, s, 0), (0, s, s), (s, s, s), (s, s, 0), "black")
    quad((0, 0, 0), (0, 0, s), (0, s, s), (0, s, 0), extra.get("x0", "black"))
    quad((s, 0, 0), (s, s, 0), (s, s, s), (s, 0, s), "black")
    quad((0, 0, 0), (0, s, 0), (s, s, 0), (s, 0, 0), "black")
    quad((0, 0, s), (s, 0, s), (s, s, s), (0, s, s), "black")
    for corners, material in extra["quads"]:
        quad(*corners, material)
    with open(folder + "/box.obj", "w") as f:
        f.write("mtllib box.mtl\n")
        for v in vertices:
            f.write("v %.9g %.9g %.9g\n" % v)
        for material, idx in faces:
            f.write("usemtl %s\nf %s\n" % (material, " ".join(map(str, idx))))
    with open(folder + "/box.mtl", "w") as f:
        f.write("newmtl black\nKd 0 0 0\nnewmtl lamp\nKd 0 0 0\nKe %g %g %g\n" % (E, E, E))
        f.write(materials)


def panel(cx, cz, half, y):
    """Corners of a square panel facing down, as written (inward winding applied by quad)."""
    return [(cx - half, y, cz - half), (cx - half, y, cz + half), (cx + half, y, cz + half),
            (cx + half, y, cz - half)]


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    length = math.sqrt(dot(a, a))
    return [x / length for x in a]


def form_factor(point, normal, polygon):
    """Point to polygon (Lambert): the polygon wholly in front of the point."""
    total = 0.0
    for i in range(len(polygon)):
        a, b = unit(sub(polygon[i], point)), unit(sub(polygon[(i + 1) % len(polygon)], point))
        angle = math.acos(max(-1.0, min(1.0, dot(a, b))))
        c = cross(a, b)
        length = math.sqrt(dot(c, c))
        if length > 0:
            total += angle * dot(normal, [x / length for x in c])
    return abs(total) / (2 * math.pi)


def pane_transmission(normal_transmittance, ior, cos_incident):
    """Radiance's glass: both faces and the light between them, both polarisations."""
    r = ((ior - 1) / (ior + 1)) ** 2
    a = (1 - r) ** 2
    t = (-a + math.sqrt(a * a + 4 * normal_transmittance ** 2 * r * r)) / (
        2 * normal_transmittance * r * r)
    cos_t = math.sqrt(1 - (1 - cos_incident ** 2) / ior ** 2)
    path = t ** (1 / cos_t)
    out = 0.0
    for rr in (((cos_incident - ior * cos_t) / (cos_incident + ior * cos_t)) ** 2,
               ((ior * cos_incident - cos_t) / (ior * cos_incident + cos_t)) ** 2):
        out += 0.5 * (1 - rr) ** 2 * path / (1 - rr * rr * path * path)
    return out


ISO_IES = ("IESNA:LM-63-2002\n[TEST] isotropic 1000 cd\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n"
           "1 1 0\n0 180\n0\n1000 1000\n")


def write_luminaire(folder, x, y, z):
    with open(folder + "/iso.ies", "w") as f:
        f.write(ISO_IES)
    with open(folder + "/layout.csv", "w") as f:
        f.write("name,photometry,x,y,z\nbulb,iso.ies,%g,%g,%g\n" % (x, y, z))


MIRROR_GLASS = "newmtl mirror\nillum 3\nKd 0 0 0\nKs %g %g %g\n"
PANE_GLASS = "newmtl glass\nillum 4\nKd 0 0 0\nTf 0.8 0.8 0.8\nNi 1.52\n"
PANE = [(0, 1.5, 0), (0, 1.5, SIZE), (SIZE, 1.5, SIZE), (SIZE, 1.5, 0)]


def write_lines(path, lines):
    with open(path, "w") as f:
        f.writelines(line + "\n" for line in lines)


def mirror_box_sensors(folder):
    """64 floor sensors and 32 on the wall facing the mirror, written to pts.txt."""
    sensors = [((i + 0.5) / 4, 0.0, (j + 0.5) / 4, 0, 1, 0) for i in range(8) for j in range(8)]
    sensors += [(SIZE, 0.25 + i * 0.45, (j + 0.5) / 4, -1, 0, 0) for i in range(4)
                for j in range(8)]
    write_lines(folder + "/pts.txt", ["%g %g %g %g %g %g" % p for p in sensors])
    return sensors


def lum_mirror(folder, reflectance):
    at = (1.4, 1.8, 1.0)
    write_box(folder, {"x0": "mirror", "quads": []}, MIRROR_GLASS % ((reflectance,) * 3))
    write_luminaire(folder, *at)
    image = (-at[0], at[1], at[2])

    def point_lux(p, n, source):
        d = sub(p, source)
        r2 = dot(d, d)
        return max(0.0, -dot(d, n)) / math.sqrt(r2) * 1000 / r2

    write_lines(folder + "/closed.txt",
                ["%.9g" % (point_lux(p[:3], p[3:], at) + reflectance * point_lux(p[:3], p[3:], image))
                 for p in mirror_box_sensors(folder)])


def mirror(folder, reflectance):
    lamp = panel(1.4, 1.0, 0.2, SIZE - 0.001)
    write_box(folder, {"x0": "mirror", "quads": [(lamp, "lamp")]},
              MIRROR_GLASS % ((reflectance,) * 3))
    image = [(-x, y, z) for (x, y, z) in lamp]
    write_lines(folder + "/closed.txt",
                ["%.9g" % (179 * E * (form_factor(p[:3], p[3:], lamp) +
                                      reflectance * form_factor(p[:3], p[3:], image)))
                 for p in mirror_box_sensors(folder)])


def pane_box(folder, with_pane, quads, source_y):
    """The black box, with the pane when asked, 6 floor sensors from x = 1 (under a source at
    height source_y over x = 1) to the wall, and the pane's transmission toward the source."""
    write_box(folder, {"quads": quads + ([(PANE, "glass")] if with_pane else [])}, PANE_GLASS)
    xs = [1.0, 1.2, 1.4, 1.6, 1.8, 1.95]
    write_lines(folder + "/pts.txt", ["%g 0 1 0 1 0" % x for x in xs])
    if with_pane:
        write_lines(folder + "/expected.txt",
                    ["%.9g" % pane_transmission(0.8, 1.52, source_y / math.hypot(source_y, x - 1.0))
                     for x in xs])


def lum_pane(folder, with_pane):
    pane_box(folder, with_pane, [], 1.9)
    write_luminaire(folder, 1.0, 1.9, 1.0)


def pane(folder, with_pane):
    lamp_y = SIZE - 0.001
    pane_box(folder, with_pane, [(panel(1.0, 1.0, 0.1, lamp_y), "lamp")], lamp_y)


if __name__ == "__main__":
    kind, folder, value = sys.argv[1], sys.argv[2], sys.argv[3]
    if kind == "mirror":
        mirror(folder, float(value))
    elif kind == "pane":
        pane(folder, value == "1")
    elif kind == "lum-mirror":
        lum_mirror(folder, float(value))
    else:
        lum_pane(folder, value == "1")
