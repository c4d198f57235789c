# rad-ff --rows / --merge: shards computed apart merge into the very file one run writes.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
M="$TMP/c.mesh"
for method in analytic hemisphere pairwise hemicube; do
  "$BIN/rad-ff" "$M" -o "$TMP/one.ff" --method $method --seed 7 -q || fail "unsharded $method"
  # Three shards (K/N), one of them at another thread count, merged in any order.
  "$BIN/rad-ff" "$M" -o "$TMP/p0.part" --method $method --seed 7 --rows 0/3 -q --threads 1 || fail "shard 0"
  "$BIN/rad-ff" "$M" -o "$TMP/p1.part" --method $method --seed 7 --rows 1/3 -q || fail "shard 1"
  "$BIN/rad-ff" "$M" -o "$TMP/p2.part" --method $method --seed 7 --rows 2/3 -q || fail "shard 2"
  mv "$TMP/one.ff" "$TMP/single.ff"
  # The merged file must be named as the single run's output was, so the commands match.
  "$BIN/rad-ff" --merge "$TMP/p2.part" "$TMP/p0.part" "$TMP/p1.part" -o "$TMP/one.ff" -q || fail "merge $method"
  cmp -s "$TMP/one.ff" "$TMP/single.ff" || fail "$method: merged shards differ from one run"
done
patches=$("$BIN/rad-info" "$M" | sed -n 's/^  patches = //p')
# A:B ranges too, and rad-info describes a part.
"$BIN/rad-ff" "$M" -o "$TMP/a.part" --rows 0:100 -q || fail "--rows A:B"
"$BIN/rad-ff" "$M" -o "$TMP/b.part" --rows 100:$patches -q || fail "--rows B:end"
"$BIN/rad-info" "$TMP/a.part" | grep -q "rows 0 to 100 (end excluded) of $patches" || fail "rad-info part: $("$BIN/rad-info" "$TMP/a.part" | head -5)"
"$BIN/rad-ff" --merge "$TMP/a.part" "$TMP/b.part" -o "$TMP/ab.ff" -q || fail "merge A:B parts"
# Gaps, overlaps, mismatches, bad ranges: clear errors, nothing written.
"$BIN/rad-ff" "$M" -o "$TMP/c.part" --rows 0:90 -q
"$BIN/rad-ff" "$M" -o "$TMP/s.part" --rows 100:$patches --seed 2 -q
expect_error "rows 0 to 99 are in no part (compute them with --rows 0:100)" "$TMP/x.ff" "$BIN/rad-ff" --merge "$TMP/b.part" -o "$TMP/x.ff"
expect_error "rows 90 to 99 are in no part" "$TMP/x.ff" "$BIN/rad-ff" --merge "$TMP/c.part" "$TMP/b.part" -o "$TMP/x.ff"
expect_error "rows 0 to 89 are in two parts" "$TMP/x.ff" "$BIN/rad-ff" --merge "$TMP/a.part" "$TMP/c.part" "$TMP/b.part" -o "$TMP/x.ff"
expect_error "are parts of different form factors: seed 2 against 1" "$TMP/x.ff" "$BIN/rad-ff" --merge "$TMP/a.part" "$TMP/s.part" -o "$TMP/x.ff"
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/other.mesh" --max-edge 0.2 -q 2>/dev/null
"$BIN/rad-ff" "$TMP/other.mesh" -o "$TMP/o.part" --rows 0/2 -q
expect_error "are parts of different form factors" "$TMP/x.ff" "$BIN/rad-ff" --merge "$TMP/o.part" "$TMP/b.part" -o "$TMP/x.ff"
expect_error "is a form-factor matrix (formfactors) file, but a form-factor rows" "$TMP/x.ff" "$BIN/rad-ff" --merge "$TMP/ab.ff" -o "$TMP/x.ff"
expect_error "--rows 5:2: rows A:B need 0 <= A < B <= $patches" "$TMP/x.part" "$BIN/rad-ff" "$M" -o "$TMP/x.part" --rows 5:2
expect_error "shard K/N needs 0 <= K < N" "$TMP/x.part" "$BIN/rad-ff" "$M" -o "$TMP/x.part" --rows 3/3
expect_error "is neither A:B" "$TMP/x.part" "$BIN/rad-ff" "$M" -o "$TMP/x.part" --rows half
# rad-gather --rows: chunks of a points file (blank lines and comments between them), merged
# in order into the bytes one run writes; a grid too.
"$BIN/rad-solve" "$M" "$TMP/ab.ff" -o "$TMP/c.rad" -q || fail "solve"
python3 - > "$TMP/pts.txt" <<'PY'
import random
random.seed(5)
print("# sensors")
for i in range(61):
    print(f"{random.uniform(0.05, 0.5):.3f} {random.uniform(0.05, 0.45):.3f} {random.uniform(0.05, 0.5):.3f} 0 1 0")
    if i % 10 == 0: print()
