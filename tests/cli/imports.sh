# Hostile imports (#28): what would hang, crash or exhaust assimp is refused or ends in an
# error naming the file, never in the tool's death; a scene reads nothing outside its folder.
source "$(dirname "$0")/lib.sh"
cd "$TMP"
# Each case within a time bound: a hang is a failure, not a stuck suite.
bounded() { timeout 60 "$@"; }

# A PLY cut short inside its header (94 bytes, no end_header): assimp reads on forever.
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n' > cut.ply
expect_error "cut.ply: PLY header has no 'end_header' line (a truncated file?)" out.mesh bounded "$BIN/rad-mesh" cut.ply -o out.mesh

# A PLY vertex of NaN (binary and ascii): assimp drops it and a quad quietly becomes less.
python3 - <<'PY'
import struct
head = ("ply\nformat {}\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n")
nan = float("nan")
open("nan.ply", "wb").write(head.format("binary_little_endian 1.0").encode() +
                            struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, nan, 0, 1, 0) +
                            struct.pack("<B4i", 4, 0, 1, 2, 3))
open("nan-ascii.ply", "w").write(head.format("ascii 1.0") + "0 0 0\n1 0 0\n1 1 nan\n0 1 0\n4 0 1 2 3\n")
PY
expect_error "nan.ply: vertex 2 has z that is not a finite number" out.mesh bounded "$BIN/rad-mesh" nan.ply -o out.mesh
expect_error "nan-ascii.ply: vertex 2 has z that is not a finite number" out.mesh bounded "$BIN/rad-mesh" nan-ascii.ply -o out.mesh

# COLLADA with an index of 1e30: assimp loops with its memory growing. The time limit and the
# memory limit each end it, as an error naming the file and which limit.
cat > huge.dae <<'DAE'
<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><up_axis>Y_UP</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 1e30</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
DAE
expect_error "huge.dae: the importer (assimp) failed on this file (time: no result after 2 s; --import-timeout S allows longer); nothing was written" \
  out.mesh bounded "$BIN/rad-mesh" huge.dae -o out.mesh --import-timeout 2 --import-memory 16G
expect_error "huge.dae: the importer (assimp) failed on this file (memory: over the limit of 300.0 MiB; --import-memory SIZE allows more)" \
  out.mesh bounded "$BIN/rad-mesh" huge.dae -o out.mesh --import-memory 300M
[ -z "$(ls -A | grep -i tmp)" ] || fail "temporary left: $(ls -A)"

# glTF: one triangle in a data: buffer, then variations.
python3 - <<'PY'
import copy, json
doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
       "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
       "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                      "min": [0, 0, 0], "max": [1, 1, 0]}],
       "bufferViews": [{"buffer": 0, "byteLength": 36}],
       "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,"
                    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]}
def write(name, change):
    d = copy.deepcopy(doc); change(d); json.dump(d, open(name, "w"))
write("ok.gltf", lambda d: None)
def deep(d):
    d["nodes"] = [{"children": [i + 1]} for i in range(19999)] + [{"mesh": 0}]
write("deep.gltf", deep)
write("cycle.gltf", lambda d: d.update(nodes=[{"mesh": 0, "children": [1]}, {"children": [0]}]))
write("twoparents.gltf", lambda d: d.update(nodes=[{"children": [2]}, {"children": [2]}, {"mesh": 0}],
                                              scenes=[{"nodes": [0, 1]}]))
write("outside.gltf", lambda d: d["buffers"][0].update(uri="../secret.bin"))
write("passwd.gltf", lambda d: d["buffers"][0].update(uri="../../../../../../etc/passwd"))
write("absolute.gltf", lambda d: d["buffers"][0].update(uri="/etc/passwd"))
write("fifo.gltf", lambda d: d["buffers"][0].update(uri="fifo.bin"))
write("negative.gltf", lambda d: d["accessors"][0].update(byteOffset=-4))
write("huge.gltf", lambda d: d["accessors"][0].update(byteOffset=2**64))
write("past.gltf", lambda d: d["accessors"][0].update(count=4))
write("view.gltf", lambda d: d["bufferViews"][0].update(byteLength=40))
write("image.gltf", lambda d: d.update(images=[{"uri": "../../x.png"}]))
# Every form of a path that reaches a file outside (#55 item 1): backslashes, escapes mixed in.
for name, uri in [("back.gltf", "..\\secret.bin"), ("mixed.gltf", "x/..\\..\\secret.bin"),
                  ("escaped.gltf", "%2e%2e/secret.bin"), ("slash.gltf", "..%2fsecret.bin"),
                  ("fileuri.gltf", "file:../secret.bin"), ("backfifo.gltf", "..\\sub\\fifo.bin")]:
    write(name, lambda d, uri=uri: d["buffers"][0].update(uri=uri))
