# rad-ff --error (#65 item 1): each row's standard error from independent batches of rays. Its
# square is an unbiased estimate of the row's summed variances, so over many rows the squared
# distance to a converged matrix averages to it (a bar always too wide or too narrow fails);
# plain and through mirrors and glass; the same bytes at 1 and 2 threads and from parts; the
# file says so (rad-info) and one without --error is unchanged.
source "$(dirname "$0")/lib.sh"
cornell_mesh 0.05 || fail "mesh"
D="$SRC/tests/data/cornell-sphere"
"$BIN/rad-mesh" "$D/CornellBox-Sphere.obj" -o "$TMP/s.mesh" --max-edge 0.3 -q 2>/dev/null || fail "mirror box mesh"
ff() { "$BIN/rad-ff" --method hemisphere -q "$@" 2>/dev/null; }
csv() { "$BIN/rad-info" --csv "$1" > "${1%.ff}.csv" || fail "rad-info --csv $1"; }
for m in c s; do
  ff "$TMP/$m.mesh" --rays 32768 -o "$TMP/${m}ref.ff" || fail "$m reference"
  csv "$TMP/${m}ref.ff"
  for seed in 1 2; do
    ff "$TMP/$m.mesh" --rays 1024 --error --seed "$seed" -o "$TMP/${m}e$seed.ff" || fail "$m --error seed $seed"
    csv "$TMP/${m}e$seed.ff"
  done
done
python3 - "$TMP" <<'PY' || fail "calibration"
import collections, sys
def load(path):
    rows, error = collections.defaultdict(dict), {}
    with open(path) as f:
        header = next(f).strip().split(",")
        for line in f:
            p = line.split(",")
            rows[int(p[0])][int(p[1])] = float(p[2])
            if len(p) > 3: error[int(p[0])] = float(p[3])
    return header, rows, error
for m in "cs":
    _, ref, _ = load("%s/%sref.csv" % (sys.argv[1], m))
    for seed in (1, 2):
        header, got, error = load("%s/%se%d.csv" % (sys.argv[1], m, seed))
        assert header[-1] == "row_error", header
        actual = sum(sum((got[i].get(k, 0) - ref[i].get(k, 0)) ** 2 for k in set(got[i]) | set(ref[i])) for i in ref)
        said = sum(e * e for e in error.values())
        print("%s seed %d: %d rows, summed squared error / summed squared bars %.3f" % (m, seed, len(error), actual / said))
        # (the reference's own variance, 1/32 of the plain 1024 rays', adds about 2%)
        assert 0.85 <= actual / said <= 1.2, actual / said
PY
# One thread and two, a run and its two parts merged: the same bytes (run in one folder, so
# the command lines they record match).
(cd "$TMP" && "$BIN/rad-ff" c.mesh --method hemisphere --rays 1024 --error --threads 1 -o x.ff -q &&
  mv x.ff one.ff && "$BIN/rad-ff" c.mesh --method hemisphere --rays 1024 --error -o x.ff -q && cmp -s one.ff x.ff) ||
  fail "--error: 1 and 2 threads differ"
(cd "$TMP" && for k in 0 1; do "$BIN/rad-ff" c.mesh --method hemisphere --rays 1024 --error --rows $k/2 -o p$k.ff -q || exit 1; done &&
  "$BIN/rad-ff" --merge p0.ff p1.ff -o x.ff -q && cmp -s one.ff x.ff) || fail "--error: merged parts differ from one run"
# rad-info says it; a file without --error has no such field, and its rows no column.
"$BIN/rad-info" "$TMP/one.ff" | grep -q "rows' standard errors (rad-ff --error): mean 0.0[0-9]*, max 0.0" ||
  fail "rad-info does not show the rows' errors: $("$BIN/rad-info" "$TMP/one.ff")"
ff "$TMP/c.mesh" --rays 1024 -o "$TMP/plain.ff" || fail "plain"
"$BIN/rad-info" "$TMP/plain.ff" | grep -q "row_errors\|standard errors" && fail "a plain matrix claims row errors"
[ "$("$BIN/rad-info" --csv "$TMP/plain.ff" | head -1)" = "row,col,f" ] || fail "a plain matrix's CSV columns changed"
# What it cannot do, refused.
expect_error "the analytic method has none to estimate that way" "$TMP/refused.ff" \
  "$BIN/rad-ff" "$TMP/c.mesh" --method analytic --error -o "$TMP/refused.ff"
expect_error "--rays 1000 must be a multiple of --batches 16" "$TMP/refused.ff" \
  "$BIN/rad-ff" "$TMP/c.mesh" --method hemisphere --rays 1000 --batches 16 --error -o "$TMP/refused.ff"
expect_error "not with --merge" "$TMP/refused.ff" "$BIN/rad-ff" --merge "$TMP/p0.ff" "$TMP/p1.ff" --error -o "$TMP/refused.ff"
finish
