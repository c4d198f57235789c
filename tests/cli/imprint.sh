# Contact imprinting (issue #14): no patch straddles a contact, hidden regions are removed,
# and light no longer leaks through walls or under objects.
source "$(dirname "$0")/lib.sh"
DATA="$SRC/tests/data"
# Mean and largest red radiosity of the patches selected by a Python condition on a patch's
# CSV row (p: dict of rad-info --csv columns).
select_radiosity() { # MESH RAD CONDITION
  "$BIN/rad-info" --csv "$1" > "$TMP/sel.mesh.csv" && "$BIN/rad-info" --csv "$2" > "$TMP/sel.rad.csv" &&
  python3 - "$3" "$TMP/sel.mesh.csv" "$TMP/sel.rad.csv" <<'PY'
import csv, sys
cond = sys.argv[1]
values = []
for p, r in zip(csv.DictReader(open(sys.argv[2])), csv.DictReader(open(sys.argv[3]))):
    p = {k: (float(v) if k not in ('group', 'material') else v) for k, v in p.items()}
    if eval(cond):
        values.append((p['area'], float(r['b_r'])))
area = sum(a for a, _ in values)
print(len(values), sum(a * b for a, b in values) / area, max(b for _, b in values))
PY
}

# Leak test: two closed rooms share a floor, ceiling, back and front wall running past the
# wall between them; the lamp is in room A. With imprinting room B gets exactly nothing.
ROOM_B="p['cx'] > 1.07 - 1e-9 and not (abs(p['cx'] - 1.07) < 1e-9 and p['nx'] < 0)"
for mode in imprint no-imprint; do
  flag=""; [ $mode = no-imprint ] && flag=--no-imprint
  "$BIN/rad-mesh" "$DATA/two-rooms/two-rooms.obj" -o "$TMP/rooms.mesh" --max-edge 0.15 $flag -q 2>"$TMP/rooms.err" || fail "mesh $mode"
  "$BIN/rad-ff" "$TMP/rooms.mesh" -o "$TMP/rooms.ff" -q || fail "ff $mode"
  "$BIN/rad-solve" "$TMP/rooms.mesh" "$TMP/rooms.ff" -o "$TMP/rooms.rad" -q || fail "solve $mode"
  read -r count mean largest < <(select_radiosity "$TMP/rooms.mesh" "$TMP/rooms.rad" "$ROOM_B")
  echo "two rooms, $mode: room B has $count patches, mean radiosity $mean, largest $largest"
  if [ $mode = imprint ]; then
    [ "$largest" = "0.0" ] || fail "room B is lit through the wall with imprinting: largest $largest"
    grep -q "imprinted: contacts cut into 4 face(s) (area 8.4); 4 hidden region(s) removed (area 0.4)" "$TMP/rooms.err" || fail "imprint report: $(cat "$TMP/rooms.err")"
  else
    python3 -c "import sys; sys.exit(not $largest > 1e-4)" || fail "the leak this test guards against is gone without imprinting? largest $largest"
  fi
done

# rad-ff counts the rays that start under or inside other geometry (a back face met within
# the patch's own size): none with imprinting, many without (the straddling floor patches).
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/ri.mesh" --max-edge 0.05 -q 2>/dev/null
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/rn.mesh" --max-edge 0.05 --no-imprint -q
"$BIN/rad-ff" "$TMP/ri.mesh" -o "$TMP/ri.ff" -q 2>"$TMP/ri.err" || fail "ff imprinted"
"$BIN/rad-ff" "$TMP/rn.mesh" -o "$TMP/rn.ff" -q 2>"$TMP/rn.err" || fail "ff not imprinted"
[ "$("$BIN/rad-info" "$TMP/ri.ff" | sed -n 's/^  rays_started_inside = //p')" = 0 ] || fail "rays started inside with imprinting"
[ ! -s "$TMP/ri.err" ] || fail "rad-ff warned on the imprinted box: $(cat "$TMP/ri.err")"
inside=$("$BIN/rad-info" "$TMP/rn.ff" | sed -n 's/^  rays_started_inside = //p')
[ "${inside:-0}" -gt 100 ] || fail "rays started inside without imprinting: '$inside'"
grep -q "ray(s) from .* patch(es) met a back face within their own patch's size: those patches are partly under or inside other geometry" "$TMP/rn.err" || fail "rad-ff warning: $(cat "$TMP/rn.err")"

