# rad-shade: flat, smoothed and albedo images from one solve; EXR opens in exrheader; bad input.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/c.rad" -q
VF="$SRC/scenes/cornell/cornell.vf"
for mode in "--flat" "--smooth average" "--smooth area" "--smooth crease" "--albedo"; do
  "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/i.exr" --view-file "$VF" -x 64 -y 64 $mode --png "$TMP/i.png" --ply "$TMP/i.ply" -q || fail "$mode"
done
if command -v exrheader >/dev/null; then
  exrheader "$TMP/i.exr" | grep -q "radiosity:provenance" || fail "exrheader does not show the provenance"
fi
head -c 8 "$TMP/i.png" | od -An -c | grep -q "P   N   G" || fail "png signature"
head -1 "$TMP/i.ply" | grep -q "^ply" || fail "ply"
expect_error "parallel" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view "-vd 0 1 0 -vu 0 1 0"
# Image memory is checked before rendering (16384^2 at --aa 8 would need 344 GiB).
expect_error "a 16384x16384 image at --aa 8 needs about 344.2 GiB, more than --max-memory" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view-file "$VF" -x 16384 -y 16384 --aa 8
expect_error "needs about 446.3 MiB, more than --max-memory 400.0 MiB" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view-file "$VF" -x 2000 -y 2000 --aa 2 --max-memory 400M
expect_error "sees no geometry" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view "-vp 0.3 0.3 -1 -vd 0 0 -1"
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/other.mesh" --max-edge 0.2 -q
expect_error "does not belong to" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/other.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view-file "$VF"
expect_error "does not exist" "" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/no/such/v.exr" --view-file "$VF"
printf -- '-vp 0 0 0\n-vh banana\n' > "$TMP/bad.vf"
expect_error "bad.vf:2:" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view-file "$TMP/bad.vf"

# A sheet lit from its back: one-sided, the view from below shows its back (warned, marked);
# --two-sided gives it a lit back and the warning goes.
SHEET="$SRC/tests/data/two-sided-sheet/sheet.obj"
BELOW="-vp 1 0.3 3.5 -vd 0 0.25 -1 -vu 0 1 0 -vh 60 -vv 60"
for sides in one two; do
  extra=(); [ $sides = two ] && extra=(--two-sided sheet)
  err=$("$BIN/rad-mesh" "$SHEET" -o "$TMP/$sides.mesh" --max-edge 0.2 "${extra[@]}" 2>&1) || fail "sheet mesh: $err"
  [ $sides = two ] && { grep -q -- "--two-sided added 25 back patch(es)" <<<"$err" || fail "two-sided message: $err"; }
  grep -q "non-manifold" <<<"$err" && fail "the two sides taken for a non-manifold mesh: $err"
  "$BIN/rad-ff" "$TMP/$sides.mesh" -o "$TMP/$sides.ff" --method hemisphere --rays 1000 -q 2>/dev/null || fail "sheet ff"
  "$BIN/rad-solve" "$TMP/$sides.mesh" "$TMP/$sides.ff" -o "$TMP/$sides.rad" -q || fail "sheet solve"
  err=$("$BIN/rad-shade" "$TMP/$sides.mesh" "$TMP/$sides.rad" -o "$TMP/$sides.exr" --view "$BELOW" -x 64 -y 64 --backfaces mark -q 2>&1) || fail "sheet shade: $err"
  if [ $sides = one ]; then
    grep -q "warning: [0-9.]*% of the image shows the back of surfaces.*marked in magenta" <<<"$err" || fail "no back-face warning: $err"
  else
    grep -q warning <<<"$err" && fail "two-sided sheet still warned: $err"
  fi
