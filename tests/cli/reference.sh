# The user guide's reference pages (docs/reference/<tool>.md) are each tool's --help of today,
# and the build made a man page of each; every option is findable from the README.
source "$(dirname "$0")/lib.sh"
BUILD="$3"
for tool in rad-mesh rad-ff rad-solve rad-shade rad-gather rad-bake rad-report rad-info; do
  python3 "$SRC/scripts/help-doc" "$BIN/$tool" --markdown "$TMP/$tool.md" || fail "help-doc $tool"
  diff -u "$SRC/docs/reference/$tool.md" "$TMP/$tool.md" >"$TMP/diff.txt" ||
    fail "docs/reference/$tool.md is not $tool --help of today (run scripts/update-reference): $(head -20 "$TMP/diff.txt")"
  page="$BUILD/man/man1/$tool.1"
  [ -s "$page" ] || fail "no man page $page"
  grep -q "^\.SH OPTIONS" "$page" || fail "$page has no OPTIONS"
  # Every option of the tool is in its page and its man page.
  for option in $("$BIN/$tool" --help | grep -oE '^  (-[a-z],)?--[a-z][a-z-]*' | sed 's/^ *//; s/^-[a-z],//'); do
    grep -qF -- "\`$option" "$SRC/docs/reference/$tool.md" || grep -qF -- ",$option" "$SRC/docs/reference/$tool.md" || fail "$tool $option is not in docs/reference/$tool.md"
    grep -qF -- "$(sed 's/-/\\-/g' <<<"$option")" "$page" || fail "$tool $option is not in its man page"
  done
  # Two links from the README: README -> docs/reference/<tool>.md.
  grep -q "docs/reference/$tool.md" "$SRC/README.md" || fail "README does not link docs/reference/$tool.md"
done
# A man page reads as one (when man is there).
if command -v man >/dev/null; then
  man -l "$BUILD/man/man1/rad-ff.1" > "$TMP/man.txt" 2>/dev/null
  grep -q "hemisphere" "$TMP/man.txt" || fail "man -l rad-ff.1 does not render"
fi
finish