# Cornell box: the floor loses exactly the blocks' footprints (shoelace over each block's
# corners at y = 0, from the OBJ itself), and the walls are the same grids as without.
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/ci.mesh" --max-edge 0.05 -q 2>/dev/null || fail "mesh cornell"
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/cn.mesh" --max-edge 0.05 --no-imprint -q || fail "mesh cornell --no-imprint"
"$BIN/rad-info" --csv "$TMP/ci.mesh" > "$TMP/ci.csv"; "$BIN/rad-info" --csv "$TMP/cn.mesh" > "$TMP/cn.csv"
python3 - "$SRC/scenes/cornell/cornell.obj" "$TMP/ci.csv" "$TMP/cn.csv" <<'PY' || fail "cornell floor area"
import csv, math, sys
obj = open(sys.argv[1]).read().splitlines()
group, verts, rings = None, [], {}
for line in obj:
    w = line.split()
    if not w: continue
    if w[0] == 'o': group = w[1]
    if w[0] == 'v':
        verts.append(tuple(map(float, w[1:4])))
        if group.endswith('block') and abs(verts[-1][1]) < 1e-12:
            rings.setdefault(group, []).append(verts[-1])
def hull_area(points):  # the footprint: convex hull of the corners on the floor (shoelace)
    pts = sorted(set((x, z) for x, _, z in points))
    def half(ps):
        h = []
        for p in ps:
            while len(h) >= 2 and (h[-1][0]-h[-2][0])*(p[1]-h[-2][1]) - (h[-1][1]-h[-2][1])*(p[0]-h[-2][0]) <= 0: h.pop()
            h.append(p)
        return h
    hull = half(pts)[:-1] + half(pts[::-1])[:-1]
    return abs(sum(hull[i][0]*hull[i-1][1] - hull[i-1][0]*hull[i][1] for i in range(len(hull)))) / 2
footprints = sum(hull_area(r) for r in rings.values())
assert len(rings) == 2, rings.keys()
def floor_area(path): return sum(float(p['area']) for p in csv.DictReader(open(path)) if p['group'] == 'floor')
full, imprinted = floor_area(sys.argv[3]), floor_area(sys.argv[2])
print(f"cornell floor {full:.12f} - footprints {footprints:.12f} = {full - footprints:.12f}; imprinted {imprinted:.12f}")
assert abs(full - footprints - imprinted) <= 1e-9 * full
# Nothing else changed: the walls, ceiling and lamp have the same patches (regular grids).
# The blocks keep their area; their sides may gain columns where the floor's band around the
# footprints asked for shorter outline pieces (shared by the floor and the sides).
def others(path): return sorted((p['group'], p['cx'], p['cy'], p['cz'], p['area']) for p in csv.DictReader(open(path)) if p['group'] != 'floor' and not p['group'].endswith('block'))
assert others(sys.argv[2]) == others(sys.argv[3])
def block_area(path, g): return sum(float(p['area']) for p in csv.DictReader(open(path)) if p['group'] == g)
for g in ('short_block', 'tall_block'):
    assert abs(block_area(sys.argv[2], g) - block_area(sys.argv[3], g)) <= 1e-9, g
PY

