#!/usr/bin/env python3
"""A side-lit room for daylight: 4 m wide (x), 3 m high (y), 6 m deep (z), its window in the
south wall (+Z; true north is -Z). Reflectances 20/50/70 (floor, walls, ceiling), LM-83's.
Writes daylight-room.obj (the window an opening) and daylight-room-glazed.obj (the same, glazed:
a pane of 0.7 transmittance at normal incidence)."""
import os

W, H, D = 4.0, 3.0, 6.0
WIN_X, WIN_Y = (0.8, 3.2), (0.9, 2.4)


def quad(corners, normal):
    """The corners wound counter-clockwise seen from the side `normal` points to."""
    a, b, c = corners[0], corners[1], corners[2]
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    return corners if sum(n[k] * normal[k] for k in range(3)) > 0 else corners[::-1]


def rect_z(z, x0, x1, y0, y1, normal):
    return quad([(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)], normal)


def faces(glazed):
    out = [
        ("floor", "floor", quad([(0, 0, 0), (W, 0, 0), (W, 0, D), (0, 0, D)], (0, 1, 0))),
        ("ceiling", "ceiling", quad([(0, H, 0), (W, H, 0), (W, H, D), (0, H, D)], (0, -1, 0))),
        ("west", "wall", quad([(0, 0, 0), (0, H, 0), (0, H, D), (0, 0, D)], (1, 0, 0))),
        ("east", "wall", quad([(W, 0, 0), (W, H, 0), (W, H, D), (W, 0, D)], (-1, 0, 0))),
        ("north", "wall", rect_z(0, 0, W, 0, H, (0, 0, 1))),
    ]
    south = (0, 0, -1)
    out += [
        ("south", "wall", rect_z(D, 0, W, 0, WIN_Y[0], south)),
        ("south", "wall", rect_z(D, 0, W, WIN_Y[1], H, south)),
        ("south", "wall", rect_z(D, 0, WIN_X[0], WIN_Y[0], WIN_Y[1], south)),
        ("south", "wall", rect_z(D, WIN_X[1], W, WIN_Y[0], WIN_Y[1], south)),
    ]
    if glazed:
        out.append(("window", "glass", rect_z(D, WIN_X[0], WIN_X[1], WIN_Y[0], WIN_Y[1], south)))
    return out


def write(name, glazed):
    lines = ["# " + name + ": written by generate.py", "mtllib daylight-room.mtl"]
    count = 0
    for group, material, corners in faces(glazed):
        lines.append("g " + group)
        lines.append("usemtl " + material)
        for x, y, z in corners:
            lines.append("v %g %g %g" % (x, y, z))
        lines.append("f %d %d %d %d" % (count + 1, count + 2, count + 3, count + 4))
        count += 4
    with open(name, "w") as f:
        f.write("\n".join(lines) + "\n")


MTL = """# LM-83's reflectances: floor 20%, walls 50%, ceiling 70%; glass of 0.7 at normal incidence
newmtl floor
Kd 0.2 0.2 0.2

newmtl wall
Kd 0.5 0.5 0.5

newmtl ceiling
Kd 0.7 0.7 0.7

newmtl glass
illum 4
Kd 0 0 0
Tf 0.7 0.7 0.7
"""

if __name__ == "__main__":
    os.chdir(os.path.dirname(os.path.abspath(__file__)))
    write("daylight-room.obj", False)
    write("daylight-room-glazed.obj", True)
    with open("daylight-room.mtl", "w") as f:
        f.write(MTL)