done
expect_error "'shet' is neither a group nor a material" "$TMP/x.mesh" "$BIN/rad-mesh" "$SHEET" -o "$TMP/x.mesh" --two-sided shet
expect_error "--two-sided-emission needs --two-sided" "$TMP/x.mesh" "$BIN/rad-mesh" "$SHEET" -o "$TMP/x.mesh" --two-sided-emission
expect_error "" "$TMP/x.exr" "$BIN/rad-shade" "$TMP/one.mesh" "$TMP/one.rad" -o "$TMP/x.exr" --view "$BELOW" --backfaces paint
# The right Cornell box shows no back face.
err=$("$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view-file "$VF" -x 64 -y 64 2>&1)
grep -q "back of surfaces" <<<"$err" && fail "back faces on the right Cornell box: $err"
# A rendered image used as a texture (map_Kd) by a material whose Kd is 0: rad-mesh says the
# texture's mean replaced it, and the reflectance is that mean (not 0).
mkdir -p "$TMP/tex"
cp "$TMP/i.png" "$TMP/tex/render.png"
printf 'newmtl painted\nKd 0 0 0\nmap_Kd render.png\nnewmtl lamp\nKe 1 1 1\n' > "$TMP/tex/t.mtl"
printf 'mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl painted\nf 1 2 3\nusemtl lamp\nf 1 3 2\n' > "$TMP/tex/t.obj"
err=$("$BIN/rad-mesh" "$TMP/tex/t.obj" -o "$TMP/tex/t.mesh" 2>&1) || fail "textured mesh: $err"
grep -q "changed: textures averaged: 1 map_Kd texture(s) multiply their Kd by their mean linear colour; replacing a Kd of 0 or none in painted" <<<"$err" || fail "texture summary: $err"
"$BIN/rad-info" --csv "$TMP/tex/t.mesh" | awk -F, '$3 == "painted" && $11 > 0.01 && $11 < 1 { ok = 1 } END { exit !ok }' || fail "texture mean not applied: $("$BIN/rad-info" --csv "$TMP/tex/t.mesh")"
rm "$TMP/tex/render.png"
err=$("$BIN/rad-mesh" "$TMP/tex/t.obj" -o "$TMP/tex/t.mesh" 2>&1) || fail "a missing texture must not fail: $err"
grep -q "warning: .*painted: texture .*render.png not found (the material keeps its Kd)" <<<"$err" || fail "missing texture warning: $err"

# Mixing light groups at shade time (a room1 with daylight and lamp, solved once).
python3 "$SRC/scenes/generate.py" room1 "$TMP/relight" --lamp || fail "generate room1 --lamp"
"$BIN/rad-mesh" "$TMP/relight/room1-lamp.obj" -o "$TMP/g.mesh" --max-edge 1 -q 2>/dev/null || fail "lamp mesh"
"$BIN/rad-ff" "$TMP/g.mesh" -o "$TMP/g.ff" --method hemisphere --rays 300 -q || fail "lamp ff"
"$BIN/rad-solve" "$TMP/g.mesh" "$TMP/g.ff" -o "$TMP/g.rad" --light-groups -q || fail "grouped solve"
RV="$SRC/scenes/room1/room1.vf"
"$BIN/rad-shade" "$TMP/g.mesh" "$TMP/g.rad" -o "$TMP/mix.exr" --view-file "$RV" -x 32 -y 32 --mix lamp=0.5,0.4,0.2 --layers -q || fail "--mix --layers"
channels=$(exrheader "$TMP/mix.exr")
for ch in R G B daylight.R daylight.G daylight.B lamp.R lamp.G lamp.B; do
  grep -q "^ *$ch, 32-bit floating-point" <<<"$channels" || fail "EXR lacks channel $ch: $channels"
done
"$BIN/rad-shade" "$TMP/g.mesh" "$TMP/g.rad" -o "$TMP/off.exr" --view-file "$RV" -x 32 -y 32 --mix-only --mix lamp=1 -q || fail "--mix-only"
expect_error "--mix: no light group 'sun'" "$TMP/x.exr" "$BIN/rad-shade" "$TMP/g.mesh" "$TMP/g.rad" -o "$TMP/x.exr" --view-file "$RV" --mix sun=1
expect_error "daylight, lamp" "$TMP/x.exr" "$BIN/rad-shade" "$TMP/g.mesh" "$TMP/g.rad" -o "$TMP/x.exr" --view-file "$RV" --mix sun=1
expect_error "has no light groups to mix" "$TMP/x.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.exr" --view-file "$VF" --mix light=2
expect_error "--png and -o both write" "$TMP/both.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/both.exr" --png "$TMP/./both.exr" --view-file "$VF"
# -o is the OpenEXR image and --png the PNG: a name saying the other format is refused.
expect_error "-o writes the OpenEXR image (high dynamic range): name it .exr, and give --png $TMP/view.png" "$TMP/view.png" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/view.png" --view-file "$VF"
expect_error "--png $TMP/view.EXR: --png writes a tone-mapped PNG: name it .png" "$TMP/named.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/named.exr" --png "$TMP/view.EXR" --view-file "$VF"
# Nonsense option values are refused with the allowed range.
expect_error "--crease-angle: 'nan' is not a number in [0, 180]" "$TMP/n.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/n.exr" --view-file "$VF" --crease-angle nan
expect_error "--exposure: 'nan' is not a number in [0, 1e+30]" "$TMP/n.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/n.exr" --view-file "$VF" --exposure nan
expect_error "--exposure: '-1'" "$TMP/n.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/n.exr" --view-file "$VF" --exposure -1
# --gather: the same PNG at 1 and 2 threads (samples seeded by index); refused with --albedo.
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/g1.exr" --png "$TMP/g1.png" --view-file "$VF" -x 48 -y 48 --gather 8 --exposure 1 --threads 1 -q || fail "--gather"
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/g2.exr" --png "$TMP/g2.png" --view-file "$VF" -x 48 -y 48 --gather 8 --exposure 1 --threads 2 -q || fail "--gather 2 threads"
cmp -s "$TMP/g1.png" "$TMP/g2.png" || fail "--gather differs between 1 and 2 threads"
expect_error "--gather shades a solution as solved" "$TMP/ga.exr" "$BIN/rad-shade" "$TMP/c.mesh" -o "$TMP/ga.exr" --view-file "$VF" --albedo --gather 8
# Exposure from the solution (#25): two views of one solve get one exposure, and the lamp in
# view of McGuire's box does not blow the picture out (under 1% of the pixels saturated).
"$BIN/rad-mesh" "$SRC/tests/data/cornell-original/CornellBox-Original.obj" -o "$TMP/mc.mesh" -q 2>/dev/null || fail "mesh McGuire"
"$BIN/rad-ff" "$TMP/mc.mesh" -o "$TMP/mc.ff" --method hemisphere --rays 500 -q 2>/dev/null || fail "ff McGuire"
"$BIN/rad-solve" "$TMP/mc.mesh" "$TMP/mc.ff" -o "$TMP/mc.rad" -q || fail "solve McGuire"
e1=$("$BIN/rad-shade" "$TMP/mc.mesh" "$TMP/mc.rad" -o "$TMP/v1.exr" --png "$TMP/v1.png" -x 128 -y 128 \
  --view "-vp 0 1 3.9 -vd 0 0 -1 -vu 0 1 0 -vh 37 -vv 37" 2>&1 | sed -n 's/.*exposure \([0-9.e+-]*\)$/\1/p')
e2=$("$BIN/rad-shade" "$TMP/mc.mesh" "$TMP/mc.rad" -o "$TMP/v2.exr" -x 128 -y 128 \
  --view "-vp 0.5 1.2 2 -vd -0.3 0.1 -1 -vu 0 1 0 -vh 50 -vv 50" 2>&1 | sed -n 's/.*exposure \([0-9.e+-]*\)$/\1/p')
[ -n "$e1" ] && [ "$e1" = "$e2" ] || fail "two views of one solution got exposures '$e1' and '$e2'"
share=$(python3 "$SRC/tests/cli/png_stats.py" "$TMP/v1.png")
python3 -c "import sys; sys.exit(not $share < 0.01)" || fail "lamp in view: $share of the pixels saturated"
# A camera too far to trace rays from is refused as rad-gather refuses such a point (#55), with
# --gather (Embree aborted there) and without.
for g in "" "--gather 4"; do
  expect_error "the camera (-vp): the point is 1e+19 units from the scene" "$TMP/far.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/far.exr" --view "-vp 1e19 0 0 -vd -1 0 0" -x 8 -y 8 $g
done
# A view file that cannot be read is an error, not the default camera (#55 item 2).
expect_error "is a folder, not a text file" "$TMP/vf.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/vf.exr" --view-file "$TMP"
expect_error "/dev/zero:1: holds a NUL byte" "$TMP/vf.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/vf.exr" --view-file /dev/zero
: > "$TMP/empty.vf"
expect_error "empty.vf: holds no view" "$TMP/vf.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/vf.exr" --view-file "$TMP/empty.vf"
expect_error "is a folder, not a text file" "$TMP/vf.glb" "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/vf.glb" --html "$TMP/vf.html" --view-file "$TMP"
# A black solution is said to be black, with how to light it (#53 item 7).
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/dark.rad" --emission light=0 -q 2>/dev/null
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/dark.rad" -o "$TMP/dark.exr" --view-file "$VF" -x 16 -y 16 -q 2> "$TMP/dark.err" || fail "rad-shade on a black solution"
grep -q "dark.rad is black: nothing in it emits light" "$TMP/dark.err" || fail "no warning for a black solution: $(cat "$TMP/dark.err")"
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/lit.exr" --view-file "$VF" -x 16 -y 16 -q 2> "$TMP/lit.err"
grep -q "is black" "$TMP/lit.err" && fail "a lit solution called black"
# --gather alone takes rad-gather's default ray count (#53 item 7).
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/ga.exr" --png "$TMP/ga.png" --view-file "$VF" -x 8 -y 8 --gather -q || fail "--gather with no count"
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/gb.exr" --png "$TMP/gb.png" --view-file "$VF" -x 8 -y 8 --gather 256 -q
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/gc.exr" --png "$TMP/gc.png" --view-file "$VF" -x 8 -y 8 --gather 2 -q
cmp -s "$TMP/ga.png" "$TMP/gb.png" || fail "--gather alone is not --gather 256"
cmp -s "$TMP/ga.png" "$TMP/gc.png" && fail "the comparison cannot tell ray counts apart"
# No camera given: the Cornell box (open towards -z) is seen from its open side, a closed room
# from inside; the printed view gives the same image again.
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/auto.exr" --png "$TMP/auto.png" -x 32 -y 24 2> "$TMP/auto.txt" || fail "rad-shade without a camera"
grep -q 'no camera given: chose --view "-vp .*" (outside, from -z' "$TMP/auto.txt" || fail "the open box is not seen from its open side: $(cat "$TMP/auto.txt")"
chosen=$(sed -n 's/.*chose --view "\([^"]*\)".*/\1/p' "$TMP/auto.txt")
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/again.exr" --png "$TMP/again.png" -x 32 -y 24 --view "$chosen" -q || fail "the printed view"
cmp -s "$TMP/auto.png" "$TMP/again.png" || fail "the printed view does not give the same image"
"$BIN/rad-mesh" "$SRC/scenes/lighting/room.obj" -o "$TMP/room.mesh" -q 2>/dev/null
"$BIN/rad-shade" "$TMP/room.mesh" --albedo -o "$TMP/room.exr" -x 32 -y 24 2> "$TMP/room.txt" || fail "rad-shade without a camera in a closed room"
grep -q "(inside, towards" "$TMP/room.txt" || fail "a closed room is not seen from inside: $(cat "$TMP/room.txt")"
# A closed house drawn z-up (#66 item 5): the camera stands inside at eye height, upright (z
# up); before, the roof was seen from above ("outside, from +z"), the house taken for y-up.
python3 "$SRC/tests/cli/interior_scenes.py" house "$TMP/house.obj"
"$BIN/rad-mesh" "$TMP/house.obj" -o "$TMP/house.mesh" -q 2>/dev/null || fail "mesh the house"
"$BIN/rad-shade" "$TMP/house.mesh" --albedo -o "$TMP/house.exr" -x 32 -y 24 2> "$TMP/house.txt" || fail "rad-shade without a camera in the house"
grep -q 'chose --view "-vp [0-9.]* [0-9.]* 1.[0-9]* -vd [-0-9.]* [-0-9.]* 0 -vu 0 0 1 .*(inside, towards [-+xy]*[,;]' "$TMP/house.txt" || fail "the house is not seen from inside, standing, z up: $(cat "$TMP/house.txt")"
expect_error "--rows renders a band of one camera's image" "$TMP/x.part" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.part" --rows 0/2
# A scene whose every patch emits: rad-shade and rad-bake expose it alike, from the solution
# (over its emitters), not rad-shade from its image and rad-bake at 1.
cat > "$TMP/glow.mtl" <<'MTL'
newmtl glow
Kd 0.5 0.5 0.5
Ke 2 1 0.5
MTL
cat > "$TMP/glow.obj" <<'OBJ'
mtllib glow.mtl
usemtl glow
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
OBJ
"$BIN/rad-mesh" "$TMP/glow.obj" -o "$TMP/glow.mesh" --max-edge 0.25 -q 2>/dev/null || fail "mesh the glowing cube"
"$BIN/rad-ff" "$TMP/glow.mesh" -o "$TMP/glow.ff" -q 2>/dev/null && "$BIN/rad-solve" "$TMP/glow.mesh" "$TMP/glow.ff" -o "$TMP/glow.rad" -q || fail "solve the glowing cube"
shade_exposure=$("$BIN/rad-shade" "$TMP/glow.mesh" "$TMP/glow.rad" -o "$TMP/glow.exr" -x 32 -y 24 2>&1 | sed -n 's/.*exposure \([0-9.e+-]*\)$/\1/p')
bake_exposure=$("$BIN/rad-bake" "$TMP/glow.mesh" "$TMP/glow.rad" -o "$TMP/glow.glb" 2>&1 | sed -n 's/.*exposure \([0-9.e+-]*\)$/\1/p')
[ -n "$shade_exposure" ] && [ "$shade_exposure" = "$bake_exposure" ] || fail "rad-shade's exposure '$shade_exposure' is not rad-bake's '$bake_exposure' on an all-emitting scene"
[ "$bake_exposure" != 1 ] || fail "rad-bake left an all-emitting scene at exposure 1"
# Luminance (#68 item 7): a furnace (a closed cube, every face emitting 1 W/m^2 with
# reflectance 0.5, so B = 1 / (1 - 0.5) = 2 W/m^2 everywhere) seen from inside: every surface
# is 179 x 2 / pi = 113.95 cd/m^2 in --luminance-table, and --falsecolor paints it the colour of
# log10(113.95 / 0.02) / 4 on the scale from 200 down 4 decades.
python3 - "$TMP" <<'PY'
import sys
tmp = sys.argv[1]
v = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]  # index = x + 2y + 4z
quads = [(1, 3, 2, 0), (6, 7, 5, 4), (4, 5, 1, 0), (3, 7, 6, 2), (2, 6, 4, 0), (5, 7, 3, 1)]
with open(f"{tmp}/furnace.obj", "w") as f:
    f.write("mtllib furnace.mtl\n")
    for p in v: f.write("v %d %d %d\n" % p)
    for k, q in enumerate(quads):
        f.write("usemtl %s\n" % ("hot" if k < 3 else "warm"))
        f.write("f %d %d %d %d\n" % tuple(i + 1 for i in q))
