"""Scenes for the automatic camera (rad-shade with no --view), #66 item 5.

python3 camera_scenes.py KIND OUT.obj   (writes camera.mtl beside OUT.obj)
  house   a closed single-storey house drawn z-up as 3ds Max exports it: 12 x 9 m, 3 m high,
          its rooms facing in, two partitions (boxes 0.1 m thick, a 1 m doorway each) making
          three rooms, a low table in each, a roof slab over the ceiling and a 1 x 1 m lamp
          on each room's ceiling
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
            f.write('mtllib camera.mtl\n')
            f.write(''.join('v %g %g %g\n' % v for v in self.vertices))
            for material, corners in self.faces:
                f.write('usemtl %s\nf %s\n' % (material, ' '.join(map(str, corners))))


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


def main():
    kind, path = sys.argv[1], sys.argv[2]
    obj = Obj()
    if kind == 'house':
        house(obj)
    else:
        sys.exit('unknown kind ' + kind)
    obj.write(path)
    mtl = path.rsplit('/', 1)[0] + '/camera.mtl' if '/' in path else 'camera.mtl'
    with open(mtl, 'w') as f:
        f.write('newmtl wall\nKd 0.7 0.7 0.7\nnewmtl roof\nKd 0.4 0.2 0.2\n'
                'newmtl table\nKd 0.5 0.35 0.2\nnewmtl light\nKd 0 0 0\nKe 5 5 5\n')


main()
