# rad-ff: byte-identical output at 1 and 2 threads, memory refusal, summary.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
for method in analytic pairwise hemisphere; do
  extra=""; [ $method = pairwise ] && extra="--samples 16"
  # The same command (the output path is part of the recorded command line), then compare.
  "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" --method $method --threads 1 --seed 5 $extra -q || fail "$method 1 thread"
  mv "$TMP/c.ff" "$TMP/1.ff"
  "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" --method $method --threads 2 --seed 5 $extra -q || fail "$method 2 threads"
  mv "$TMP/c.ff" "$TMP/2.ff"
  cmp -s "$TMP/1.ff" "$TMP/2.ff" || fail "$method differs between 1 and 2 threads"
done
err=$("$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/s.ff" 2>&1) || fail "summary run"
grep -q "non-zeros.*rays.*rays/s.*row sums mean" <<<"$err" || fail "summary: $err"
expect_error "more than --max-memory" "$TMP/m.ff" "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/m.ff" --max-memory 10K
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
finish