# A closed Cornell box (front wall added): every row of the form factors sums to 1 within
# the method's accuracy, the patches beside the blocks included; without imprinting, those
# straddling a block's foot lose what their hidden part would see.
{ cat "$SRC/scenes/cornell/cornell.obj"; printf 'o front\nv 0 0 0\nv 0.556 0 0\nv 0.556 0.5488 0\nv 0 0.5488 0\nusemtl white\nf -4 -3 -2 -1\n'; } > "$TMP/closed.obj"
cp "$SRC/scenes/cornell/cornell.mtl" "$TMP/"
for mode in imprint no-imprint; do
  flag=""; [ $mode = no-imprint ] && flag=--no-imprint
  "$BIN/rad-mesh" "$TMP/closed.obj" -o "$TMP/closed.mesh" --max-edge 0.05 $flag -q 2>/dev/null || fail "mesh closed $mode"
  "$BIN/rad-ff" "$TMP/closed.mesh" -o "$TMP/closed.ff" -q || fail "ff closed $mode"
  "$BIN/rad-info" --csv "$TMP/closed.ff" > "$TMP/closed.csv"
  patches=$("$BIN/rad-info" "$TMP/closed.mesh" | sed -n 's/^  patches = //p')
  python3 - "$TMP/closed.csv" "$patches" $mode <<'PY' || fail "closed box row sums ($mode)"
import csv, sys
sums = [0.0] * int(sys.argv[2])
for row in csv.DictReader(open(sys.argv[1])): sums[int(row['row'])] += float(row['f'])
low, high = min(sums), max(sums)
print(f"closed Cornell box, {sys.argv[3]}: {len(sums)} rows sum to {low:.4f} .. {high:.4f}")
if sys.argv[3] == 'imprint': assert 0.99 <= low and high <= 1.01
else: assert low < 0.9  # the straddling patches this guards against
PY
done

