"""The sun's beam in rad-shade --sky against rad-gather's (#69 item 5): the pixels of a camera
looking straight down at the floor against rho x lux / 179 x exposure at the floor points the
beam lights, away from the patch's edges.
    python3 sharp_beam.py TESTS_CLI_DIR IMAGE.png POINTS.txt LUX.txt"""
import sys
sys.path.insert(0, sys.argv[1])
from png_stats import read_png
width, height, rows = read_png(sys.argv[2])
exposure, rho, cam_x, cam_z, cam_h = 0.01, 0.2, 2.0, 3.0, 2.9
points = [l.split() for l in open(sys.argv[3])]
lux = [float(l) for l in open(sys.argv[4])]
lit = {}
for p, e in zip(points, lux):
    lit[(round(float(p[0]), 3), round(float(p[2]), 3))] = e
def srgb_to_linear(v):
    v /= 255
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4
checked = sunny = 0
worst = 0
for (x, z), e in lit.items():
    # Skip points near the patch's edge: a neighbour 0.2 m away differs by more than 5%.
    near = [lit.get((round(x + dx, 3), round(z + dz, 3))) for dx, dz in ((0.2, 0), (-0.2, 0), (0, 0.2), (0, -0.2))]
    if any(n is None or abs(n - e) > 0.05 * e for n in near):
        continue
    # Screen right is -x, up is +z; 90 degrees across: half the image is cam_h metres.
    px = width / 2 * (1 - (x - cam_x) / cam_h)
    py = height / 2 * (1 - (z - cam_z) / cam_h)
    r = rows[int(py)][3 * int(px)]
    shown = srgb_to_linear(r) / exposure
    expected = rho * e / 179
    if expected * exposure > 0.98 or e < 20000:  # saturated, or too dark for 8 bits
        continue
    worst = max(worst, abs(shown - expected) / expected)
    checked += 1
    sunny += e > 20000
print(f"{sunny} sunlit floor points, worst {100 * worst:.2f}% from the gather")
assert sunny > 20, (checked, sunny)
assert worst < 0.03, worst
