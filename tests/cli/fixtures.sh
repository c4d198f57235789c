# Real scenes written outside this project (tests/data, from ../shared/fixtures/obj): each
# meshes with default options, says what it repaired, and runs through the whole chain.
source "$(dirname "$0")/lib.sh"
D="$SRC/tests/data"
MC="-vp 0 1 3.9 -vd 0 0 -1 -vu 0 1 0 -vh 37 -vv 37"      # McGuire's boxes (metres)
EC="-vp 278 273 -800 -vd 0 0 1 -vu 0 1 0 -vh 39 -vv 39"   # the original box (millimetres)
TV="-vp 0 0 6 -vd 0 0 -1 -vu 0 1 0 -vh 40 -vv 40"        # the torus
# name | OBJ | view | what rad-mesh must say (regex; "" for nothing) | --max-edge, then rad-solve options
while IFS='|' read -r name obj view expect solve; do
  [ -z "$name" ] && continue
  read -r edge options <<<"$solve"
  err=$(cd "$TMP" && "$BIN/rad-mesh" "$D/$obj" -o "$TMP/$name.mesh" --max-edge "$edge" 2>&1) \
    || fail "$name: rad-mesh with default options: $err"
  if [ -n "$expect" ]; then
    grep -q -- "$expect" <<<"$err" || fail "$name: rad-mesh did not say /$expect/: $err"
  fi
  # Mirrors and glass are understood now, not warned about as black.
  grep -q "nearly black" <<<"$err" && fail "$name: rad-mesh still calls a material nearly black: $err"
  "$BIN/rad-ff" "$TMP/$name.mesh" -o "$TMP/$name.ff" --method hemisphere --rays 400 -q 2>/dev/null || fail "$name: rad-ff"
  # shellcheck disable=SC2086
  "$BIN/rad-solve" "$TMP/$name.mesh" "$TMP/$name.ff" -o "$TMP/$name.rad" -q $options 2>/dev/null || fail "$name: rad-solve"
  "$BIN/rad-shade" "$TMP/$name.mesh" "$TMP/$name.rad" -o "$TMP/$name.exr" --view "${!view}" -x 48 -y 48 -q 2>/dev/null || fail "$name: rad-shade"
done <<'LIST'
original|cornell-original/CornellBox-Original.obj|MC|triangulated: 1 non-planar face(s).*line 62|0.2
pathed|cornell-original/variant-pathed/CornellBox-Original.obj|MC|changed: material library 'scenes/CornellBox-Original.mtl' (line 12) as .*variant-pathed/CornellBox-Original.mtl (found by its file name|0.2
sphere|cornell-sphere/CornellBox-Sphere.obj|MC|material 'leftSphere': mirror, reflectance 0.95,0.95,0.95 at normal incidence (Fresnel)|0.2
water|cornell-water/CornellBox-Water.obj|MC|material 'water': refracting boundary of a medium of index 1.33|0.2
embree|embree-cornell/cornell_box.obj|EC|material 'light' has Ka 20,20,20 (brighter than 1) and no Ke: did you mean Ke?|100 --reflectance white=0.75 --reflectance red=0.75,0,0 --reflectance green=0,0.75,0 --reflectance light=0.75 --emission light=20
nomaterial|no-material/no_material.obj|EC|defaulted: 18 face(s) without a known material (first at line 24)|100 --emission default=1
missing|no-material/missing_material_file.obj|EC|material(s) not defined in any material library: white (line 11), light (line 32)|100 --emission light=1
torus|torus-creases/catmark_torus_creases0.obj|TV|defaulted: 32 face(s) without a known material (first at line 62)|0.5 --emission default=1
toruslit|torus-creases/torus-lit.obj|TV||0.5
LIST
# The original box refuses Kd 1 at solve time, listing every material at once, before the
# form factors are read (a missing .ff is not even looked at).
err=$("$BIN/rad-solve" "$TMP/embree.mesh" "$TMP/no-such.ff" -o "$TMP/x.rad" 2>&1); rc=$?
[ $rc -eq 1 ] || fail "Kd 1 accepted (exit $rc): $err"
for m in white red green light; do grep -q "material '$m' has reflectance" <<<"$err" || fail "refusal lacks $m: $err"; done
grep -q "no-such.ff" <<<"$err" && fail "the form factors were read before the materials were checked: $err"
finish