# Near contacts (#53 item 5): a Cornell-size box (0.556 x 0.5488 x 0.5592 m, facing in) split
# by a wall, each room with a lamp 1 cm under the ceiling, the left one ten times the right.
# 'gap': the wall a 2 cm slab (its sides and top, x = 0.268 .. 0.288) ending 1 mm below the
# ceiling; 'sheet': one face at x = 0.3 from floor to ceiling, not sharing the ceiling's
# vertices; 'welded': that face's top is the edge between the ceiling's two quads.
two_rooms() { # VARIANT OUT.obj
  python3 - "$1" "$2" <<'PY'
import sys
variant, out = sys.argv[1], sys.argv[2]
W, H, D, x0, x1, xm = 0.556, 0.5488, 0.5592, 0.268, 0.288, 0.3
V, F = [], []
def face(points, group, material):
    F.append((group, material, [len(V) + k + 1 for k in range(len(points))]))
    V.extend(points)
face([(0,0,D),(W,0,D),(W,0,0),(0,0,0)], 'floor', 'white')
if variant == 'welded':  # two quads sharing the edge x = xm (vertices 7 and 8)
    face([(W,H,0),(W,H,D),(xm,H,D),(xm,H,0)], 'ceiling', 'white')
    F.append(('ceiling', 'white', [8, 7, 9, 10]))
    V.extend([(0,H,D),(0,H,0)])
else:
    face([(W,H,0),(W,H,D),(0,H,D),(0,H,0)], 'ceiling', 'white')
face([(0,H,0),(0,H,D),(0,0,D),(0,0,0)], 'left', 'white')
face([(W,0,D),(W,H,D),(W,H,0),(W,0,0)], 'right', 'white')
face([(W,0,0),(W,H,0),(0,H,0),(0,0,0)], 'back', 'white')
face([(0,H,D),(W,H,D),(W,0,D),(0,0,D)], 'front', 'white')
if variant == 'gap':
    t = H - 0.001
    face([(x0,0,0),(x0,0,D),(x0,t,D),(x0,t,0)], 'wall', 'white')
    face([(x1,0,0),(x1,t,0),(x1,t,D),(x1,0,D)], 'wall', 'white')
    face([(x0,t,0),(x0,t,D),(x1,t,D),(x1,t,0)], 'wall', 'white')
elif variant == 'sheet':
    face([(xm,0,0),(xm,H,0),(xm,H,D),(xm,0,D)], 'wall', 'white')
else:
    F.append(('wall', 'white', [len(V) + 1, 7, 8, len(V) + 2]))
    V.extend([(xm,0,D),(xm,0,0)])
for cx, m in ((0.134, 'bright'), (0.422, 'dim')):
    y, s = H - 0.01, 0.05
    face([(cx-s,y,D/2-s),(cx+s,y,D/2-s),(cx+s,y,D/2+s),(cx-s,y,D/2+s)], 'lamp', m)
with open(out, 'w') as f:
    f.write('mtllib two-rooms.mtl\n' + ''.join('v %.6f %.6f %.6f\n' % v for v in V))
    for g, m, c in F: f.write('g %s\nusemtl %s\nf %s\n' % (g, m, ' '.join(map(str, c))))
PY
}
printf 'newmtl white\nKd 0.75 0.75 0.75\nnewmtl bright\nKd 0 0 0\nKe 100 100 100\nnewmtl dim\nKd 0 0 0\nKe 10 10 10\n' > "$TMP/two-rooms.mtl"
# The ceiling's patches whose centroids lie left of LO cover exactly x = 0 .. LO, and those
# right of HI exactly HI .. 0.556: none reaches across the wall.
check_ceiling_sides() { # MESH LO HI
  "$BIN/rad-info" --csv "$1" > "$TMP/sides.csv"
  python3 - "$TMP/sides.csv" "$2" "$3" <<'PY'
import csv, sys
lo, hi, D = float(sys.argv[2]), float(sys.argv[3]), 0.5592
left = right = 0.0
for p in csv.DictReader(open(sys.argv[1])):
    if p['group'] != 'ceiling': continue
    x = float(p['cx'])
    if x < lo: left += float(p['area'])
    if x > hi: right += float(p['area'])
print(f"ceiling left of the wall {left:.9f} (exactly {lo * D:.9f}), right {right:.9f} ({(0.556 - hi) * D:.9f})")
assert abs(left - lo * D) < 1e-9 and abs(right - (0.556 - hi) * D) < 1e-9
PY
}
for variant in sheet welded; do
  two_rooms $variant "$TMP/$variant.obj"
  "$BIN/rad-mesh" "$TMP/$variant.obj" -o "$TMP/$variant.mesh" --max-edge 0.05 -q 2>/dev/null || fail "mesh $variant"
  check_ceiling_sides "$TMP/$variant.mesh" 0.3 0.3 || fail "a ceiling patch reaches across the $variant wall"
done
# The slab 1 mm below the ceiling: with the default contact gap the ceiling is cut along the
# slab's top edges. Each ceiling patch along the junction (centroid within 2 cm of the slab)
# is compared with rad-gather --exact at its centroid (rho x irradiance, the exact sum over
# every patch): within 5% on both sides. With --contact-gap 0 the ceiling's patches straddle
# the slab and average both rooms, as before: the bright side's read low, the dim side's high.
two_rooms gap "$TMP/gap.obj"
for gap in default 0; do
  flags=(); [ $gap = 0 ] && flags=(--contact-gap 0)
  "$BIN/rad-mesh" "$TMP/gap.obj" -o "$TMP/gap.mesh" --max-edge 0.02 "${flags[@]}" -q 2>"$TMP/gap.err" || fail "mesh gap $gap"
  # The strips under the slab and at its ends are footprints (bounded mostly by contact
  # lines), though they reach the floor's and walls' outlines: no warning (there was one a
  # group, 3.6% removed, "reaching the faces' own outlines").
  ! grep -q "imprinting removed" "$TMP/gap.err" || fail "the slab's footprints warned of: $(cat "$TMP/gap.err")"
  "$BIN/rad-ff" "$TMP/gap.mesh" -o "$TMP/gap.ff" -q 2>/dev/null || fail "ff gap $gap"
  "$BIN/rad-solve" "$TMP/gap.mesh" "$TMP/gap.ff" -o "$TMP/gap.rad" -q || fail "solve gap $gap"
  "$BIN/rad-info" --csv "$TMP/gap.mesh" > "$TMP/gap.mesh.csv"
  "$BIN/rad-info" --csv "$TMP/gap.rad" > "$TMP/gap.rad.csv"
  python3 - "$TMP/gap.mesh.csv" <<'PY' > "$TMP/junction.txt"