PY
"$BIN/rad-mesh" ok.gltf -o ok.mesh -q 2>/dev/null || fail "the plain glTF triangle"
mkdir -p sub && cp outside.gltf sub/
python3 -c "import struct, sys; sys.stdout.buffer.write(struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0))" > secret.bin
mkfifo sub/fifo.bin && cp fifo.gltf sub/
expect_error "deep.gltf: the node hierarchy is over 1000 levels deep" out.mesh bounded "$BIN/rad-mesh" deep.gltf -o out.mesh
expect_error "cycle.gltf: the node hierarchy has a cycle" out.mesh bounded "$BIN/rad-mesh" cycle.gltf -o out.mesh
expect_error "twoparents.gltf: node 2 has more than one parent" out.mesh bounded "$BIN/rad-mesh" twoparents.gltf -o out.mesh
expect_error "outside.gltf: buffer 0 uri '../secret.bin' lies outside the scene's folder" out.mesh bounded "$BIN/rad-mesh" sub/outside.gltf -o out.mesh
expect_error "(--allow-outside-refs allows it)" out.mesh bounded "$BIN/rad-mesh" passwd.gltf -o out.mesh
expect_error "absolute.gltf: buffer 0 uri '/etc/passwd' is an absolute path" out.mesh bounded "$BIN/rad-mesh" absolute.gltf -o out.mesh
expect_error "fifo.gltf: buffer 0 uri 'fifo.bin' is not a regular file (a FIFO, device or folder is never opened)" out.mesh \
  bounded "$BIN/rad-mesh" sub/fifo.gltf -o out.mesh --allow-outside-refs
expect_error "negative.gltf: accessor 0: byteOffset -4 is not a whole number from 0" out.mesh bounded "$BIN/rad-mesh" negative.gltf -o out.mesh
expect_error "huge.gltf: accessor 0: byteOffset 1.8446744073709552e+19 is not a whole number from 0" out.mesh bounded "$BIN/rad-mesh" huge.gltf -o out.mesh
expect_error "past.gltf: accessor 0 (4 elements from byte 0) runs past the end of bufferView 0 (36 bytes)" out.mesh bounded "$BIN/rad-mesh" past.gltf -o out.mesh
expect_error "view.gltf: bufferView 0 (bytes 0 to 40) runs past the end of buffer 0 (36 bytes)" out.mesh bounded "$BIN/rad-mesh" view.gltf -o out.mesh
expect_error "image.gltf: image 0 uri '../../x.png' lies outside" out.mesh bounded "$BIN/rad-mesh" image.gltf -o out.mesh
mkdir -p forms
cp back.gltf mixed.gltf escaped.gltf slash.gltf fileuri.gltf forms/
for f in back mixed escaped slash fileuri; do
  err=$(bounded "$BIN/rad-mesh" forms/$f.gltf -o out.mesh 2>&1 >/dev/null); rc=$?
  [ $rc -eq 1 ] || fail "$f.gltf: exit $rc (wanted 1): $err"
  grep -q "outside the scene's folder\|is an absolute path" <<<"$err" || fail "$f.gltf: $err"
  [ ! -e out.mesh ] || fail "$f.gltf: out.mesh was written"
done
# A backslash path to a FIFO outside is refused, not opened (it blocked until the timeout).
mkdir -p forms2 && cp backfifo.gltf forms2/
expect_error "the importer asked for" out.mesh bounded "$BIN/rad-mesh" forms2/backfifo.gltf -o out.mesh
# A link inside the folder to a file outside is outside.
mkdir -p linked && cp ok.gltf linked/ && ln -s ../secret.bin linked/inner.bin
python3 -c "import json; d = json.load(open('linked/ok.gltf')); d['buffers'][0]['uri'] = 'inner.bin'; json.dump(d, open('linked/link.gltf', 'w'))"
expect_error "lies outside the scene's folder" out.mesh bounded "$BIN/rad-mesh" linked/link.gltf -o out.mesh
# Allowed by hand, the buffer outside is read.
"$BIN/rad-mesh" sub/outside.gltf -o out.mesh --allow-outside-refs -q 2>/dev/null || fail "--allow-outside-refs"
[ -e out.mesh ] || fail "--allow-outside-refs wrote nothing"
rm -f out.mesh
# The scene file itself: a FIFO is never opened.
mkfifo scene.glb
expect_error "scene.glb: not a regular file" out.mesh bounded "$BIN/rad-mesh" scene.glb -o out.mesh

