# rad-ff: byte-identical output at 1 and 2 threads, memory refusal, summary.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
for method in analytic pairwise hemisphere hemicube; do
  extra=""; [ $method = pairwise ] && extra="--samples 16"; [ $method = hemicube ] && extra="--resolution 20"
  # The same command (the output path is part of the recorded command line), then compare.
  "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" --method $method --threads 1 --seed 5 $extra -q || fail "$method 1 thread"
  mv "$TMP/c.ff" "$TMP/1.ff"
  "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" --method $method --threads 2 --seed 5 $extra -q || fail "$method 2 threads"
  mv "$TMP/c.ff" "$TMP/2.ff"
  cmp -s "$TMP/1.ff" "$TMP/2.ff" || fail "$method differs between 1 and 2 threads"
done
# With 4 KiB pages (the tools otherwise restart themselves once with glibc.malloc.hugetlb=1):
# the same bytes (2.ff is the last method's, hemicube).
RADIOSITY_HUGE_PAGES=0 "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" --method hemicube --threads 2 --seed 5 --resolution 20 -q || fail "4 KiB pages"
cmp -s "$TMP/c.ff" "$TMP/2.ff" || fail "rad-ff differs with 4 KiB pages"
rm -f "$TMP/c.ff"
err=$("$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/s.ff" 2>&1) || fail "summary run"
grep -q "non-zeros.*rays.*rays/s.*row sums mean" <<<"$err" || fail "summary: $err"
# --estimate: a few rows measured, the cost said in one line (and hemisphere's beside an
# O(n^2) method's), nothing written; without it, -o is required.
before=$(ls -A "$TMP")
err=$("$BIN/rad-ff" "$TMP/c.mesh" --estimate --method analytic 2>&1) || fail "--estimate: $err"
grep -Eq "^rad-ff: analytic: about [0-9.]+ (s|min|h) for [0-9]+ rows on [0-9]+ thread\(s\) \(measured on ([2-9]|[12][0-9]|3[0-2]) rows\); --method hemisphere: about [0-9.]+ (s|min|h)$" <<<"$err" ||
  fail "--estimate line: $err"
err=$("$BIN/rad-ff" "$TMP/c.mesh" --estimate --method hemisphere --rows 0/4 2>&1) || fail "--estimate --rows: $err"
rows=$("$BIN/rad-info" "$TMP/c.mesh" | sed -n 's/^  patches = //p')
grep -q "^rad-ff: hemisphere: about .* for $((rows / 4)) rows on" <<<"$err" || fail "--estimate --rows line: $err"
grep -q "method hemisphere" <<<"$err" && fail "hemisphere suggested to itself: $err"
[ "$(ls -A "$TMP")" = "$before" ] || fail "--estimate wrote: $(ls -A "$TMP")"
expect_error "--output is required (or --estimate" "" "$BIN/rad-ff" "$TMP/c.mesh"
expect_error "--rows: empty: give A:B or K/N" "$TMP/r.ff" "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/r.ff" --rows ''
# Under an address-space limit Embree's failure to start says "out of memory" (exit 2).
err=$(ulimit -v 120000; "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/u.ff" -q 2>&1); rc=$?
[ $rc -eq 2 ] && grep -q "out of memory" <<<"$err" || fail "ulimit -v: exit $rc: $err"
expect_error "" "" "$BIN/rad-ff" a.ff b.ff --merge --estimate
expect_error "more than --max-memory" "$TMP/m.ff" "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/m.ff" --max-memory 10K
# The estimate counts what grows with the options (hemisphere's per-ray table), so a huge
# --rays is refused at once instead of allocating gigabytes.
expect_error "need up to 3.0 GiB, more than --max-memory 100.0 MiB (use fewer --rays" "$TMP/m.ff" \
  "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/m.ff" --method hemisphere --rays 100000000 --max-memory 100M
expect_error "more than --max-memory 100.0 MiB (use a lower --resolution" "$TMP/m.ff" \
  "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/m.ff" --method hemicube --resolution 4096 --max-memory 100M
