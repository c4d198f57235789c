# rad-report (#52): the lighting example's surfaces (formats/README.md's example, as it stands)
# through rad-gather --surfaces and rad-report; the page, in headless Chromium, loads with no
# console error and no network request, its figures equal rad-gather's to the digits shown and
# its isolines lie at their levels; the PDF has the page count and the tables; the same bytes
# at any thread count; refusals name the file, the line and the fix, and leave no output.
source "$(dirname "$0")/lib.sh"
WEB="$SRC/web"
[ -d "$WEB/node_modules/puppeteer-core" ] || { echo "FAIL: web/node_modules is missing: run scripts/install-deps"; exit 1; }
command -v chromium >/dev/null || { echo "FAIL: chromium is missing: run scripts/install-deps"; exit 1; }
command -v pdftotext >/dev/null || { echo "FAIL: pdftotext is missing: run scripts/install-deps"; exit 1; }
L="$SRC/scenes/lighting"
"$BIN/rad-mesh" "$L/room.obj" -o "$TMP/l.mesh" --unit m -q 2>/dev/null || fail "rad-mesh"
"$BIN/rad-ff" "$TMP/l.mesh" -o "$TMP/l.ff" -q || fail "rad-ff"
"$BIN/rad-ff" "$TMP/l.mesh" --luminaires "$L/layout.csv" -o "$TMP/l.lum" -q || fail "rad-ff --luminaires"
"$BIN/rad-solve" "$TMP/l.mesh" "$TMP/l.ff" --direct "$TMP/l.lum" -o "$TMP/l.rad" -q || fail "rad-solve"
# The example in formats/README.md, as it stands: the first code block after its heading.
awk '/^### Calculation surfaces/ {on=1} on && /^```csv/ {copy=1; next} copy && /^```/ {exit} copy' \
  "$SRC/formats/README.md" > "$TMP/calc.csv"
grep -q '^name,kind,' "$TMP/calc.csv" || fail "no example in formats/README.md: $(head -3 "$TMP/calc.csv")"
cmp -s "$TMP/calc.csv" "$L/calc.csv" || fail "scenes/lighting/calc.csv is not formats/README.md's example"

# rad-gather --surfaces: a line per sensor, surface by surface, and the figures on stderr.
# 32 rays (not 256) for the gather: the view in the report is a final gather at every pixel.
RAYS="--rays 32"
# shellcheck disable=SC2086
"$BIN/rad-gather" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/calc.csv" $RAYS -o "$TMP/g.csv" 2> "$TMP/g.err" ||
  fail "rad-gather --surfaces: $(cat "$TMP/g.err")"
[ "$(head -1 "$TMP/g.csv")" = "surface,index,column,row,x,y,z,lux" ] || fail "rad-gather --surfaces header: $(head -1 "$TMP/g.csv")"
# The work plane: 9 x 5 sensors (5 m x 3 m after the 0.5 m band, p = 0.616 m), then the desk's 16 x 8.
[ "$(grep -c '^work plane,' "$TMP/g.csv")" = 45 ] || fail "work plane sensors: $(grep -c '^work plane,' "$TMP/g.csv")"
[ "$(grep -c '^desk,' "$TMP/g.csv")" = 128 ] || fail "desk sensors: $(grep -c '^desk,' "$TMP/g.csv")"
grep -q "^rad-gather: work plane (workplane, 9 x 5 sensors at 0.616 m, 0 without a value): Em" "$TMP/g.err" ||
  fail "rad-gather's work plane line: $(cat "$TMP/g.err")"
grep -q "south wall.*meets its requirements" "$TMP/g.err" || fail "the wall's verdict: $(cat "$TMP/g.err")"
# Sensors face where the file says: the ceiling's down (gathered from below, they see the room).
grep -q '^ceiling,0,0,0,0.333333,3,0.333333,[0-9]' "$TMP/g.csv" || fail "the ceiling's first sensor: $(grep -m1 '^ceiling' "$TMP/g.csv")"

# The report, and its PDF.
# shellcheck disable=SC2086
"$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/calc.csv" $RAYS -o "$TMP/r.html" --pdf "$TMP/r.pdf" \
  --date 2026-12-05 --project "Lighting example" 2> "$TMP/r.err" || fail "rad-report: $(cat "$TMP/r.err")"
grep -q "4 surface(s) (272 points, 0 failing their requirements), 1 observer(s)" "$TMP/r.err" || fail "rad-report summary: $(cat "$TMP/r.err")"
out=$(node "$WEB/test-report.mjs" --page "$TMP/r.html" --values "$TMP/g.csv" 2>&1) || fail "the page in Chromium: $out"
# The drawings (#68 item 1): the ceiling as a reflected ceiling plan (L1 over the floor plan's
# L1: the same side of both), each luminaire's 0.2 m square opening at its size, a scale bar,
# the surface's dimensions.
python3 - "$TMP/r.html" <<'PY' || fail "the plans' drawing"
import re, sys
page = open(sys.argv[1]).read()
def plan(name):
    return re.search(r'<section class="part surface" id="surface-\d+"><h2>%s</h2>(.*?)</section>' % name, page, re.S).group(1)
def where(section, lum):
    g = re.search(r'<g class="luminaire" data-name="%s">(.*?)</g>' % lum, section).group(1)
    cx, cy = (float(v) for v in re.search(r'<circle cx="([-0-9.]+)" cy="([-0-9.]+)" r="7"', g).groups())
    return cx, cy, g
