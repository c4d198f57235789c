# How outputs are written (issue #18, items 8-12): devices written in place, collisions and
# unwritable targets refused before any work, a run's outputs landing together or not at
# all, and temporaries left by a killed run cleaned up.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q || fail "rad-ff"
VF="$SRC/scenes/cornell/cornell.vf"
M="$TMP/c.mesh"; F="$TMP/c.ff"
"$BIN/rad-solve" "$M" "$F" -o "$TMP/c.rad" -q || fail "rad-solve"
R="$TMP/c.rad"

# 9. Devices are written in place, never replaced by a renamed file; a full device is an
#    error (exit 2), and a pipe behind /dev/stdout gets the bytes.
# (Only where /dev/full is the device it should be: a test must not make things worse.)
[ -c /dev/full ] || { echo "FAIL: /dev/full is not a device on this machine"; exit 1; }
"$BIN/rad-solve" "$M" "$F" -o /dev/null -q || fail "-o /dev/null"
[ -c /dev/null ] || fail "/dev/null is no longer a device"
err=$("$BIN/rad-solve" "$M" "$F" -o /dev/full -q 2>&1); rc=$?
[ $rc -eq 2 ] || fail "-o /dev/full: exit $rc (wanted 2): $err"
grep -q "No space left" <<<"$err" || fail "-o /dev/full message: $err"
[ -c /dev/full ] || fail "/dev/full is no longer a device"
"$BIN/rad-solve" "$M" "$F" -o /dev/stdout -q | cat > "$TMP/piped.rad"
"$BIN/rad-info" "$TMP/piped.rad" >/dev/null || fail "-o /dev/stdout into a pipe: not a valid file"
[ -L /dev/stdout ] || fail "/dev/stdout is no longer a link"
"$BIN/rad-shade" "$M" "$R" -o /dev/null --png /dev/null --view-file "$VF" -x 40 -y 40 -q ||
  fail "rad-shade -o /dev/null"

# 11. A secondary output that fails leaves no output of the run behind.
err=$("$BIN/rad-solve" "$M" "$F" -o "$TMP/s.rad" --log /dev/full -q 2>&1); rc=$?
[ $rc -eq 2 ] || fail "--log /dev/full: exit $rc: $err"
[ ! -e "$TMP/s.rad" ] || fail "--log failed but -o was written"
err=$("$BIN/rad-solve" "$M" "$F" -o "$TMP/s.rad" --snapshot "$TMP/snap-%d.rad" --snapshot-at 1,2 \
  --log /dev/full -q 2>&1); rc=$?
[ $rc -eq 2 ] || fail "--log /dev/full with snapshots: exit $rc: $err"
[ -z "$(ls "$TMP" | grep -e snap- -e s.rad)" ] || fail "snapshots left behind: $(ls "$TMP")"
err=$("$BIN/rad-shade" "$M" "$R" -o "$TMP/s.exr" --png /dev/full --ply "$TMP/s.ply" \
  --view-file "$VF" -x 40 -y 40 -q 2>&1); rc=$?
[ $rc -eq 2 ] || fail "--png /dev/full: exit $rc: $err"
[ ! -e "$TMP/s.exr" ] && [ ! -e "$TMP/s.ply" ] || fail "--png failed but other outputs were written"
[ -z "$(ls -A "$TMP" | grep tmp)" ] || fail "temporary files left: $(ls -A "$TMP")"
# ... and when all succeed, all are there.
"$BIN/rad-solve" "$M" "$F" -o "$TMP/s.rad" --snapshot "$TMP/snap-%d.rad" --snapshot-at 1,2 \
  --log "$TMP/s.csv" -q || fail "solve with log and snapshots"
for f in s.rad s.csv snap-1.rad snap-2.rad; do [ -s "$TMP/$f" ] || fail "$f missing"; done
rm -f "$TMP"/s.* "$TMP"/snap-*

# 10. A snapshot pattern that would overwrite an input or another output is refused first.
expect_error "--snapshot $TMP/it-%d.rad would overwrite -o $TMP/it-5.rad" "$TMP/it-5.rad" \
  "$BIN/rad-solve" "$M" "$F" -o "$TMP/it-5.rad" --snapshot "$TMP/it-%d.rad" --snapshot-at 5
expect_error "would overwrite -o $TMP/it-10.rad" "$TMP/it-10.rad" \
  "$BIN/rad-solve" "$M" "$F" -o "$TMP/it-10.rad" --snapshot "$TMP/it-%d.rad" --snapshot-every 5
# Only the iterations it writes count: -o it-10 beside snapshots 1 and 4 is fine.
"$BIN/rad-solve" "$M" "$F" -o "$TMP/it-10.rad" --iterations 10 --snapshot "$TMP/it-%d.rad" \
  --snapshot-at 1,4 -q || fail "snapshots 1,4 beside -o it-10"
