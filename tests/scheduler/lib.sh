# Helpers for the scheduler tests: bash tests/scheduler/X.sh BIN_DIR SOURCE_DIR (as root).
set -uo pipefail
BIN="$(cd "$1" && pwd)"
SRC="$(cd "$2" && pwd)"
TMP=$(mktemp -d)
WORK="$TMP/work"
FAILS=0
fail() { echo "FAIL: $*"; FAILS=$((FAILS + 1)); }
# step WHAT: where the test is, and how long it has run (for CI logs).
step() { echo "$(basename "$0"): ${SECONDS}s: $*" >&2; }
finish() { if [ $FAILS -eq 0 ]; then echo "all checks passed"; exit 0; else exit 1; fi; }
# The office scene, small (8 desks, about 25,000 patches), meshed into $WORK/office.mesh.
make_office() {
  mkdir -p "$WORK"
  python3 "$SRC/scenes/generate.py" office "$WORK/office" --desks 8 >/dev/null || fail "generate the office"
  "$BIN/rad-mesh" "$WORK/office/office.obj" -o "$WORK/office.mesh" --max-edge 0.12 -q 2>/dev/null || fail "mesh the office"
}
# one_run NAME COMMAND...: COMMAND -o NAME here, kept as single-NAME (a merge writes NAME
# with the same command, so the two can be compared byte for byte).
one_run() {
  local name="$1"; shift
  "$@" -o "$name" 2>/dev/null || fail "one-machine run of $name"
  mv "$name" "single-$name"
}
# same NAME WHAT: the merged NAME is single-NAME, byte for byte.
same() {
  [ -e "$1" ] || { fail "$2: no merged $1"; return; }
  cmp -s "$1" "single-$1" || fail "$2: the merge differs from one run"
}
# wait_for_job ID: until Slurm no longer lists the job as pending or running (2 minutes).
wait_for_job() {
  for _ in $(seq 1200); do
    [ -z "$(squeue -h -j "$1" -o %T 2>/dev/null)" ] && return 0
    sleep 0.1
  done
  fail "job $1 did not end"
}
# make_ff ARGS...: Makefile.examples' office form factors (2 desks, 3 shards) into $WORK/mk,
# run from $WORK, with ARGS (SCHEDULER=...); its output in make.txt.
make_ff() {
  (cd "$WORK" && make -f "$SRC/Makefile.examples" BIN="$BIN" OUT=mk DESKS=2 SHARDS=3 "$@" mk/office.ff) >make.txt 2>&1
}
# check_make SCHEDULER ARGS...: the office's form factors through Make with that scheduler are
# the bytes of SCHEDULER=local; remade after a part and the result are lost, only that part is
# computed again ($1's script says which shards it runs).
check_make() {
  local scheduler="$1"; shift
  if [ ! -e "$WORK/mk/local.ff" ]; then
    make_ff -j2 || fail "make SCHEDULER=local: $(tail -3 make.txt)"
    mv "$WORK/mk/office.ff" "$WORK/mk/local.ff"
  fi
  rm -rf "$WORK/mk/office.ff.parts"
  make_ff SCHEDULER="$scheduler" "$@" || fail "make SCHEDULER=$scheduler: $(tail -3 make.txt)"
  cmp -s "$WORK/mk/office.ff" "$WORK/mk/local.ff" || fail "make SCHEDULER=$scheduler: not the bytes of SCHEDULER=local"
  rm -f "$WORK/mk/office.ff" "$WORK/mk/office.ff.parts/office.ff.part1"
  local kept
  kept=$(stat -c %Y "$WORK/mk/office.ff.parts/office.ff.part0")
  make_ff SCHEDULER="$scheduler" "$@" || fail "make SCHEDULER=$scheduler again: $(tail -3 make.txt)"
  cmp -s "$WORK/mk/office.ff" "$WORK/mk/local.ff" || fail "make SCHEDULER=$scheduler again: not the bytes of SCHEDULER=local"
  [ "$(stat -c %Y "$WORK/mk/office.ff.parts/office.ff.part0")" = "$kept" ] || fail "make SCHEDULER=$scheduler again: a part that was there was computed again"
}