with open(f"{tmp}/furnace.mtl", "w") as f:
    f.write("newmtl hot\nKd 0.5 0.5 0.5\nKe 1 1 1\nnewmtl warm\nKd 0.5 0.5 0.5\nKe 1 1 1\n")
PY
{ "$BIN/rad-mesh" "$TMP/furnace.obj" -o "$TMP/furnace.mesh" --max-edge 0.25 -q 2>/dev/null &&
  "$BIN/rad-ff" "$TMP/furnace.mesh" -o "$TMP/furnace.ff" -q && "$BIN/rad-solve" "$TMP/furnace.mesh" "$TMP/furnace.ff" -o "$TMP/furnace.rad" -q; } ||
  fail "solve the furnace"
"$BIN/rad-shade" "$TMP/furnace.mesh" "$TMP/furnace.rad" -o "$TMP/furnace.exr" -x 64 -y 48 --view "-vp 0.5 0.5 0.5 -vd 1 0.3 0.2 -vu 0 0 1 -vh 100 -vv 80" \
  --falsecolor "$TMP/furnace-fc.png" --luminance-table "$TMP/furnace.csv" 2> "$TMP/furnace.err" || fail "rad-shade --falsecolor: $(cat "$TMP/furnace.err")"
grep -qF -- "--falsecolor $TMP/furnace-fc.png: 0.02 to 200 cd/m^2, logarithmic" "$TMP/furnace.err" || fail "the scale: $(cat "$TMP/furnace.err")"
python3 - "$TMP/furnace.csv" "$TMP/furnace-fc.png" "$SRC/tests/cli" <<'PY' || fail "the furnace's luminance"
import csv, math, sys
sys.path.insert(0, sys.argv[3])
from png_stats import read_png
rows = list(csv.DictReader(open(sys.argv[1])))
want = 179 * 2 / math.pi
assert [r["surface"] for r in rows] == ["hot", "warm"], rows
assert sum(int(r["pixels"]) for r in rows) == 64 * 48, rows
assert abs(sum(float(r["share"]) for r in rows) - 1) < 1e-5, rows
for r in rows:
    for key in ("mean_cd_m2", "max_cd_m2"):
        assert abs(float(r[key]) / want - 1) < 0.005, (r, want)