# OBJ: a material library or texture outside the scene's folder.
mkdir -p obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n' > tri.txt
printf 'newmtl grey\nKd 0.5 0.5 0.5\n' > up.mtl
{ echo 'mtllib ../up.mtl'; cat tri.txt; } > obj/up.obj
{ echo 'mtllib /etc/passwd'; cat tri.txt; } > obj/abs.obj
printf 'newmtl grey\nKd 0.5 0.5 0.5\nmap_Kd ../../../../../etc/passwd\n' > obj/tex.mtl
{ echo 'mtllib tex.mtl'; cat tri.txt; } > obj/tex.obj
expect_error "up.obj:1: mtllib '../up.mtl' lies outside the scene's folder obj (--allow-outside-refs allows it)" out.mesh "$BIN/rad-mesh" obj/up.obj -o out.mesh
expect_error "abs.obj:1: mtllib '/etc/passwd' is an absolute path" out.mesh "$BIN/rad-mesh" obj/abs.obj -o out.mesh
expect_error "tex.mtl: material 'grey' map_Kd '../../../../../etc/passwd' lies outside" out.mesh "$BIN/rad-mesh" obj/tex.obj -o out.mesh
"$BIN/rad-mesh" obj/up.obj -o out.mesh --allow-outside-refs -q 2>/dev/null || fail "OBJ --allow-outside-refs"
rm -f out.mesh

# Values: a vt or vn index that does not exist is reported (ignored; --strict refuses), an
# emission a solve would overflow on is refused where it enters (rad-mesh, rad-solve).
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/9/9 2/9/9 3/9/9\n' > dangling.obj
err=$("$BIN/rad-mesh" dangling.obj -o out.mesh 2>&1) || fail "dangling vt/vn: $err"
grep -q "changed: ignored: 3 face corner(s) name a texture coordinate or normal that does not exist (first at line 4: '1/9/9' refers to texture coordinate (vt) 9, but only 0 are defined)" <<<"$err" ||
  fail "dangling vt/vn not reported: $err"
expect_error "dangling.obj:4: face corner '1/9/9' refers to texture coordinate (vt) 9" out2.mesh "$BIN/rad-mesh" dangling.obj -o out2.mesh --strict
printf 'newmtl lamp\nKd 0.5 0.5 0.5\nKe 1e300 1e300 1e300\n' > hot.mtl
{ echo 'mtllib hot.mtl'; sed 's/grey/lamp/' tri.txt; } > hot.obj
expect_error "hot.obj: material 'lamp' emits 1e+300 W/m^2, over the limit of 1e+20" out2.mesh "$BIN/rad-mesh" hot.obj -o out2.mesh
python3 - <<'PY'
import json
d = json.load(open("ok.gltf"))
d["materials"] = [{"emissiveFactor": [1, 1, 1],
                   "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1e308}}}]
d["meshes"][0]["primitives"][0]["material"] = 0
d["extensionsUsed"] = ["KHR_materials_emissive_strength"]
json.dump(d, open("strength.gltf", "w"))
PY
expect_error "strength.gltf: material" out2.mesh "$BIN/rad-mesh" strength.gltf -o out2.mesh
"$BIN/rad-ff" out.mesh -o out.ff -q 2>/dev/null || fail "rad-ff on the dangling triangle"
expect_error "material 'default' emits 1e+30 W/m^2, over the limit of 1e+20" out.rad "$BIN/rad-solve" out.mesh out.ff -o out.rad --emission default=1e30,1,1
# One 19,602-triangle mesh placed at 1000 nodes: its faces, instances counted, are refused
# against --max-memory as soon as they are counted (the parent ran past 60 s and 6.3 GB).
mkdir -p inst && (cd inst && python3 - <<'PY'
import json, struct
n = 100
pos = b"".join(struct.pack("<3f", i / n, 0, j / n) for j in range(n) for i in range(n))
idx = b"".join(struct.pack("<6I", j * n + i, j * n + i + n, j * n + i + 1, j * n + i + 1, j * n + i + n, j * n + i + n + 1)
               for j in range(n - 1) for i in range(n - 1))
open("grid.bin", "wb").write(pos + idx)
json.dump({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(1000))}],
           "nodes": [{"mesh": 0, "translation": [k % 40 * 1.1, 0, k // 40 * 1.1]} for k in range(1000)],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "buffers": [{"uri": "grid.bin", "byteLength": len(pos) + len(idx)}],
           "bufferViews": [{"buffer": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": n * n, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 0, 1]},
                         {"bufferView": 1, "componentType": 5125, "count": len(idx) // 4, "type": "SCALAR"}]},
          open("inst.gltf", "w"))
PY
)
start=$(date +%s)
expect_error "inst.gltf: its 19602000 faces (instances counted) need about 7.3 GiB to mesh, more than --max-memory 1.0 GiB" inst.mesh \
  bounded "$BIN/rad-mesh" inst/inst.gltf -o inst.mesh --max-memory 1G
[ $(( $(date +%s) - start )) -lt 20 ] || fail "the instanced glTF was not refused up front"
finish