floor, ceiling = plan("work plane"), plan("ceiling")
assert "a reflected ceiling plan" in ceiling and "a reflected ceiling plan" not in floor
assert '<text class="dimensions"' in floor and "6.00 m &#215; 4.00 m</text>" in floor, "the work plane's dimensions"
# The key plan: the desk's calculation area where the room has it (x 2.2 to 3.8 of 0 to 6 m,
# z 1.6 to 2.4 of 0 to 4 m), the ceiling not drawn over the room.
key = re.search(r'<svg class="key-plan".*?</svg>', page, re.S).group(0)
room = [float(v) for v in re.search(r'<rect class="room" x="([0-9.]+)" y="([0-9.]+)" width="([0-9.]+)" height="([0-9.]+)"', key).groups()]
desk = [float(v) for v in re.search(r'data-surface="desk"><rect x="([0-9.]+)" y="([0-9.]+)" width="([0-9.]+)" height="([0-9.]+)"', key).groups()]
k = room[2] / 6
for got, want in ((desk[0], room[0] + 2.2 * k), (desk[1], room[1] + 1.6 * k), (desk[2], 1.6 * k), (desk[3], 0.8 * k)):
    assert abs(got - want) < 0.02, (desk, room)
assert 'data-surface="ceiling"' not in key
# The room cut at the work plane's height: the four walls, on the room's outline.
cut = re.search(r'<path class="cut" data-surface="work plane" d="([^"]*)"', key)
assert cut, "the key plan has no cut"
ends = [tuple(map(float, e)) for e in re.findall(r'[ML]([-0-9.]+) ([-0-9.]+)', cut.group(1))]
on_edge = lambda x, y: min(abs(x - room[0]), abs(x - room[0] - room[2]), abs(y - room[1]), abs(y - room[1] - room[3])) < 0.02
assert ends and all(on_edge(x, y) for x, y in ends), ends[:6]
for section in (floor, ceiling):
    l1, l3 = where(section, "L1"), where(section, "L3")
    assert l1[1] < l3[1], "L1 (z = 1) is drawn below L3 (z = 3) in one plan: %s %s" % (l1[:2], l3[:2])
    scale = float(re.search(r'data-metres="([0-9.]+)"', section).group(1))
    assert scale in (0.5, 1, 2), scale
    corners = [tuple(map(float, c)) for c in re.findall(r'([-0-9.]+) ([-0-9.]+)', re.search(r'<path class="opening" d="([^"]*)"', l1[2]).group(1))]
    side = max(c[0] for c in corners) - min(c[0] for c in corners)
    bar = re.search(r'<g class="scale-bar"[^>]*>(.*?)</g>', section).group(1)
    quarter = float(re.search(r'width="([0-9.]+)"', bar).group(1))
    assert abs(side / (4 * quarter / scale) - 0.2) < 0.002, (side, quarter, scale)