expect_error "the hemi-cube's resolution is an even number from 2 to 4096" "$TMP/h.ff" \
  "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/h.ff" --method hemicube --resolution 51
expect_error "not a size" "$TMP/m.ff" "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/m.ff" --max-memory lots
# Interrupted: no output file and no temporary left behind.
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/big.mesh" --max-edge 0.02 -q
timeout -s INT 1 "$BIN/rad-ff" "$TMP/big.mesh" -o "$TMP/big.ff" --method pairwise -q
[ ! -e "$TMP/big.ff" ] || fail "interrupted run left an output"
[ -z "$(ls -A "$TMP" | grep tmp)" ] || fail "temporary file left: $(ls -A "$TMP")"
# Exit codes by class: a write the system refuses is 2 ("system error"), not bad input.
err=$("$BIN/rad-ff" "$TMP/c.mesh" -o /proc/radiosity-test.ff -q 2>&1); rc=$?
[ $rc -eq 2 ] || fail "unwritable output: exit $rc (wanted 2): $err"
grep -q "system error" <<<"$err" || fail "unwritable output message: $err"
# --help lists every registered method.
help=$("$BIN/rad-ff" --help)
for m in analytic pairwise hemisphere; do grep -q "$m:" <<<"$help" || fail "--help lacks $m"; done
expect_error "" "$TMP/m.ff" "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/m.ff" --method radiance
expect_error "" "$TMP/m.ff" "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/m.ff" --threads -1
# Scale: the same box in nanometres and in gigametres has the same form factors (ray offsets
# are relative to the scene; a fixed 1e-9 offset gave a nanometre box none at all).
declare -A sum
for scale in 1e-9 1 1e9; do
  mkdir -p "$TMP/s$scale"
  awk -v s=$scale '/^v / { printf "v %.17g %.17g %.17g\n", $2 * s, $3 * s, $4 * s; next } { print }' \
    "$SRC/scenes/cornell/cornell.obj" > "$TMP/s$scale/cornell.obj"
  cp "$SRC/scenes/cornell/cornell.mtl" "$TMP/s$scale/"
  "$BIN/rad-mesh" "$TMP/s$scale/cornell.obj" -o "$TMP/s$scale.mesh" --max-edge none -q 2>/dev/null || fail "mesh at scale $scale"
  sum[$scale]=$("$BIN/rad-ff" "$TMP/s$scale.mesh" -o "$TMP/s$scale.ff" --method hemisphere --rays 500 2>&1 | sed -n 's/.*row sums mean \([0-9.]*\).*/\1/p')
done
[ "${sum[1e-9]}" = "${sum[1]}" ] && [ "${sum[1e9]}" = "${sum[1]}" ] || fail "row sums change with scale: ${sum[1e-9]} ${sum[1]} ${sum[1e9]}"
# Far from the origin (georeferenced): the ray scene is recentred, so float keeps its detail.
mkdir -p "$TMP/far"
awk '/^v / { printf "v %.17g %.17g %.17g\n", $2 + 1e7, $3, $4 - 3e6; next } { print }' \
  "$SRC/scenes/cornell/cornell.obj" > "$TMP/far/cornell.obj"
cp "$SRC/scenes/cornell/cornell.mtl" "$TMP/far/"
"$BIN/rad-mesh" "$TMP/far/cornell.obj" -o "$TMP/far.mesh" --max-edge none -q 2>/dev/null || fail "mesh far away"
far=$("$BIN/rad-ff" "$TMP/far.mesh" -o "$TMP/far.ff" --method hemisphere --rays 500 2>&1 | sed -n 's/.*row sums mean \([0-9.]*\).*/\1/p')
# Moved by 2e7 times its size, the corners lose digits, and a few patches draw other random
# numbers (their streams are keyed by their quantised corners): the same to noise, 1e-3.
# Before the recentring, float rays gave 0.9973 here.
awk -v a="$far" -v b="${sum[1]}" 'BEGIN { d = a - b; exit !(d < 1e-3 && d > -1e-3) }' ||
  fail "row sums change far from the origin: $far vs ${sum[1]}"
