# Direct light through mirrors and glass at the defaults (#65 item 3): a lamp seen in a planar
# mirror is a virtual source, found by every point (it was found only by the indirect rays
# that happened to land on its image), and a lamp behind a pane of glass lights what is
# behind it by the pane's transmission at each angle (the glass stopped it); luminaires the
# same, on the patches (rad-ff --luminaires) and at the points. Against closed forms
# (tests/cli/specular_boxes.py), deterministic at any thread count.
source "$(dirname "$0")/lib.sh"
BOXES="$SRC/tests/cli/specular_boxes.py"
# box KIND NAME VALUE: writes the scene into $TMP/NAME, runs the chain (with its luminaires
# when it has a layout) and rad-gather --lux at its points into got.txt, all at the defaults.
box() {
  local dir="$TMP/$2"
  mkdir -p "$dir"
  python3 "$BOXES" "$1" "$dir" "$3" || { fail "writing $2"; return; }
  local direct=()
  "$BIN/rad-mesh" "$dir/box.obj" -o "$dir/box.mesh" -q 2>/dev/null &&
    "$BIN/rad-ff" "$dir/box.mesh" -o "$dir/box.ff" -q 2>/dev/null || { fail "$2: mesh and form factors"; return; }
  if [ -e "$dir/layout.csv" ]; then
    "$BIN/rad-ff" "$dir/box.mesh" --luminaires "$dir/layout.csv" -o "$dir/box.lum" -q 2>/dev/null || fail "$2: rad-ff --luminaires"
    direct=(--direct "$dir/box.lum")
  fi
  "$BIN/rad-solve" "$dir/box.mesh" "$dir/box.ff" "${direct[@]}" -o "$dir/box.rad" -q || fail "$2: rad-solve"
  "$BIN/rad-gather" "$dir/box.mesh" "$dir/box.rad" --points "$dir/pts.txt" --lux -q > "$dir/got.txt" || fail "$2: rad-gather"
}
# against_closed NAME LIMIT: every point within LIMIT (relative) of closed.txt.
against_closed() {
  python3 - "$TMP/$1/got.txt" "$TMP/$1/closed.txt" "$1" "$2" <<'PY' || fail "$1 is off its closed form"
import sys
got = [float(l.split()[0]) for l in open(sys.argv[1]) if l.strip()]
closed = [float(l) for l in open(sys.argv[2])]
assert len(got) == len(closed) == 96, (len(got), len(closed))
errors = [abs(g - c) / c for g, c in zip(got, closed)]
print("%s: worst %.3f%%, mean %.3f%%" % (sys.argv[3], 100 * max(errors), 100 * sum(errors) / len(errors)))
assert max(errors) < float(sys.argv[4])
PY
}
# pane_ratio BARE BEHIND LIMIT: behind the pane, the bare box's light times expected.txt.
pane_ratio() {
  python3 - "$TMP/$1/got.txt" "$TMP/$2/got.txt" "$TMP/$2/expected.txt" "$3" <<'PY' || fail "the light through the pane ($2) is off"
import sys
bare, behind, expected = ([float(l.split()[0]) for l in open(p) if l.strip()] for p in sys.argv[1:4])
assert len(bare) == len(behind) == len(expected) == 6
for b, g, t in zip(bare, behind, expected):
    print("pane: %.4f of the light, expected %.4f" % (g / b, t))
    assert abs(g / b - t) < float(sys.argv[4]) * t, (g / b, t)
assert abs(behind[0] / bare[0] - 0.8) < 0.008
PY
}

# A black box whose one wall is a 0.9 mirror, a ceiling panel: at 96 points on the floor and
# the wall facing the mirror, E (F(lamp) + 0.9 F(its image)) within 2% (measured 0.6%; without
# the mirror the direct light alone is 0.8% off, its light tree's grouping).
box mirror mirror 0.9
against_closed mirror 0.02
# The same bytes at 1 and 2 threads.
"$BIN/rad-gather" "$TMP/mirror/box.mesh" "$TMP/mirror/box.rad" --points "$TMP/mirror/pts.txt" --lux -q \
  --threads 1 > "$TMP/mirror/one.txt" || fail "rad-gather --threads 1"
cmp -s "$TMP/mirror/one.txt" "$TMP/mirror/got.txt" || fail "the mirror box differs at 1 and 2 threads"

# A pane of 0.8 between a panel and the floor: the lux behind it is the lux without it times
# the pane's transmission at the angle to the lamp (0.8 straight under it) within 0.5%.
box pane pane0 0
box pane pane1 1
pane_ratio pane0 pane1 0.005

