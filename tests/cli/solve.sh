# rad-solve: stale form factors, overrides equal re-meshing, snapshots, logs, bad input.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/other.mesh" --max-edge 0.2 -q
expect_error "c.ff is stale" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/other.mesh" "$TMP/c.ff" -o "$TMP/x.rad"
# An override equals re-meshing with the changed MTL (same geometry, so the .ff is reused).
mkdir "$TMP/alt"; cp "$SRC/scenes/cornell/cornell.obj" "$TMP/alt/"
sed 's/^Ke 40 32 20$/Ke 10 20 30/; s/^Kd 0.63 0.065 0.05$/Kd 0.5 0.5 0.1/' "$SRC/scenes/cornell/cornell.mtl" > "$TMP/alt/cornell.mtl"
"$BIN/rad-mesh" "$TMP/alt/cornell.obj" -o "$TMP/alt.mesh" --max-edge 0.1 -q
"$BIN/rad-solve" "$TMP/alt.mesh" "$TMP/c.ff" -o "$TMP/remeshed.rad" -q || fail "solve with re-meshed materials"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/override.rad" --emission light=10,20,30 --reflectance red=0.5,0.5,0.1 -q || fail "override"
cmp -s <("$BIN/rad-info" --csv "$TMP/remeshed.rad") <("$BIN/rad-info" --csv "$TMP/override.rad") || fail "override differs from re-meshing"
"$BIN/rad-info" "$TMP/override.rad" | grep -q "override.emission.light = 10,20,30" || fail "override recorded"
# Emission scale is linear.
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/a.rad" -q
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/b.rad" --emission-scale 2 -q
python3 - "$TMP" "$BIN" <<'PY' || fail "emission scale"
import subprocess, sys
tmp, bin = sys.argv[1], sys.argv[2]
read = lambda p: [list(map(float, l.split(",")[1:])) for l in subprocess.check_output([bin + "/rad-info", "--csv", p], text=True).splitlines()[1:]]
a, b = read(tmp + "/a.rad"), read(tmp + "/b.rad")
sys.exit(any(abs(2 * x - y) > 1e-6 * max(1, y) for ra, rb in zip(a, b) for x, y in zip(ra, rb)))
PY
# Snapshots and the log.
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/gs.rad" --iterations 10 --snapshot "$TMP/it-%d.rad" --snapshot-at 1,4 --log "$TMP/log.csv" -q
[ -e "$TMP/it-1.rad" ] && [ -e "$TMP/it-4.rad" ] || fail "snapshots"
[ "$(head -1 "$TMP/log.csv")" = "iteration,residual,power_r,power_g,power_b,seconds" ] || fail "log header"
[ "$(tail -n +2 "$TMP/log.csv" | wc -l)" -eq 10 ] || fail "log rows"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/pr.rad" --method pr --sweeps 2 -q
"$BIN/rad-info" "$TMP/pr.rad" | grep -q "iterations = $((2 * $("$BIN/rad-info" --csv "$TMP/c.mesh" | tail -n +2 | wc -l)))" || fail "sweeps-equivalent"
expect_error "may not converge" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --reflectance white=1,0.5,0.5
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/f.rad" --reflectance white=1,0.5,0.5 --force --iterations 3 -q || fail "--force"
err=$("$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/k.rad" --emission light=0 -q 2>&1)
grep -q "no patch emits light" <<<"$err" || fail "black warning"
expect_error "no material or group 'lamp'" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --emission lamp=1,1,1
expect_error "is not MATERIAL=r,g,b" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --emission light
expect_error "'x' in 'light=1,x,3' is not a number" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --emission light=1,x,3
# Real-valued options reject NaN and out-of-range values; iteration lists are whole numbers.
expect_error "not a number in [0, 1]" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --tolerance nan
expect_error "not a number in [0, 1]" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --tolerance 2
expect_error "not a number in [0, 1e+06]" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --method pr --sweeps nan
expect_error "'1x' is not an iteration number" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --snapshot "$TMP/s-%d.rad" --snapshot-at 1x
expect_error "--sweeps applies to shooting solvers" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --sweeps 2

