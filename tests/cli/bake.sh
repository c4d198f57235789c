# rad-bake: vertex-colour, lightmap and light-group glbs pass the Khronos glTF-Validator (the
# Cornell box and two public fixtures); the viewer page, in headless Chromium, shows what
# rad-shade shows from the same camera, and its sliders relight as rad-shade --mix does.
source "$(dirname "$0")/lib.sh"
WEB="$SRC/web"
[ -d "$WEB/node_modules/gltf-validator" ] && [ -d "$WEB/node_modules/puppeteer-core" ] ||
  { echo "FAIL: web/node_modules is missing: run scripts/install-deps"; exit 1; }
command -v chromium >/dev/null || { echo "FAIL: chromium is missing: run scripts/install-deps"; exit 1; }
validate() { node "$WEB/validate-gltf.mjs" "$@" || fail "glTF-Validator: $*"; }
# page_matches PAGE REFERENCE [SETTINGS]: the page's pixels within 1% of the reference's.
page_matches() {
  local out
  out=$(node "$WEB/test-viewer.mjs" --page "$1" --reference "$2" --max-difference 0.01 ${3:+--set "$3"} 2>&1) ||
    fail "page $1 against $2 ${3:-}: $out"
  echo "$out"
}

cornell_mesh 0.05
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/c.rad" -q
VF="$SRC/scenes/cornell/cornell.vf"
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/c.exr" --view-file "$VF" --png "$TMP/c.png" -q

# Vertex colours and a 512x512 lightmap, each with its page.
"$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/vc.glb" --html "$TMP/vc.html" --view-file "$VF" -q ||
  fail "vertex-colour bake"
err=$("$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/lm.glb" --lightmap 512 --html "$TMP/lm.html" \
  --view-file "$VF" --exr "$TMP/lm.exr" --png "$TMP/lm.png" 2>&1) || fail "lightmap bake: $err"
grep -q "rad-bake: wrote .*lm.glb (971 patches, 16 charts in a 512x512 lightmap at [0-9.]* texels/m), exposure" <<<"$err" || fail "summary: $err"
head -c 8 "$TMP/lm.png" | od -An -c | grep -q "P   N   G" || fail "atlas png"
if command -v exrheader >/dev/null; then
  exrheader "$TMP/lm.exr" | grep -q "dataWindow (type box2i): (0 0) - (511 511)" || fail "atlas exr size"
fi
# For engines: the scene's materials and the irradiance atlas, shown by three.js's
# MeshStandardMaterial with the atlas as its light map (the page given that glb instead).
"$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/lm-u.glb" --lightmap 512 --engine "$TMP/engine.glb" -q ||
  fail "engine bake"
validate "$TMP/vc.glb" "$TMP/lm.glb" "$TMP/engine.glb"
page_matches "$TMP/vc.html" "$TMP/c.png"
page_matches "$TMP/lm.html" "$TMP/c.png"
out=$(node "$WEB/test-viewer.mjs" --page "$TMP/lm.html" --glb "$TMP/engine.glb" --reference "$TMP/c.png" --max-difference 0.01 2>&1) ||
  fail "engine glb in three.js: $out"
echo "$out"
# The comparison can fail: at 1.5 times the exposure the page is far from rad-shade's image.
node "$WEB/test-viewer.mjs" --page "$TMP/lm.html" --reference "$TMP/c.png" --max-difference 0.01 \
  --set '{"exposure": 1.5}' >/dev/null 2>&1 && fail "the page at another exposure matched"
# The same bake twice, and at one thread: the same bytes (the same command line, from two
# folders, as the glb records it).
mkdir -p "$TMP/one" "$TMP/two"
(cd "$TMP/one" && "$BIN/rad-bake" ../c.mesh ../c.rad -o lm.glb --lightmap 512 -q)
(cd "$TMP/two" && "$BIN/rad-bake" ../c.mesh ../c.rad -o lm.glb --lightmap 512 -q --threads 1)
cmp -s "$TMP/one/lm.glb" "$TMP/two/lm.glb" || fail "two bakes differ (one at one thread)"

# Light groups: the lamp and a glowing green wall, one lightmap each; the page's sliders mix
# them as rad-shade --mix does.
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/g.rad" --light-groups --emission green=1,3,0.5 -q
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/g.rad" -o "$TMP/g.exr" --view-file "$VF" --png "$TMP/g.png" --exposure 0.7 -q
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/g.rad" -o "$TMP/gm.exr" --view-file "$VF" --mix light=0.3 --png "$TMP/gm.png" --exposure 0.7 -q
"$BIN/rad-bake" "$TMP/c.mesh" "$TMP/g.rad" -o "$TMP/g.glb" --lightmap 512 --html "$TMP/g.html" \
  --view-file "$VF" --exposure 0.7 --exr "$TMP/g-atlas.exr" -q || fail "light-group bake"
validate "$TMP/g.glb"
page_matches "$TMP/g.html" "$TMP/g.png"
page_matches "$TMP/g.html" "$TMP/gm.png" '{"weights": {"light": 0.3}}'
# The same by moving the slider, as a user would.
out=$(node "$WEB/test-viewer.mjs" --page "$TMP/g.html" --reference "$TMP/gm.png" --max-difference 0.01 --slide light=0.3 2>&1) ||
  fail "the light slider: $out"
