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
finish
