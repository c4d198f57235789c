# The chain with GNU parallel over ssh (an sshd started here on the loopback address, with a
# key made for the test): shards run by scripts/parallel-shards in a working folder of their
# own on the "remote" machine, the inputs sent and the parts returned by parallel, merged here
# byte for byte as one run writes; a failed shard is rerun alone from the job log.
#   bash tests/scheduler/parallel.sh BIN_DIR SOURCE_DIR      (as root)
source "$(dirname "$0")/lib.sh"
SSHD="$TMP/sshd"
trap '"$SRC/tests/scheduler/sshd-loopback" stop "$SSHD"; rm -rf "$TMP"' EXIT
SSH="$("$SRC/tests/scheduler/sshd-loopback" start "$SSHD")" || { echo "FAIL: the test sshd did not start"; exit 1; }
LOGIN="$(id -un)@127.0.0.1"
step "mesh the office"
make_office
cd "$WORK" || exit 1
SHARDS="$SRC/scripts/parallel-shards"
# What parallel leaves in the remote's ~/.parallel/tmp (working folders, removed after); not
# its own cache of each host's properties, tmp/sshlogin, which it makes on a machine's first
# run and keeps (on a fresh machine the count went from 0 to 1 with no folder left behind).
remote_folders() { find "$HOME/.parallel/tmp" -mindepth 1 -maxdepth 1 -type d ! -name sshlogin 2>/dev/null | wc -l; }
folders_before=$(remote_folders)

# A rad-ff that fails once for shard 2 (while $FLAG exists), as a machine that goes down.
FLAG="$TMP/fail-shard-2"
cat >"$TMP/flaky-rad-ff" <<EOF
#!/usr/bin/env bash
case " \$* " in *" --rows 2/4 "*) if [ -e "$FLAG" ]; then rm -f "$FLAG"; echo "flaky-rad-ff: shard 2 fails this time" >&2; exit 3; fi ;; esac
exec "$BIN/rad-ff" "\$@"
EOF
chmod +x "$TMP/flaky-rad-ff"
touch "$FLAG"

step "form factors: 4 shards over ssh, one fails"
one_run office.ff "$BIN/rad-ff" office.mesh --method hemisphere --rays 1000 -q
# The merge's command must be one run's: the flaky tool is named rad-ff too.
mkdir -p "$TMP/tools" && ln -s "$TMP/flaky-rad-ff" "$TMP/tools/rad-ff"
FF=("$TMP/tools/rad-ff" office.mesh --method hemisphere --rays 1000 -q)
"$SHARDS" -n 4 --ssh "$SSH" -S "$LOGIN" --transfer office.mesh office.ff -- "${FF[@]}" 2> first.txt && fail "a failed shard went unreported"
grep -q "shard(s) 2 failed" first.txt || fail "the failed shard is not named: $(cat first.txt)"
[ ! -e office.ff ] || fail "office.ff written although a shard failed"
for k in 0 1 3; do [ -e office.ff.parts/office.ff.part$k ] || fail "part $k did not come back"; done
[ ! -e office.ff.parts/office.ff.part2 ] || fail "the failed shard left a part"
# The job log: every shard ran over ssh, sent the mesh and returned its part.
awk -F'\t' -v login="$LOGIN" 'NR > 1 && ($2 != login || $5 <= 0 || ($7 == 0 && $6 <= 0)) { bad = 1 } END { exit bad }' office.ff.parts/office.ff.joblog ||
  fail "a shard did not run over ssh with its files sent and returned: $(cut -f 2-8 office.ff.parts/office.ff.joblog)"
[ "$(remote_folders)" = "$folders_before" ] || fail "the remote working folders were not removed"

