"""Scenes for tests/cli/surfaces.sh: one room, its back wall drawn in several ways.

python3 surface_scenes.py KIND OUT.obj
  quad      the back wall as one quad
  two       as two triangles
  fan       as a fan of 64 thin triangles from one corner
  tjoined   as a quad on the left half and two on the right half, one above the other: the
            corner they share lies on the left quad's side (a T-junction, no shared corner)
  twice     as one quad facing in and a copy facing out (a wrongly facing copy)
  sheet     the quad wall, and a sheet in the middle of the room drawn once each way
  outward   every face of the room facing out, with a box on the floor and a small box on it
            (their faces out, rightly)
  inward    the same room facing in, as it should
  beam      the inward room with a beam through its right wall, sticking out by 1
  holed     the back wall with a 16-sided window, as a fan of triangles around it, and a
            shelf 6 cm deep along the left wall (a region narrower than a cell)
  tiles     the floor's first 30 cm from the back wall as a row of tiles (their own material)
            whose joints are 5 mm apart in pairs: points a wall's band cannot mesh well
  frame     a picture frame of 2 cm strips around a 1 m opening, standing in the room (one
            region, thin everywhere though its rectangle is a metre wide)
  posts     two posts standing on the floor, 1.5 cm and 20 cm square (their footprints are
            holes in the floor once imprinted)
  baseboard a block 1 m long, 1 cm deep and 10 cm tall standing on the floor against the back
            wall (short steps in the floor's outline at its ends)
  rug       a rug (its own material) lying in the floor's plane, 2 m x 1.5 m, whose far side
            steps by 3 cm halfway along: a step where nothing rises, in both regions' outlines
  neck      a strip 3 cm high and 2 m long standing in the room, 2 cm high for 20 cm in its
            middle (a notch from its top): a region a little over a tenth of a 25 cm cell
            wide, under a tenth at its neck
  columns   round columns of 40 sides (5 cm across, and 12 cm) standing on the floor, their tops
            drawn as fans from their centres: outlines of short pieces round a region a fifth
            of a 25 cm cell across, and a hole in the floor round each
python3 surface_scenes.py gltf CORNELL.obj OUT.gltf
  the OBJ's faces as glTF triangles, one mesh per material (Kd as base colour, Ke as emission)
"""
import base64
import math
import json
import struct
import sys

W, H, D = 4.0, 2.5, 3.0  # room: x 0..W, y 0..H, z 0..D; the back wall is z = 0


def holed_wall(v, faces):
    """The back wall around a 16-gon window: triangles from each window edge to the points of
    the wall's outline (the corners, and the points at the window corners' angles)."""
    cx, cy, r, n = 2.0, 1.25, 0.5, 16
    angles = [2 * math.pi * (k + 0.5) / n for k in range(n)]

    def outer(a):  # where the ray from the centre at angle a meets the wall's outline
        dx, dy = math.cos(a), math.sin(a)
        t = min((W - cx) / dx if dx > 0 else -cx / dx if dx < 0 else 1e9,
                (H - cy) / dy if dy > 0 else -cy / dy if dy < 0 else 1e9)
        return (cx + t * dx, cy + t * dy, 0)

    corners = [(W, H), (0, H), (0, 0), (W, 0)]
    corner_angles = [math.atan2(y - cy, x - cx) % (2 * math.pi) for x, y in corners]
    base = len(v)
    v.extend((cx + r * math.cos(a), cy + r * math.sin(a), 0) for a in angles)  # the window
    for k in range(n):
        a0, a1 = angles[k], angles[(k + 1) % n] + (2 * math.pi if k == n - 1 else 0)
        chain = [outer(a0)] + [(x, y, 0) for (x, y), a in zip(corners, corner_angles)
                               if a0 < a < a1 or a0 < a + 2 * math.pi < a1] + [outer(a1)]
        ids = []
        for p in chain:
            v.append(p)
            ids.append(len(v))
        for q in range(len(ids) - 1):
            faces.append(("back", [base + 1 + k, ids[q], ids[q + 1]]))
        faces.append(("back", [base + 1 + k, ids[-1], base + 1 + (k + 1) % n]))


