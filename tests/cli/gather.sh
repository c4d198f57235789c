# rad-gather: streaming points in order, lux, header, errors naming the line, --keep-going,
# the work-plane grid and its false-colour map, determinism at any thread count.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q || fail "rad-ff"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/c.rad" -q || fail "rad-solve"
M="$TMP/c.mesh"; R="$TMP/c.rad"
printf '0.278 0.01 0.28 0 1 0\n# a comment\n\n0.1 0.3 0.3 1 0 0\n0.5 0.3 0.3 -1 0 0\n' > "$TMP/p.txt"
out=$("$BIN/rad-gather" "$M" "$R" --points "$TMP/p.txt" -q) || fail "gather"
[ "$(wc -l <<<"$out")" -eq 3 ] || fail "one line per point: $out"
# Red wall on the left (x = 0.556 side faces -x): the sensor facing it gets redder light.
python3 - "$out" <<'PY' || fail "values: $out"
import sys
rows = [list(map(float, l.split())) for l in sys.argv[1].splitlines()]
assert all(len(r) == 3 and all(v > 0 for v in r) for r in rows), rows
PY
# A point the ray tracer cannot reach from (x = 1e19: Embree aborts on it) is refused by line.
printf '0.278 0.3 0.28 0 1 0\n1e19 0 0 0 1 0\n' > "$TMP/far.txt"
expect_error "far.txt:2: the point is 1e+19 units from the scene" "" "$BIN/rad-gather" "$M" "$R" --points "$TMP/far.txt"
far=$("$BIN/rad-gather" "$M" "$R" --points "$TMP/far.txt" --keep-going -q 2>/dev/null) || fail "far point --keep-going"
[ "$(tail -1 <<<"$far")" = "nan nan nan" ] || fail "far point not nan: $far"
# A reader that goes away is a normal end (exit 0, as for rad-info); a full disk is exit 2.
for i in $(seq 1 9000); do echo "0.278 0.3 0.28 0 1 0"; done > "$TMP/many.txt"
"$BIN/rad-gather" "$M" "$R" --points "$TMP/many.txt" --rays 2 -q 2>"$TMP/pipe.err" | head -1 >/dev/null
[ "${PIPESTATUS[0]}" -eq 0 ] || fail "rad-gather exits non-zero when its reader closes the pipe"
[ ! -s "$TMP/pipe.err" ] || fail "rad-gather complains about a closed pipe: $(cat "$TMP/pipe.err")"
"$BIN/rad-gather" "$M" "$R" --points "$TMP/many.txt" --rays 2 -q > /dev/full 2>/dev/null; rc=$?
[ $rc -eq 2 ] || fail "rad-gather > /dev/full: exit $rc (wanted 2)"
# Same input from stdin and from a file, 1 and 2 threads: byte-identical.
a=$("$BIN/rad-gather" "$M" "$R" -q --threads 1 < "$TMP/p.txt")
b=$("$BIN/rad-gather" "$M" "$R" -q --threads 2 --points "$TMP/p.txt")
[ "$a" = "$out" ] && [ "$b" = "$out" ] || fail "stdin/file/threads differ"
# Lux: 179 x (0.265 R + 0.670 G + 0.065 B) of the same irradiance.
lux=$("$BIN/rad-gather" "$M" "$R" --points "$TMP/p.txt" --lux -q | head -1)
python3 -c "
r,g,b = map(float, '''$(head -1 <<<"$out")'''.split())
assert abs(179*(0.265*r+0.670*g+0.065*b) - $lux) < 1e-3 * $lux" || fail "lux $lux"
head=$("$BIN/rad-gather" "$M" "$R" --points "$TMP/p.txt" --header -q | head -1)
grep -q "^# rad-gather .*mesh $M xxh64:.*radiosity $R xxh64:.*columns: irradiance r g b" <<<"$head" || fail "header: $head"
# Errors name the line; lines before it are written; nothing after.
printf '0.278 0.01 0.28 0 1 0\n0.2 0.2 0.2 0 0 0\n0.3 0.3 0.3 0 1 0\n' > "$TMP/bad.txt"
err=$("$BIN/rad-gather" "$M" "$R" --points "$TMP/bad.txt" -q 2>&1 >"$TMP/bad.out"); rc=$?
[ $rc -eq 1 ] || fail "zero direction: exit $rc"
grep -q "$TMP/bad.txt:2: the direction dx dy dz is zero" <<<"$err" || fail "zero direction message: $err"
[ "$(wc -l < "$TMP/bad.out")" -eq 1 ] || fail "lines before the bad one: $(cat "$TMP/bad.out")"
err=$(printf '0.278 0.01 0.28 0 1\n' | "$BIN/rad-gather" "$M" "$R" -q 2>&1)
grep -q "<stdin>:1: expected six numbers" <<<"$err" || fail "five numbers: $err"
err=$(printf '0.278 -0.3 0.28 0 1 0\n' | "$BIN/rad-gather" "$M" "$R" -q 2>&1)
grep -q "<stdin>:1: 100% of the surfaces the point sees show their back" <<<"$err" || fail "below the floor: $err"
# A point under a block (inside it): refused; --keep-going writes nan and goes on.
printf '0.278 0.01 0.28 0 1 0\n0.18 0.05 0.16 0 1 0\n0.278 0.01 0.28 0 1 0\n' > "$TMP/inside.txt"
kept=$("$BIN/rad-gather" "$M" "$R" --points "$TMP/inside.txt" --keep-going -q 2>"$TMP/kept.err") || fail "--keep-going"
[ "$(sed -n 2p <<<"$kept")" = "nan nan nan" ] || fail "--keep-going line 2: $kept"
[ "$(sed -n 1p <<<"$kept")" = "$(sed -n 1p <<<"$out")" ] || fail "--keep-going changed line 1"
grep -q "1 point(s) could not be gathered.*inside.txt:2" "$TMP/kept.err" || fail "--keep-going warning: $(cat "$TMP/kept.err")"
# -o: written atomically; a failure leaves nothing.
"$BIN/rad-gather" "$M" "$R" --points "$TMP/p.txt" -o "$TMP/g.txt" -q || fail "-o"
[ "$(cat "$TMP/g.txt")" = "$out" ] || fail "-o differs from stdout"
expect_error "inside.txt:2:" "$TMP/g2.txt" "$BIN/rad-gather" "$M" "$R" --points "$TMP/inside.txt" -o "$TMP/g2.txt"
# Work plane: a grid of upward sensors at 0.1 m, in lux, with a false-colour map.
"$BIN/rad-gather" "$M" "$R" --grid "0.02 0.02 0.54 0.54 0.1 13 13" --lux --png "$TMP/plane.png" \
  --keep-going -o "$TMP/plane.txt" -q 2>/dev/null || fail "--grid"
