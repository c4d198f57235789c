# Helpers for the command-line tests: bash tests/cli/X.sh BIN_DIR SOURCE_DIR
set -uo pipefail
BIN="$1"; SRC="$2"
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
FAILS=0
fail() { echo "FAIL: $*"; FAILS=$((FAILS + 1)); }
# expect_error EXPECTED_FRAGMENT OUTPUT_FILE_THAT_MUST_NOT_EXIST COMMAND...
expect_error() {
  local fragment="$1" output="$2"; shift 2
  local err rc
  err=$("$@" 2>&1 >/dev/null); rc=$?
  [ $rc -eq 1 ] || fail "exit $rc (wanted 1): $*"
  grep -qF -- "$fragment" <<<"$err" || fail "message '$err' lacks '$fragment': $*"
  [ -z "$output" ] || [ ! -e "$output" ] || fail "$output was written: $*"
}
finish() { if [ $FAILS -eq 0 ]; then echo "all checks passed"; exit 0; else exit 1; fi; }
cornell_mesh() { "$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/c.mesh" --max-edge "${1:-0.1}" -q; }
