# Luminaires through the chain (#49): rad-ff --luminaires writes a .lum, rad-solve --direct takes
# it as the first bounce, rad-gather adds the luminaires' direct light exactly. Checked against
# closed forms: a cosine distribution's flux (1000 pi lm), the integrating-sphere relation in a
# closed box, the inverse-square law at points; refusals name FILE:LINE; determinism.
source "$(dirname "$0")/lib.sh"
P="$SRC/tests/data/photometry"
mkdir -p "$TMP/box"
# A closed 2 m cube, every face white 0.5, facing in; a luminaire at its centre.
cat > "$TMP/box/box.obj" <<'OBJ'
mtllib box.mtl
v 0 0 0
v 2 0 0
v 0 2 0
v 2 2 0
v 0 0 2
v 2 0 2
v 0 2 2
v 2 2 2
usemtl white
f 1 2 4 3
f 5 7 8 6
f 1 5 6 2
f 3 4 8 7
f 1 3 7 5
f 2 6 8 4
OBJ
printf 'newmtl white\nKd 0.5 0.5 0.5\n' > "$TMP/box/box.mtl"
# I = 1000 cos(gamma) on the lower hemisphere, 1 degree steps: 1000 pi lm.
python3 - "$TMP/box/cos.ies" <<'PY'
import math, sys
g = list(range(0, 91))
with open(sys.argv[1], "w") as f:
    f.write("IESNA:LM-63-2002\n[TEST] cosine\nTILT=NONE\n1 -1 1 %d 1 1 2 0 0 0\n1 1 0\n" % len(g))
    f.write(" ".join(map(str, g)) + "\n0\n")
    f.write(" ".join("%.6f" % (1000 * math.cos(math.radians(x))) for x in g) + "\n")
PY
printf 'name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,maintenance,group\nlamp,cos.ies,1,1,1,,,,,,\n' > "$TMP/box/layout.csv"
"$BIN/rad-mesh" "$TMP/box/box.obj" -o "$TMP/box.mesh" --max-edge 0.25 -q || fail "rad-mesh"
"$BIN/rad-ff" "$TMP/box.mesh" -o "$TMP/box.ff" --method analytic -q || fail "rad-ff"
"$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/layout.csv" -o "$TMP/box.lum" 2> "$TMP/ff.err" || fail "rad-ff --luminaires: $(cat "$TMP/ff.err")"
grep -q "1 luminaire(s) from 1 photometric file(s) in 1 light group(s): 3141.5[0-9] lm emitted" "$TMP/ff.err" || fail "flux: $(cat "$TMP/ff.err")"
"$BIN/rad-solve" "$TMP/box.mesh" "$TMP/box.ff" --direct "$TMP/box.lum" -o "$TMP/box.rad" 2> "$TMP/solve.err" || fail "rad-solve --direct: $(cat "$TMP/solve.err")"
# rad-solve's flux of the cosine luminaire: 1000 pi within 0.1%.
python3 - "$TMP/solve.err" <<'PY' || fail "solve summary: $(cat "$TMP/solve.err")"
import math, re, sys
text = open(sys.argv[1]).read()
lm = float(re.search(r"light group\(s\): ([0-9.e+]+) lm", text).group(1))
assert abs(lm - 1000 * math.pi) < 1e-3 * 1000 * math.pi, lm
# Integrating sphere: every surface rho = 0.5, so the mean irradiance over all surfaces is
# Phi / (S (1 - rho)), and the reflected power sum B A = rho Phi / (1 - rho) = Phi: the
# power rad-solve reports in lm equals the luminaire's flux within 0.5%.
power = float(re.search(r"W \(([0-9.e+]+) lm\)", text).group(1))
assert abs(power - 1000 * math.pi) < 5e-3 * 1000 * math.pi, power
PY
"$BIN/rad-info" "$TMP/box.lum" | grep -q "kind:      luminaires" || fail "rad-info on a .lum"
"$BIN/rad-info" "$TMP/box.rad" | grep -q "light_group.lamp = luminaires of" || fail "group recorded"
# The same bytes at 1 and 2 threads.
"$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/layout.csv" -o "$TMP/t.lum" --threads 1 -q
mv "$TMP/t.lum" "$TMP/t1.lum"
"$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/layout.csv" -o "$TMP/t.lum" --threads 2 -q
cmp -s "$TMP/t.lum" "$TMP/t1.lum" || fail ".lum differs between 1 and 2 threads"
# Shards: three parts merged (in any order) are the bytes of one run; a missing or doubled part
# is named with its rows.
mkdir -p "$TMP/one" "$TMP/parts"
"$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/layout.csv" -o "$TMP/one/box.lum" -q
mv "$TMP/one/box.lum" "$TMP/single.lum"
for k in 0 1 2; do
  "$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/layout.csv" --rows $k/3 -o "$TMP/parts/$k.lum" -q || fail "part $k"
