# Mirrors and glass through the chain (#50): McGuire's sphere box (a mirror ball and a glass
# ball) meshes with its specular parts said, rad-ff follows them (and the methods that cannot
# say so), a .ff is tied to the specular parts it was made for, the mirror ball mirrors the
# room in rad-shade's image, and light through clear glass reaches the floor under it.
source "$(dirname "$0")/lib.sh"
D="$SRC/tests/data/cornell-sphere"
VIEW="-vp 0 1 3.4 -vd 0 0 -1 -vu 0 1 0 -vh 40 -vv 40"
cp "$D"/CornellBox-Sphere.* "$TMP/"
# The same box with the balls made plain diffuse (illum 2), and with clear glass.
sed 's/illum [357]/illum 2/' "$D/CornellBox-Sphere.mtl" > "$TMP/diffuse.mtl"
sed 's/CornellBox-Sphere.mtl/diffuse.mtl/' "$D/CornellBox-Sphere.obj" > "$TMP/diffuse.obj"

err=$("$BIN/rad-mesh" "$TMP/CornellBox-Sphere.obj" -o "$TMP/s.mesh" --max-edge 0.2 2>&1) || fail "rad-mesh: $err"
grep -q "material 'rightSphere': refracting boundary of a medium of index 2.5" <<<"$err" || fail "no note of the glass: $err"
"$BIN/rad-mesh" "$TMP/CornellBox-Sphere.obj" -o "$TMP/clear.mesh" --max-edge 0.2 \
  --transmittance rightSphere=1 -q 2>/dev/null || fail "rad-mesh --transmittance"
"$BIN/rad-mesh" "$TMP/diffuse.obj" -o "$TMP/d.mesh" --max-edge 0.2 -q 2>/dev/null || fail "rad-mesh diffuse"
expect_error "material 'leftSphere' is a mirror in its file" "$TMP/x.mesh" \
  "$BIN/rad-mesh" "$TMP/CornellBox-Sphere.obj" -o "$TMP/x.mesh" --transmittance leftSphere=0.5
expect_error "--thin leftSphere: material 'leftSphere' is a mirror" "$TMP/x.mesh" \
  "$BIN/rad-mesh" "$TMP/CornellBox-Sphere.obj" -o "$TMP/x.mesh" --thin leftSphere

"$BIN/rad-info" "$TMP/s.mesh" | grep -q "mirrors and glass: leftSphere (fresnel), rightSphere (dielectric)" \
  || fail "rad-info does not list the mesh's mirrors and glass"

# rad-ff: auto picks the rays that follow them; methods that do not, say so.
err=$("$BIN/rad-ff" "$TMP/s.mesh" -o "$TMP/s.ff" --rays 1024 2>&1) || fail "rad-ff: $err"
grep -q "hemisphere .*mirrors and glass" <<<"$err" || fail "auto did not say why hemisphere: $err"
for m in analytic pairwise hierarchical; do
  expect_error "--method $m does not follow light through mirrors and glass" "$TMP/x.ff" \
    "$BIN/rad-ff" "$TMP/s.mesh" -o "$TMP/x.ff" --method $m
done
"$BIN/rad-info" "$TMP/s.ff" > "$TMP/info.txt"
grep -q "specular_materials = leftSphere=fresnel,rightSphere=dielectric" "$TMP/info.txt" || fail "the .ff does not record its specular parts"
# Deterministic at any thread count.
mkdir "$TMP/one"
(cd "$TMP/one" && cp ../s.mesh . && "$BIN/rad-ff" s.mesh -o s.ff --rays 1024 --threads 1 -q)
(cd "$TMP" && "$BIN/rad-ff" s.mesh -o s2.ff --rays 1024 --threads 2 -q && mv s2.ff s.ff2)
body() { "$BIN/rad-info" "$1" | grep '^size:' || echo "no $1"; }
[ -s "$TMP/one/s.ff" ] && [ "$(body "$TMP/one/s.ff")" = "$(body "$TMP/s.ff2")" ] || fail "rad-ff with mirrors and glass differs at 1 and 2 threads"
"$BIN/rad-ff" "$TMP/clear.mesh" -o "$TMP/clear.ff" --rays 1024 -q || fail "rad-ff clear"
"$BIN/rad-ff" "$TMP/d.mesh" -o "$TMP/d.ff" --rays 1024 -q || fail "rad-ff diffuse"
# A .ff made for other specular parts (the glass's transmittance changed) is stale.
expect_error "is stale" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/clear.mesh" "$TMP/s.ff" -o "$TMP/x.rad"
for m in s clear d; do
  "$BIN/rad-solve" "$TMP/$m.mesh" "$TMP/$m.ff" -o "$TMP/$m.rad" -q || fail "rad-solve $m"
  "$BIN/rad-shade" "$TMP/$m.mesh" "$TMP/$m.rad" -o "$TMP/$m.exr" --png "$TMP/$m.png" --view "$VIEW" \
    -x 128 -y 128 --exposure 4 -q 2>/dev/null || fail "rad-shade $m"
