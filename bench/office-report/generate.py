#!/usr/bin/env python3
"""A designer's office for the report check (#68): 7.2 x 5.4 x 3 m (x, z; y up, metres), a
glazed wall at z = 0 (sill 0.9 m, head 2.7 m), a door in the wall x = 0 standing open into the
room, four desks (1.6 x 0.8 m, 0.72 m high), a cabinet against the wall x = 7.2; six linear
luminaires (EULUMDAT, 1.48 m) in two rows and two downlights (IES) by the door.

Writes office.obj, office.mtl, layout.csv and calc.csv into the folder given (default: .)."""
import os
import sys

W, H, D = 7.2, 3.0, 5.4
out = sys.argv[1] if len(sys.argv) > 1 else "."
vertices, faces = [], []


def quad(material, a, b, c, d):
    """A quad a-b-c-d, counter-clockwise seen from its front."""
    i = len(vertices)
    vertices.extend([a, b, c, d])
    faces.append((material, [i + 1, i + 2, i + 3, i + 4]))


def box(material, x0, y0, z0, x1, y1, z1, bottom=False):
    """A box's outside faces (its bottom only when asked: it stands on the floor)."""
    quad(material, (x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))  # top
    quad(material, (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))  # +z
    quad(material, (x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0))  # -z
    quad(material, (x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1))  # +x
    quad(material, (x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))  # -x
    if bottom:
        quad(material, (x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))


# The room, faces toward the inside.
quad("floor", (0, 0, 0), (0, 0, D), (W, 0, D), (W, 0, 0))
quad("ceiling", (0, H, 0), (W, H, 0), (W, H, D), (0, H, D))
quad("wall", (0, 0, D), (0, H, D), (W, H, D), (W, 0, D))  # back wall z = D
quad("wall", (W, 0, 0), (W, 0, D), (W, H, D), (W, H, 0))  # x = W (cabinet side)
# The wall x = 0 with a door opening z 0.6..1.5, y 0..2.1.
dz0, dz1, dh = 0.6, 1.5, 2.1
quad("wall", (0, 0, 0), (0, H, 0), (0, H, dz0), (0, 0, dz0))
quad("wall", (0, 0, dz1), (0, H, dz1), (0, H, D), (0, 0, D))
quad("wall", (0, dh, dz0), (0, H, dz0), (0, H, dz1), (0, dh, dz1))
# The door leaf standing open at 90 degrees into the room, hinged at z = 1.5, both sides drawn.
quad("door", (0.9, 0, dz1), (0.0, 0, dz1), (0.0, dh, dz1), (0.9, dh, dz1))  # faces -z
quad("door", (0.0, 0, dz1 + 0.04), (0.9, 0, dz1 + 0.04), (0.9, dh, dz1 + 0.04), (0.0, dh, dz1 + 0.04))
# The glazed wall z = 0: the window x 0.6..6.6, y 0.9..2.7, glass in it.
wx0, wx1, wy0, wy1 = 0.6, 6.6, 0.9, 2.7
quad("wall", (W, 0, 0), (W, H, 0), (wx1, H, 0), (wx1, 0, 0))
quad("wall", (wx0, 0, 0), (wx0, H, 0), (0, H, 0), (0, 0, 0))
quad("wall", (wx1, 0, 0), (wx1, wy0, 0), (wx0, wy0, 0), (wx0, 0, 0))
quad("wall", (wx1, wy1, 0), (wx1, H, 0), (wx0, H, 0), (wx0, wy1, 0))
quad("glass", (wx1, wy0, 0), (wx1, wy1, 0), (wx0, wy1, 0), (wx0, wy0, 0))
# Four desks in two rows facing the window, and a cabinet against x = W.
for x0 in (1.4, 3.9):
    for z0 in (1.6, 3.4):
        box("desk", x0, 0, z0, x0 + 1.6, 0.72, z0 + 0.8)
box("cabinet", W - 0.45, 0, 3.6, W, 2.0, 4.8)

with open(os.path.join(out, "office.obj"), "w") as f:
    f.write("# A designer's office for the report check (bench/office-report/generate.py)\n")
    f.write("mtllib office.mtl\n")
    f.writelines("v %g %g %g\n" % v for v in vertices)
    current = None
    for material, face in faces:
        if material != current:
            f.write("usemtl %s\n" % material)
            current = material
        f.write("f %s\n" % " ".join(map(str, face)))
with open(os.path.join(out, "office.mtl"), "w") as f:
    f.write("newmtl floor\nKd 0.2 0.2 0.2\nnewmtl wall\nKd 0.5 0.5 0.5\n"
            "newmtl ceiling\nKd 0.7 0.7 0.7\nnewmtl desk\nKd 0.45 0.35 0.25\n"
            "newmtl cabinet\nKd 0.5 0.5 0.45\nnewmtl door\nKd 0.3 0.22 0.15\n"
            "newmtl glass\nKd 0 0 0\nKs 0.08 0.08 0.08\nTf 0.8 0.8 0.8\nd 0.2\nillum 4\n")
with open(os.path.join(out, "layout.csv"), "w") as f:
    f.write("name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,maintenance,group\n")
    k = 0
    for z in (1.8, 3.6):
        for x in (1.2, 3.6, 6.0):
            k += 1
            f.write("T%d,linear.ldt,%g,2.95,%g,,,,0,0.8,rows\n" % (k, x, z))
    f.write("D1,downlight.ies,0.9,3,0.45,,,,,0.8,door\n")
    f.write("D2,downlight.ies,0.9,3,2.2,,,,,0.8,door\n")
with open(os.path.join(out, "calc.csv"), "w") as f:
    f.write("name,kind,x,y,z,ux,uy,uz,vx,vy,vz,spacing,border,Em,U0,Emin,UGRL,angle\n")
    f.write("work plane,workplane,0,0.8,%g,%g,0,0,0,0,%g,,,500,0.6,,,\n" % (D, W, -D))
    for i, (x0, z0) in enumerate(((1.4, 1.6), (3.9, 1.6), (1.4, 3.4), (3.9, 3.4))):
        f.write("desk %d,task,%g,0.721,%g,1.6,0,0,0,0,-0.8,0.1,,500,0.6,,,\n" % (i + 1, x0, z0 + 0.8))
    f.write("back wall,wall,%g,0,%g,%g,0,0,0,3,0,,,,,,,\n" % (W, D - 0.001, -W))
    f.write("ceiling,ceiling,0,%g,0,%g,0,0,0,0,%g,,,,,,,\n" % (H - 0.001, W, D))
    f.write("people,cylindrical,0,1.2,%g,%g,0,0,0,0,%g,,,150,,,,\n" % (D, W, -D))
    f.write("desk 1 chair,observer,2.2,1.2,3.0,0,0,-1,,,,,,,,,19,\n")
    f.write("from the door,camera,0.5,1.6,1.0,1,-0.15,0.6,,,,,,,,,,80\n")