done
"$BIN/rad-ff" --merge "$TMP/parts/2.lum" "$TMP/parts/0.lum" "$TMP/parts/1.lum" -o "$TMP/one/box.lum" -q || fail "merge"
cmp -s "$TMP/one/box.lum" "$TMP/single.lum" || fail "merged .lum differs from one run's"
expect_error "are in no part (compute them with --rows" "$TMP/one/gap.lum" "$BIN/rad-ff" --merge "$TMP/parts/0.lum" "$TMP/parts/2.lum" -o "$TMP/one/gap.lum"
expect_error "are in two parts" "$TMP/one/dup.lum" "$BIN/rad-ff" --merge "$TMP/parts/0.lum" "$TMP/parts/0.lum" "$TMP/parts/1.lum" "$TMP/parts/2.lum" -o "$TMP/one/dup.lum"
expect_error "is a whole luminaires file, not a part" "$TMP/one/w.lum" "$BIN/rad-ff" --merge "$TMP/single.lum" -o "$TMP/one/w.lum"

# Inverse-square law at points through rad-gather: an isotropic 1000 cd source 2 m over a
# black floor (nothing reflects): E = I cos^3 / h^2 at every point within 0.1%.
mkdir -p "$TMP/plane"
printf 'mtllib p.mtl\nv -10 0 -10\nv -10 0 10\nv 10 0 10\nv 10 0 -10\nusemtl black\nf 1 2 3 4\n' > "$TMP/plane/p.obj"
printf 'newmtl black\nKd 0 0 0\n' > "$TMP/plane/p.mtl"
printf 'IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 180\n0\n1000 1000\n' > "$TMP/plane/iso.ies"
printf 'name,photometry,x,y,z\nbulb,iso.ies,0,2,0\n' > "$TMP/plane/layout.csv"
"$BIN/rad-mesh" "$TMP/plane/p.obj" -o "$TMP/p.mesh" --max-edge 2 -q || fail "plane mesh"
# rad-info says where a mesh lies and in what unit (#53 item 7).
"$BIN/rad-mesh" "$TMP/plane/p.obj" -o "$TMP/mm.mesh" --max-edge 2 --unit mm -q 2>/dev/null
"$BIN/rad-info" "$TMP/mm.mesh" | grep -q "bounding box (-10, 0, -10) to (10, 0, 10), unit mm" || fail "rad-info: $("$BIN/rad-info" "$TMP/mm.mesh" | grep contents)"
"$BIN/rad-ff" "$TMP/p.mesh" -o "$TMP/p.ff" -q || fail "plane ff"
"$BIN/rad-ff" "$TMP/p.mesh" --luminaires "$TMP/plane/layout.csv" -o "$TMP/p.lum" -q || fail "plane lum"
"$BIN/rad-solve" "$TMP/p.mesh" "$TMP/p.ff" --direct "$TMP/p.lum" -o "$TMP/p.rad" -q || fail "plane solve"
python3 -c "
for x in range(-4, 5):
    for z in range(-4, 5):
        print(x * 0.5, 0, z * 0.7, 0, 1, 0)" > "$TMP/pts.txt"