# A 1000 cd point luminaire in the mirror box: I cos / r^2 from it and 0.9 of it from its
# image (to rounding), and behind the pane by the pane's transmission.
box lum-mirror lmirror 0.9
against_closed lmirror 0.005
# The .lum: the luminaire's light on the floor's patches, its image's included, adds up to
# the closed form's flux onto the floor (quadrature).
"$BIN/rad-info" --csv "$TMP/lmirror/box.mesh" > "$TMP/lmirror/mesh.csv"
"$BIN/rad-info" --csv "$TMP/lmirror/box.lum" > "$TMP/lmirror/lum.csv"
python3 - "$TMP/lmirror" <<'PY' || fail "the .lum's floor flux is off"
import csv, math, sys
folder = sys.argv[1]
mesh = list(csv.DictReader(open(folder + "/mesh.csv")))
lum = {int(r["patch"]): float(r["e_g"]) for r in csv.DictReader(open(folder + "/lum.csv"))}
floor = [r for r in mesh if abs(float(r["cy"])) < 1e-9 and float(r["ny"]) > 0.99]
got = 179 * sum(lum.get(int(r["patch"]), 0) * float(r["area"]) for r in floor)
n, h, closed = 400, 2.0 / 400, 0.0
for i in range(n):
    for j in range(n):
        x, z = (i + 0.5) * h, (j + 0.5) * h
        for s, w in (((1.4, 1.8, 1.0), 1), ((-1.4, 1.8, 1.0), 0.9)):
            d = (x - s[0], -s[1], z - s[2])
            r2 = sum(c * c for c in d)
            closed += w * 1000 * s[1] / math.sqrt(r2) / r2 * h * h
print("floor flux from the .lum %.2f lm, closed form %.2f lm" % (got, closed))
assert abs(got - closed) < 0.002 * closed
PY
box lum-pane lpane0 0
box lum-pane lpane1 1
pane_ratio lpane0 lpane1 0.002
# The sun in a planar mirror (#65 item 3): an open-topped black 4 x 1 x 2 m box whose west wall
# (x = 0) is a 0.9 mirror, the sun 30 degrees up in the east (beam only: perez:800,0). A floor
# sensor 1 m from the mirror sees the sun directly (over the east wall) and its image in the
# mirror (at the same elevation): 1.9 times what it reads with a black west wall. It read 1.0.
sunbox() { # $1: the west wall's material
  python3 - "$TMP/sun-$1.obj" "$1" <<'PY'
import sys
v, f = [], []
def quad(a, b, c, d, m):
    i = len(v); v.extend([a, b, c, d]); f.append((m, [i + 1, i + 2, i + 3, i + 4]))
X, Y, Z = 4.0, 1.0, 2.0
quad((0, 0, 0), (0, 0, Z), (X, 0, Z), (X, 0, 0), "black")            # floor, up
quad((0, 0, 0), (0, Y, 0), (0, Y, Z), (0, 0, Z), sys.argv[2])         # west wall, facing +x
quad((X, 0, 0), (X, 0, Z), (X, Y, Z), (X, Y, 0), "black")             # east wall, facing -x
quad((0, 0, 0), (X, 0, 0), (X, Y, 0), (0, Y, 0), "black")             # north wall (z = 0), +z
quad((0, 0, Z), (0, Y, Z), (X, Y, Z), (X, 0, Z), "black")             # south wall, -z
with open(sys.argv[1], "w") as out:
    out.write("mtllib sun.mtl\n")
    for p in v: out.write("v %g %g %g\n" % p)
    for m, idx in f: out.write("usemtl %s\nf %s\n" % (m, " ".join(map(str, idx))))
PY
  printf 'newmtl black\nKd 0 0 0\nnewmtl mirror\nillum 3\nKd 0 0 0\nKs 0.9 0.9 0.9\n' > "$TMP/sun.mtl"
  "$BIN/rad-mesh" "$TMP/sun-$1.obj" -o "$TMP/sun-$1.mesh" --max-edge 0.5 -q 2>/dev/null || fail "mesh sun-$1"
  "$BIN/rad-ff" "$TMP/sun-$1.mesh" --sky reinhart:1 -o "$TMP/sun-$1.sky" -q 2>/dev/null || fail "sky sun-$1"
  "$BIN/rad-ff" "$TMP/sun-$1.mesh" -o "$TMP/sun-$1.ff" -q 2>/dev/null || fail "ff sun-$1"
  "$BIN/rad-solve" "$TMP/sun-$1.mesh" "$TMP/sun-$1.ff" --direct "$TMP/sun-$1.sky" -o "$TMP/sun-$1.rad" -q || fail "solve sun-$1"
  echo "1 0.01 1 0 1 0" | "$BIN/rad-gather" "$TMP/sun-$1.mesh" "$TMP/sun-$1.rad" --sky perez:800,0 --sun 30,90 -q
}
black=$(sunbox black) || fail "the sun box, black"
mirror=$(sunbox mirror) || fail "the sun box, mirror"
python3 -c "
b, m = float('$black'), float('$mirror')
print('sun in a mirror: %.1f lx with a black wall, %.1f with a 0.9 mirror: ratio %.4f' % (b, m, m / b))
assert b > 1000 and abs(m / b - 1.9) < 0.01 * 1.9, (b, m)" || fail "the sun's image in a mirror"
finish