# The picture: 64 x 48 of the image, then the legend; every image pixel the furnace's colour.
width, height, pixels = read_png(sys.argv[2])
t = math.log10(want / 0.02) / 4
stops = [(0.0, 0.05, 0.05, 0.35), (0.2, 0.10, 0.30, 0.90), (0.4, 0.10, 0.75, 0.75),
         (0.6, 0.40, 0.85, 0.20), (0.8, 0.95, 0.80, 0.10), (1.0, 0.85, 0.10, 0.10)]
k = next(i for i in range(1, len(stops)) if t <= stops[i][0])
w = (t - stops[k - 1][0]) / (stops[k][0] - stops[k - 1][0])
colour = [round(255 * (stops[k - 1][c] + (stops[k][c] - stops[k - 1][c]) * w)) for c in (1, 2, 3)]
for y in range(48):
    for x in range(64):
        got = pixels[y][3 * x:3 * x + 3]
        assert all(abs(a - b) <= 2 for a, b in zip(got, colour)), (x, y, list(got), colour)
PY
expect_error "--falsecolor and --luminance-table show luminance: not with --albedo" "$TMP/x.exr" \
  "$BIN/rad-shade" "$TMP/furnace.mesh" -o "$TMP/x.exr" --albedo --falsecolor "$TMP/x.png"
expect_error "--falsecolor and --luminance-table are written by a run of the whole image" "$TMP/x.exr" \
  "$BIN/rad-shade" --merge "$TMP/furnace.exr" -o "$TMP/x.exr" --falsecolor "$TMP/x.png"
expect_error "--falsecolor-decades 12: give 1 to 9 decades" "$TMP/x.exr" \
  "$BIN/rad-shade" "$TMP/furnace.mesh" "$TMP/furnace.rad" -o "$TMP/x.exr" -x 8 -y 8 --falsecolor "$TMP/x.png" --falsecolor-decades 12
finish
