# Direct light through mirrors and glass at the defaults (#65 item 3): a lamp seen in a planar
# mirror is a virtual source, found by every point (it was found only by the indirect rays
# that happened to land on its image), and a lamp behind a pane of glass lights what is
# behind it by the pane's transmission at each angle (the glass stopped it). Both against
# closed forms (tests/cli/specular_boxes.py), deterministic at any thread count.
source "$(dirname "$0")/lib.sh"
BOXES="$SRC/tests/cli/specular_boxes.py"
chain() { # DIR: mesh, form factors, solve
  "$BIN/rad-mesh" "$1/box.obj" -o "$1/box.mesh" -q 2>/dev/null &&
    "$BIN/rad-ff" "$1/box.mesh" -o "$1/box.ff" -q 2>/dev/null &&
    "$BIN/rad-solve" "$1/box.mesh" "$1/box.ff" -o "$1/box.rad" -q
}

# A black box whose one wall is a 0.9 mirror: at 96 points on the floor and the wall facing
# the mirror, E (F(lamp) + 0.9 F(its image)) within 2% (measured 0.6%; without the mirror the
# direct light alone is 0.8% off, its light tree's grouping).
mkdir -p "$TMP/mirror"
python3 "$BOXES" mirror "$TMP/mirror" 0.9 || fail "writing the mirror box"
chain "$TMP/mirror" || fail "the mirror box's chain"
"$BIN/rad-gather" "$TMP/mirror/box.mesh" "$TMP/mirror/box.rad" --points "$TMP/mirror/pts.txt" --lux -q \
  > "$TMP/mirror/got.txt" || fail "rad-gather on the mirror box"
python3 - "$TMP/mirror/got.txt" "$TMP/mirror/closed.txt" <<'PY' || fail "the mirror box is off its closed form"
import sys
got = [float(l.split()[0]) for l in open(sys.argv[1]) if l.strip()]
closed = [float(l) for l in open(sys.argv[2])]
assert len(got) == len(closed) == 96, (len(got), len(closed))
errors = [abs(g - c) / c for g, c in zip(got, closed)]
print("mirror box: worst %.3f%%, mean %.3f%%" % (100 * max(errors), 100 * sum(errors) / len(errors)))
assert max(errors) < 0.02
PY
# The same bytes at 1 and 2 threads.
"$BIN/rad-gather" "$TMP/mirror/box.mesh" "$TMP/mirror/box.rad" --points "$TMP/mirror/pts.txt" --lux -q \
  --threads 1 > "$TMP/mirror/one.txt" || fail "rad-gather --threads 1"
cmp -s "$TMP/mirror/one.txt" "$TMP/mirror/got.txt" || fail "the mirror box differs at 1 and 2 threads"

# A pane of 0.8 between a lamp and the floor: the lux behind it is the lux without it times
# the pane's transmission at the angle to the lamp (0.8 straight under it) within 0.5%.
for w in 0 1; do
  mkdir -p "$TMP/pane$w"
  python3 "$BOXES" pane "$TMP/pane$w" $w || fail "writing pane box $w"
  chain "$TMP/pane$w" || fail "pane box $w's chain"
  "$BIN/rad-gather" "$TMP/pane$w/box.mesh" "$TMP/pane$w/box.rad" --points "$TMP/pane$w/pts.txt" --lux -q \
    > "$TMP/pane$w/got.txt" || fail "rad-gather on pane box $w"
done
python3 - "$TMP/pane0/got.txt" "$TMP/pane1/got.txt" "$TMP/pane1/expected.txt" <<'PY' || fail "the light through the pane is off"
import sys
bare, behind, expected = ([float(l.split()[0]) for l in open(p) if l.strip()] for p in sys.argv[1:4])
assert len(bare) == len(behind) == len(expected) == 6
for b, g, t in zip(bare, behind, expected):
    print("pane: %.4f of the light, expected %.4f" % (g / b, t))
    assert abs(g / b - t) < 0.005 * t, (g / b, t)
assert abs(behind[0] / bare[0] - 0.8) < 0.008
PY

# Luminaires too: a 1000 cd point luminaire in the mirror box is seen as its image (I cos / r^2
# from both, the image's times 0.9), and behind the pane by the pane's transmission; the
# luminaires' direct light on the patches (rad-ff --luminaires) takes both, so the solve and
# the points agree.
lum_chain() { # DIR
  "$BIN/rad-mesh" "$1/box.obj" -o "$1/box.mesh" -q 2>/dev/null &&
    "$BIN/rad-ff" "$1/box.mesh" -o "$1/box.ff" -q 2>/dev/null &&
    "$BIN/rad-ff" "$1/box.mesh" --luminaires "$1/layout.csv" -o "$1/box.lum" -q 2>/dev/null &&
    "$BIN/rad-solve" "$1/box.mesh" "$1/box.ff" --direct "$1/box.lum" -o "$1/box.rad" -q
}
mkdir -p "$TMP/lmirror"
python3 "$BOXES" lum-mirror "$TMP/lmirror" 0.9 || fail "writing the luminaire mirror box"
lum_chain "$TMP/lmirror" || fail "the luminaire mirror box's chain"
"$BIN/rad-gather" "$TMP/lmirror/box.mesh" "$TMP/lmirror/box.rad" --points "$TMP/lmirror/pts.txt" --lux -q \
  > "$TMP/lmirror/got.txt" || fail "rad-gather on the luminaire mirror box"
python3 - "$TMP/lmirror/got.txt" "$TMP/lmirror/closed.txt" <<'PY' || fail "the luminaire's image is off"
import sys
got = [float(l.split()[0]) for l in open(sys.argv[1]) if l.strip()]
closed = [float(l) for l in open(sys.argv[2])]
errors = [abs(g - c) / c for g, c in zip(got, closed)]
print("luminaire in the mirror box: worst %.3f%%" % (100 * max(errors)))
assert len(got) == 96 and max(errors) < 0.005
PY
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
for w in 0 1; do
  mkdir -p "$TMP/lpane$w"
  python3 "$BOXES" lum-pane "$TMP/lpane$w" $w || fail "writing luminaire pane box $w"
  lum_chain "$TMP/lpane$w" || fail "luminaire pane box $w's chain"
  "$BIN/rad-gather" "$TMP/lpane$w/box.mesh" "$TMP/lpane$w/box.rad" --points "$TMP/lpane$w/pts.txt" --lux -q \
    > "$TMP/lpane$w/got.txt" || fail "rad-gather on luminaire pane box $w"
done
python3 - "$TMP/lpane0/got.txt" "$TMP/lpane1/got.txt" "$TMP/lpane1/expected.txt" <<'PY' || fail "the luminaire's light through the pane is off"
import sys
bare, behind, expected = ([float(l.split()[0]) for l in open(p) if l.strip()] for p in sys.argv[1:4])
for b, g, t in zip(bare, behind, expected):
    print("luminaire through the pane: %.4f of the light, expected %.4f" % (g / b, t))
    assert abs(g / b - t) < 0.002 * t, (g / b, t)
PY
finish
