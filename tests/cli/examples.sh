# The Cornell chain through Makefile.examples in a temporary folder; changing the light
# colour re-runs rad-solve and rad-shade only, never rad-ff; a rebuilt tool remakes what it
# made. The tools are copies (their times kept), so that touching one leaves the build alone.
source "$(dirname "$0")/lib.sh"
cd "$SRC"
mkdir -p "$TMP/bin"
cp -p "$BIN"/rad-mesh "$BIN"/rad-ff "$BIN"/rad-solve "$BIN"/rad-shade "$TMP/bin/"
MK="make -f Makefile.examples BIN=$TMP/bin OUT=$TMP/out SIZE=-x\ 96\ -y\ 96"
eval $MK cornell >"$TMP/make.log" 2>&1 || { cat "$TMP/make.log"; fail "make cornell"; }
for f in cornell.mesh cornell.ff cornell.rad cornell-gs-1.rad cornell-gs-4.rad cornell-pr-10.rad cornell-apr-100.rad; do
  "$BIN/rad-info" "$TMP/out/$f" >/dev/null || fail "rad-info $f"
done
for f in cornell.exr cornell.png cornell-blue.exr fig3-cornell-gs-1.exr fig3-cornell-apr-10.png; do
  [ -s "$TMP/out/$f" ] || fail "missing $f"
done
dry=$(eval $MK -n cornell)
grep -q "rad-" <<<"$dry" && fail "an up-to-date tree would re-run: $dry"
# A rebuilt rad-shade re-renders and re-runs nothing before it; a rebuilt rad-mesh remakes the
# whole chain (before, outputs depended on the scenes alone and stayed stale).
touch "$TMP/bin/rad-shade"
dry=$(eval $MK -n cornell)
grep -q "rad-shade" <<<"$dry" || fail "a rebuilt rad-shade must re-render"
grep -q "rad-mesh\|rad-ff\|rad-solve" <<<"$dry" && fail "a rebuilt rad-shade re-runs more: $dry"
eval $MK cornell >"$TMP/make2.log" 2>&1 || { cat "$TMP/make2.log"; fail "make cornell again"; }
touch "$TMP/bin/rad-mesh"
dry=$(eval $MK -n cornell)
grep -q "rad-mesh" <<<"$dry" && grep -q "rad-ff" <<<"$dry" && grep -q "rad-shade" <<<"$dry" ||
  fail "a rebuilt rad-mesh must remake the chain: $dry"
eval $MK cornell >"$TMP/make3.log" 2>&1 || { cat "$TMP/make3.log"; fail "make cornell a third time"; }
dry=$(eval $MK -n cornell LIGHT=10,20,40)
grep -q "rad-solve" <<<"$dry" || fail "a new light colour must re-run rad-solve"
grep -q "rad-shade" <<<"$dry" || fail "a new light colour must re-run rad-shade"
grep -q "rad-ff\|rad-mesh" <<<"$dry" && fail "a new light colour must not re-run rad-ff: $dry"
# Relighting: one solve with light groups, three lighting states by rad-shade --mix.
eval $MK relight >"$TMP/relight.log" 2>&1 || { cat "$TMP/relight.log"; fail "make relight"; }
[ "$(grep -c "rad-solve" "$TMP/relight.log")" -eq 1 ] || fail "relight must solve once: $(cat "$TMP/relight.log")"
[ "$(grep -c "rad-shade" "$TMP/relight.log")" -eq 3 ] || fail "relight must render three states"
for f in relight-daylight.png relight-lamp.png relight-both-warm.png relight-both-warm.exr; do
  [ -s "$TMP/out/$f" ] || fail "missing $f"
done
exrheader "$TMP/out/relight-both-warm.exr" | grep -q "lamp.R" || fail "relight layers"
finish

