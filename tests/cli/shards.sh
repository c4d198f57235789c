# rad-ff --rows / --merge: shards computed apart merge into the very file one run writes.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
M="$TMP/c.mesh"
for method in analytic hemisphere; do
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
finish