# Beyond what float and double resolve: refused with the accepted range, not solved wrongly.
awk '/^v / { printf "v %.17g %.17g %.17g\n", $2 * 1e30, $3 * 1e30, $4 * 1e30; next } { print }' \
  "$SRC/scenes/cornell/cornell.obj" > "$TMP/far/huge.obj"
expect_error "units across; the ray tracer (Embree, single precision) resolves scenes from 1e-11 to 1e+13" \
  "$TMP/huge.mesh" "$BIN/rad-mesh" "$TMP/far/huge.obj" -o "$TMP/huge.mesh"
awk '/^v / { printf "v %.17g %.17g %.17g\n", $2 + 1e10, $3, $4; next } { print }' \
  "$SRC/scenes/cornell/cornell.obj" > "$TMP/far/off.obj"
expect_error "lies 1e+10 units from the origin" "$TMP/off.mesh" "$BIN/rad-mesh" "$TMP/far/off.obj" -o "$TMP/off.mesh"
# Outputs checked before any work: a missing folder, an input as output.
err=$("$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/nofolder/x.ff" --method pairwise 2>&1); rc=$?
[ $rc -eq 1 ] || fail "missing folder: exit $rc"
grep -q "the folder '$TMP/nofolder' does not exist (nothing was computed)" <<<"$err" || fail "missing folder message: $err"
cp "$TMP/c.mesh" "$TMP/keep.mesh"
expect_error "is also an input of this run" "" "$BIN/rad-ff" "$TMP/keep.mesh" -o "$TMP/../$(basename "$TMP")/keep.mesh"
cmp -s "$TMP/c.mesh" "$TMP/keep.mesh" || fail "the input was overwritten"
# Rows that do not fit in --max-memory wait on disk beside the output: the same bytes.
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/fine.mesh" --max-edge 0.016 -q 2>/dev/null
"$BIN/rad-ff" "$TMP/fine.mesh" -o "$TMP/fine.ff" --method hemisphere --rays 300 -q || fail "fine mesh"
mv "$TMP/fine.ff" "$TMP/fine-memory.ff"
spilled=$("$BIN/rad-ff" "$TMP/fine.mesh" -o "$TMP/fine.ff" --method hemisphere --rays 300 --max-memory 60M 2>&1) || fail "spilled run: $spilled"
grep -q "waited on disk in $TMP" <<<"$spilled" || fail "the rows did not spill: $spilled"
# (the command lines differ: compare the bodies' checksums)
body_hash() { head -c 4096 "$1" | grep -a '^body_hash='; }
[ -n "$(body_hash "$TMP/fine.ff")" ] && [ "$(body_hash "$TMP/fine.ff")" = "$(body_hash "$TMP/fine-memory.ff")" ] ||
  fail "spilled rows give another body"
[ "$(ls -A "$TMP" | grep -c spool)" -eq 0 ] || fail "spill files left behind"
# --method auto (the default): analytic for a small mesh, hemisphere above 2500 patches, said.
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/auto-small.mesh" --max-edge 0.1 -q 2>/dev/null
err=$("$BIN/rad-ff" "$TMP/auto-small.mesh" -o "$TMP/auto-small.ff" 2>&1) || fail "auto small: $err"
grep -q "rad-ff: --method auto: analytic for [0-9]* patches" <<<"$err" || fail "auto small: $err"
"$BIN/rad-info" "$TMP/auto-small.ff" | grep -q "method.*analytic" || fail "auto small header: $("$BIN/rad-info" "$TMP/auto-small.ff")"
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/auto-big.mesh" --max-edge 0.025 -q 2>/dev/null
err=$("$BIN/rad-ff" "$TMP/auto-big.mesh" -o "$TMP/auto-big.ff" --rays 200 2>&1) || fail "auto big: $err"
grep -q "rad-ff: --method auto: hemisphere for [0-9]* patches" <<<"$err" || fail "auto big: $err"
"$BIN/rad-info" "$TMP/auto-big.ff" | grep -q "method.*hemisphere" || fail "auto big header: $("$BIN/rad-info" "$TMP/auto-big.ff")"
# Warnings people can read (#53 item 6): 60 boxes, each its own group, inside a room drawn
# facing out, so that every box looks at the backs of its walls: at most 20 lines, the largest
# first, and a count of the rest; -v lists them all.
python3 - "$TMP/boxes.obj" <<'PY'
import sys
out = ["mtllib none.mtl"]
v = []
def quad(g, a, b, c, d):
    v.extend([a, b, c, d]); n = len(v)
    out.append(f"g {g}\nf {n-3} {n-2} {n-1} {n}")