PY
echo "$out" | head -3
# Title block, summary and method; one page per surface; luminaires; glare; the view and method.
pages=$(pdfinfo "$TMP/r.pdf" | awk '/^Pages:/ {print $2}')
[ "$pages" = 11 ] || fail "the PDF has $pages pages (wanted 11: summary, the room, 4 surfaces, luminaires, their UGR table, glare, views with their luminance, method)"
# The camera's view is rad-shade's image, byte for byte, by the command the page gives.
# Its luminance (#68 item 7): the false-colour picture is rad-shade --falsecolor's, byte for
# byte, and each surface's luminance its --luminance-table's, to the digits shown.
python3 - "$TMP/r.html" "$TMP/view.png" "$TMP/shade.sh" "$TMP/view-fc.png" "$TMP/view-lum.txt" <<'PY' || fail "no view in the page"
import base64, html, re, sys
page = open(sys.argv[1]).read()
# (the title block shows the first view too: the same image as the views' section)
views = page[page.index('id="views"'):]
pngs = re.findall(r'src="data:image/png;base64,([^"]*)"', views)
cover = re.search(r'<figure class="title-view"><img alt="[^"]*" src="data:image/png;base64,([^"]*)"', page)
# (at half size: a PNG's width and height are bytes 16-24 of it)
thumb = base64.b64decode(cover.group(1)) if cover else b""
full = base64.b64decode(pngs[0])
size = lambda png: (int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big"))
assert cover and size(thumb) == tuple(v // 2 for v in size(full)), "the title block's view is not the first view at half size"
open(sys.argv[2], "wb").write(base64.b64decode(pngs[0].replace("\n", "")))
open(sys.argv[4], "wb").write(base64.b64decode(pngs[1].replace("\n", "")))
command = html.unescape(re.search(r'<code class="command">([^<]*)</code>', page).group(1))
open(sys.argv[3], "w").write(command.replace("--png FILE", "--png shade.png -o shade.exr -q")
                             .replace("--falsecolor FILE", "--falsecolor shade-fc.png")
                             .replace("--luminance-table FILE", "--luminance-table shade-lum.csv") + "\n")
table = re.search(r'<table class="luminances"[^>]*>(.*?)</table>', page, re.S).group(1)
rows = re.findall(r'<tr><td>([^<]*)</td><td class="num">([^<]*)</td><td class="num">([^<]*)</td><td class="num">([^<]*)</td></tr>', table)
open(sys.argv[5], "w").write("".join("%s %s %s\n" % (html.unescape(n), mean, top) for n, share, mean, top in rows))
PY
(cd "$TMP" && PATH="$BIN:$PATH" bash shade.sh) || fail "the page's rad-shade command: $(cat "$TMP/shade.sh")"
cmp -s "$TMP/view.png" "$TMP/shade.png" || fail "the page's view is not rad-shade's image ($(cat "$TMP/shade.sh"))"
cmp -s "$TMP/view-fc.png" "$TMP/shade-fc.png" || fail "the page's luminance picture is not rad-shade --falsecolor's"
python3 - "$TMP/shade-lum.csv" "$TMP/view-lum.txt" <<'PY' || fail "the page's surface luminances are not rad-shade --luminance-table's"
import csv, sys
shown = [line.split() for line in open(sys.argv[2])]
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(shown) == len(rows) >= 3, (shown, rows)
for (name, mean, top), r in zip(shown, rows):
    assert name == r["surface"], (name, r)
    for text, value in ((mean, float(r["mean_cd_m2"])), (top, float(r["max_cd_m2"]))):
        digits = len(text.replace(".", "").lstrip("0"))
        assert abs(float(text) - value) <= 0.51 * abs(value) * 10 ** (1 - digits) + 1e-12, (text, value)
PY
pdftotext -layout "$TMP/r.pdf" "$TMP/r.txt" || fail "pdftotext"
em=$(grep -o '<td class="num em">[^<]*' "$TMP/r.html" | head -1 | sed 's/.*>//')
for text in "Lighting report: Lighting example" "2026-12-05" "Summary" "Em (lx)" "Emin/Emax" "work plane" \
            "south wall" "LED Downlight - Absolute Photometry" "led_downlight.ies" "W/m²" "UGR" "desk chair" "Calculation area" "$em"; do
  grep -qF -- "$text" "$TMP/r.txt" || fail "the PDF's text lacks '$text'"
done
# Each surface's page starts with its name, and its table is on the same page (no table split).
for surface in "work plane" desk "south wall" ceiling; do
  awk -v s="$surface" 'BEGIN {RS="\f"} index($0, s "\n") && index($0, "Calculation area") && index($0, "Verdict") {found=1} END {exit !found}' \
    "$TMP/r.txt" || fail "no page of the PDF holds $surface's heading and whole table"
done
# The same bytes at one thread and two; the page names its inputs' hashes.
# shellcheck disable=SC2086
"$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/calc.csv" $RAYS -o "$TMP/r1.html" --date 2026-12-05 \
  --project "Lighting example" --threads 1 -q || fail "rad-report --threads 1"
cmp -s "$TMP/r.html" "$TMP/r1.html" || fail "rad-report differs at 1 and 2 threads"
[ "$(grep -o '<td class="hash">xxh64:[0-9a-f]\{16\}</td>' "$TMP/r.html" | wc -l)" = 6 ] ||
  fail "the page does not name its inputs' and the solution's inputs' hashes (6)"
# --area: the power density over the area given.
grep -v ',camera,' "$TMP/calc.csv" > "$TMP/nocamera.csv"
"$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" -o "$TMP/a.html" --area 12 -q --date x ||
  fail "rad-report --area"
grep -q '<span class="density">8.33</span>' "$TMP/a.html" || fail "100 W over 12 m^2: $(grep -o 'class="density">[^<]*' "$TMP/a.html")"
# --point-tables and --north (#68 item 1): under each plan its values laid out as the plan (the
# work plane's the very values rad-gather --surfaces wrote, as the page rounds them; rows with v
# up the page), a north arrow where north lies (90: +x, the plans' u), the room cut at the plane.
# shellcheck disable=SC2086
"$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" $RAYS -o "$TMP/t.html" -q --date x \
  --point-tables --north 90 --client "Client & Co" --designer "D. <Signer>" || fail "rad-report --point-tables --north"
grep -q '<tr><th>Client</th><td>Client &amp; Co</td></tr><tr><th>Designer</th><td>D. &lt;Signer&gt;</td></tr>' "$TMP/t.html" ||
  fail "the title block has no client and designer"
# The solution's provenance has the .lum's own command beside the form factors' (both lines
# of ancestors), and the page lists it.
grep -q "<li>rad-ff [^<]*--luminaires" "$TMP/t.html" || fail "the page's provenance lacks rad-ff --luminaires"

python3 - "$TMP/t.html" "$TMP/g.csv" <<'PY' || fail "the point tables or north"
import csv, re, sys
page = open(sys.argv[1]).read()
tables = re.findall(r'<table class="point-table">(.*?)</table>', page, re.S)
assert len(tables) == 4, len(tables)
def matches(text, lux):  # the page's 3 figures of the CSV's 6 (a half unit either way)
    a = abs(lux)
    decimals = 0 if a >= 99.95 else 1 if a >= 9.995 else 2
    return len(text.split(".")[-1] if "." in text else "") == decimals and \
        abs(float(text) - lux) <= 0.5 * 10 ** -decimals + 1e-3
plane = {(int(r["column"]), int(r["row"])): float(r["lux"]) for r in csv.DictReader(open(sys.argv[2]))
         if r["surface"] == "work plane"}
rows = [re.findall(r'<td class="num">([^<]*)</td>', row) for row in re.findall(r"<tr>(.*?)</tr>", tables[0])]
assert len(rows) == 5 and all(len(r) == 9 for r in rows), [len(r) for r in rows]
for k, row in enumerate(rows):
    for column, text in enumerate(row):
        assert matches(text, plane[(column, 4 - k)]), (k, column, text, plane[(column, 4 - k)])
norths = re.findall(r'<g class="north" data-north-deg="90" data-dx="([^"]*)" data-dy="([^"]*)"', page)
assert len(norths) == 3, norths  # the work plane, the desk and the ceiling: not the wall
for dx, dy in norths:
    assert abs(float(dx) - 1) < 1e-3 and abs(float(dy)) < 1e-3, (dx, dy)
assert page.count('<path class="cut"') >= 2, page.count('<path class="cut"')
print("point tables and north: ok")
PY
# A wall's surface given facing into the wall a millimetre away reads the wall's own light:
# rad-gather and rad-report say so (naming the line), the page marks it; facing the room, not.
printf 'name,kind,x,y,z,ux,uy,uz,vx,vy,vz,spacing,border,Em\ninto,wall,0,0,3.999,6,0,0,0,3,0,0.5,,\nroom,wall,6,0,3.999,-6,0,0,0,3,0,0.5,,\n' > "$TMP/facing.csv"
"$BIN/rad-gather" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/facing.csv" --rays 32 -o "$TMP/facing.out" 2> "$TMP/facing.err" ||
  fail "rad-gather facing"
grep -q "warning: $TMP/facing.csv:2: surface 'into' faces a surface 0.001 m in front of its points" "$TMP/facing.err" ||
  fail "no warning for a surface facing into its wall: $(cat "$TMP/facing.err")"
grep -q "surface 'room' faces" "$TMP/facing.err" && fail "a surface facing the room was warned of"
"$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/facing.csv" --rays 32 -o "$TMP/facing.html" --date x 2> "$TMP/facing-r.err" ||
  fail "rad-report facing"
grep -q "surface 'into' faces a surface 0.001 m" "$TMP/facing-r.err" || fail "rad-report does not warn: $(cat "$TMP/facing-r.err")"
[ "$(grep -c '<tr class="warning"><th>Warning</th><td>its points face a surface 0.001 m' "$TMP/facing.html")" = 1 ] ||
  fail "the page does not mark the one surface facing into its wall"
# --estimate (#70 item 10): the first 256 sensors gathered and timed, the whole run's time
# said, nothing written; only with --surfaces.
est=$("$BIN/rad-gather" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" --estimate -o "$TMP/est.csv" 2>&1) ||
  fail "rad-gather --estimate: $est"
grep -Eq "^rad-gather: 272 sensor\(s\) on 4 surface\(s\): about [0-9.]+ (s|min|h) on [0-9]+ thread\(s\) \(measured on the first 256\)$" <<<"$est" ||
  fail "rad-gather --estimate says: $est"
[ ! -e "$TMP/est.csv" ] || fail "rad-gather --estimate wrote its output"
expect_error "--estimate measures a --surfaces run" "" \
  "$BIN/rad-gather" "$TMP/l.mesh" "$TMP/l.rad" --grid "0 0 1 1 0.8 2 2" --estimate
# --energy: EN 15193-1's LENI by hand for 100 W over 12 m^2 of office (2250 h with daylight, 250
# without), FO 0.9, FD 0.8, 2 W of controls' standby, 4 W charging all year:
# W_L = 100 (2250 x 0.9 x 0.8 + 250 x 0.9) / 1000 = 184.5 kWh; W_P = (2 x 6260 + 4 x 8760) / 1000
# = 47.56 kWh; LENI = 232.06 / 12 = 19.34 kWh/(m^2 a).
"$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" -o "$TMP/e.html" --area 12 --date x \
  --energy "office, FO=0.9,FD=0.8,Ppc=2,Pem=4" 2> "$TMP/e.err" || fail "rad-report --energy: $(cat "$TMP/e.err")"
for want in '<span class="wl">184.5</span>' '<span class="wp">47.6</span>' '<span class="leni">19.34</span>'; do
  grep -qF "$want" "$TMP/e.html" || fail "--energy: no $want in $(grep -o '<section[^>]*id="energy".*' "$TMP/e.html" | head -c 3000)"
done
grep -q '<tr data-key="FD">.*<td>given</td></tr><tr data-key="Ppc">' "$TMP/e.html" || fail "--energy: FD not marked given"
grep -q '<tr data-key="te">.*<td>default</td></tr>' "$TMP/e.html" || fail "--energy: te not marked default"
grep -qF "LENI 19.34 kWh/(m^2 a)" "$TMP/e.err" || fail "--energy summary: $(cat "$TMP/e.err")"
# The room (#68 item 2): its extent and each material's area and luminous reflectance.
python3 - "$TMP/e.html" <<'PY' || fail "the room's summary"
import re, sys
page = open(sys.argv[1]).read()
room = re.search(r'<section id="room">(.*?)</section>', page, re.S).group(1)
assert "Extent 6.00 &#215; 3.00 &#215; 4.00 m" in room, room[:300]
rows = dict((n, (float(a), float(r))) for n, a, r in
            re.findall(r'<tr><td>([^<]*)</td><td class="num">([^<]*)</td><td class="num">([^<]*)</td></tr>', room))
# desk: 0.265 x 0.45 + 0.670 x 0.3 + 0.065 x 0.18 = 0.332
assert rows["floor"][1] == 0.20 and rows["ceiling"][1] == 0.80 and rows["wall"][1] == 0.50, rows
assert rows["desk"][1] == 0.33, rows
assert rows["ceiling"][0] == 24.00, rows
PY
# The maintenance factor by its parts: the product is the factor, shown with its parts; a
# maintenance column that disagrees with them is refused.
mkdir -p "$TMP/parts" && cp "$SRC/scenes/lighting/led_downlight.ies" "$TMP/parts/"
sed '1s/$/,llmf,lsf,lmf,rsmf/; 2,$s/,0\.8,downlights$/,,downlights,0.9,1,0.95,0.94/' "$SRC/scenes/lighting/layout.csv" > "$TMP/parts/layout.csv"
{ "$BIN/rad-ff" "$TMP/l.mesh" --luminaires "$TMP/parts/layout.csv" -o "$TMP/parts.lum" -q &&
  "$BIN/rad-solve" "$TMP/l.mesh" "$TMP/l.ff" --direct "$TMP/parts.lum" -o "$TMP/parts.rad" -q &&
  "$BIN/rad-report" "$TMP/l.mesh" "$TMP/parts.rad" --surfaces "$TMP/nocamera.csv" -o "$TMP/parts.html" --date x -q; } ||
  fail "a layout with the maintenance factor's parts"
grep -qF '<td class="num">0.80 = 0.90 &#215; 1.00 &#215; 0.95 &#215; 0.94</td>' "$TMP/parts.html" ||
  fail "the parts: $(grep -o 'Maintenance factor.\{0,600\}' "$TMP/parts.html" | head -c 600)"
sed '2s/,,downlights,0.9,/,0.8,downlights,0.9,/; 2s/,0.94$/,0.8/' "$TMP/parts/layout.csv" > "$TMP/parts/bad.csv"
expect_error "bad.csv:2: maintenance 0.8 is not llmf x lsf x lmf x rsmf = 0.684" "$TMP/x.lum" \
  "$BIN/rad-ff" "$TMP/l.mesh" --luminaires "$TMP/parts/bad.csv" -o "$TMP/x.lum"
expect_error "'offices' is not a building type; give one of office, education" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" -o "$TMP/x.html" --energy offices
expect_error "'fo=0.9' is not KEY=VALUE with a key of tD" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" -o "$TMP/x.html" --energy office,fo=0.9
expect_error "FD is a dependency factor, 0 to 1" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" -o "$TMP/x.html" --energy office,FD=8

# Daylight: the glazed room's daylight factor and a year in Denver, the same numbers as
# rad-gather --surfaces (its df column; its --metrics' da300, sun_hours, udi_useful).
D="$SRC/scenes/daylight-room"
"$BIN/rad-mesh" "$D/daylight-room-glazed.obj" -o "$TMP/d.mesh" --unit m -q 2>/dev/null || fail "rad-mesh daylight"
{ "$BIN/rad-ff" "$TMP/d.mesh" -o "$TMP/d.ff" -q && "$BIN/rad-ff" "$TMP/d.mesh" --sky reinhart:1 -o "$TMP/d.sky" -q; } ||
  fail "rad-ff daylight"
"$BIN/rad-solve" "$TMP/d.mesh" "$TMP/d.ff" --direct "$TMP/d.sky" -o "$TMP/d.rad" -q || fail "rad-solve daylight"
EPW="$SRC/tests/data/denver-tmy3.epw"
"$BIN/rad-gather" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$D/calc.csv" --sky cie-overcast --daylight-factor \
  -o "$TMP/df.csv" 2> "$TMP/df.err" || fail "rad-gather --surfaces --daylight-factor: $(cat "$TMP/df.err")"
grep -q "^rad-gather: work plane: daylight factor mean" "$TMP/df.err" || fail "no work plane DF line: $(cat "$TMP/df.err")"
"$BIN/rad-gather" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$D/calc.csv" --epw "$EPW" --annual -o "$TMP/d.ill" \
  --metrics "$TMP/m.csv" > "$TMP/year.txt" -q || fail "rad-gather --surfaces --annual"
grep -q "^  work plane: sDA300/50%" "$TMP/year.txt" || fail "no work plane sDA line: $(cat "$TMP/year.txt")"
"$BIN/rad-report" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$D/calc.csv" --epw "$EPW" -o "$TMP/d.html" --pdf "$TMP/d.pdf" \
  --date 2026-12-05 -q || fail "rad-report daylight"
for q in df:df da300:m; do
  out=$(node "$WEB/test-report.mjs" --page "$TMP/d.html" --values "$TMP/${q#*:}.csv" --quantity "${q%:*}" 2>&1) ||
    fail "the daylight page's ${q%:*} in Chromium: $out"
done
[ "$(pdfinfo "$TMP/d.pdf" | awk '/^Pages:/ {print $2}')" = 5 ] || fail "the daylight PDF is not 5 pages (summary, the room, the work plane and its plans, the back wall)"
# The work plane's requirements (DF 2%, sDA 55%, ASE 10%) judged from its figures: the verdict
# is "fails" exactly when one of them is missed.
python3 - "$TMP/m.csv" "$TMP/df.csv" "$TMP/d.html" <<'PY' || fail "the daylight verdict"
import csv, re, sys
plane = lambda path: [r for r in csv.DictReader(open(path)) if r["surface"] == "work plane"]
m, df = plane(sys.argv[1]), plane(sys.argv[2])
mean_df = sum(float(r["df"]) for r in df) / len(df)
sda = 100 * sum(float(r["da300"]) >= 0.5 for r in m) / len(m)
ase = 100 * sum(int(r["sun_hours"]) > 250 for r in m) / len(m)
meets = mean_df >= 2 and sda >= 55 and ase <= 10
page = open(sys.argv[3]).read()
row = re.search(r'<tr data-surface="work plane">.*?</tr>', page).group(0)
shown = "meets" if 'class="pass"' in row else "fails" if 'class="fail"' in row else "none"
print("work plane: DF %.2f%%, sDA %.1f%%, ASE %.1f%%: %s (page: %s)" % (mean_df, sda, ase, "meets" if meets else "fails", shown))
sys.exit(0 if shown == ("meets" if meets else "fails") else 1)
PY
pdftotext "$TMP/d.pdf" "$TMP/d.txt"; grep -q "sDA300/50%" "$TMP/d.txt" || fail "the daylight PDF's text lacks sDA300/50%"
"$BIN/rad-report" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$D/calc.csv" --epw "$EPW" -o "$TMP/d1.html" \
  --date 2026-12-05 -q --threads 1 || fail "rad-report daylight --threads 1"
cmp -s "$TMP/d.html" "$TMP/d1.html" || fail "the daylight report differs at 1 and 2 threads"
# EN 17037 (#69 item 3), the daylight factor method on the work plane: E_v,d,med the median of the
# 4380 brightest hours of the EPW's diffuse horizontal illuminance (field 19), each level's
# target and minimum as daylight factors, the shares of the plane's points (rad-gather's
# df column) at them, met when 50% and 95% reach them; worked here.
python3 - "$EPW" "$TMP/df.csv" "$TMP/d.html" <<'PY' || fail "EN 17037 on the work plane"
import csv, re, sys
lux = sorted((float(l.split(",")[18]) for l in list(open(sys.argv[1]))[8:]), reverse=True)
half = lux[:len(lux) // 2]
median = 0.5 * (half[len(half) // 2 - 1] + half[len(half) // 2])
df = [float(r["df"]) for r in csv.DictReader(open(sys.argv[2])) if r["surface"] == "work plane"]
page = open(sys.argv[3]).read()
cell = re.search(r'<td class="en17037" data-achieved="([a-z]+)">(.*?)</table>', page, re.S)
assert "E<sub>v,d,med</sub> %.0f lx" % median in cell.group(2), (median, cell.group(2)[:300])
best = "none"
for name, target, minimum in (("minimum", 300, 100), ("medium", 500, 300), ("high", 750, 500)):
    dt, dtm = 100 * target / median, 100 * minimum / median
    st = sum(v >= dt for v in df) / len(df)
    stm = sum(v >= dtm for v in df) / len(df)
    row = re.search(r'<tr data-level="%s">(.*?)</tr>' % name, cell.group(2)).group(1)
    nums = re.findall(r'<td class="num">([^<]*)</td>', row)
    assert nums == ["%.2f" % dt, "%.1f" % (100 * st), "%.2f" % dtm, "%.1f" % (100 * stm)], (name, nums, dt, st, dtm, stm)
    met = st >= 0.5 and stm >= 0.95
    assert ('class="pass">met' in row) == met, (name, row)
    if met: best = name
assert cell.group(1) == best, (cell.group(1), best)
print("EN 17037: E_v,d,med %.0f lx, level %s" % (median, best))
PY
# EN 17037 by illuminance on the work plane: the page's shares of the daylight hours and its
# level are rad-gather --surfaces --annual's.
python3 - "$TMP/year.txt" "$TMP/d.html" <<'PY' || fail "EN 17037 by illuminance on the page"
import re, sys
said = re.search(r"work plane: EN 17037 by illuminance, over 4380 daylight hours: (.*)", open(sys.argv[1]).read()).group(1)
page = open(sys.argv[2]).read()
cell = re.search(r'<td class="en17037-hourly" data-achieved="([a-z]+)">(.*?)</table>', page, re.S)
assert said.endswith("level " + cell.group(1)), (said, cell.group(1))
for name, t, m in re.findall(r"(minimum|medium|high) \(\d+ lx over 50% in ([\d.]+)%, \d+ lx over 95% in ([\d.]+)%", said):
    row = re.search(r'<tr data-level="%s">(.*?)</tr>' % name, cell.group(2)).group(1)
    nums = re.findall(r'<td class="num">([^<]*)</td>', row)
    assert nums == [t, m], (name, nums, t, m)
print("EN 17037 by illuminance on the page: level", cell.group(1))
PY
expect_error "a daylight solution's observers get their daylight glare (DGP) over a year: give --epw FILE" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$TMP/calc.csv" -o "$TMP/x.html"
# A daylight solution's observers (#69 item 2): their DGP over the year in the report, the
# numbers rad-gather --annual --glare gives for the same eye (the winter solstice's and the
# summer solstice's working hours, to keep it short).
python3 - "$EPW" "$TMP/solstices.txt" <<'PY'
import sys
rows = [l.split(",") for l in open(sys.argv[1]).readlines()[8:]]
with open(sys.argv[2], "w") as out:
    for r in rows:
        out.write("1\n" if (r[1], r[2]) in (("12", "21"), ("6", "21")) and 9 <= int(r[3]) <= 17 else "0\n")
PY
{ cat "$D/calc.csv"; echo "at the desk,observer,2,1.2,2,0,0,1"; } > "$TMP/eye-calc.csv"
"$BIN/rad-report" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$TMP/eye-calc.csv" --epw "$EPW" --occupancy "$TMP/solstices.txt" \
  -o "$TMP/dgp.html" --date 2026-12-05 -q || fail "rad-report with a daylight observer"
"$BIN/rad-gather" "$TMP/d.mesh" "$TMP/d.rad" --epw "$EPW" --annual --occupancy "$TMP/solstices.txt" \
  --glare "2 1.2 2 0 0 1" -o "$TMP/dgp.csv" -q || fail "rad-gather --annual --glare for the report's observer"
python3 - "$TMP/dgp.csv" "$TMP/dgp.html" <<'PY' || fail "the report's daylight glare is not rad-gather's"
import csv, re, sys
y = next(csv.DictReader(open(sys.argv[1])))
page = open(sys.argv[2]).read()
assert '<a href="#daylight-glare">Daylight glare (DGP)</a>' in page
row = re.search(r'<tr data-observer="at the desk">(.*?)</tr>', page).group(1)
cells = re.findall(r'<td[^>]*>([^<]*)</td>', row)
want = [y["hours"]] + ["%.1f%%" % (100 * float(y[k])) for k in ("over_035", "over_040", "over_045")] + ["%.3f" % float(y["mean_dgp"]), y["en17037"]]
assert cells[2:] == want, (cells, want)
assert int(y["hours"]) == 18, y
print("the desk's daylight glare on the page:", cells[2:])
PY
grep -v ',observer,' "$TMP/calc.csv" > "$TMP/noobserver.csv"
expect_error "views of a daylight solution" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$TMP/noobserver.csv" -o "$TMP/x.html"
expect_error "--epw and --occupancy are for a daylight solution" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/calc.csv" --epw "$EPW" -o "$TMP/x.html"
expect_error "--energy is for a solution lit by luminaires" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$TMP/noobserver.csv" -o "$TMP/x.html" --energy office
printf 'name,kind,x,y,z,ux,uy,uz,vx,vy,vz\nexit,escape-route,0,0.02,4,4,0,0,0,0,-2\n' > "$TMP/route.csv"
expect_error "route.csv:2: an escape-route is lit by emergency luminaires (EN 1838), and a daylight solution has none" \
  "$TMP/x.html" "$BIN/rad-report" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$TMP/route.csv" -o "$TMP/x.html"
printf 'name,kind,x,y,z,ux,uy,uz,vx,vy,vz\nfaces,cylindrical,0,1.2,6,4,0,0,0,0,-6\n' > "$TMP/cyl.csv"
expect_error "cyl.csv:2: a cylindrical surface's daylight is not computed yet" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$TMP/cyl.csv" -o "$TMP/x.html"
expect_error "route.csv:2: an escape-route is lit by emergency luminaires" "$TMP/x.csv" \
  "$BIN/rad-gather" "$TMP/d.mesh" "$TMP/d.rad" --surfaces "$TMP/route.csv" --sky cie-overcast --daylight-factor -o "$TMP/x.csv"

# Refusals: the file and line, the fix; no output left.
printf 'name,kind,x,y,z,ux,uy,uz,vx,vy,vz\nwp,workplane,0,0.8,4,6,0,0,0,0,-4\nwp,wall,0,0,0,6,0,0,0,3,0\n' > "$TMP/twice.csv"
expect_error "twice.csv:3: 'wp' is named twice" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/twice.csv" -o "$TMP/x.html"
expect_error "twice.csv:3: 'wp' is named twice" "$TMP/x.csv" \
  "$BIN/rad-gather" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/twice.csv" -o "$TMP/x.csv"
expect_error "--surfaces writes lux at its own sensors" "$TMP/x.csv" \
  "$BIN/rad-gather" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/calc.csv" --grid "0 0 1 1 1 2 2" -o "$TMP/x.csv"
# Glare needs luminaires: a Cornell box lit by its own lamp has none.
cornell_mesh 0.25
{ "$BIN/rad-ff" "$TMP/c.mesh" -o "$TMP/c.ff" -q && "$BIN/rad-solve" "$TMP/c.mesh" "$TMP/c.ff" -o "$TMP/c.rad" -q; } || fail "cornell"
printf 'name,kind,x,y,z,ux,uy,uz\neye,observer,0,0.5,0.5,0,0,-1\n' > "$TMP/eye.csv"
expect_error "the solution has none" "$TMP/x.html" \
  "$BIN/rad-report" "$TMP/c.mesh" "$TMP/c.rad" --surfaces "$TMP/eye.csv" -o "$TMP/x.html"
# No Chromium: a system error (exit 2) saying how to get it, and neither output written.
err=$(RAD_CHROMIUM=/nonexistent/chromium "$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" \
  -o "$TMP/y.html" --pdf "$TMP/y.pdf" 2>&1); rc=$?
[ $rc -eq 2 ] || fail "a missing Chromium: exit $rc ($err)"
grep -qF "RAD_CHROMIUM" <<<"$err" || fail "a missing Chromium: '$err' does not say what to set"
if [ -e "$TMP/y.html" ] || [ -e "$TMP/y.pdf" ]; then fail "a failed --pdf left an output"; fi

# The PDF step (#70 item 3), with stand-in browsers (RAD_CHROMIUM): the page's file:// URL is
# percent-encoded (a TMPDIR holding '#' pointed it at the folder above), the browser is told
# to keep off the network, and a "PDF" that is not one is refused (it gave exit 0).
mkdir -p "$TMP/browsers" "$TMP/tmp#dir%41"
cat > "$TMP/browsers/recording" <<'SH'
#!/usr/bin/env bash
# Decodes the page's URL, checks the page is there, records the flags, writes a tiny PDF.
out="" url=""
for a in "$@"; do case "$a" in --print-to-pdf=*) out="${a#--print-to-pdf=}" ;; file://*) url="$a" ;; esac; done
printf '%s\n' "$@" > "$FLAGS"
page=$(python3 -c 'import sys, urllib.parse; print(urllib.parse.unquote(sys.argv[1][len("file://"):]))' "$url")
grep -q "<html" "$page" || { echo "no page at $page (from $url)" >&2; exit 3; }
printf '%%PDF-1.4\n%%stand-in\n' > "$out"
SH
cat > "$TMP/browsers/liar" <<'SH'
#!/usr/bin/env bash
for a in "$@"; do case "$a" in --print-to-pdf=*) echo "this is not a PDF" > "${a#--print-to-pdf=}" ;; esac; done
SH
chmod +x "$TMP/browsers/recording" "$TMP/browsers/liar"
err=$(FLAGS="$TMP/flags.txt" TMPDIR="$TMP/tmp#dir%41" RAD_CHROMIUM="$TMP/browsers/recording" "$BIN/rad-report" \
  "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" -o "$TMP/u.html" --pdf "$TMP/u.pdf" -q 2>&1) \
  || fail "--pdf with a TMPDIR holding '#' and '%41': $err"
head -c 5 "$TMP/u.pdf" 2>/dev/null | grep -q '%PDF-' || fail "the stand-in's PDF was not kept"
for flag in --disable-background-networking --disable-component-update --disable-sync; do
  grep -qx -- "$flag" "$TMP/flags.txt" || fail "the browser is not given $flag"
done
err=$(RAD_CHROMIUM="$TMP/browsers/liar" "$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" --surfaces "$TMP/nocamera.csv" \
  -o "$TMP/z.html" --pdf "$TMP/z.pdf" 2>&1); rc=$?
[ $rc -eq 2 ] || fail "a browser that writes no PDF: exit $rc ($err)"
grep -q "wrote a file that is not a PDF" <<<"$err" || fail "the non-PDF is not named: $err"
if [ -e "$TMP/z.html" ] || [ -e "$TMP/z.pdf" ]; then fail "a non-PDF left an output"; fi
ls -A "$TMP" | grep -q '\.tmp\.' && fail "a temporary file was left: $(ls -A "$TMP" | grep '\.tmp\.')"
# Ctrl-C or a kill while the browser prints (#70 item 3): the browser ends too (timeout kept it
# in a process group the signal never reached), and nothing is left: no PDF written after
# rad-report has gone, no temporary folder; rad-report ends as the signal ends it.
cat > "$TMP/browsers/slow" <<'SH'
#!/usr/bin/env bash
# Prints slowly, then writes its "PDF" (unless it is stopped first).
echo $$ > "$SLOW_PID"
for a in "$@"; do case "$a" in --print-to-pdf=*) out="${a#--print-to-pdf=}" ;; esac; done
sleep 6
printf '%%PDF-1.4\n%%late\n' > "$out"
SH
chmod +x "$TMP/browsers/slow"
mkdir -p "$TMP/sig" "$TMP/sigtmp"
for sig in INT TERM; do
  rm -f "$TMP/slow.pid"
  SLOW_PID="$TMP/slow.pid" TMPDIR="$TMP/sigtmp" RAD_CHROMIUM="$TMP/browsers/slow" "$BIN/rad-report" "$TMP/l.mesh" "$TMP/l.rad" \
    --surfaces "$TMP/nocamera.csv" -o "$TMP/sig/s.html" --pdf "$TMP/sig/s.pdf" -q 2>/dev/null &
  report=$!
  for _ in $(seq 100); do [ -s "$TMP/slow.pid" ] && break; sleep 0.1; done
  [ -s "$TMP/slow.pid" ] || fail "the slow browser never started ($sig)"
  kill -"$sig" "$report"
  wait "$report"; rc=$?
  [ $rc -ge 128 ] || fail "rad-report ended with $rc after SIG$sig (wanted a signal's end)"
  browser=$(cat "$TMP/slow.pid" 2>/dev/null)
  sleep 0.5
  [ -n "$browser" ] && kill -0 "$browser" 2>/dev/null && fail "the browser still runs after SIG$sig to rad-report"
  sleep 6.5 # past the time the browser would have written its PDF
  [ -z "$(ls -A "$TMP/sig")" ] || fail "files left after SIG$sig: $(ls -A "$TMP/sig")"
  [ -z "$(ls -A "$TMP/sigtmp")" ] || fail "a temporary folder left after SIG$sig: $(ls -A "$TMP/sigtmp")"
done
finish