[ -s "$TMP/it-1.rad" ] && [ -s "$TMP/it-4.rad" ] && [ -s "$TMP/it-10.rad" ] || fail "it-1/4/10 missing"
cp "$F" "$TMP/f7.ff"
expect_error "would overwrite the input" "" \
  "$BIN/rad-solve" "$M" "$TMP/f7.ff" -o "$TMP/o.rad" --snapshot "$TMP/./f%d.ff" --snapshot-at 7
cmp -s "$F" "$TMP/f7.ff" || fail "the input was changed"
expect_error "--snapshot $TMP/it-3.%d would overwrite --log $TMP/it-3.7" "$TMP/o.rad" \
  "$BIN/rad-solve" "$M" "$F" -o "$TMP/o.rad" --log "$TMP/it-3.7" --snapshot "$TMP/it-3.%d" --snapshot-at 2,7
expect_error "has no %d" "$TMP/o.rad" "$BIN/rad-solve" "$M" "$F" -o "$TMP/o.rad" \
  --snapshot "$TMP/it.rad" --snapshot-at 1
expect_error "the folder '$TMP/none' does not exist" "$TMP/o.rad" "$BIN/rad-solve" "$M" "$F" \
  -o "$TMP/o.rad" --snapshot "$TMP/none/it-%d.rad" --snapshot-at 1

# 11. Found before the work: an output that is a folder, a folder we may not write in.
expect_error "is a folder" "" "$BIN/rad-ff" "$M" -o "$TMP"
if [ "$(id -u)" -ne 0 ]; then
  mkdir "$TMP/ro" && chmod 555 "$TMP/ro"
  err=$("$BIN/rad-ff" "$M" -o "$TMP/ro/x.ff" 2>&1); rc=$?
  [ $rc -eq 2 ] && grep -q "nothing was computed" <<<"$err" || fail "read-only folder: $rc $err"
fi

# 12. A temporary left by a killed run (.NAME.tmp.PID, PID gone) is removed by the next run
#     writing that output; one of a live process, and one holding a lock, are left alone.
sleep 60 >/dev/null 2>&1 & live=$!
touch "$TMP/.k.rad.tmp.999999" "$TMP/.k.rad.tmp.$live" "$TMP/.k.rad.tmpX" "$TMP/.other.rad.tmp.999999"
ln -s "$TMP/c.rad" "$TMP/.k.rad.tmp.999998"
exec 9>"$TMP/.k.rad.tmp.999997" && flock 9 # this shell holds the lock
"$BIN/rad-solve" "$M" "$F" -o "$TMP/k.rad" -q || fail "solve over stale temporaries"
[ ! -e "$TMP/.k.rad.tmp.999999" ] || fail "stale temporary of a dead PID kept"
[ ! -L "$TMP/.k.rad.tmp.999998" ] || fail "stale link of a dead PID kept"
cmp -s "$R" "$TMP/c.rad" || fail "the stale link's target was changed"
[ -e "$TMP/.k.rad.tmp.$live" ] || fail "temporary of a live process removed"
[ -e "$TMP/.k.rad.tmp.999997" ] || fail "locked temporary removed"
[ -e "$TMP/.k.rad.tmpX" ] && [ -e "$TMP/.other.rad.tmp.999999" ] || fail "unrelated files removed"
exec 9>&-
kill $live 2>/dev/null; wait $live 2>/dev/null

# 13. Two writers in two PID namespaces on one folder (two containers on one volume, both
#     PID 1): the other's temporary, named for its PID 1 and locked, is never deleted, and
#     this run's output lands. Needs unshare (root); skipped where it cannot run.
if unshare --pid --fork true 2>/dev/null; then
  unshare --pid --fork flock "$TMP/.ns.rad.tmp.1" sleep 30 & other=$!
  for i in $(seq 50); do [ -e "$TMP/.ns.rad.tmp.1" ] && break; sleep 0.1; done
  unshare --pid --fork "$BIN/rad-solve" "$M" "$F" -o "$TMP/ns.rad" -q || fail "solve as PID 1"
  [ -e "$TMP/.ns.rad.tmp.1" ] || fail "the other PID 1's locked temporary was deleted"
  "$BIN/rad-info" "$TMP/ns.rad" >/dev/null 2>&1 || fail "the run as PID 1 lost its output"
  kill $other 2>/dev/null; wait $other 2>/dev/null
else
  echo "note: unshare --pid unavailable: two-namespace check skipped"
fi

# 7. A header larger than readers accept is never written: refused before the work.
args=(); for i in $(seq 60000); do args+=("--emission=m$i=1,1,1"); done
err=$("$BIN/rad-solve" "$M" "$F" -o "$TMP/h.rad" "${args[@]}" 2>&1); rc=$?
[ $rc -eq 1 ] || fail "60000 --emission: exit $rc"
grep -q "pass fewer or shorter arguments" <<<"$err" || fail "60000 --emission message: ${err:0:300}"
[ ! -e "$TMP/h.rad" ] || fail "a header too big was written"
finish