echo "$out"
if command -v exrheader >/dev/null; then
  exrheader "$TMP/g-atlas.exr" | grep -q "light.R" || fail "no light-group layers in the atlas EXR"
fi

# Public fixtures: the original Cornell box (OBJ) and the glTF living room (given a light).
"$BIN/rad-mesh" "$SRC/tests/data/cornell-original/CornellBox-Original.obj" -o "$TMP/o.mesh" -q 2>/dev/null
"$BIN/rad-ff" "$TMP/o.mesh" -o "$TMP/o.ff" -q 2>/dev/null
"$BIN/rad-solve" "$TMP/o.mesh" "$TMP/o.ff" -o "$TMP/o.rad" -q
"$BIN/rad-mesh" "$SRC/tests/data/living-room/living_room.glb" -o "$TMP/lr.mesh" -q 2>/dev/null
"$BIN/rad-ff" "$TMP/lr.mesh" -o "$TMP/lr.ff" --method hemisphere --rays 256 -q 2>/dev/null
"$BIN/rad-solve" "$TMP/lr.mesh" "$TMP/lr.ff" -o "$TMP/lr.rad" --emission ceiling=30 -q
# Light groups: a second emitter in each (the short box, the table top).
"$BIN/rad-solve" "$TMP/o.mesh" "$TMP/o.ff" -o "$TMP/o-g.rad" --light-groups --emission shortBox=2,2,2 -q
"$BIN/rad-solve" "$TMP/lr.mesh" "$TMP/lr.ff" -o "$TMP/lr-g.rad" --light-groups --emission ceiling=30 --emission top=3 -q
for s in o lr; do
  "$BIN/rad-bake" "$TMP/$s.mesh" "$TMP/$s.rad" -o "$TMP/$s-vc.glb" -q || fail "$s vertex colours"
  "$BIN/rad-bake" "$TMP/$s.mesh" "$TMP/$s.rad" -o "$TMP/$s-lm.glb" --lightmap 1024 -q || fail "$s lightmap"
  "$BIN/rad-bake" "$TMP/$s.mesh" "$TMP/$s-g.rad" -o "$TMP/$s-g.glb" --lightmap 1024 -q || fail "$s light groups"
  validate "$TMP/$s-vc.glb" "$TMP/$s-lm.glb" "$TMP/$s-g.glb"
done

# Bad input: a stale radiosity, options that need --lightmap or --html, a page without a camera.
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/other.mesh" --max-edge 0.2 -q
expect_error "does not belong to" "$TMP/x.glb" "$BIN/rad-bake" "$TMP/other.mesh" "$TMP/c.rad" -o "$TMP/x.glb"
expect_error "need --lightmap SIZE" "$TMP/x.glb" "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.glb" --engine "$TMP/e.glb"
expect_error "need --lightmap SIZE" "$TMP/x.glb" "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.glb" --png "$TMP/x.png"
expect_error "--html needs a camera" "$TMP/x.glb" "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.glb" --html "$TMP/x.html"
expect_error "are for the --html page" "$TMP/x.glb" "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.glb" --view-file "$VF"
expect_error "do not fit a 64x64 lightmap at" "$TMP/x.glb" "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.glb" --lightmap 64 --texels-per-metre 1000
[ -e "$TMP/x.html" ] && fail "a page was written by a failed run"
# The work a lightmap implies is estimated and checked before baking (#55 item 3).
expect_error "--lightmap 4096 with 0 light group(s) needs about 528.0 MiB, more than --max-memory 100.0 MiB" "$TMP/mem.glb" \
  "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/mem.glb" --lightmap 4096 --max-memory 100M
# The default follows the job's limit, not the machine's RAM (#70 item 10): under ulimit -v
# 800000 (781 MiB) a 2.1 GiB atlas is refused before baking; before, it was baked until the
# allocation failed (exit 2, "out of memory", after the work).
expect_error "needs about 2.1 GiB, more than --max-memory's default 625.0 MiB (80% of the address-space limit (ulimit -v), 781.2 MiB)" "$TMP/mem.glb" \
  bash -c 'ulimit -v 800000 && exec "$@"' limited "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/mem.glb" --lightmap 8192

