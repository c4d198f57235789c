# rad-shade: flat, smoothed and albedo images from one solve; EXR opens in exrheader; bad input.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/c.rad" -q
VF="$SRC/scenes/cornell/cornell.vf"
for mode in "--flat" "--smooth average" "--smooth area" "--smooth crease" "--albedo"; do
  "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/i.exr" --view-file "$VF" -x 64 -y 64 $mode --png "$TMP/i.png" --ply "$TMP/i.ply" -q || fail "$mode"
done
if command -v exrheader >/dev/null; then
  exrheader "$TMP/i.exr" | grep -q "radiosity:provenance" || fail "exrheader does not show the provenance"
fi
head -c 8 "$TMP/i.png" | od -An -c | grep -q "P   N   G" || fail "png signature"
head -1 "$TMP/i.ply" | grep -q "^ply" || fail "ply"
expect_error "parallel" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view "-vd 0 1 0 -vu 0 1 0"
expect_error "sees no geometry" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view "-vp 0.3 0.3 -1 -vd 0 0 -1"
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/other.mesh" --max-edge 0.2 -q
expect_error "does not belong to" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/other.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view-file "$VF"
expect_error "does not exist" "" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/no/such/v.exr" --view-file "$VF"
printf -- '-vp 0 0 0\n-vh banana\n' > "$TMP/bad.vf"
expect_error "bad.vf:2:" "$TMP/v.exr" "$BIN/rad-shade" "$TMP/c.mesh" "$TMP/c.rad" -o "$TMP/v.exr" --view-file "$TMP/bad.vf"
finish
