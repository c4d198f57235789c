# EN 1838 (#68 item 5): a 12 x 2 x 3 m corridor with two emergency luminaires of 100 cd in
# every direction; rad-gather --surfaces and rad-report give its escape route's centre line and
# an open area the emergency luminaires' direct light alone (times their share on battery and
# maintenance), equal to the inverse-square law worked here; the verdicts follow EN 1838's 1 lx,
# 0.5 lx and Emax/Emin <= 40; what cannot be lit so is refused with the line and the fix.
source "$(dirname "$0")/lib.sh"
python3 - "$TMP" <<'PY'
import sys
tmp = sys.argv[1]
# A box 12 (x) by 3 (y, up) by 2 (z) m, faces inward.
v = [(0,0,0),(12,0,0),(12,0,2),(0,0,2),(0,3,0),(12,3,0),(12,3,2),(0,3,2)]
faces = [(4,3,2,1),(6,7,8,5),(2,6,5,1),(8,7,3,4),(5,8,4,1),(3,7,6,2)]
with open(f"{tmp}/corridor.obj", "w") as f:
    f.write("mtllib corridor.mtl\nusemtl wall\n")
    for p in v: f.write("v %g %g %g\n" % p)
    for q in faces: f.write("f %d %d %d %d\n" % q)
with open(f"{tmp}/corridor.mtl", "w") as f:
    f.write("newmtl wall\nKd 0.5 0.5 0.5\n")
# 100 cd in every direction from a 5 cm square opening (absolute photometry), 3 W.
with open(f"{tmp}/point.ies", "w") as f:
    f.write("IESNA:LM-63-2002\n[LUMINAIRE] emergency point\nTILT=NONE\n"
            "1 -1 1 3 1 1 2 0.05 0.05 0\n1 1 3\n0 90 180\n0\n100 100 100\n")
PY
cat > "$TMP/layout.csv" <<'CSV'
name,photometry,x,y,z,maintenance,emergency
E1,point.ies,3,2.9,1,0.8,0.3
E2,point.ies,9,2.9,1,0.8,0.3
CSV
sed 's/0\.3$/0.1/' "$TMP/layout.csv" > "$TMP/dim.csv"
# The route's centre line 2 cm over the floor; an open area over the whole floor (0.5 m border).
cat > "$TMP/calc.csv" <<'CSV'
name,kind,x,y,z,ux,uy,uz,vx,vy,vz
route,escape-route,0,0.02,2,12,0,0,0,0,-2
hall,open-area,0,0.02,2,12,0,0,0,0,-2
CSV
{ "$BIN/rad-mesh" "$TMP/corridor.obj" -o "$TMP/c.mesh" --unit m -q 2>/dev/null && "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q; } ||
  fail "rad-mesh, rad-ff"
for layout in layout dim; do
  { "$BIN/rad-ff" "$TMP/c.mesh" --luminaires "$TMP/$layout.csv" -o "$TMP/$layout.lum" -q &&
    "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" --direct "$TMP/$layout.lum" -o "$TMP/$layout.rad" -q; } || fail "the $layout solution"
  "$BIN/rad-gather" "$TMP/c.mesh" "$TMP/$layout.rad" --surfaces "$TMP/calc.csv" -o "$TMP/$layout.g.csv" 2> "$TMP/$layout.g.err" ||
    fail "rad-gather --surfaces ($layout): $(cat "$TMP/$layout.g.err")"
done
# Every sensor against 0.3 x 0.8 x 100 cd x cos / d^2 from both luminaires (the direct light
# alone: the corridor's walls reflect half, and none of it may count).
python3 - "$TMP/layout.g.csv" <<'PY' || fail "the emergency lux against the inverse-square law"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
route = [r for r in rows if r["surface"] == "route"]
hall = [r for r in rows if r["surface"] == "hall"]
assert len(route) == 48, f"route: {len(route)} points, wanted 48 (12 m at 0.25 m, one row)"
assert all(abs(float(r["z"]) - 1) < 1e-9 for r in route), "the route's points are not on its centre line"
assert len(hall) == 44 * 4, f"hall: {len(hall)} points, wanted 44 x 4 (11 m x 1 m at 0.25 m)"
worst = 0
for r in route + hall:
    x, y, z = float(r["x"]), float(r["y"]), float(r["z"])
    e = 0
    for lx in (3, 9):
        d2 = (x - lx) ** 2 + (2.9 - y) ** 2 + (z - 1) ** 2
        e += 0.3 * 0.8 * 100 * (2.9 - y) / d2 ** 1.5
    worst = max(worst, abs(float(r["lux"]) / e - 1))
assert worst < 1e-4, f"worst relative difference {worst}"
PY
grep -q "route (escape-route, 48 x 1 sensors at 0.25 m, 0 without a value).*meets its requirements" "$TMP/layout.g.err" ||
  fail "the route's line: $(cat "$TMP/layout.g.err")"
grep -q "route (escape-route.*FAILS its requirements" "$TMP/dim.g.err" || fail "the dim route passes: $(cat "$TMP/dim.g.err")"
# The report: the same figures, EN 1838's requirements, the verdicts.
"$BIN/rad-report" "$TMP/c.mesh" "$TMP/layout.rad" --surfaces "$TMP/calc.csv" -o "$TMP/r.html" --date x -q ||
  fail "rad-report"
python3 - "$TMP/r.html" "$TMP/layout.g.csv" <<'PY' || fail "the report's route figures"
import csv, re, sys
html = open(sys.argv[1]).read()
lux = [float(r["lux"]) for r in csv.DictReader(open(sys.argv[2])) if r["surface"] == "route"]
section = re.search(r'id="surface-1">(.*?)</section>', html, re.S).group(1)
def cell(cls):
    return re.search(r'class="num %s">([^<]*)<' % cls, section).group(1)
assert abs(float(cell("emin")) - min(lux)) <= 0.006 * min(lux), (cell("emin"), min(lux))
assert abs(float(cell("emax")) - max(lux)) <= 0.006 * max(lux), (cell("emax"), max(lux))
assert cell("max-over-min") == "%.1f" % (max(lux) / min(lux)), cell("max-over-min")
assert "Emin &#8805; 1 lx, Emax/Emin &#8804; 40" in section, "EN 1838's requirement not shown"
assert "emergency luminaires' direct light only" in section
assert 'class="pass"' in section, "the route does not meet"
PY
# Refusals: no emergency luminaire in the layout; a daylight solution.
sed 's/,emergency$//; s/,0\.3$//' "$TMP/layout.csv" > "$TMP/none.csv"
{ "$BIN/rad-ff" "$TMP/c.mesh" --luminaires "$TMP/none.csv" -o "$TMP/none.lum" -q &&
  "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" --direct "$TMP/none.lum" -o "$TMP/none.rad" -q; } || fail "the plain solution"
expect_error "calc.csv:2: an escape route or open area is lit by emergency luminaires (EN 1838), and the solution's layout marks none: give the layout an 'emergency' column" \
  "$TMP/x.html" "$BIN/rad-report" "$TMP/c.mesh" "$TMP/none.rad" --surfaces "$TMP/calc.csv" -o "$TMP/x.html"
printf 'name,photometry,x,y,z,emergency\nE1,point.ies,3,2.9,1,1.5\n' > "$TMP/bad.csv"
expect_error "bad.csv:2: emergency is the share of the flux" "$TMP/x.lum" \
  "$BIN/rad-ff" "$TMP/c.mesh" --luminaires "$TMP/bad.csv" -o "$TMP/x.lum"
finish