done

# The mirror ball shows the room (bright, with the red wall on its left), where the diffuse
# ball of Kd 0.01 is black.
python3 - "$SRC/tests/cli" "$TMP/s.png" "$TMP/d.png" <<'PY' || fail "the mirror ball does not mirror the room"
import sys
sys.path.insert(0, sys.argv[1])
from png_stats import read_png
def box(path, x0, x1, y0, y1):
    w, h, rows = read_png(path)
    px = [rows[y][3 * x:3 * x + 3] for y in range(y0, y1) for x in range(x0, x1)]
    return [sum(p[c] for p in px) / len(px) for c in range(3)]
mirror, diffuse = box(sys.argv[2], 36, 52, 86, 104), box(sys.argv[3], 36, 52, 86, 104)
left = box(sys.argv[2], 31, 36, 88, 100)  # the ball's left rim: the red wall
print("mirror", mirror, "diffuse", diffuse, "left rim", left)
assert sum(mirror) > 3 * sum(diffuse) + 60, "no brighter than a black ball"
assert left[0] > 1.5 * left[1], "the red wall is not in it"
PY

# Light through the clear glass ball reaches the floor under it (a caustic): more there than
# under the file's dark glass (Tf 0.1), and more than under the diffuse ball.
GRID="0.25 0.2 0.65 0.55 0.002 4 4"
for m in s clear d; do
  "$BIN/rad-gather" "$TMP/$m.mesh" "$TMP/$m.rad" --grid "$GRID" --lux --rays 2048 -q 2>/dev/null \
    | awk '{s += $1} END {printf "%.6g\n", s / NR}' > "$TMP/$m.lux" || fail "rad-gather $m"
done
python3 - "$(cat "$TMP/clear.lux")" "$(cat "$TMP/s.lux")" "$(cat "$TMP/d.lux")" <<'PY' || fail "no light through the glass"
import sys
clear, dark, diffuse = map(float, sys.argv[1:4])
print("under the ball: clear", clear, "file's glass", dark, "diffuse", diffuse)
assert clear > 1.5 * dark and dark > diffuse
PY
# rad-bake: the baked light is diffuse; --engine's glb gives the engine the mirror as a smooth
# metal and the glass its transmission and index, so it can reflect and refract.
"$BIN/rad-bake" "$TMP/s.mesh" "$TMP/s.rad" -o "$TMP/s.glb" --lightmap 128 --engine "$TMP/e.glb" -q \
  || fail "rad-bake"
python3 - "$TMP/e.glb" <<'PY' || fail "the engine glb lacks the specular parameters"
import json, struct, sys
data = open(sys.argv[1], "rb").read()
doc = json.loads(data[20:20 + struct.unpack("<I", data[12:16])[0]])
m = {x["name"]: x for x in doc["materials"]}
assert m["leftSphere"]["pbrMetallicRoughness"]["metallicFactor"] == 1
glass = m["rightSphere"]["extensions"]
assert glass["KHR_materials_ior"]["ior"] == 2.5
assert abs(glass["KHR_materials_transmission"]["transmissionFactor"] - 0.1) < 1e-9
assert "KHR_materials_transmission" in doc["extensionsUsed"]
PY
WEB="$SRC/web"
if [ -d "$WEB/node_modules/gltf-validator" ]; then
  node "$WEB/validate-gltf.mjs" "$TMP/s.glb" "$TMP/e.glb" > /dev/null || fail "glTF-Validator: the glbs with mirrors and glass"
fi
finish
