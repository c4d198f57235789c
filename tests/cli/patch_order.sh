# rad-mesh numbers patches in Morton order of their centroids (--patch-order morton, the
# default); the order must change nothing but the numbers. Compared by patch centroid.
# (test_scene checks the order itself on exact values.)
source "$(dirname "$0")/lib.sh"
for order in morton faces; do
  "$BIN/rad-mesh" "$SRC/scenes/cornell/cornell.obj" -o "$TMP/$order.mesh" --max-edge 0.08 -q --patch-order $order 2>/dev/null ||
    fail "rad-mesh --patch-order $order"
  "$BIN/rad-ff" "$TMP/$order.mesh" -o "$TMP/$order.hff" --method hemisphere --rays 400 -q || fail "hemisphere $order"
  "$BIN/rad-ff" "$TMP/$order.mesh" -o "$TMP/$order.aff" -q || fail "analytic $order"
  "$BIN/rad-solve" "$TMP/$order.mesh" "$TMP/$order.hff" -o "$TMP/$order.jacobi.rad" --method jacobi --iterations 40 -q || fail "jacobi $order"
  "$BIN/rad-solve" "$TMP/$order.mesh" "$TMP/$order.hff" -o "$TMP/$order.gs.rad" --method gs --tolerance 1e-9 -q || fail "gs $order"
  for f in mesh hff aff jacobi.rad gs.rad; do "$BIN/rad-info" --csv "$TMP/$order.$f" > "$TMP/$order.$f.csv"; done
done
cmp -s "$TMP/morton.mesh" "$TMP/faces.mesh" && fail "the two orders gave the same mesh"
python3 - "$TMP" <<'PY' || fail "the patch order changed more than the numbers"
import csv, sys
d = sys.argv[1]
def rows(name): return list(csv.DictReader(open(f"{d}/{name}.csv")))
def key(r): return tuple(round(float(r[c]), 12) for c in ("cx", "cy", "cz", "nx", "ny", "nz"))
m, f = rows("morton.mesh"), rows("faces.mesh")
index = {key(r): i for i, r in enumerate(m)}
assert len(index) == len(m) == len(f), "patches differ or share a centroid"
to_m = [index[key(r)] for r in f]
assert to_m != list(range(len(f))), "the order did not change"
# Every patch's group, material and area travel with it.
for i, r in enumerate(f):
    for c in ("group", "material", "area"):
        assert r[c] == m[to_m[i]][c], (i, c)
# Form factors: the same entries, value for value, once renumbered (each patch's random
# streams are keyed by its corners, not its number).
for kind in ("hff", "aff"):
    a = {(int(r["row"]), int(r["col"])): r["f"] for r in rows("morton." + kind)}
    b = {(to_m[int(r["row"])], to_m[int(r["col"])]): r["f"] for r in rows("faces." + kind)}
    assert a == b, kind + " differs"
# Jacobi: the same sums in another order, so equal to rounding (and CSV's 10 digits); Gauss-Seidel visits patches
# in another order, so equal to its tolerance.
for kind, tol in (("jacobi.rad", 1e-9), ("gs.rad", 1e-7)):
    a = {int(r["patch"]): r for r in rows("morton." + kind)}
    worst = 0
    for r in rows("faces." + kind):
        s = a[to_m[int(r["patch"])]]
        for c in ("b_r", "b_g", "b_b"):
            x, y = float(r[c]), float(s[c])
            worst = max(worst, abs(x - y) / max(abs(x), 1e-300))
    assert worst <= tol, f"{kind}: relative difference {worst}"
    print(kind, "worst relative difference", worst)
PY
finish
