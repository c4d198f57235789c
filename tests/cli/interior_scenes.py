"""Interiors for #66 items 3 and 5: faults to be judged per connected piece, in one ungrouped
material, and a house for the automatic camera.

python3 interior_scenes.py KIND OUT.obj   (writes interior.mtl beside OUT.obj)
  apart     two closed rooms 3 x 2.5 x 3, room A in z > 0 and room B in z < 0, 2 m apart in x;
            each room's wall in the plane z = 0 is drawn twice, once each way: in that plane
            A's scene is on the +z side and B's on the -z side
  touching  the same with B's wall meeting A's at x = 3 (the two walls share an edge)
  lamps     a closed room 6 x 3 x 4, a shade (a box open at the bottom, faces out) hung from
            near its ceiling and two lamps of one material: one inside the shade facing up
            into it, one free, facing the floor
  house     a closed single-storey house drawn z-up as 3ds Max exports it: 12 x 9 m, 3 m high,
            its rooms facing in, two partitions (boxes 0.1 m thick, a 1 m doorway each) making
            three rooms, a low table in each, a roof slab over the ceiling and a 1 x 1 m lamp
            on each room's ceiling
  tunnel    a tunnel 100 m long: a half-round vault of radius 3 m in 128 long thin facets (two
            triangles each) drawn facing out, open at both ends, standing on a floor 7 m wide
            (wider than the vault) facing up, all in one material with no groups (the subway of
            #66 item 2)
  fin       the tunnel with a fin 0.5 m high (material 'fin') standing on the vault's crown,
            along the facets' long side at its top: the vault is two surfaces there
  column    a closed room 6 x 3 x 6 facing in, and two pillars of radius 0.3 m, each a ring of
            96 long thin facets (quads) facing out: one capped at both ends, hanging clear of
            floor and ceiling (0.5 to 2.5 m), one from floor to ceiling
"""
import sys


def newell(points):
    n = [0.0, 0.0, 0.0]
    for i, a in enumerate(points):
        b = points[(i + 1) % len(points)]
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    return n


class Obj:
    def __init__(self):
        self.vertices, self.faces = [], []

    def face(self, points, material, toward=None, away=None):
        """A face whose front faces `toward` (or away from `away`) the given point."""
        target = toward if toward is not None else away
        centre = [sum(p[i] for p in points) / len(points) for i in range(3)]
        n = newell(points)
        facing = sum(n[i] * (target[i] - centre[i]) for i in range(3)) > 0
        if facing != (toward is not None):
            points = points[::-1]
        self.faces.append((material, [len(self.vertices) + k + 1 for k in range(len(points))]))
        self.vertices.extend(points)

    def box(self, lo, hi, material, inward=False, skip=()):
        """A box's faces, facing out (or in); `skip` names faces left out (e.g. 'z0')."""
        centre = [(lo[i] + hi[i]) / 2 for i in range(3)]
        for axis in range(3):
            for side, value in (('0', lo[axis]), ('1', hi[axis])):
                if 'xyz'[axis] + side in skip:
                    continue
                a, b = [c for c in range(3) if c != axis]
                quad = []
                for u, v in ((lo[a], lo[b]), (hi[a], lo[b]), (hi[a], hi[b]), (lo[a], hi[b])):
                    p = [0.0, 0.0, 0.0]
                    p[axis], p[a], p[b] = value, u, v
                    quad.append(tuple(p))
                if inward:
                    self.face(quad, material, toward=centre)
                else:
                    self.face(quad, material, away=centre)

    def write(self, path):
        with open(path, 'w') as f:
            f.write('mtllib interior.mtl\n')
            f.write(''.join('v %g %g %g\n' % v for v in self.vertices))
            for material, corners in self.faces:
                f.write('usemtl %s\nf %s\n' % (material, ' '.join(map(str, corners))))