# A daylight solution's page (#51, #69 item 5): it relights by date and time from a basis of
# the sky's groups and the sun patches' own, under a clear, partly cloudy or overcast day or a
# weather file's hour, the sun's beam sharp (shadow maps in the page, rays in rad-shade); at
# each it shows what rad-shade shows under the same sky (--sky clear, partly-cloudy, overcast,
# epw:FILE) at the same place and time, within 1%, at rad-shade's own exposure: the sun
# patches' shapes and brightness included (the page as it drew the patch before, blurred
# over its sky patch, was 2.8% from rad-shade's sharp one at 10 October 14:00). The view looks at the floor the sun lights, not at
# the window: rad-shade draws nothing behind glass, the page draws the sky (checked apart).
D="$SRC/scenes/daylight-room"
EPW="$SRC/tests/data/denver-tmy3.epw"
"$BIN/rad-mesh" "$D/daylight-room-glazed.obj" -o "$TMP/d.mesh" --max-edge 0.5 -q 2>/dev/null
"$BIN/rad-ff" "$TMP/d.mesh" -o "$TMP/d.ff" --rays 1024 -q
"$BIN/rad-ff" "$TMP/d.mesh" --sky reinhart:1 -o "$TMP/d.sky" -q
"$BIN/rad-solve" "$TMP/d.mesh" "$TMP/d.ff" --direct "$TMP/d.sky" -o "$TMP/d.rad" -q
DV="-vp 2 2.6 0.5 -vd 0 -0.75 0.66 -vu 0 1 0 -vh 60 -vv 60"
PLACE=39.83,-104.65,-7
err=$("$BIN/rad-bake" "$TMP/d.mesh" "$TMP/d.rad" -o "$TMP/d.glb" --lightmap 128 --html "$TMP/d.html" \
  --location $PLACE --epw "$EPW" --view "$DV" 2>&1) || fail "daylight page: $err"
grep -q "relights by date and time from [0-9]* components of the solution's 146 sky groups (over a year of clear, partly cloudy and overcast days and the weather file's hours" <<<"$err" ||
  fail "daylight page summary: $err"
validate "$TMP/d.glb"
for when in "2025-03-21 12:00 80 12 clear" "2025-06-21 09:00 172 9 clear" "2025-06-21 02:00 172 2 clear" \
  "2025-10-10 14:00 283 14 clear" "2025-06-21 10:00 172 10 partly-cloudy" "2025-12-21 12:00 355 12 overcast" \
  "2025-12-21 11:00 355 11 weather" "2025-03-21 15:00 80 15 weather"; do
  set -- $when
  if [ "$5" = weather ]; then sky=(--sky "epw:$EPW"); else sky=(--sky "$5" --location $PLACE); fi
  out=$("$BIN/rad-shade" "$TMP/d.mesh" "$TMP/d.rad" -o "$TMP/dref.exr" --png "$TMP/dref.png" "${sky[@]}" \
    --date "$1" --time "$2" --view "$DV" 2>&1) || fail "rad-shade --sky $5 at $1 $2: $out"
  exposure=$(sed -n 's/.*exposure \([0-9.e+-]*\)$/\1/p' <<<"$out" | head -1)
  [ "$4" = 2 ] && exposure=0.01 # night: nothing to expose
  page_matches "$TMP/d.html" "$TMP/dref.png" "{\"day\":$3,\"hour\":$4,\"sky\":\"$5\",\"exposure\":$exposure}" >/dev/null
done
# Another sky than the reference's is not within 1% (the comparison can fail).
node "$WEB/test-viewer.mjs" --page "$TMP/d.html" --reference "$TMP/dref.png" --max-difference 0.01 \
  --set '{"day":80,"hour":15,"sky":"overcast","exposure":'"$exposure"'}' >/dev/null 2>&1 &&
  fail "the page under an overcast sky matched the weather file's hour"
# The window drawn as glass: looking at it, the page shows the sky outside (its mean luminance
# as a display value, pi L / 179 x exposure) through the pane's transmittance, the linear
# product encoded to sRGB as every pixel is.
WV="-vp 2 1.5 0.3 -vd 0 -0.25 1 -vu 0 1 0 -vh 75 -vv 75"
"$BIN/rad-bake" "$TMP/d.mesh" "$TMP/d.rad" -o "$TMP/w.glb" --lightmap 128 --html "$TMP/w.html" \
  --location $PLACE --view "$WV" -q || fail "window page"
probe=$(node "$WEB/test-viewer.mjs" --page "$TMP/w.html" --probe 256,160 --set '{"day":80,"hour":12,"sky":"clear","exposure":0.005}' 2>&1) ||
  fail "probing the window: $probe"
python3 - "$probe" <<'PY' || fail "the window: $probe"
import json, sys
p = json.loads(sys.argv[1].split("probe: ", 1)[1])
linear = min(1.0, p["panes"][0] * p["outside"][0])
srgb = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
assert p["panes"] == [0.7000000000000001] or abs(p["panes"][0] - 0.7) < 1e-9, p
assert 0.05 < p["outside"][0] < 1, p  # the sky is seen, not black, not clipped
assert all(abs(v - 255 * srgb) <= 2 for v in p["pixel"]), (p, 255 * srgb)
PY
expect_error "bake its page with --html, --lightmap SIZE and --location" "$TMP/x.glb" \
  "$BIN/rad-bake" "$TMP/d.mesh" "$TMP/d.rad" -o "$TMP/x.glb"
# Another mesh's daylight solution is refused before its basis is made of it.
expect_error "does not belong to" "$TMP/x.glb" "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/d.rad" -o "$TMP/x.glb" \
  --lightmap 128 --html "$TMP/x.html" --location $PLACE --view "$DV"
expect_error "is none" "$TMP/x.glb" "$BIN/rad-bake" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.glb" --location $PLACE
finish