import csv, sys
for p in csv.DictReader(open(sys.argv[1])):
    x = float(p['cx'])
    if p['group'] == 'ceiling' and (0.248 < x < 0.268 or 0.288 < x < 0.308):
        print(p['patch'], p['rho_r'], p['cx'], float(p['cy']) - 1e-6, p['cz'], 0, -1, 0)
PY
  cut -d' ' -f3- "$TMP/junction.txt" | "$BIN/rad-gather" "$TMP/gap.mesh" "$TMP/gap.rad" --exact -q > "$TMP/junction.gathered" || fail "gather gap $gap"
  python3 - "$TMP/junction.txt" "$TMP/junction.gathered" "$TMP/gap.rad.csv" $gap <<'PY' || fail "ceiling along the slab 1 mm under it, contact gap $gap"
import csv, sys
b = {int(r['patch']): float(r['b_r']) for r in csv.DictReader(open(sys.argv[3]))}
ratios = {'bright': [], 'dim': []}
for line, gathered in zip(open(sys.argv[1]), open(sys.argv[2])):
    w = line.split()
    ratios['bright' if float(w[2]) < 0.268 else 'dim'].append(b[int(w[0])] / (float(w[1]) * float(gathered.split()[0])))
for side, r in ratios.items():
    print(f"contact gap {sys.argv[4]}: {side} room, {len(r)} ceiling patches along the slab: patch / gathered {min(r):.3f} .. {max(r):.3f}")
assert all(ratios.values())
worst = max(abs(x - 1) for r in ratios.values() for x in r)
if sys.argv[4] == 'default': assert worst <= 0.05, worst
else: assert min(ratios['bright']) < 0.9 and max(ratios['dim']) > 1.1, ratios
PY
done

