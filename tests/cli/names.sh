# Names that are not UTF-8, too long, or hold control characters (#55 item 4): one rule for
# every output (radfmt/names.hpp): rad-mesh makes a scene's names UTF-8 text of at most 200
# bytes (Latin-1 bytes transcoded, control characters '?'), tools refuse such names given on the
# command line or in a layout, and every output reads back (glb, EXR layers, .rad headers).
source "$(dirname "$0")/lib.sh"
mkdir -p "$TMP/s"
long=$(printf 'L%.0s' $(seq 1 300))
# A box with a Latin-1 material name ("caf\xe9"), a Latin-1 group, and a lamp of 300 characters.
python3 - "$TMP/s" "$long" <<'PY'
import sys
d, long = sys.argv[1], sys.argv[2]
obj = b"mtllib s.mtl\n"
for x, y, z in [(0,0,0),(1,0,0),(0,1,0),(1,1,0),(0,0,1),(1,0,1),(0,1,1),(1,1,1),(0.4,0.99,0.4),(0.6,0.99,0.4),(0.6,0.99,0.6),(0.4,0.99,0.6)]:
    obj += b"v %g %g %g\n" % (x, y, z)
obj += b"g caf\xe9\nusemtl caf\xe9\nf 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n"
obj += b"g lamp\nusemtl " + long.encode() + b"\nf 9 10 11 12\n"
open(d + "/s.obj", "wb").write(obj)
open(d + "/s.mtl", "wb").write(b"newmtl caf\xe9\nKd 0.5 0.5 0.5\nnewmtl " + long.encode() + b"\nKd 0 0 0\nKe 10 10 10\n")
PY
"$BIN/rad-mesh" "$TMP/s/s.obj" -o "$TMP/s.mesh" --two-sided lamp 2> "$TMP/mesh.err" || fail "rad-mesh: $(cat "$TMP/mesh.err")"
grep -q "changed: names: [0-9]* material name(s) made UTF-8 text.*first 'caf\\\\xE9' is 'café'" "$TMP/mesh.err" || fail "no changed: line for the material names: $(cat "$TMP/mesh.err")"
grep -q "changed: names: 1 group name(s)" "$TMP/mesh.err" || fail "no changed: line for the group: $(cat "$TMP/mesh.err")"
"$BIN/rad-info" --csv "$TMP/s.mesh" | grep -q ",café,café," || fail "Latin-1 not transcoded: $("$BIN/rad-info" --csv "$TMP/s.mesh" | sed -n 2p)"
"$BIN/rad-ff" "$TMP/s.mesh" -o "$TMP/s.ff" -q 2>/dev/null || fail "rad-ff"
"$BIN/rad-solve" "$TMP/s.mesh" "$TMP/s.ff" -o "$TMP/s.rad" --light-groups -q || fail "rad-solve --light-groups"
# The lamp's group is named after its 200-byte material name: the EXR keeps its R, G and B.
"$BIN/rad-shade" "$TMP/s.mesh" "$TMP/s.rad" -o "$TMP/s.exr" --layers -x 16 -y 16 \
  --view "-vp 0.5 0.5 0.5 -vd 0 -1 0 -vu 0 0 1 -vh 90 -vv 90" -q || fail "rad-shade --layers"
if command -v exrheader >/dev/null; then
  for c in R G B; do
    exrheader "$TMP/s.exr" | grep -q "$(printf 'L%.0s' $(seq 1 200)).$c" || fail "layer channel $c lost"
  done
fi
# rad-bake writes a glb and a page whose JSON holds the names (it exited 3 on Latin-1).
"$BIN/rad-bake" "$TMP/s.mesh" "$TMP/s.rad" -o "$TMP/s.glb" -q || fail "rad-bake on transcoded names"
python3 - "$TMP/s.glb" <<'PY' || fail "the glb's JSON does not read back"
import json, struct, sys
data = open(sys.argv[1], "rb").read()
length = struct.unpack("<I", data[12:16])[0]
json.loads(data[20:20 + length].decode("utf-8"))
PY
# A light group's name from the command line: control characters and over 200 bytes refused.
expect_error "--group: 'x?y' is a name holding a control character" "$TMP/g.rad" "$BIN/rad-solve" "$TMP/s.mesh" "$TMP/s.ff" -o "$TMP/g.rad" --group $'x\ny'=caf%C3%A9
expect_error "is a name of 300 bytes (at most 200)" "$TMP/g.rad" "$BIN/rad-solve" "$TMP/s.mesh" "$TMP/s.ff" -o "$TMP/g.rad" --group "$long=café"
expect_error "is a name that is not UTF-8 text" "$TMP/g.rad" "$BIN/rad-solve" "$TMP/s.mesh" "$TMP/s.ff" -o "$TMP/g.rad" --group $'caf\xe9'=café
finish