def box(x0, x1, y0, y1, z0, z1):
    """The six faces of a box (floor, ceiling, x0, x1, z1, z0 walls), unoriented."""
    return [
        [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
        [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],
        [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],
        [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
        [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
        [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
    ]


def lamp(obj, x, y, z, facing_y):
    q = [(x - 0.2, y, z - 0.2), (x + 0.2, y, z - 0.2), (x + 0.2, y, z + 0.2), (x - 0.2, y, z + 0.2)]
    obj.face(q, 'light', toward=(x, y + facing_y, z))


def rooms(obj, bx):
    a, b = box(0, 3, 0, 2.5, 0, 3), box(bx, bx + 3, 0, 2.5, -3, 0)
    ca, cb = (1.5, 1.25, 1.5), (bx + 1.5, 1.25, -1.5)
    for q in a:
        obj.face(q, 'white', toward=ca)
    for q in b:
        obj.face(q, 'white', toward=cb)
    obj.face(a[5], 'white', away=ca)  # A's z = 0 wall again, facing out of A
    obj.face(b[4], 'white', away=cb)  # B's z = 0 wall again, facing out of B
    lamp(obj, 1.5, 2.49, 1.5, -1)
    lamp(obj, bx + 1.5, 2.49, -1.5, -1)


def lamps(obj):
    centre = (3, 1.5, 2)
    for q in box(0, 6, 0, 3, 0, 4):
        obj.face(q, 'white', toward=centre)
    shade = box(1.0, 1.8, 2.3, 2.8, 1.6, 2.4)
    for q in shade[1:]:  # open at the bottom
        obj.face(q, 'shade', away=(1.4, 2.55, 2.0))
    lamp(obj, 1.4, 2.5, 2.0, +1)  # inside the shade, facing up into it
    lamp(obj, 4.4, 2.9, 2.0, -1)  # free, facing the floor


def house(obj):
    obj.box((0, 0, 0), (12, 9, 3), 'wall', inward=True)
    obj.box((-0.3, -0.3, 3.0), (12.3, 9.3, 3.3), 'roof', skip=('z0',))
    for x in (4, 8):
        obj.box((x - 0.05, 0, 0), (x + 0.05, 4, 3), 'wall', skip=('y0', 'z0', 'z1'))
        obj.box((x - 0.05, 5, 0), (x + 0.05, 9, 3), 'wall', skip=('y1', 'z0', 'z1'))
    for room in range(3):
        x = 2 + 4 * room
        obj.box((x - 0.6, 3.9, 0), (x + 0.6, 5.1, 0.7), 'table', skip=('z0',))
        obj.face([(x - 0.5, 4, 2.99), (x + 0.5, 4, 2.99), (x + 0.5, 5, 2.99), (x - 0.5, 5, 2.99)],
                 'light', toward=(x, 4.5, 0))


def tunnel(obj, fin=False):
    import math
    length, radius, segments = 100.0, 3.0, 128
    ring = lambda z: [(radius * math.cos(math.pi * k / segments),
                       radius * math.sin(math.pi * k / segments), z) for k in range(segments + 1)]
    near, far = ring(0.0), ring(length)
    for k in range(segments):
        a0, a1, b1, b0 = near[k], near[k + 1], far[k + 1], far[k]
        middle = ((a0[0] + a1[0]) / 2 * 2, (a0[1] + a1[1]) / 2 * 2, length / 2)  # outside
        obj.face([a0, a1, b1], 'white', toward=middle)
        obj.face([a0, b1, b0], 'white', toward=middle)
    w = radius + 0.5
    obj.face([(-w, 0, 0), (-w, 0, length), (w, 0, length), (w, 0, 0)], 'white',
             toward=(0, 1, length / 2))
    if fin:
        top = near[segments // 2], far[segments // 2]
        up = [(p[0], p[1] + 0.5, p[2]) for p in top]
        obj.face([top[0], top[1], up[1], up[0]], 'fin', toward=(1, 3, length / 2))


def column(obj):
    import math
    obj.box((0, 0, 0), (6, 3, 6), 'wall', inward=True)
    segments, radius = 96, 0.3

    def pillar(cx, cz, y0, y1, caps):
        ring = [(cx + radius * math.cos(2 * math.pi * k / segments), 0.0,
                 cz + radius * math.sin(2 * math.pi * k / segments)) for k in range(segments)]
        for k in range(segments):
            a, b = ring[k], ring[(k + 1) % segments]
            outside = (a[0] + b[0] - cx, 1.5, a[2] + b[2] - cz)  # the axis mirrored in (a + b) / 2
            obj.face([(a[0], y0, a[2]), (b[0], y0, b[2]), (b[0], y1, b[2]), (a[0], y1, a[2])],
                     'white', toward=outside)
        if caps:
            obj.face([(p[0], y0, p[2]) for p in ring], 'white', toward=(cx, y0 - 1, cz))
            obj.face([(p[0], y1, p[2]) for p in ring], 'white', toward=(cx, y1 + 1, cz))

    pillar(2, 2, 0.5, 2.5, True)   # free, capped
    pillar(4, 4, 0.0, 3.0, False)  # from floor to ceiling
    obj.face([(2.5, 2.99, 2.5), (3.5, 2.99, 2.5), (3.5, 2.99, 3.5), (2.5, 2.99, 3.5)], 'light',
             toward=(2.5, 0, 2.5))


def main():
    kind, path = sys.argv[1], sys.argv[2]
    obj = Obj()
    if kind in ('apart', 'touching'):
        rooms(obj, 5 if kind == 'apart' else 3)
    elif kind == 'lamps':
        lamps(obj)
    elif kind == 'house':
        house(obj)
    elif kind in ('tunnel', 'fin'):
        tunnel(obj, kind == 'fin')
    elif kind == 'column':
        column(obj)
    else:
        sys.exit('unknown kind ' + kind)
    obj.write(path)
    mtl = path.rsplit('/', 1)[0] + '/interior.mtl' if '/' in path else 'interior.mtl'
    with open(mtl, 'w') as f:
        f.write('newmtl white\nKd 0.6 0.6 0.6\nnewmtl shade\nKd 0.5 0.5 0.5\n'
                'newmtl wall\nKd 0.7 0.7 0.7\nnewmtl roof\nKd 0.4 0.2 0.2\n'
                'newmtl table\nKd 0.5 0.35 0.2\nnewmtl light\nKd 0 0 0\nKe 10 10 10\n'
                'newmtl fin\nKd 0.3 0.3 0.3\n')


main()