# Imprinting never deletes what is seen, whichever way the faces were drawn (#53 item 4):
# - a tunnel 20 m long: a floor, a vault of 120 facets (welded, open), two rails along it and
#   a bench, both without bottoms, and a lamp. The floor loses exactly the rails' and the
#   bench's footprints (8 + 1 m^2) with the vault wound outward, inward or at random, by
#   default and with --orient fix. Before, a vault wound outward or at random hid the whole
#   floor by default, and at random (this seed) 23.5 of its 51 m^2 with --orient fix.
# - a floor drawn facing down over a closed room below (its ceiling's back 20 cm under it),
#   a block standing on it: the floor loses the block's footprint (1 m^2) only. Before, all
#   of it (the backs of the room below, from the floor's front).
tunnel() { # OUT WINDING(outward|inward|random) | OUT storey
  python3 - "$@" <<'PY'
import math, random, sys
out, kind = sys.argv[1], sys.argv[2]
random.seed(1)
verts, faces = [], []
def quad(group, pts):
    verts.extend(pts)
    n = len(verts)
    faces.append((group, [n - 3, n - 2, n - 1, n]))
def box(group, x0, y0, z0, x1, y1, z1, bottom=False, inward=False):
    sides = [[(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],
             [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
             [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
             [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],
             [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)]]
    if bottom: sides.append([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)])
    for p in sides: quad(group, p[::-1] if inward else p)
if kind == 'storey':
    quad('floor', [(0, 0, 0), (4, 0, 0), (4, 0, 4), (0, 0, 4)])  # facing down
    for p in ([(0, 0, 0), (0, 3, 0), (4, 3, 0), (4, 0, 0)], [(0, 0, 4), (4, 0, 4), (4, 3, 4), (0, 3, 4)],
              [(0, 0, 0), (0, 0, 4), (0, 3, 4), (0, 3, 0)], [(4, 0, 0), (4, 3, 0), (4, 3, 4), (4, 0, 4)],
              [(0, 3, 0), (0, 3, 4), (4, 3, 4), (4, 3, 0)]):
        quad('room', p[::-1])  # walls and ceiling facing in, open below
    box('block', 1.5, 0, 1.5, 2.5, 1, 2.5)
    box('below', 0, -3, 0, 4, -0.2, 4, bottom=True, inward=True)
    quad('lamp', [(1.5, 2.95, 1.5), (2.5, 2.95, 1.5), (2.5, 2.95, 2.5), (1.5, 2.95, 2.5)])
else:
    for i in range(12):
        a0, a1 = math.pi * i / 12, math.pi * (i + 1) / 12
        for k in range(10):
            x0, x1 = 2.0 * k, 2.0 * (k + 1)
            p = [(x0, 1.5 * math.sin(a0), 1.5 + 1.5 * math.cos(a0)), (x1, 1.5 * math.sin(a0), 1.5 + 1.5 * math.cos(a0)),
                 (x1, 1.5 * math.sin(a1), 1.5 + 1.5 * math.cos(a1)), (x0, 1.5 * math.sin(a1), 1.5 + 1.5 * math.cos(a1))]
            flip = {'outward': False, 'inward': True, 'random': random.random() < 0.5}[kind]
            quad('vault', p[::-1] if flip else p)
    quad('floor', [(0, 0, 0), (0, 0, 3), (20, 0, 3), (20, 0, 0)])
    box('rail', 0, 0, 1, 20, 0.2, 1.2); box('rail', 0, 0, 1.8, 20, 0.2, 2)
    box('bench', 5, 0, 0.1, 7, 0.5, 0.6)
    quad('lamp', [(9, 1.4, 1), (11, 1.4, 1), (11, 1.4, 2), (9, 1.4, 2)])
with open(out, 'w') as f:
    f.write('mtllib tunnel.mtl\n')
    f.writelines('v %.9g %.9g %.9g\n' % v for v in verts)
    for group, idx in faces:
        f.write('g %s\nusemtl %s\nf %s\n' % (group, 'lamp' if group == 'lamp' else 'grey', ' '.join(map(str, idx))))
with open(out.rsplit('/', 1)[0] + '/tunnel.mtl', 'w') as f:
    f.write('newmtl grey\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0.5 0.5 0.5\nKe 10 10 10\n')
PY
}
floor_area() { "$BIN/rad-info" --csv "$1" | awk -F, '$2 == "floor" { a += $4 } END { printf "%.6f", a }'; }
for winding in outward inward random; do
  tunnel "$TMP/tunnel-$winding.obj" $winding
  for flag in "" "--orient fix"; do
    # shellcheck disable=SC2086
    "$BIN/rad-mesh" "$TMP/tunnel-$winding.obj" -o "$TMP/tunnel.mesh" $flag -q 2>/dev/null || fail "mesh tunnel $winding $flag"
    area=$(floor_area "$TMP/tunnel.mesh")
    echo "tunnel, vault wound $winding${flag:+, $flag}: floor $area m^2 (60 less the footprints' 9)"
    [ "$area" = 51.000000 ] || fail "tunnel, vault wound $winding $flag: floor $area m^2, not 51"
    [ -n "$flag" ] || continue
    # --orient fix makes the vault face in, whichever part of it was drawn facing out (the
    # random one: 56 of its 120 facets face in, and the rest are turned to agree with them;
    # before, turning the 56 was refused as making things worse, and the vault stayed mixed).
    "$BIN/rad-info" --csv "$TMP/tunnel.mesh" | awk -F, '$2 == "vault" { n++; if ($9 * (0 - $6) + $10 * (1.5 - $7) <= 0) out++ }
      END { exit !(n > 0 && out == 0) }' || fail "tunnel, vault wound $winding, --orient fix: the vault does not all face in"
  done
done
tunnel "$TMP/storey.obj" storey
"$BIN/rad-mesh" "$TMP/storey.obj" -o "$TMP/storey.mesh" -q 2>/dev/null || fail "mesh storey"
area=$(floor_area "$TMP/storey.mesh")
echo "a floor drawn facing down over a room: $area m^2 (16 less the block's 1)"
[ "$area" = 15.000000 ] || fail "a floor drawn facing down over a room: $area m^2, not 15"

# Foot test: a box on a lit floor. No floor patch is under the box; the mean radiosity of
# the box's lowest 20 cm (its lowest row at h) converges under refinement (h, h/2, h/4: the
# second change at most 3/4 of the first). First-order convergence halves the change, and
# the visibility sampling's noise (about 5e-4 at h) moves the ratio by 0.1 with the patches'
# order alone, so half is no bound to test against.
declare -a band
for h in 0.2 0.1 0.05; do
  "$BIN/rad-mesh" "$DATA/box-on-floor/box-on-floor.obj" -o "$TMP/foot.mesh" --max-edge $h -q 2>/dev/null || fail "mesh foot $h"
  "$BIN/rad-ff" "$TMP/foot.mesh" -o "$TMP/foot.ff" -q || fail "ff foot $h"
  "$BIN/rad-solve" "$TMP/foot.mesh" "$TMP/foot.ff" -o "$TMP/foot.rad" -q || fail "solve foot $h"
  read -r n under _ < <(select_radiosity "$TMP/foot.mesh" "$TMP/foot.rad" "p['group'] == 'floor' and abs(p['cx']) < 0.25 and abs(p['cz']) < 0.25" 2>/dev/null || echo "0 0 0")
  [ "$n" = 0 ] || fail "$n floor patches under the box at h=$h"
  read -r n mean _ < <(select_radiosity "$TMP/foot.mesh" "$TMP/foot.rad" "p['group'] == 'box' and p['ny'] < 0.5 and p['cy'] < 0.2")
  band+=("$mean")
done
echo "box's lowest 20 cm at h, h/2, h/4: ${band[*]}"
python3 -c "
a, b, c = ${band[0]}, ${band[1]}, ${band[2]}
assert abs(c - b) <= 0.75 * abs(b - a), (a, b, c)" || fail "the box's foot does not converge: ${band[*]}"
# A tunnel's floor under a vault drawn facing out, open at both ends (#66 item 2): the floor
# inside the vault's springlines was taken for a footprint (the vault's backs all round it,
# parity odd) and removed, 600 of its 700 m^2, said only as a change. The vault's ends are
# openings the scene's open side reaches in by: the floor is kept.
python3 "$SRC/tests/cli/interior_scenes.py" tunnel "$TMP/tunnel.obj"
"$BIN/rad-mesh" "$TMP/tunnel.obj" -o "$TMP/tunnel.mesh" 2> "$TMP/tunnel.err" || fail "mesh the tunnel"
floor=$("$BIN/rad-info" --csv "$TMP/tunnel.mesh" | awk -F, 'NR > 1 && $9 > 0.999 { a += $4 } END { printf "%.2f", a }')
[ "$floor" = 700.00 ] || fail "the tunnel's floor was not kept whole: $floor m^2: $(cat "$TMP/tunnel.err")"
grep -q "imprinted: contacts cut into 1 face(s) (area 700); 0 hidden region(s) removed" "$TMP/tunnel.err" || fail "a region of the tunnel's floor was removed: $(cat "$TMP/tunnel.err")"
finish