W = 10.0
# The room facing out (each wall wound a, d, c, b of its inward quad).
out_quad = lambda g, a, b, c, d: quad(g, a, d, c, b)
out_quad("floor", (0,0,0), (0,0,W), (W,0,W), (W,0,0)); out_quad("ceiling", (0,W,0), (W,W,0), (W,W,W), (0,W,W))
out_quad("south", (0,0,0), (W,0,0), (W,W,0), (0,W,0)); out_quad("north", (0,0,W), (0,W,W), (W,W,W), (W,0,W))
out_quad("west", (0,0,0), (0,W,0), (0,W,W), (0,0,W)); out_quad("east", (W,0,0), (W,0,W), (W,W,W), (W,W,0))
for k in range(60):
    s = 0.2 + 0.01 * k  # boxes of different sizes: the largest first
    x, z = 0.5 + (k % 8) * 1.2, 0.5 + (k // 8) * 1.2
    y = 3.0
    c = lambda i, j, l: (x + i * s, y + j * s, z + l * s)
    g = f"box{k}"
    quad(g, c(0,0,0), c(1,0,0), c(1,0,1), c(0,0,1)); quad(g, c(0,1,0), c(0,1,1), c(1,1,1), c(1,1,0))
    quad(g, c(0,0,0), c(0,1,0), c(1,1,0), c(1,0,0)); quad(g, c(0,0,1), c(1,0,1), c(1,1,1), c(0,1,1))
    quad(g, c(0,0,0), c(0,0,1), c(0,1,1), c(0,1,0)); quad(g, c(1,0,0), c(1,1,0), c(1,1,1), c(1,0,1))
open(sys.argv[1], "w").write("\n".join(f"v {a} {b} {c}" for a, b, c in v) + "\n" + "\n".join(out) + "\n")
PY
"$BIN/rad-mesh" "$TMP/boxes.obj" -o "$TMP/boxes.mesh" --max-edge 1 --no-imprint -q 2>/dev/null || fail "boxes mesh"
"$BIN/rad-ff" "$TMP/boxes.mesh" -o "$TMP/boxes.ff" --method hemisphere --rays 256 -q 2> "$TMP/boxes.err"
"$BIN/rad-ff" "$TMP/boxes.mesh" -o "$TMP/boxes.ff" --method hemisphere --rays 256 -q -v 2> "$TMP/boxes-v.err"
all=$(grep -c "^rad-ff: warning: .*: group " "$TMP/boxes-v.err")
[ "$all" -gt 20 ] || fail "only $all groups warned about with -v (the test needs more than 20)"
n=$(grep -c "^rad-ff: warning: .*: group " "$TMP/boxes.err")
[ "$n" -eq 20 ] || fail "$n box warning lines (wanted the 20 worst of $all)"
grep -q "$((all - 20)) more group(s) face the wrong way or look at backs.*rad-ff -v lists them all" "$TMP/boxes.err" || fail "no count of the rest: $(tail -1 "$TMP/boxes.err")"
# The largest area first: box sizes grow with their number (the room's walls, larger, lead).
python3 - "$TMP/boxes-v.err" <<'PY2' || fail "not the largest first"
import re, sys
sizes = [int(m) for m in re.findall(r"group box(\d+):", open(sys.argv[1]).read())]
assert sizes == sorted(sizes, reverse=True), sizes[:10]
PY2
finish
