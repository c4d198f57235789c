"""Per-surface comparison of two solutions of one mesh, shared by the bench scripts that
compare a method with a reference (bench/hierarchical, bench/corridor,
bench/fixtures-hierarchical)."""
import csv
import math


def solution(path):
    """Per patch, r + g + b of a solution written as CSV by rad-info --csv."""
    return [sum(float(r[k]) for k in ("b_r", "b_g", "b_b")) for r in csv.DictReader(open(path))]


def lamp_in_mesh(patch):
    """The default patches to leave out: those that emit in the mesh."""
    return float(patch["e_r"]) > 0


def surface_means(mesh, ref, other, skip=lamp_in_mesh):
    """Area-weighted sums per group of the reference and the other solution, the area per
    group, and the per-patch rms of other against ref relative to ref (None when every patch
    is left out); patches for which skip(mesh row) holds are left out."""
    sa, sb, area = {}, {}, {}
    num = den = 0.0
    for m, x, y in zip(mesh, ref, other):
        if skip(m):
            continue
        a, g = float(m["area"]), m["group"]
        sa[g] = sa.get(g, 0) + a * x
        sb[g] = sb.get(g, 0) + a * y
        area[g] = area.get(g, 0) + a
        num += a * (y - x) ** 2
        den += a * x * x
    return sa, sb, area, (math.sqrt(num / den) if den > 0 else None)