step "rerun: only the failed shard"
lines_before=$(wc -l <office.ff.parts/office.ff.joblog)
before=$(stat -c %Y office.ff.parts/office.ff.part0)
"$SHARDS" -n 4 --ssh "$SSH" -S "$LOGIN" --transfer office.mesh office.ff -- "${FF[@]}" 2> second.txt || fail "rerun: $(cat second.txt)"
# The failed shard's line is replaced by its rerun's, last; the others' lines are kept.
[ "$(wc -l <office.ff.parts/office.ff.joblog)" = "$lines_before" ] || fail "the rerun ran more than the failed shard: $(cut -f 1,7,9 office.ff.parts/office.ff.joblog)"
tail -n 1 office.ff.parts/office.ff.joblog | awk -F'\t' '$7 == 0 && $9 ~ /--rows 2\/4 / { ok = 1 } END { exit !ok }' || fail "the rerun did not run shard 2: $(cut -f 1,7,9 office.ff.parts/office.ff.joblog)"
[ "$(stat -c %Y office.ff.parts/office.ff.part0)" = "$before" ] || fail "a finished part was computed again"
same office.ff "form factors over ssh"

step "solve here, image bands over ssh"
"$BIN/rad-solve" office.mesh office.ff -o office.rad -q || fail "solve"
SHADE=("$BIN/rad-shade" office.mesh office.rad --png office.png --gather 8 -x 64 -y 48
  --view "-vp 1 2.2 0.5 -vd 1 -0.35 1 -vu 0 1 0 -vh 80 -vv 55" -q)
one_run office.exr "${SHADE[@]}"
mv office.png single-office.png
"$SHARDS" -n 3 --ssh "$SSH" -S "$LOGIN" --transfer office.mesh --transfer office.rad office.exr -- "${SHADE[@]}" 2>/dev/null || fail "image bands over ssh"
same office.exr "gathered image over ssh (EXR)"
cmp -s office.png single-office.png || fail "gathered image over ssh (PNG): the merge differs from one run"

step "make SCHEDULER=parallel"
check_make parallel HOSTS="$LOGIN" SSH="$SSH"
# The job log: the lost part's line dropped and run again last, the others' lines kept.
[[ "$(tail -n 1 "$WORK/mk/office.ff.parts/office.ff.joblog")" == *"--rows 1/3 "* ]] || fail "make SCHEDULER=parallel again: the lost part did not run again last: $(cut -f 1,7,9 "$WORK/mk/office.ff.parts/office.ff.joblog")"
[ "$(wc -l <"$WORK/mk/office.ff.parts/office.ff.joblog")" = 4 ] || fail "make SCHEDULER=parallel again: the job log has other than one line a shard"

step "hostile names (#70 item 1): OUTPUT and --parts never run as code"
mkdir -p "$WORK/hostile" && cd "$WORK/hostile" || exit 1
cp "$WORK/office.mesh" .
# GNU parallel's {= perl =} in a path: refused, and nothing runs.
"$SHARDS" -n 2 'r{=system("touch PWNED")=}.ff' -- "$BIN/rad-ff" office.mesh --rays 64 -q 2> braces.txt &&
  fail "an OUTPUT with {= =} was taken"
grep -q "may not contain { or }" braces.txt || fail "the brace refusal does not say why: $(cat braces.txt)"
"$SHARDS" -n 2 --parts 'p{=system("touch PWNED")=}' x.ff -- "$BIN/rad-ff" office.mesh --rays 64 -q 2>/dev/null &&
  fail "--parts with {= =} was taken"
# A shell's $(...) in a path is a file name, first run and rerun (the rerun read the job log
# through sh -c before).
for run in first second; do
  "$SHARDS" -n 2 'd$(touch PWNED).ff' -- "$BIN/rad-ff" office.mesh --rays 64 -q 2>/dev/null || fail "d\$(...).ff: $run run"
done
[ -e 'd$(touch PWNED).ff' ] || fail "d\$(touch PWNED).ff was not written"
[ ! -e PWNED ] && [ ! -e "$WORK/PWNED" ] || fail "a path ran as code (PWNED exists)"

step "a part that is a link is not a done shard (#70 item 9)"
"$SHARDS" -n 2 l.ff -- "$BIN/rad-ff" office.mesh --rays 64 -q 2>/dev/null || fail "sharded l.ff"
cp l.ff l-first.ff
rm l.ff && ln -sf /etc/passwd l.ff.parts/l.ff.part1
"$SHARDS" -n 2 l.ff -- "$BIN/rad-ff" office.mesh --rays 64 -q 2> link.txt || fail "a linked part: $(cat link.txt)"
grep -q "l.ff.part1 is a symbolic link, not a part a shard wrote: removed" link.txt || fail "the linked part is not named: $(cat link.txt)"
cmp -s l.ff l-first.ff || fail "with a linked part, the merge is not the first run's bytes"
[ ! -L l.ff.parts/l.ff.part1 ] || fail "the link is still there"

