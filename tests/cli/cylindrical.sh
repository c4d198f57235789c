# Cylindrical illuminance (#68 item 3): EN 12464-1's Ez = (1/pi) x the integral of L sin(theta)
# over the sphere, checked where it is known in closed form: (1) a black room lit by one
# luminaire of 100 cd in every direction, Ez = I sin(theta) / (pi d^2) and Eh = I cos(theta) /
# d^2 at every point; (2) a furnace of radiosity B = 2 W/m^2 everywhere, Ez = Eh = 179 x B lx and
# a modelling index of 1. rad-gather --surfaces and rad-report give the same Ez.
source "$(dirname "$0")/lib.sh"
python3 - "$TMP" <<'PY'
import sys
tmp = sys.argv[1]
def box(path, mtl, size, materials):
    sx, sy, sz = size
    v = [(x * sx, y * sy, z * sz) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    quads = [(1, 3, 2, 0), (6, 7, 5, 4), (4, 5, 1, 0), (3, 7, 6, 2), (2, 6, 4, 0), (5, 7, 3, 1)]
    with open(path, "w") as f:
        f.write("mtllib %s\n" % mtl)
        for p in v: f.write("v %g %g %g\n" % p)
        for k, q in enumerate(quads):
            f.write("usemtl %s\n" % materials[k % len(materials)])
            f.write("f %d %d %d %d\n" % tuple(i + 1 for i in q))
box(f"{tmp}/black.obj", "black.mtl", (6, 3, 4), ["black"])
open(f"{tmp}/black.mtl", "w").write("newmtl black\nKd 0 0 0\n")
box(f"{tmp}/furnace.obj", "furnace.mtl", (4, 3, 4), ["glow"])
open(f"{tmp}/furnace.mtl", "w").write("newmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n")
with open(f"{tmp}/point.ies", "w") as f:
    f.write("IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0.05 0.05 0\n1 1 3\n0 90 180\n0\n100 100 100\n")
PY
printf 'name,photometry,x,y,z\nL,point.ies,2,2.8,1.5\n' > "$TMP/layout.csv"
# Seated eye height (1.2 m) over the black room, its 0.5 m band left out, 0.5 m apart.
printf 'name,kind,x,y,z,ux,uy,uz,vx,vy,vz,spacing\nfaces,cylindrical,0,1.2,4,6,0,0,0,0,-4,0.5\n' > "$TMP/calc.csv"
{ "$BIN/rad-mesh" "$TMP/black.obj" -o "$TMP/b.mesh" --unit m -q 2>/dev/null && "$BIN/rad-ff" "$TMP/b.mesh" -o "$TMP/b.ff" -q &&
  "$BIN/rad-ff" "$TMP/b.mesh" --luminaires "$TMP/layout.csv" -o "$TMP/b.lum" -q 2>/dev/null &&
  "$BIN/rad-solve" "$TMP/b.mesh" "$TMP/b.ff" --direct "$TMP/b.lum" -o "$TMP/b.rad" -q; } || fail "the black room"
"$BIN/rad-gather" "$TMP/b.mesh" "$TMP/b.rad" --surfaces "$TMP/calc.csv" -o "$TMP/b.csv" 2> "$TMP/b.err" ||
  fail "rad-gather --surfaces: $(cat "$TMP/b.err")"
grep -q "faces (cylindrical, 10 x 6 sensors at 0.5 m, 0 without a value): Em .*, modelling Ez/Eh [0-9.]* (" "$TMP/b.err" ||
  fail "the cylindrical line: $(cat "$TMP/b.err")"
# Semi-cylindrical illuminance toward u (+x): I sin(theta) (1 + cos psi) / (pi d^2), psi the
# horizontal angle between +x and the luminaire.
printf 'name,kind,x,y,z,ux,uy,uz,vx,vy,vz,spacing\nfaces,semi-cylindrical,0,1.2,4,6,0,0,0,0,-4,0.5\n' > "$TMP/semi.csv"
"$BIN/rad-gather" "$TMP/b.mesh" "$TMP/b.rad" --surfaces "$TMP/semi.csv" -o "$TMP/bs.csv" -q || fail "rad-gather semi-cylindrical"
python3 - "$TMP/b.csv" "$TMP/bs.csv" <<'PY' || fail "Ez and E_sc of one luminaire against their closed forms"
import csv, math, sys
def worst(path, closed_form, floor):
    rows = list(csv.DictReader(open(path)))
    assert len(rows) == 60, (path, len(rows))
    out = 0
    for r in rows:
        x, y, z = float(r["x"]), float(r["y"]), float(r["z"])
        dx, dy, dz = 2 - x, 2.8 - y, 1.5 - z
        d2 = dx * dx + dy * dy + dz * dz
        h = math.hypot(dx, dz)
        want = closed_form(dx, h, d2)
        out = max(out, abs(float(r["lux"]) - want) / max(want, floor))
    return out
# Ez = I sin(theta) / (pi d^2); E_sc = that x (1 + cos psi), cos psi = dx / h.
ez = worst(sys.argv[1], lambda dx, h, d2: 100 * h / math.sqrt(d2) / (math.pi * d2), 0)
esc = worst(sys.argv[2], lambda dx, h, d2: 100 * h / math.sqrt(d2) * (1 + dx / h) / (math.pi * d2), 1e-3)
assert ez < 1e-5 and esc < 1e-5, (ez, esc)  # the CSV's six digits
PY
# The modelling index on the page: the mean of (sin(theta) / pi) / cos(theta) over the points.
"$BIN/rad-report" "$TMP/b.mesh" "$TMP/b.rad" --surfaces "$TMP/calc.csv" -o "$TMP/b.html" --date x -q || fail "rad-report"
python3 - "$TMP/b.html" "$TMP/b.csv" <<'PY' || fail "the report's modelling index"
import csv, math, re, sys
page = open(sys.argv[1]).read()
shown = re.search(r'class="num modelling">([0-9.]+) \(([0-9.]+) to ([0-9.]+)\)<', page).groups()
ratios = []
for r in csv.DictReader(open(sys.argv[2])):
    x, y, z = float(r["x"]), float(r["y"]), float(r["z"])
    dx, dy, dz = 2 - x, 2.8 - y, 1.5 - z
    ratios.append(math.sqrt(dx * dx + dz * dz) / (math.pi * dy))
want = (sum(ratios) / len(ratios), min(ratios), max(ratios))
assert all(abs(float(s) - w) <= 0.0051 for s, w in zip(shown, want)), (shown, want)
assert "Ez, mean (lx)" in page
PY
# The furnace: Ez = Eh = 179 x 2 lx at every point, modelling 1.
printf 'name,kind,x,y,z,ux,uy,uz,vx,vy,vz,spacing\nfaces,cylindrical,0,1.6,4,4,0,0,0,0,-4,1\n' > "$TMP/fcalc.csv"
{ "$BIN/rad-mesh" "$TMP/furnace.obj" -o "$TMP/f.mesh" --unit m -q 2>/dev/null && "$BIN/rad-ff" "$TMP/f.mesh" -o "$TMP/f.ff" -q &&
  "$BIN/rad-solve" "$TMP/f.mesh" "$TMP/f.ff" -o "$TMP/f.rad" -q; } || fail "the furnace"
"$BIN/rad-gather" "$TMP/f.mesh" "$TMP/f.rad" --surfaces "$TMP/fcalc.csv" -o "$TMP/f.csv" 2> "$TMP/f.err" ||
  fail "rad-gather --surfaces in the furnace: $(cat "$TMP/f.err")"
python3 - "$TMP/f.csv" <<'PY' || fail "Ez in the furnace"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 9, len(rows)
for r in rows:
    assert abs(float(r["lux"]) / (179 * 2) - 1) < 0.002, r
PY
grep -q "modelling Ez/Eh 1.00 (1.00 to 1.00)" "$TMP/f.err" || fail "the furnace's modelling index: $(cat "$TMP/f.err")"
sed 's/,cylindrical,/,semi-cylindrical,/' "$TMP/fcalc.csv" > "$TMP/fsemi.csv"
"$BIN/rad-gather" "$TMP/f.mesh" "$TMP/f.rad" --surfaces "$TMP/fsemi.csv" -o "$TMP/fs.csv" -q || fail "semi-cylindrical in the furnace"
python3 - "$TMP/fs.csv" <<'PY' || fail "E_sc in the furnace"
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    assert abs(float(r["lux"]) / (179 * 2) - 1) < 0.002, r
PY
finish
