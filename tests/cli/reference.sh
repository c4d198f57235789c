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
  for option in $("$BIN/$tool" --help | grep -oE '^  (  )?(-[a-z],)?--[a-z][a-z-]*' | sed 's/^ *//; s/^-[a-z],//'); do
    grep -qF -- "\`$option" "$SRC/docs/reference/$tool.md" || grep -qF -- ",$option" "$SRC/docs/reference/$tool.md" || fail "$tool $option is not in docs/reference/$tool.md"
    grep -qF -- "$(sed 's/-/\\-/g' <<<"$option")" "$page" || fail "$tool $option is not in its man page"
  done
  # Two links from the README: README -> docs/reference/<tool>.md.
  grep -q "docs/reference/$tool.md" "$SRC/README.md" || fail "README does not link docs/reference/$tool.md"
done
# The common options are declared once (#71): in every tool that takes one, it sits in the
# "Common options" group with the same type, bound, default and default's sentence.
for tool in rad-mesh rad-ff rad-solve rad-shade rad-gather rad-bake rad-report; do
  help=$("$BIN/$tool" --help)
  grep -q '^\[Option Group: Common options\]' <<<"$help" || fail "$tool has no Common options group"
  common=$(sed -n '/^\[Option Group: Common options\]/,$p' <<<"$help")
  for option in --threads --seed --max-memory --quiet --verbose --rows --merge; do
    if grep -qE -- "^ +(-[a-z],)?$option\b" <<<"$help" && ! grep -qE -- "^    (-[a-z],)?$option\b" <<<"$common"; then
      fail "$tool declares $option outside the common options"
    fi
  done
  if grep -q -- '--threads' <<<"$help"; then
    tr -s ' \n' ' ' <<<"$common" | grep -qE -- '--threads INT:INT in \[0 - [0-9]+\]=0 Worker threads \(0: all cores\) ' ||
      fail "$tool's --threads differs: $(grep -A1 -- '--threads' <<<"$help")"
  fi
  if grep -q -- '--max-memory' <<<"$help"; then
    tr -s ' \n' ' ' <<<"$common" | grep -qF "default: 80% of what the job may use: physical memory, its cgroup limit or ulimit -v, the least)" ||
      fail "$tool's --max-memory default is described otherwise"
  fi
done
# A man page reads as one (when man is there).
if command -v man >/dev/null; then
  man -l "$BUILD/man/man1/rad-ff.1" > "$TMP/man.txt" 2>/dev/null
  grep -q "hemisphere" "$TMP/man.txt" || fail "man -l rad-ff.1 does not render"
fi
finish