step "parts from another mesh are not done shards (#70 item 9)"
"$BIN/rad-mesh" "$WORK/office/office.obj" -o other.mesh --max-edge 0.2 -q 2>/dev/null || fail "mesh other"
"$SHARDS" -n 2 o.ff -- "$BIN/rad-ff" other.mesh --rays 64 -q 2>/dev/null || fail "sharded o.ff"
rm o.ff
# The mesh made again, finer: the parts there are the old mesh's (the merge refused them on
# every rerun, advising to run the same command again).
"$BIN/rad-mesh" "$WORK/office/office.obj" -o other.mesh --max-edge 0.15 -q 2>/dev/null || fail "mesh other again"
one_run o.ff "$BIN/rad-ff" other.mesh --rays 64 -q
"$SHARDS" -n 2 o.ff -- "$BIN/rad-ff" other.mesh --rays 64 -q 2> other.txt || fail "parts of another mesh: $(cat other.txt)"
# Each part is read and named with the input that changed (before, the stamp named them
# together: "made by another command or from inputs that have changed since").
for k in 0 1; do
  grep -q "o.ff.part$k is not a done shard: .*other.mesh has changed since (xxh64:[0-9a-f]* recorded, xxh64:[0-9a-f]* now) -- removed" other.txt ||
    fail "the old mesh's part $k is not named: $(cat other.txt)"
done
same o.ff "parts of another mesh computed again"

step "parts of another command on the same mesh are not done shards"
# Their inputs are this command's (rad-info --check-inputs passes them); the stamp is not.
"$SHARDS" -n 2 r.ff -- "$BIN/rad-ff" office.mesh --rays 64 -q 2>/dev/null || fail "sharded r.ff"
rm r.ff
one_run r.ff "$BIN/rad-ff" office.mesh --rays 32 -q
"$SHARDS" -n 2 r.ff -- "$BIN/rad-ff" office.mesh --rays 32 -q 2> rays.txt || fail "another command: $(cat rays.txt)"
grep -q "removed r.ff.parts/r.ff.part0 r.ff.parts/r.ff.part1: made by another command or from inputs that have changed since" rays.txt ||
  fail "the other command's parts are not named: $(cat rays.txt)"
same r.ff "parts of another command computed again"

step "a part copied in from another mesh's run is not a done shard (#70 item 9)"
# The stamp is this command's; the part is a plain file that reads, but other.mesh's.
"$SHARDS" -n 2 c.ff -- "$BIN/rad-ff" office.mesh --rays 64 -q 2>/dev/null || fail "sharded c.ff"
cp c.ff c-first.ff && rm c.ff
cp o.ff.parts/o.ff.part1 c.ff.parts/c.ff.part1
"$SHARDS" -n 2 c.ff -- "$BIN/rad-ff" office.mesh --rays 64 -q 2> copied.txt || fail "a copied part: $(cat copied.txt)"
grep -q "c.ff.part1 is not a done shard: .*office.mesh is not among its inputs (it was made from another file) -- removed" copied.txt ||
  fail "the copied part is not named: $(cat copied.txt)"
cmp -s c.ff c-first.ff || fail "with a copied part, the merge is not the first run's bytes"
# A part that does not read (cut short) is not done either.
rm c.ff && head -c 4000 c.ff.parts/c.ff.part0 > cut.part && mv cut.part c.ff.parts/c.ff.part0
"$SHARDS" -n 2 c.ff -- "$BIN/rad-ff" office.mesh --rays 64 -q 2> cut.txt || fail "a cut part: $(cat cut.txt)"
grep -q "c.ff.part0 is not a done shard: " cut.txt || fail "the cut part is not named: $(cat cut.txt)"
cmp -s c.ff c-first.ff || fail "with a cut part, the merge is not the first run's bytes"
finish
