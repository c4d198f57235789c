# rad-info: headers and CSV for each kind; damaged files give a clear error and exit 1.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.15
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/c.rad" -q
out=$("$BIN/rad-info" "$TMP/c.rad") || fail "rad-info on a radiosity file"
grep -q "kind:      radiosity" <<<"$out" || fail "kind line"
grep -q "1. rad-mesh" <<<"$out" && grep -q "2. rad-ff" <<<"$out" && grep -q "3. rad-solve.*(this file)" <<<"$out" || fail "provenance chain: $out"
grep -q "xxh64:.*c.ff" <<<"$out" || fail "input hashes"
[ "$("$BIN/rad-info" --csv "$TMP/c.mesh" | head -1)" = "patch,group,material,area,cx,cy,cz,nx,ny,nz,rho_r,rho_g,rho_b,e_r,e_g,e_b,corners" ] || fail "mesh csv header"
[ "$("$BIN/rad-info" --csv "$TMP/c.ff" | head -1)" = "row,col,f" ] || fail "ff csv header"
[ "$("$BIN/rad-info" --csv "$TMP/c.rad" | head -1)" = "patch,b_r,b_g,b_b" ] || fail "rad csv header"
patches=$("$BIN/rad-info" --csv "$TMP/c.mesh" | tail -n +2 | wc -l)
[ "$patches" -eq "$("$BIN/rad-info" --csv "$TMP/c.rad" | tail -n +2 | wc -l)" ] || fail "row counts"
# grep -q exits at its first match; rad-info must treat the closed pipe as a normal end
# (exit 0, no message), so this holds under pipefail every time, not four runs in five.
for run in 1 2 3 4 5; do
  "$BIN/rad-info" --csv "$TMP/c.mesh" | grep -q ",light,.*,40,32,20,4$" || fail "light material with Ke in CSV (run $run)"
done
"$BIN/rad-info" --csv "$TMP/c.ff" 2>"$TMP/pipe.err" | head -1 >/dev/null
[ "${PIPESTATUS[0]}" -eq 0 ] || fail "rad-info exits non-zero when its reader closes the pipe"
[ ! -s "$TMP/pipe.err" ] || fail "rad-info complains about a closed pipe: $(cat "$TMP/pipe.err")"
# A write that fails (a full disk) cuts the CSV: a system error, exit 2, not 0.
"$BIN/rad-info" --csv "$TMP/c.mesh" > /dev/full 2>"$TMP/full.err"; rc=$?
[ $rc -eq 2 ] || fail "rad-info --csv > /dev/full: exit $rc (wanted 2)"
grep -q "cannot write to standard output" "$TMP/full.err" || fail "full disk message: $(cat "$TMP/full.err")"
size=$(stat -c %s "$TMP/c.ff")
for cut in 5 100 $((size / 2)) $((size - 1)); do
  head -c $cut "$TMP/c.ff" > "$TMP/cut.ff"
  expect_error "truncated" "" "$BIN/rad-info" "$TMP/cut.ff"
done
cp "$TMP/c.ff" "$TMP/flip.ff"; printf 'X' | dd of="$TMP/flip.ff" bs=1 seek=40 conv=notrunc status=none
expect_error "checksum mismatch" "" "$BIN/rad-info" "$TMP/flip.ff"
cp "$TMP/c.ff" "$TMP/flip2.ff"; printf '\x7f' | dd of="$TMP/flip2.ff" bs=1 seek=$((size - 3)) conv=notrunc status=none
expect_error "corrupt body" "" "$BIN/rad-info" "$TMP/flip2.ff"
echo "hello" > "$TMP/text.ff"
expect_error "wrong magic" "" "$BIN/rad-info" "$TMP/text.ff"
sed 's/^version=[0-9]*$/version=7/' "$TMP/c.rad" > "$TMP/v.rad"
expect_error "corrupt header: checksum mismatch" "" "$BIN/rad-info" "$TMP/v.rad"
expect_error "was expected" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/x.rad"
expect_error "cannot open" "" "$BIN/rad-info" "$TMP/missing.ff"
# A byte other than zero in the padding between header and body (outside both checksums).
python3 - "$TMP/c.rad" "$TMP/pad.rad" <<'PY'
import sys
data = bytearray(open(sys.argv[1], "rb").read())
pad = data.find(b"\n\n") + 2
assert data[pad] == 0, "no padding after this header"
data[pad] = ord("X")
open(sys.argv[2], "wb").write(data)
PY
expect_error "pad.rad: corrupt: non-zero padding between the header and the body at byte" "" "$BIN/rad-info" "$TMP/pad.rad"
expect_error "non-zero padding between the header and the body" "$TMP/y.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/pad.rad" -o "$TMP/y.exr" --view "-vp 0.278 0.273 -0.8 -vd 0 0 1 -vu 0 1 0 -vh 40 -vv 40"
finish