# Light groups: room1 with its daylight and a ceiling lamp, one run, a group per emitter.
python3 "$SRC/scenes/generate.py" room1 "$TMP/relight" --lamp || fail "generate room1 --lamp"
"$BIN/rad-mesh" "$TMP/relight/room1-lamp.obj" -o "$TMP/g.mesh" --max-edge 1 -q 2>/dev/null || fail "lamp mesh"
"$BIN/rad-ff" "$TMP/g.mesh" -o "$TMP/g.ff" --method hemisphere --rays 500 -q || fail "lamp ff"
err=$("$BIN/rad-solve" "$TMP/g.mesh" "$TMP/g.ff" -o "$TMP/g.rad" --light-groups 2>&1) || fail "--light-groups: $err"
grep -q "2 light group(s): daylight lamp" <<<"$err" || fail "solve summary: $err"
info=$("$BIN/rad-info" "$TMP/g.rad")
grep -q "2 light group(s): daylight lamp" <<<"$info" || fail "rad-info: $info"
grep -q "light_group.lamp = lamp=40,36,30" <<<"$info" || fail "group emission in the header: $info"
[ "$("$BIN/rad-info" --csv "$TMP/g.rad" | head -1)" = "patch,group,b_r,b_g,b_b" ] || fail "grouped CSV header"
[ "$("$BIN/rad-info" --csv "$TMP/g.rad" | grep -c ",lamp,")" -eq "$("$BIN/rad-info" --csv "$TMP/g.mesh" | tail -n +2 | wc -l)" ] || fail "one CSV row per patch and group"
err=$("$BIN/rad-solve" "$TMP/g.mesh" "$TMP/g.ff" -o "$TMP/g1.rad" --group all=daylight,lamp 2>&1) || fail "--group: $err"
grep -q "1 light group(s): all" <<<"$err" || fail "--group summary: $err"
expect_error "--group x: no material 'lamb'" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/g.mesh" "$TMP/g.ff" -o "$TMP/x.rad" --group x=lamb
expect_error "no material emits light" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/g.mesh" "$TMP/g.ff" -o "$TMP/x.rad" --light-groups --emission lamp=0 --emission daylight=0
expect_error "--log and -o both write" "$TMP/same.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/same.rad" --log "$TMP/same.rad"
expect_error "is also an input of this run" "" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/c.ff"
expect_error "--tolerance 0 is never reached" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --tolerance 0
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --tolerance 0 --iterations 3 -q || fail "--tolerance 0 with --iterations"
rm -f "$TMP/x.rad"
expect_error "--emission-scale 1e+308 makes material 'light' emit" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --emission-scale 1e308
# Every "at most X" a tool prints is accepted (#55 item 8): the usable scale it names solves.
usable=$("$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --emission-scale 1e308 2>&1 | sed -n 's/.*a scale of at most \([0-9.e+]*\) is usable.*/\1/p')
[ -n "$usable" ] || fail "no usable scale named"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/x.rad" --emission-scale "$usable" -q || fail "the usable scale $usable is refused"
# An output given as a link is written where it points and keeps that file's mode (0600 stays).
mkdir -p "$TMP/private"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/private/secret.rad" -q
chmod 600 "$TMP/private/secret.rad"
ln -s "$TMP/private/secret.rad" "$TMP/link.rad"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/link.rad" -q || fail "write through a link"
[ -L "$TMP/link.rad" ] || fail "the link was replaced"
[ "$(stat -c %a "$TMP/private/secret.rad")" = 600 ] || fail "mode widened to $(stat -c %a "$TMP/private/secret.rad")"
# Run through the dynamic loader or under valgrind, the huge-page restart must not exec the
# loader with the tool's arguments (#55 item 7): the tool runs on, and -v says why not.
ldso=$(ls /lib64/ld-linux-*.so.* /lib/ld-linux-*.so.* 2>/dev/null | head -1)
if [ -n "$ldso" ]; then
  "$ldso" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/ldso.rad" -v 2> "$TMP/ldso.err" || fail "rad-solve through $ldso: $(tail -2 "$TMP/ldso.err")"
  grep -q "not restarted for huge pages: the process image is not the program itself" "$TMP/ldso.err" || fail "-v does not say why: $(grep pages "$TMP/ldso.err")"
  "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/direct.rad" -q
  cmp -s <("$BIN/rad-info" --csv "$TMP/ldso.rad") <("$BIN/rad-info" --csv "$TMP/direct.rad") || fail "through the loader the solution differs"
fi
if command -v valgrind >/dev/null; then
  valgrind -q --tool=none "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/vg.rad" -q || fail "rad-solve under valgrind"
fi
# An OBJ without materials lights its lamp by its group or object name (#53 item 7), and says so.
"$BIN/rad-mesh" "$SRC/tests/data/no-material/no_material.obj" -o "$TMP/nm.mesh" -q 2>/dev/null || fail "no-material mesh"
"$BIN/rad-ff" "$TMP/nm.mesh" -o "$TMP/nm.ff" -q 2>/dev/null
"$BIN/rad-solve" "$TMP/nm.mesh" "$TMP/nm.ff" -o "$TMP/nm.rad" --emission light=17,12,4 2> "$TMP/nm.err" || fail "--emission by object name: $(cat "$TMP/nm.err")"
grep -q "no material has that name; group 'light' (.* patches) emits 17,12,4" "$TMP/nm.err" || fail "does not say which: $(cat "$TMP/nm.err")"
"$BIN/rad-shade" "$TMP/nm.mesh" "$TMP/nm.rad" -o "$TMP/nm.exr" -x 16 -y 16 --view "-vp 278 273 -800 -vd 0 0 1 -vh 40 -vv 40" -q 2> "$TMP/nm-shade.err" || fail "shade"
grep -q "is black" "$TMP/nm-shade.err" && fail "the group's light did not light the solve"
expect_error "no material or group 'lamp' in the mesh (materials: default; groups:" "$TMP/nm2.rad" "$BIN/rad-solve" "$TMP/nm.mesh" "$TMP/nm.ff" -o "$TMP/nm2.rad" --emission lamp=1
finish