PY
mkdir -p "$TMP/g"
(cd "$TMP/g" && "$BIN/rad-gather" ../c.mesh ../c.rad --points ../pts.txt -o out.txt --header --lux --rays 32 --keep-going -q 2>/dev/null && mv out.txt single.txt) || fail "gather one run"
for k in 0 1 2; do
  (cd "$TMP/g" && "$BIN/rad-gather" ../c.mesh ../c.rad --points ../pts.txt -o g$k.part --header --lux --rays 32 --keep-going --rows $k/3 --threads $((k % 2 + 1)) -q 2>/dev/null) || fail "gather shard $k"
done
(cd "$TMP/g" && "$BIN/rad-gather" --merge g2.part g0.part g1.part -o out.txt -q) || fail "gather merge"
cmp -s "$TMP/g/out.txt" "$TMP/g/single.txt" || fail "merged gather parts differ from one run"
[ "$(grep -vc '^#' "$TMP/g/out.txt")" = 61 ] || fail "merged gather: not 61 values"
expect_error "sensors 20 to 39 are in no part (compute them with --rows 20:40)" "$TMP/g/x.txt" "$BIN/rad-gather" --merge "$TMP/g/g0.part" "$TMP/g/g2.part" -o "$TMP/g/x.txt"
expect_error "are in two parts" "$TMP/g/x.txt" "$BIN/rad-gather" --merge "$TMP/g/g0.part" "$TMP/g/g1.part" "$TMP/g/g1.part" "$TMP/g/g2.part" -o "$TMP/g/x.txt"
(cd "$TMP/g" && "$BIN/rad-gather" ../c.mesh ../c.rad --points ../pts.txt -o o1.part --lux --rays 32 --keep-going --rows 1/3 -q 2>/dev/null)
expect_error "are parts of different runs" "$TMP/g/x.txt" "$BIN/rad-gather" --merge "$TMP/g/g0.part" "$TMP/g/o1.part" "$TMP/g/g2.part" -o "$TMP/g/x.txt"
expect_error "not a part from rad-gather --rows" "$TMP/g/x.txt" "$BIN/rad-gather" --merge "$TMP/g/single.txt" -o "$TMP/g/x.txt"
# A part changed after it was written (#70 item 9): a line that is no value (markup, an empty
# line) is refused at its line, never copied into the output; a line too many is said as such.
for extra in '<script>alert(1)</script>' '' '1.5'; do
  { cat "$TMP/g/g1.part"; printf '%s\n' "$extra"; } > "$TMP/g/bad1.part"
  err=$("$BIN/rad-gather" --merge "$TMP/g/g0.part" "$TMP/g/bad1.part" "$TMP/g/g2.part" -o "$TMP/g/x.txt" 2>&1); rc=$?
  [ $rc -eq 1 ] && [ ! -e "$TMP/g/x.txt" ] || fail "a part with the line '$extra' added: exit $rc"
  case "$extra" in
    1.5) grep -q "bad1.part: holds 21 value line(s) for the 20 sensors 20:40 (lines were added" <<<"$err" || fail "one line too many: $err" ;;
    *) grep -q "bad1.part:[0-9]*: not a value line as rad-gather writes them" <<<"$err" || fail "'$extra' is not named: $err" ;;
  esac
done
expect_error "--rows splits a --points FILE or a --grid" "$TMP/g/x.part" "$BIN/rad-gather" "$M" "$TMP/c.rad" -o "$TMP/g/x.part" --rows 0/2
expect_error "(the sensors)" "$TMP/g/x.part" "$BIN/rad-gather" "$M" "$TMP/c.rad" --points "$TMP/pts.txt" -o "$TMP/g/x.part" --rows 0/62
GRID="0.05 0.05 0.5 0.5 0.01 7 5"
(cd "$TMP/g" && "$BIN/rad-gather" ../c.mesh ../c.rad --grid "$GRID" -o grid.txt --lux --rays 16 -q && mv grid.txt grid1.txt) || fail "grid one run"
(cd "$TMP/g" && "$BIN/rad-gather" ../c.mesh ../c.rad --grid "$GRID" -o a.part --lux --rays 16 --rows 0:17 -q && "$BIN/rad-gather" ../c.mesh ../c.rad --grid "$GRID" -o b.part --lux --rays 16 --rows 17:35 -q && "$BIN/rad-gather" --merge a.part b.part -o grid.txt -q) || fail "grid parts"
cmp -s "$TMP/g/grid.txt" "$TMP/g/grid1.txt" || fail "merged grid parts differ from one run"

