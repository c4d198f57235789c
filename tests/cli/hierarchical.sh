# rad-ff --method hierarchical and rad-solve over its links: the chain end to end, the
# file's header, thread-count identity, overrides and light groups, and the refusals.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.1
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.links" --method hierarchical --threads 1 -q || fail "rad-ff hierarchical"
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c2.links" --method hierarchical --threads 2 -q
cmp -s <("$BIN/rad-info" --csv "$TMP/c.links") <("$BIN/rad-info" --csv "$TMP/c2.links") || fail "links differ between 1 and 2 threads"
"$BIN/rad-info" "$TMP/c.links" | grep -q "kind:      links" || fail "rad-info names the kind"
"$BIN/rad-info" "$TMP/c.links" | grep -q "method = hierarchical" || fail "header records the method"
"$BIN/rad-info" "$TMP/c.links" | grep -q "epsilon = 0.02" || fail "header records epsilon"
# The chain: solve (gs, jacobi), then shade as any .rad.
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.links" -o "$TMP/gs.rad" -q || fail "solve gs over links"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.links" -o "$TMP/jacobi.rad" --method jacobi -q || fail "solve jacobi over links"
"$BIN/rad-shade" "$TMP/c.mesh" "$TMP/gs.rad" -o "$TMP/gs.exr" --view-file "$SRC/scenes/cornell/cornell.vf" -x 64 -q || fail "shade a solution over links"
# Gauss-Seidel and Jacobi converge to one solution.
python3 - "$TMP" "$BIN" <<'PY' || fail "gs and jacobi over links disagree"
import subprocess, sys
tmp, bin = sys.argv[1], sys.argv[2]
read = lambda p: [list(map(float, l.split(",")[1:])) for l in subprocess.check_output([bin + "/rad-info", "--csv", p], text=True).splitlines()[1:]]
a, b = read(tmp + "/gs.rad"), read(tmp + "/jacobi.rad")
sys.exit(any(abs(x - y) > 1e-4 * max(1, y) for ra, rb in zip(a, b) for x, y in zip(ra, rb)))
PY
# Materials and lights change without rad-ff: an override, light groups, a log.
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.links" -o "$TMP/blue.rad" --emission light=10,20,30 -q || fail "override over links"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.links" -o "$TMP/groups.rad" --light-groups --log "$TMP/log.csv" -q || fail "light groups over links"
"$BIN/rad-info" "$TMP/groups.rad" | grep -q "light group" || fail "groups stored"
[ "$(head -1 "$TMP/log.csv")" = "iteration,residual,power_r,power_g,power_b,seconds" ] || fail "log over links"
# Links are refined finer for the mesh's emitters: a material made to emit at solve time is warned about.
"$BIN/rad-info" "$TMP/c.links" | grep -q "emitters = light" || fail "header records the emitters"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.links" -o "$TMP/white.rad" --emission white=1,1,1 -q 2> "$TMP/warn.txt" || fail "solve with a new emitter"
grep -q "material 'white' emits" "$TMP/warn.txt" || fail "no warning for an emitter the links were not refined for"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.links" -o "$TMP/white.rad" --emission light=1,1,1 -q 2> "$TMP/warn.txt"
! grep -q "emits, but" "$TMP/warn.txt" || fail "warned about the mesh's own emitter"
# --emitters refines for a material made to emit at solve time: no warning then.
"$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/w.links" --method hierarchical --emitters white -q
"$BIN/rad-info" "$TMP/w.links" | grep "emitters = " | grep -q "white" || fail "--emitters recorded"
"$BIN/rad-solve" "$TMP/c.mesh" "$TMP/w.links" -o "$TMP/white.rad" --emission white=1,1,1 -q 2> "$TMP/warn.txt"
! grep -q "emits, but" "$TMP/warn.txt" || fail "warned although --emitters named the material"
# Refusals: a stale file, shooting solvers, shards and estimates.
"$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/other.mesh" --max-edge 0.2 -q
expect_error "c.links is stale" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/other.mesh" "$TMP/c.links" -o "$TMP/x.rad"
expect_error "use --method gs or jacobi" "$TMP/x.rad" "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.links" -o "$TMP/x.rad" --method pr
expect_error "neither --rows nor --estimate" "$TMP/x.links" "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/x.links" --method hierarchical --rows 0/2
expect_error "--epsilon" "$TMP/x.links" "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/x.links" --method hierarchical --epsilon 0
"$BIN/rad-ff" --help | grep -q "hierarchical" || fail "--help lists hierarchical"
finish