"$BIN/rad-gather" "$TMP/p.mesh" "$TMP/p.rad" --points "$TMP/pts.txt" --lux -q > "$TMP/lux.txt" || fail "gather"
python3 - "$TMP/pts.txt" "$TMP/lux.txt" <<'PY' || fail "inverse-square law"
import sys
pts = [list(map(float, l.split())) for l in open(sys.argv[1])]
lux = [float(l) for l in open(sys.argv[2])]
assert len(pts) == len(lux) == 81
for p, e in zip(pts, lux):
    r2 = p[0] ** 2 + p[2] ** 2
    expect = 1000 * 2 ** 3 / (4 + r2) ** 1.5 / 4 * 1  # I cos^3 / h^2, cos = 2 / sqrt(4 + r^2)
    assert abs(e - expect) <= 1e-3 * expect, (p, e, expect)
PY
# Solved with relative paths in its folder, read from elsewhere: the .lum is found beside the .rad.
(cd "$TMP" && "$BIN/rad-solve" p.mesh p.ff --direct p.lum -o rel.rad -q) || fail "relative solve"
(cd / && "$BIN/rad-gather" "$TMP/p.mesh" "$TMP/rel.rad" --points "$TMP/pts.txt" --lux -q) | cmp -s - "$TMP/lux.txt" || fail "the .lum beside the .rad"
# A moved .lum is found with --direct; a missing one is named.
mv "$TMP/p.lum" "$TMP/moved.lum"
expect_error "p.lum: the luminaires file the solution was solved with is not there" "" "$BIN/rad-gather" "$TMP/p.mesh" "$TMP/p.rad" --points "$TMP/pts.txt"
"$BIN/rad-gather" "$TMP/p.mesh" "$TMP/p.rad" --points "$TMP/pts.txt" --lux -q --direct "$TMP/moved.lum" | cmp -s - "$TMP/lux.txt" || fail "--direct FILE"

# Refusals: a malformed photometric file names its line; a file out of the layout's folder.
cp "$P/MALFORMED_mdl-sdk_test_file_format_error.ies" "$TMP/plane/bad.ies"
printf 'name,photometry,x,y,z\nbulb,bad.ies,0,2,0\n' > "$TMP/plane/bad.csv"
expect_error "bad.ies:3: expected the number of lamps, found 'file'" "$TMP/bad.lum" "$BIN/rad-ff" "$TMP/p.mesh" --luminaires "$TMP/plane/bad.csv" -o "$TMP/bad.lum"
printf 'name,photometry,x,y,z\nbulb,../box/cos.ies,0,2,0\n' > "$TMP/plane/out.csv"
expect_error "out.csv:2: '../box/cos.ies' leads out of the layout's folder" "$TMP/bad.lum" "$BIN/rad-ff" "$TMP/p.mesh" --luminaires "$TMP/plane/out.csv" -o "$TMP/bad.lum"
ln -s "$TMP/box/cos.ies" "$TMP/plane/link.ies"
printf 'name,photometry,x,y,z\nbulb,link.ies,0,2,0\n' > "$TMP/plane/link.csv"
expect_error "link.csv:2: 'link.ies' leads out of the layout's folder (a link)" "$TMP/bad.lum" "$BIN/rad-ff" "$TMP/p.mesh" --luminaires "$TMP/plane/link.csv" -o "$TMP/bad.lum"
printf 'IESNA:LM-63-2002\nTILT=../box/lamp.tlt\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 180\n0\n1000 1000\n' > "$TMP/plane/tilt.ies"
printf 'name,photometry,x,y,z\nbulb,tilt.ies,0,2,0\n' > "$TMP/plane/tilt.csv"
expect_error "tilt.ies:2: '../box/lamp.tlt' leads out of the layout's folder" "$TMP/bad.lum" "$BIN/rad-ff" "$TMP/p.mesh" --luminaires "$TMP/plane/tilt.csv" -o "$TMP/bad.lum"
# A luminaire under the floor (behind it) is warned about, by name and row.
printf 'name,photometry,x,y,z\nbulb,iso.ies,0,2,0\ncellar,iso.ies,0,-1,0\n' > "$TMP/plane/under.csv"
"$BIN/rad-ff" "$TMP/p.mesh" --luminaires "$TMP/plane/under.csv" -o "$TMP/under.lum" -q 2> "$TMP/under.err"
grep -q "under.csv:3: luminaire 'cellar': .* inside a closed object or behind a wall" "$TMP/under.err" || fail "enclosed warning: $(cat "$TMP/under.err")"
grep -q "'bulb'" "$TMP/under.err" && fail "bulb warned: $(cat "$TMP/under.err")"
# The channels a solve holds grow with its light groups: checked against --max-memory (#55 item 3).
expect_error "1 light group(s) over" "$TMP/mem.rad" "$BIN/rad-solve" "$TMP/box.mesh" "$TMP/box.ff" --direct "$TMP/box.lum" -o "$TMP/mem.rad" --max-memory 10K
expect_error "layout.csv: 1 light group(s) over" "$TMP/mem.lum" "$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/layout.csv" -o "$TMP/mem.lum" --max-memory 1K
# The groups are counted as the layout is read, before its luminaires are built: a run too big
# for its memory is refused before a row that would fail the build is reached (#70 item 10;
# a million rows: 8 s, then refused; now 1.8 s).
printf 'name,photometry,x,y,z,maintenance,group\na,cos.ies,1,1,1,,g1\nb,cos.ies,1,1,1,2,g2\n' > "$TMP/box/big.csv"
expect_error "big.csv: 2 light group(s) over" "$TMP/mem.lum" "$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/big.csv" -o "$TMP/mem.lum" --max-memory 1K
expect_error "big.csv:3: maintenance must be in (0, 1]" "$TMP/mem.lum" "$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/big.csv" -o "$TMP/mem.lum"