def block(quad, x0, x1, y0, y1, z0, z1):
    """A block standing on y = y0: its top and four sides, facing out."""
    quad("box", (x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))
    quad("box", (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0))
    quad("box", (x1, y0, z1), (x1, y1, z1), (x0, y1, z1), (x0, y0, z1))
    quad("box", (x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (x0, y0, z0))
    quad("box", (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))


def column(v, faces, cx, cz, radius, height, sides):
    """A round column standing on the floor: its sides and its top as a fan from its centre."""
    base = len(v)
    for k in range(sides):
        a = 2 * math.pi * k / sides
        x, z = cx + radius * math.cos(a), cz - radius * math.sin(a)
        v.extend([(x, 0, z), (x, height, z)])
    v.append((cx, height, cz))
    for k in range(sides):
        b0, t0 = base + 1 + 2 * k, base + 2 + 2 * k
        b1, t1 = base + 1 + 2 * ((k + 1) % sides), base + 2 + 2 * ((k + 1) % sides)
        faces.append(("column", [b0, b1, t1, t0]))
        faces.append(("column", [len(v), t0, t1]))


def room(kind):
    v, faces = [], []  # faces: (material, [vertex indices from 1])

    def quad(mat, *corners):
        base = len(v)
        v.extend(corners)
        faces.append((mat, [base + 1, base + 2, base + 3, base + 4]))

    def reversed_quad(mat, *corners):
        quad(mat, *reversed(corners))

    add = reversed_quad if kind == "outward" else quad
    if kind == "tiles":
        add("floor", (0, 0, 0.3), (0, 0, D), (W, 0, D), (W, 0, 0.3))
        joints = sorted({0.0, W} | {round(x + d, 6) for x in (0.5, 1.3, 2.1, 2.9, 3.5) for d in (0, 0.005)})
        for k, (x0, x1) in enumerate(zip(joints, joints[1:])):
            add("tile" + "ab"[k % 2], (x0, 0, 0), (x0, 0, 0.3), (x1, 0, 0.3), (x1, 0, 0))
    elif kind == "rug":  # the floor around the rug as five rectangles (x0, x1, z0, z1)
        step = 2.53
        for x0, x1, z0, z1 in ((0, 1, 0, D), (3, W, 0, D), (1, 3, 0, 1), (1, 2, step, D), (2, 3, 2.5, D)):
            add("floor", (x0, 0, z0), (x0, 0, z1), (x1, 0, z1), (x1, 0, z0))
        add("rug", (1, 0, 1), (1, 0, 2.5), (3, 0, 2.5), (3, 0, 1))
        add("rug", (1, 0, 2.5), (1, 0, step), (2, 0, step), (2, 0, 2.5))
    else:
        add("floor", (0, 0, 0), (0, 0, D), (W, 0, D), (W, 0, 0))
    add("ceiling", (0, H, 0), (W, H, 0), (W, H, D), (0, H, D))
    add("left", (0, 0, 0), (0, H, 0), (0, H, D), (0, 0, D))
    add("right", (W, 0, 0), (W, 0, D), (W, H, D), (W, H, 0))
    add("front", (0, 0, D), (0, H, D), (W, H, D), (W, 0, D))
    # The lamp: a square just below the ceiling, facing down.
    quad("light", (1.5, H - 0.01, 1.0), (2.5, H - 0.01, 1.0), (2.5, H - 0.01, 2.0), (1.5, H - 0.01, 2.0))
    back = [(0, 0, 0), (W, 0, 0), (W, H, 0), (0, H, 0)]  # facing +z, into the room
    if kind == "two":
        base = len(v)
        v.extend(back)
        faces.append(("back", [base + 1, base + 2, base + 3]))
        faces.append(("back", [base + 1, base + 3, base + 4]))
    elif kind == "fan":
        # From corner (0,0): 32 points up the right side, 32 along the top (right to left).
        rim = [(W, H * k / 32, 0) for k in range(33)] + [(W - W * k / 32, H, 0) for k in range(1, 33)]
        base = len(v)
        v.append((0, 0, 0))
        v.extend(rim)
        for k in range(len(rim) - 1):
            faces.append(("back", [base + 1, base + 2 + k, base + 3 + k]))
    elif kind == "tjoined":
        quad("back", (0, 0, 0), (W / 2, 0, 0), (W / 2, H, 0), (0, H, 0))
        quad("back", (W / 2, 0, 0), (W, 0, 0), (W, H / 2, 0), (W / 2, H / 2, 0))
        quad("back", (W / 2, H / 2, 0), (W, H / 2, 0), (W, H, 0), (W / 2, H, 0))
    elif kind == "holed":
        holed_wall(v, faces)
        quad("shelf", (0, 1, 1), (0, 1, 1.06), (3, 1, 1.06), (3, 1, 1))
    elif kind == "outward":
        reversed_quad("back", *back)
    else:
        quad("back", *back)
    if kind == "twice":
        reversed_quad("back", *back)
    if kind == "frame":  # x 1..3, y 0.5..1.5 at z = 1.5, facing +z; strips 2 cm wide
        o, i = (1.0, 0.5, 3.0, 1.5), (1.02, 0.52, 2.98, 1.48)
        quad("frame", (o[0], o[1], 1.5), (o[2], o[1], 1.5), (i[2], i[1], 1.5), (i[0], i[1], 1.5))
        quad("frame", (o[2], o[1], 1.5), (o[2], o[3], 1.5), (i[2], i[3], 1.5), (i[2], i[1], 1.5))
        quad("frame", (o[2], o[3], 1.5), (o[0], o[3], 1.5), (i[0], i[3], 1.5), (i[2], i[3], 1.5))
        quad("frame", (o[0], o[3], 1.5), (o[0], o[1], 1.5), (i[0], i[1], 1.5), (i[0], i[3], 1.5))
    if kind == "neck":  # x 1..3, y 1..1.03 at z = 1.5, facing +z; 2 cm high for x 1.9..2.1
        base = len(v)
        v.extend([(1, 1, 1.5), (3, 1, 1.5), (3, 1.03, 1.5), (2.1, 1.03, 1.5), (2.1, 1.02, 1.5),
                  (1.9, 1.02, 1.5), (1.9, 1.03, 1.5), (1, 1.03, 1.5)])
        faces.append(("neck", [base + k for k in range(1, 9)]))
    if kind == "sheet":
        quad("sheet", (1, 0.5, 1.5), (3, 0.5, 1.5), (3, 1.5, 1.5), (1, 1.5, 1.5))
        reversed_quad("sheet", (1, 0.5, 1.5), (3, 0.5, 1.5), (3, 1.5, 1.5), (1, 1.5, 1.5))
    if kind in ("outward", "inward"):  # a box standing on the floor, its faces out (as they should be)
        x0, x1, z0, z1, top = 1.0, 2.0, 1.0, 2.0, 0.8
        quad("box", (x0, top, z0), (x0, top, z1), (x1, top, z1), (x1, top, z0))
        quad("box", (x0, 0, z0), (x0, top, z0), (x1, top, z0), (x1, 0, z0))
        quad("box", (x1, 0, z1), (x1, top, z1), (x0, top, z1), (x0, 0, z1))
        quad("box", (x0, 0, z1), (x0, top, z1), (x0, top, z0), (x0, 0, z0))
        quad("box", (x1, 0, z0), (x1, top, z0), (x1, top, z1), (x1, 0, z1))
        # A small box standing on it: the contact is cut into the big box's top.
        a0, a1, b0, b1, y0, y1 = 1.25, 1.75, 1.25, 1.75, top, top + 0.4
        quad("box", (a0, y1, b0), (a0, y1, b1), (a1, y1, b1), (a1, y1, b0))
        quad("box", (a0, y0, b0), (a0, y1, b0), (a1, y1, b0), (a1, y0, b0))
        quad("box", (a1, y0, b1), (a1, y1, b1), (a0, y1, b1), (a0, y0, b1))
        quad("box", (a0, y0, b1), (a0, y1, b1), (a0, y1, b0), (a0, y0, b0))
        quad("box", (a1, y0, b0), (a1, y1, b0), (a1, y1, b1), (a1, y0, b1))
    if kind == "posts":
        for x0, z0, side in ((1.0, 1.0, 0.015), (2.5, 1.5, 0.2)):
            block(quad, x0, x0 + side, 0.0, 0.5, z0, z0 + side)
    if kind == "baseboard":
        block(quad, 1.0, 2.0, 0.0, 0.1, 0.0, 0.01)
    if kind == "columns":
        for cx, cz, radius in ((1.0, 1.5, 0.025), (3.0, 1.5, 0.06)):
            column(v, faces, cx, cz, radius, 1.2, 40)
    if kind == "beam":  # a closed box from x = 3 to 5, through the right wall at x = 4
        x0, x1, y0, y1, z0, z1 = 3.0, 5.0, 1.0, 1.4, 1.3, 1.7
        quad("beam", (x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))
        quad("beam", (x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))
        quad("beam", (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0))
        quad("beam", (x1, y0, z1), (x1, y1, z1), (x0, y1, z1), (x0, y0, z1))
        quad("beam", (x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (x0, y0, z0))
        quad("beam", (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))
    return v, faces


def write_obj(path, v, faces):
    mtl = path[:-4] + ".mtl"
    name = mtl.rsplit("/", 1)[-1]
    with open(path, "w") as out:
        out.write(f"mtllib {name}\n")
        for p in v:
            out.write("v %.9g %.9g %.9g\n" % p)
        current = None
        for mat, idx in faces:
            if mat != current:
                out.write(f"g {mat}\nusemtl {mat}\n")
                current = mat
            out.write("f " + " ".join(map(str, idx)) + "\n")
    colours = {"floor": "0.6 0.6 0.6", "ceiling": "0.7 0.7 0.7", "left": "0.6 0.2 0.2",
               "right": "0.2 0.6 0.2", "front": "0.5 0.5 0.5", "back": "0.5 0.5 0.7",
               "sheet": "0.5 0.5 0.5", "box": "0.5 0.5 0.5", "beam": "0.5 0.5 0.5", "shelf": "0.5 0.5 0.5", "light": "0.5 0.5 0.5",
               "rug": "0.3 0.3 0.6"}
    with open(mtl, "w") as out:
        for mat, kd in colours.items():
            out.write(f"newmtl {mat}\nKd {kd}\n")
            if mat == "light":
                out.write("Ke 20 20 20\n")


def read_obj(path):
    """Vertices, and triangles by material, of a simple OBJ with its MTL's Kd and Ke."""
    v, tris, mat, mtllib = [], {}, None, None
    for line in open(path):
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            v.append(tuple(map(float, t[1:4])))
        elif t[0] == "usemtl":
            mat = t[1]
        elif t[0] == "mtllib":
            mtllib = t[1]
        elif t[0] == "f":
            idx = [int(x.split("/")[0]) for x in t[1:]]
            idx = [i - 1 if i > 0 else len(v) + i for i in idx]
            for k in range(1, len(idx) - 1):
                tris.setdefault(mat, []).append((idx[0], idx[k], idx[k + 1]))
    materials, name = {}, None
    for line in open(path.rsplit("/", 1)[0] + "/" + mtllib):
        t = line.split()
        if not t:
            continue
        if t[0] == "newmtl":
            name = t[1]
            materials[name] = {"Kd": [0.5, 0.5, 0.5], "Ke": [0, 0, 0]}
        elif t[0] in ("Kd", "Ke") and name:
            materials[name][t[0]] = list(map(float, t[1:4]))
    return v, tris, materials


def write_gltf(obj, out_path):
    v, tris, materials = read_obj(obj)
    blob, meshes, accessors, views, gl_materials, nodes = b"", [], [], [], [], []
    for mat, faces in tris.items():
        used = sorted({i for f in faces for i in f})
        remap = {i: k for k, i in enumerate(used)}
        positions = b"".join(struct.pack("<3f", *v[i]) for i in used)
        indices = b"".join(struct.pack("<3I", *(remap[i] for i in f)) for f in faces)
        for data, target in ((positions, 34962), (indices, 34963)):
            views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
            blob += data
        lo = [min(v[i][c] for i in used) for c in range(3)]
        hi = [max(v[i][c] for i in used) for c in range(3)]
        accessors.append({"bufferView": len(views) - 2, "componentType": 5126, "count": len(used),
                          "type": "VEC3", "min": lo, "max": hi})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": 3 * len(faces),
                          "type": "SCALAR"})
        m = materials.get(mat, {"Kd": [0.5] * 3, "Ke": [0] * 3})
        ke = m["Ke"]
        strength = max(ke) if max(ke) > 1 else 1
        material = {"name": mat, "pbrMetallicRoughness": {"baseColorFactor": m["Kd"] + [1],
                                                          "metallicFactor": 0}}
        if max(ke) > 0:
            material["emissiveFactor"] = [c / strength for c in ke]
            material["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        gl_materials.append(material)
        meshes.append({"name": mat, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                    "indices": len(accessors) - 1,
                                                    "material": len(gl_materials) - 1}]})
        nodes.append({"name": mat, "mesh": len(meshes) - 1})
    gltf = {"asset": {"version": "2.0", "generator": "tests/cli/surface_scenes.py"},
            "extensionsUsed": ["KHR_materials_emissive_strength"],
            "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
            "meshes": meshes, "materials": gl_materials, "accessors": accessors,
            "bufferViews": views,
            "buffers": [{"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]}
    with open(out_path, "w") as out:
        json.dump(gltf, out)


if __name__ == "__main__":
    if sys.argv[1] == "gltf":
        write_gltf(sys.argv[2], sys.argv[3])
    else:
        write_obj(sys.argv[2], *room(sys.argv[1]))