[ "$(wc -l < "$TMP/plane.txt")" -eq 169 ] || fail "grid lines: $(wc -l < "$TMP/plane.txt")"
python3 - "$TMP/plane.png" <<'PY' || fail "png"
import struct, sys
data = open(sys.argv[1], 'rb').read()
assert data[:8] == b'\x89PNG\r\n\x1a\n'
w, h = struct.unpack('>II', data[16:24])
assert w > 400 and h > 300, (w, h)
PY
# --lux-max fixes the legend's top for every plane drawn with it: far above the values, the
# first cell is the bottom colour (dark blue); by default it is not.
"$BIN/rad-gather" "$M" "$R" --grid "0.02 0.02 0.54 0.54 0.1 13 13" --lux --png "$TMP/plane-max.png" \
  --lux-max 1e6 --keep-going -o "$TMP/plane.txt" -q 2>/dev/null || fail "--lux-max"
python3 - "$TMP/plane-max.png" "$TMP/plane.png" "$SRC/tests/cli" <<'PY' || fail "--lux-max colours"
import sys
sys.path.insert(0, sys.argv[3])
from png_stats import read_png
def first_cell(path):
    w, h, rows = read_png(path)
    return tuple(rows[58][3 * 14:3 * 14 + 3])
fixed, default = first_cell(sys.argv[1]), first_cell(sys.argv[2])
assert all(abs(a - b) <= 2 for a, b in zip(fixed, (13, 13, 89))), fixed
assert default != fixed, default
PY
expect_error "--lux-max scales the --png" "" "$BIN/rad-gather" "$M" "$R" --grid "0 0 1 1 0.1 4 4" --lux-max 100
expect_error "--png draws a --grid" "$TMP/x.png" "$BIN/rad-gather" "$M" "$R" --png "$TMP/x.png"
expect_error "--grid takes seven numbers" "" "$BIN/rad-gather" "$M" "$R" --grid "0 0 1 1 0.1 4"
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/other.mesh" --max-edge 0.2 -q
expect_error "does not belong to" "" "$BIN/rad-gather" "$TMP/other.mesh" "$R"
# Streaming: 20,000 points through a pipe, one line each, in order.
python3 -c "
for k in range(20000): print(0.05 + 0.45 * (k % 100) / 100, 0.4, 0.05 + 0.45 * (k // 100) / 200, 0, 1, 0)" |
  "$BIN/rad-gather" "$M" "$R" --rays 8 --shadow-rays 2 -q | wc -l | grep -qx 20000 || fail "streaming 20000 points"
# A work plane through furniture (#25): the sensors inside the box have no value (nan, counted),
# never 0, and the summary's Emin, Eavg, Emax and U0 are those of the sensors with a value.
python3 "$SRC/tests/cli/surface_scenes.py" inward "$TMP/inward.obj"
"$BIN/rad-mesh" "$TMP/inward.obj" -o "$TMP/in.mesh" --max-edge 0.25 -q 2>/dev/null || fail "mesh inward"
"$BIN/rad-ff" "$TMP/in.mesh" -o "$TMP/in.ff" -q 2>/dev/null || fail "ff inward"
"$BIN/rad-solve" "$TMP/in.mesh" "$TMP/in.ff" -o "$TMP/in.rad" -q || fail "solve inward"
err=$("$BIN/rad-gather" "$TMP/in.mesh" "$TMP/in.rad" --grid "0 0 4 3 0.5 8 6" --lux --error -o "$TMP/plane.txt" --png "$TMP/plane.png" 2>&1) ||
  fail "work plane through a box: $err"
# The box stands on x 1..2, z 1..2 (below 0.8): the sensors at x, z = 1.25 and 1.75 are in it.
python3 - "$TMP/plane.txt" "$err" <<'PY' || fail "work plane: $err"
import math, re, sys
rows = [[float(v) for v in line.split()] for line in open(sys.argv[1])]
assert all(len(r) == 2 for r in rows), "--lux --error: two columns"
values = [r[0] for r in rows]
errors = [r[1] for r in rows if not math.isnan(r[0])]
assert all(e > 0 for e in errors), "a sensor's standard error is not positive"
inside = [k for k, v in enumerate(values) if math.isnan(v)]
want = [j * 8 + i for j in (2, 3) for i in (2, 3)]
assert inside == want, (inside, want)
assert all(v > 0 for v in values if not math.isnan(v)), "a sensor with a value reads 0"
good = [v for v in values if not math.isnan(v)]
m = re.search(r"(\d+) sensor\(s\) with a value, (\d+) inside .*Emin ([0-9.e+]+) ± [0-9.e+-]+ lx, "
              r"Eavg ([0-9.e+]+) ± ([0-9.e+-]+) lx, Emax ([0-9.e+]+) ± [0-9.e+-]+ lx, "
              r"U0 = Emin/Eavg = ([0-9.]+) ± [0-9.e+-]+", sys.argv[2])
assert m, sys.argv[2]
count, nan, emin, eavg, eavg_error, emax, u0 = m.groups()
assert int(count) == len(good) and int(nan) == 4
mean = sum(good) / len(good)
# Eavg's error: the sensors' errors added in quadrature over their count (independent streams).
pooled = math.sqrt(sum(e * e for e in errors)) / len(errors)
assert abs(float(eavg_error) - pooled) <= 0.05 * pooled, (eavg_error, pooled)
for said, value in ((emin, min(good)), (eavg, mean), (emax, max(good)), (u0, min(good) / mean)):
    assert abs(float(said) - value) <= 2e-3 * value, (said, value)
PY
# --exact anywhere on a patch (#25 item 7): points over the short block's top between its
# patches' centres (on their edges and inside them) agree with the ray mode; the patch a point
# lies on used to count with form factor 1 or 0.5 (+72% and more).
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/ex.mesh" --max-edge 0.1 -q 2>/dev/null || fail "mesh exact"
"$BIN/rad-ff" "$TMP/ex.mesh" -o "$TMP/ex.ff" -q 2>/dev/null || fail "ff exact"
"$BIN/rad-solve" "$TMP/ex.mesh" "$TMP/ex.ff" -o "$TMP/ex.rad" -q || fail "solve exact"
"$BIN/rad-info" --csv "$TMP/ex.mesh" | python3 -c "
import csv, itertools, sys
tops = [r for r in csv.DictReader(sys.stdin) if r['group'] == 'short_block' and float(r['ny']) > 0.99]
c = [(float(r['cx']), float(r['cy']), float(r['cz'])) for r in tops]
pts = c + [tuple((a[k] + b[k]) / 2 for k in range(3)) for a, b in itertools.combinations(c, 2)]
pts += [tuple(sum(p[k] for p in c) / len(c) for k in range(3))]
for p in pts: print('%.9g %.9g %.9g 0 1 0' % p)" > "$TMP/top.txt"
[ "$(wc -l < "$TMP/top.txt")" -ge 10 ] || fail "block top points: $(cat "$TMP/top.txt")"
"$BIN/rad-gather" "$TMP/ex.mesh" "$TMP/ex.rad" --points "$TMP/top.txt" --exact -q > "$TMP/top-exact.txt" || fail "gather exact"
"$BIN/rad-gather" "$TMP/ex.mesh" "$TMP/ex.rad" --points "$TMP/top.txt" --rays 1024 -q > "$TMP/top-rays.txt" || fail "gather rays"
paste "$TMP/top-exact.txt" "$TMP/top-rays.txt" | awk '{ d = ($1 - $4) / $4; if (d < 0) d = -d; if (d > 0.05) { print "point " NR ": exact " $1 ", rays " $4; bad = 1 } } END { exit bad }' ||
  fail "--exact disagrees with the ray mode on the block top"
# A grid out of the ray tracer's reach is refused with that reason, as a point is (#55): not
# written as every sensor "inside or behind objects".
expect_error "--grid: its corner (1e+25, 0.3, 0.1): the point is 1e+25 units from the scene" "$TMP/farg.txt" "$BIN/rad-gather" "$M" "$R" --grid "1e25 0.1 2e25 0.5 0.3 4 4" --lux -o "$TMP/farg.txt"
# A read error is an error (#55 item 2): a folder, /dev/zero, a line over 1 MiB; the output is
# not written (it held the points before the bad line, and said exit 0).
expect_error "is a folder, not a text file" "$TMP/rd.txt" "$BIN/rad-gather" "$M" "$R" --points "$TMP" -o "$TMP/rd.txt"
expect_error "/dev/zero:1: holds a NUL byte" "$TMP/rd.txt" "$BIN/rad-gather" "$M" "$R" --points /dev/zero -o "$TMP/rd.txt"
{ printf '0.278 0.3 0.28 0 1 0\n0.278 0.3 0.28 0 1 0\n'; head -c 2000000 /dev/zero | tr '\0' 'x'; echo; } > "$TMP/long.txt"
expect_error "long.txt:3: a line longer than 1.0 MiB" "$TMP/rd.txt" "$BIN/rad-gather" "$M" "$R" --points "$TMP/long.txt" -o "$TMP/rd.txt"
err=$("$BIN/rad-gather" "$M" "$R" --points "$TMP/long.txt" -o "$TMP/rd.txt" 2>&1)
[ "${#err}" -lt 400 ] || fail "the message quotes the whole line (${#err} bytes)"
finish