# Positions (#70 items 4 and 7): a row far past the scene is refused at its row (at 1e20 it
# aborted on Embree's assertion), an empty x is refused, one outside the box is warned about,
# and an aim of 1e200,-1e200,0 is the direction it says (it was normalised to zero).
H='name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,maintenance,group'
for x in 1e20 1e300; do
  printf '%s\nlamp,cos.ies,%s,1,1,,,,,,\n' "$H" "$x" > "$TMP/box/far.csv"
  expect_error "far.csv:2: luminaire 'lamp' at (${x/e/e+}, 1, 1) lies" "$TMP/far.lum" \
    "$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/far.csv" -o "$TMP/far.lum"
done
printf '%s\nlamp,cos.ies,,1,1,,,,,,\n' "$H" > "$TMP/box/nox.csv"
expect_error "nox.csv:2: x is empty: every luminaire needs its x, y and z" "$TMP/nox.lum" \
  "$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/nox.csv" -o "$TMP/nox.lum"
printf '%s\nlamp,cos.ies,1,1,3,,,,,,\n' "$H" > "$TMP/box/out.csv"
err=$("$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/out.csv" -o "$TMP/out.lum" -q 2>&1) || fail "outside: $err"
grep -q "out.csv:2: luminaire 'lamp' at (1, 1, 3) lies 1 units outside the scene's bounds" <<<"$err" || fail "no warning outside the box: $err"
"$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/layout.csv" -o "$TMP/in.lum" -q 2>&1 | grep -q "outside" && fail "a lamp inside warned"
for aim in "1,-1,0" "1e200,-1e200,0"; do
  printf '%s\nlamp,cos.ies,1,1,1,%s,,,\n' "$H" "$aim" > "$TMP/box/aim.csv"
  "$BIN/rad-ff" "$TMP/box.mesh" --luminaires "$TMP/box/aim.csv" -o "$TMP/aim.lum" -q || fail "aim $aim"
  "$BIN/rad-info" --csv "$TMP/aim.lum" > "$TMP/aim-${aim%%,*}.csv"
done
cmp -s "$TMP/aim-1.csv" "$TMP/aim-1e200.csv" || fail "aim 1e200,-1e200,0 differs from 1,-1,0"
finish