# rad-shade --rows: bands of the image (rasterised, gathered, albedo with its exposure from
# the whole image, back faces marked), merged into the EXR and PNG one run writes.
VF="$SRC/scenes/cornell/cornell.vf"
mkdir -p "$TMP/s"
for look in "--smooth crease" "--gather 8" "--albedo" "--backfaces mark --exposure 2"; do
  rad="../c.rad"; [ "$look" = "--albedo" ] && rad=""
  (cd "$TMP/s" && rm -f img.exr img.png && "$BIN/rad-shade" ../c.mesh $rad -o img.exr --png img.png --view-file "$VF" -x 48 -y 40 $look -q && mv img.exr one.exr && mv img.png one.png) || fail "shade one run ($look)"
  for k in 0 1 2; do
    (cd "$TMP/s" && "$BIN/rad-shade" ../c.mesh $rad -o i$k.part --png img.png --view-file "$VF" -x 48 -y 40 $look --rows $k/3 --threads $((k % 2 + 1)) -q) || fail "shade band $k ($look)"
  done
  [ ! -e "$TMP/s/img.png" ] || fail "a band wrote the PNG ($look)"
  # A merge writes only what its command line names (#70 item 2): without --png, no PNG.
  (cd "$TMP/s" && "$BIN/rad-shade" --merge i1.part i2.part i0.part -o img.exr -q) || fail "shade merge ($look)"
  [ ! -e "$TMP/s/img.png" ] || fail "the merge wrote the PNG path a part recorded ($look)"
  (cd "$TMP/s" && "$BIN/rad-shade" --merge i1.part i2.part i0.part -o img.exr --png img.png -q) || fail "shade merge --png ($look)"
  cmp -s "$TMP/s/img.exr" "$TMP/s/one.exr" || fail "merged bands' EXR differs from one run ($look)"
  cmp -s "$TMP/s/img.png" "$TMP/s/one.png" || fail "merged bands' PNG differs from one run ($look)"
done
expect_error "rows 13 to 25 are in no part (compute them with --rows 13:26)" "$TMP/s/x.exr" "$BIN/rad-shade" --merge "$TMP/s/i0.part" "$TMP/s/i2.part" -o "$TMP/s/x.exr"
(cd "$TMP/s" && "$BIN/rad-shade" ../c.mesh ../c.rad -o o1.part --view-file "$VF" -x 48 -y 40 --rows 1/3 -q)
expect_error "are parts of different images" "$TMP/s/x.exr" "$BIN/rad-shade" --merge "$TMP/s/i0.part" "$TMP/s/o1.part" "$TMP/s/i2.part" -o "$TMP/s/x.exr"
expect_error "not a part from rad-shade --rows" "$TMP/s/x.exr" "$BIN/rad-shade" --merge "$TMP/s/one.exr" -o "$TMP/s/x.exr"
expect_error "--ply and --layers are written by a run of the whole image" "$TMP/s/x.part" "$BIN/rad-shade" "$M" "$TMP/c.rad" -o "$TMP/s/x.part" --view-file "$VF" --rows 0/2 --ply "$TMP/s/x.ply"
# --rows and --merge are declared once for the three sharding tools (#71): an empty --rows and
# --rows with --merge are refused by each, before anything is read or written.
for tool in rad-ff rad-gather rad-shade; do
  expect_error "--rows: empty: give A:B or K/N" "$TMP/e.out" "$BIN/$tool" "$M" "$TMP/c.rad" -o "$TMP/e.out" --rows ''
  expect_error "--rows excludes --merge" "$TMP/e.out" "$BIN/$tool" --merge "$TMP/p0.part" --rows 0/2 -o "$TMP/e.out"
done
# A FIFO among the parts is refused at once, as /dev/zero is (#70 item 9: the merge hung on it).
mkfifo "$TMP/fifo.part"
err=$(timeout 20 "$BIN/rad-ff" --merge "$TMP/p0.part" "$TMP/fifo.part" -o "$TMP/fifo.ff" 2>&1 >/dev/null); rc=$?
[ $rc -eq 1 ] || fail "rad-ff --merge with a FIFO part: exit $rc (124: it hung): $err"
grep -q "fifo.part: is not a regular file (a FIFO, socket or device)" <<<"$err" || fail "the FIFO's refusal: $err"
[ ! -e "$TMP/fifo.ff" ] || fail "a merge with a FIFO part wrote its output"
finish
