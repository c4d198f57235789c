# The chain on a real Slurm cluster (one host, started here from Debian's packages): the office
# scene's form factors (hemisphere and hierarchical), its gathered image and its sensors
# computed as array jobs by scripts/slurm-shards and merged by a job that runs after them,
# each compared byte for byte with a one-machine run; a task cancelled mid-way makes the
# merge fail naming the missing rows, and the same command again computes only that task.
#   bash tests/scheduler/slurm.sh BIN_DIR SOURCE_DIR      (as root)
source "$(dirname "$0")/lib.sh"
CLUSTER="$TMP/cluster"
trap '"$SRC/tests/scheduler/slurm-cluster" stop "$CLUSTER"; rm -rf "$TMP"' EXIT
eval "$("$SRC/tests/scheduler/slurm-cluster" start "$CLUSTER")" || { echo "FAIL: the Slurm cluster did not start"; exit 1; }
sinfo -h -o '%D node(s) %c cpu(s) %T' >&2
step "mesh the office"
make_office
cd "$WORK" || exit 1
SHARDS="$SRC/scripts/slurm-shards"

# Form factors, hemisphere: one task is cancelled while it runs. The tasks take both CPUs
# each, so they run one after another and the cancelled one is caught mid-way.
step "form factors (hemisphere): one run, then 4 tasks, one cancelled"
FF=(rad-ff office.mesh --method hemisphere --rays 4000 -q)
one_run office.ff "$BIN/${FF[0]}" "${FF[@]:1}"
"$SHARDS" -n 4 --sbatch "--cpus-per-task=2" office.ff -- "$BIN/${FF[0]}" "${FF[@]:1}" 2> submit.txt || fail "submit the form factors"
array=$(sed -n 's/^slurm-shards: array job \([0-9]*\):.*/\1/p' submit.txt)
merge=$(sed -n 's/^slurm-shards: merge job \([0-9]*\) .*/\1/p' submit.txt)
[ -n "$array" ] && [ -n "$merge" ] || fail "job ids not reported: $(cat submit.txt)"
# Cancelled once its rad-ff has run a moment (a task takes seconds).
running=0
for _ in $(seq 1200); do
  pgrep -f -- "--rows 2/4" >/dev/null && running=1 && break
  sleep 0.05
done
[ $running = 1 ] || fail "task 2's rad-ff never ran"
sleep 0.3
[ "$(squeue -h -r -j "${array}_2" -o %T 2>/dev/null)" = RUNNING ] || fail "task 2 is not running"
scancel "${array}_2"
wait_for_job "$merge"
merge_state=$(scontrol show job "$merge" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
[ "$merge_state" = FAILED ] || fail "the merge job is $merge_state, not FAILED, after a task was cancelled"
patches=$("$BIN/rad-info" office.mesh | sed -n 's/^  patches = //p')
grep -q "rows $((2 * patches / 4)) to $((3 * patches / 4 - 1)) are in no part" office.ff.parts/office.ff.merge.log ||
  fail "the merge does not name the cancelled task's rows: $(cat office.ff.parts/office.ff.merge.log)"
[ ! -e office.ff ] || fail "the failed merge wrote office.ff"
[ ! -e office.ff.parts/office.ff.part2 ] || fail "the cancelled task left a part"
step "resubmit"
before=$(stat -c %Y office.ff.parts/office.ff.part0)
"$SHARDS" -n 4 --sbatch "--cpus-per-task=2" --wait office.ff -- "$BIN/${FF[0]}" "${FF[@]:1}" 2> resubmit.txt || fail "resubmit: $(cat resubmit.txt)"
grep -q "shard(s) 2 of 4" resubmit.txt || fail "the resubmission ran more than the missing task: $(cat resubmit.txt)"
[ "$(stat -c %Y office.ff.parts/office.ff.part0)" = "$before" ] || fail "a finished part was computed again"
same office.ff "form factors (hemisphere)"
# A part that is a link (to /etc/passwd) is not a done task (#70 item 9): removed, named, and
# its task run again.
rm office.ff && ln -sf /etc/passwd office.ff.parts/office.ff.part1
"$SHARDS" -n 4 --wait office.ff -- "$BIN/${FF[0]}" "${FF[@]:1}" 2> linked.txt || fail "a linked part: $(cat linked.txt)"
grep -q "office.ff.part1 is a symbolic link, not a part a shard wrote: removed" linked.txt || fail "the linked part is not named: $(cat linked.txt)"
grep -q "shard(s) 1 of 4" linked.txt || fail "the linked part's task did not run again: $(cat linked.txt)"
same office.ff "form factors (hemisphere), a linked part computed again"

# Hierarchical links, in 4 tasks.
step "links (hierarchical)"
LINKS=(rad-ff office.mesh --method hierarchical --epsilon 0.05 -q)
one_run office.links "$BIN/${LINKS[0]}" "${LINKS[@]:1}"
"$SHARDS" -n 4 --wait office.links -- "$BIN/${LINKS[0]}" "${LINKS[@]:1}" 2>/dev/null || fail "hierarchical shards"
same office.links "links (hierarchical)"

# The rest of the chain: solve here, then the gathered image in bands and the sensors in
# chunks, on the cluster.
step "solve, image, sensors"
"$BIN/rad-solve" office.mesh office.ff -o office.rad -q || fail "solve"
SHADE=(rad-shade office.mesh office.rad --png office.png --gather 16 -x 96 -y 64
  --view "-vp 1 2.2 0.5 -vd 1 -0.35 1 -vu 0 1 0 -vh 80 -vv 55" -q)
one_run office.exr "$BIN/${SHADE[0]}" "${SHADE[@]:1}"
mv office.png single-office.png
"$SHARDS" -n 4 --wait office.exr -- "$BIN/${SHADE[0]}" "${SHADE[@]:1}" 2>/dev/null || fail "image bands"
same office.exr "gathered image (EXR)"
cmp -s office.png single-office.png || fail "gathered image (PNG): the merge differs from one run"
GATHER=(rad-gather office.mesh office.rad --grid "0.5 0.5 6.5 11.5 0.8 12 22" --lux --header -q)
one_run office.lux "$BIN/${GATHER[0]}" "${GATHER[@]:1}"
"$SHARDS" -n 4 --wait office.lux -- "$BIN/${GATHER[0]}" "${GATHER[@]:1}" 2>/dev/null || fail "sensor chunks"
same office.lux "work-plane sensors"

step "make SCHEDULER=slurm"
check_make slurm
grep -q "shard(s) 1 of 3" "$WORK/make.txt" || fail "make SCHEDULER=slurm again: not only the lost part: $(cat "$WORK/make.txt")"
finish
