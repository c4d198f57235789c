# Melanopic EDI at the eye (#69 item 4): light of a known spectrum weighed by CIE S 026's
# melanopic function through the chain's RGB bands. Checked against the standard's published
# ratios (D65's melanopic EDI is its illuminance; illuminant A's is 0.4958 of it) in a room of
# grey surfaces, superposition (two lamp colours gathered each by its own spectrum add up to
# the two runs of one group each), what a coloured desk does, refusals and determinism.
source "$(dirname "$0")/lib.sh"
L="$SRC/scenes/lighting"
mkdir -p "$TMP/room"
cp "$L/room.obj" "$L/led_downlight.ies" "$TMP/room/"
sed 's/^Kd 0.45 0.3 0.18$/Kd 0.4 0.4 0.4/' "$L/room.mtl" > "$TMP/room/room.mtl"
grep -q "Kd 0.4 0.4 0.4" "$TMP/room/room.mtl" || fail "the desk was not made grey"
"$BIN/rad-mesh" "$TMP/room/room.obj" -o "$TMP/grey.mesh" -q || fail "mesh"
"$BIN/rad-ff" "$TMP/grey.mesh" -o "$TMP/grey.ff" -q || fail "ff"
# One layout of two lamp colours in two groups, and each group alone.
header="name,photometry,x,y,z,aim_x,aim_y,aim_z,spin,maintenance,group,cct"
warm=$'L1,led_downlight.ies,1.5,3,1,,,,,0.8,warm,3000\nL2,led_downlight.ies,4.5,3,1,,,,,0.8,warm,3000'
cool=$'L3,led_downlight.ies,1.5,3,3,,,,,0.8,cool,6500\nL4,led_downlight.ies,4.5,3,3,,,,,0.8,cool,6500'
printf '%s\n%s\n%s\n' "$header" "$warm" "$cool" > "$TMP/room/both.csv"
printf '%s\n%s\n' "$header" "$warm" > "$TMP/room/warm.csv"
printf '%s\n%s\n' "$header" "$cool" > "$TMP/room/cool.csv"
for s in both warm cool; do
  "$BIN/rad-ff" "$TMP/grey.mesh" --luminaires "$TMP/room/$s.csv" -o "$TMP/$s.lum" -q || fail "lum $s"
  "$BIN/rad-solve" "$TMP/grey.mesh" "$TMP/grey.ff" --direct "$TMP/$s.lum" -o "$TMP/$s.rad" -q || fail "solve $s"
done
# Eyes at 1.2 m looking level (the lines of an observer's vertical illuminance), and one
# looking down at the work plane.
printf '3 1.2 3.6 0 0 -1\n1 1.2 2 1 0 0\n5 1.2 0.5 -1 0 0.2\n2 0.8 2 0 1 0\n' > "$TMP/eyes.txt"
gather() { "$BIN/rad-gather" "$TMP/grey.mesh" "$@" --points "$TMP/eyes.txt" --lux --melanopic --error --rays 512 -q; }

# D65 on grey surfaces: melanopic EDI is the illuminance (mel-DER 1), within 0.5%.
gather "$TMP/warm.rad" --spectrum d65 > "$TMP/d65.txt" || fail "gather d65"
awk '{ r = $3 / $1; if (r < 0.995 || r > 1.005) bad = bad " " NR ":" r } END { if (bad) { print "D65 ratio off:" bad; exit 1 } }' "$TMP/d65.txt" || fail "$(cat "$TMP/d65.txt")"
# Illuminant A: CIE S 026's 0.4958, within 0.5%.
gather "$TMP/warm.rad" --spectrum a > "$TMP/a.txt" || fail "gather a"
awk '{ r = $3 / $1; if (r < 0.4958 * 0.995 || r > 0.4958 * 1.005) bad = bad " " NR ":" r } END { if (bad) { print "A ratio off:" bad; exit 1 } }' "$TMP/a.txt" || fail "$(cat "$TMP/a.txt")"

# Two colours in one solution: each group's light is weighed by its own lamp's blackbody,
# so the sum is what the two single-group solutions give, within their error bars.
gather "$TMP/both.rad" > "$TMP/both.txt" 2>"$TMP/both.err" || fail "gather both: $(cat "$TMP/both.err")"
gather "$TMP/warm.rad" > "$TMP/warm.txt" || fail "gather warm"
gather "$TMP/cool.rad" > "$TMP/cool.txt" || fail "gather cool"
paste -d ' ' "$TMP/both.txt" "$TMP/warm.txt" "$TMP/cool.txt" | awk '
  { sum = $7 + $11; bar = 3 * sqrt($4 * $4 + $8 * $8 + $12 * $12) + 1e-3 * sum
    if ((sum - $3) > bar || ($3 - sum) > bar) bad = bad " " NR ": " $3 " vs " sum " +- " bar
    # and not one spectrum for both: the cool share has the higher ratio
    if ($11 / $9 <= $7 / $5 * 1.3) bad = bad " " NR ": cool ratio " $11 / $9 " vs warm " $7 / $5 }
  END { if (bad) { print bad; exit 1 } }' || fail "superposition: $(paste -d ' ' "$TMP/both.txt" "$TMP/warm.txt" "$TMP/cool.txt")"
grep -q "melanopic: warm: 3000 K blackbody" <<<"$("$BIN/rad-gather" "$TMP/grey.mesh" "$TMP/both.rad" --points "$TMP/eyes.txt" --lux --melanopic --rays 64 2>&1 >/dev/null)" ||
  fail "the sources are not said"
# The same bytes at any thread count.
gather "$TMP/both.rad" --threads 1 > "$TMP/both1.txt" || fail "threads 1"
cmp -s "$TMP/both.txt" "$TMP/both1.txt" || fail "--threads 1 changes the melanopic output"

# The example's brown desk: under D65, an eye looking at it gets less melanopic light than
# lux (the desk sends back less blue than it gets); the grey copy's eye does not.
"$BIN/rad-mesh" "$L/room.obj" -o "$TMP/brown.mesh" -q || fail "mesh brown"
"$BIN/rad-ff" "$TMP/brown.mesh" -o "$TMP/brown.ff" -q || fail "ff brown"
"$BIN/rad-ff" "$TMP/brown.mesh" --luminaires "$L/layout.csv" -o "$TMP/brown.lum" -q || fail "lum brown"
"$BIN/rad-solve" "$TMP/brown.mesh" "$TMP/brown.ff" --direct "$TMP/brown.lum" -o "$TMP/brown.rad" -q || fail "solve brown"
echo "2.2 1.6 2.0 0 -1 0.2" > "$TMP/desk-eye.txt"
r=$("$BIN/rad-gather" "$TMP/brown.mesh" "$TMP/brown.rad" --points "$TMP/desk-eye.txt" --lux --melanopic --spectrum d65 -q | awk '{ print $2 / $1 }')
awk -v r="$r" 'BEGIN { exit !(r < 0.97) }' || fail "an eye over the brown desk under D65: ratio $r (expected below 0.97)"

# Observers of a calculation-surface file: the eye's vertical illuminance and its melanopic EDI.
err=$("$BIN/rad-gather" "$TMP/brown.mesh" "$TMP/brown.rad" --surfaces "$L/calc.csv" --melanopic --spectrum cct:4000 -o "$TMP/s.csv" 2>&1) || fail "surfaces: $err"
grep -qE "^rad-gather: observer desk chair: Ev [0-9.]+ ± [0-9.]+ lx .*melanopic EDI [0-9.]+ ± [0-9.]+ lx, mel-DER 0\.[0-9]+ at the eye \(WELL: [0-9]+ EML, M/P" <<<"$err" || fail "observer line: $err"

# Daylight under one sky: the sky's light is D65 unless --spectrum says; grey room, D65:
# melanopic EDI is lux; illuminant A's ratio is CIE S 026's; walls painted blue raise the
# ratio at an eye facing one (the reflected light is bluer than the sky's).
D="$SRC/scenes/daylight-room"
mkdir -p "$TMP/day" "$TMP/blue"
cp "$D/daylight-room-glazed.obj" "$D/daylight-room.mtl" "$TMP/day/"
cp "$D/daylight-room-glazed.obj" "$TMP/blue/"
sed '/^newmtl wall$/,/^newmtl/ s/^Kd .*/Kd 0.15 0.3 0.7/' "$D/daylight-room.mtl" > "$TMP/blue/daylight-room.mtl"
grep -q "Kd 0.15 0.3 0.7" "$TMP/blue/daylight-room.mtl" || fail "the walls were not painted"
for r in day blue; do
  "$BIN/rad-mesh" "$TMP/$r/daylight-room-glazed.obj" -o "$TMP/$r.mesh" --unit m -q || fail "mesh $r"
  "$BIN/rad-ff" "$TMP/$r.mesh" -o "$TMP/$r.ff" -q || fail "ff $r"
  "$BIN/rad-ff" "$TMP/$r.mesh" --sky reinhart:1 -o "$TMP/$r.sky" -q || fail "sky $r"
  "$BIN/rad-solve" "$TMP/$r.mesh" "$TMP/$r.ff" --direct "$TMP/$r.sky" -o "$TMP/$r.rad" -q || fail "solve $r"
done
printf '2 1.2 3 0 0 -1
2 0.8 2 0 1 0
1 1.2 5 1 0 0
3.5 1.2 4 1 0 0
' > "$TMP/day-eyes.txt"
SKY=(--sky cie:12 --date 2024-06-21 --time 12:00 --location 39.7,-105,-7)
daylight() { "$BIN/rad-gather" "$TMP/$1.mesh" "$TMP/$1.rad" --points "$TMP/day-eyes.txt" "${SKY[@]}" --melanopic -q "${@:2}"; }
daylight day > "$TMP/day-d65.txt" || fail "daylight d65"
awk '{ r = $2 / $1; if (r < 0.995 || r > 1.005) bad = bad " " NR ":" r } END { if (bad) { print bad; exit 1 } }' "$TMP/day-d65.txt" || fail "daylight D65 ratio: $(cat "$TMP/day-d65.txt")"
daylight day --spectrum a > "$TMP/day-a.txt" || fail "daylight a"
awk '{ r = $2 / $1; if (r < 0.4958 * 0.995 || r > 0.4958 * 1.005) bad = bad " " NR ":" r } END { if (bad) { print bad; exit 1 } }' "$TMP/day-a.txt" || fail "daylight A ratio: $(cat "$TMP/day-a.txt")"
daylight blue > "$TMP/blue-d65.txt" || fail "daylight blue"
r=$(sed -n 4p "$TMP/blue-d65.txt" | awk '{ print $2 / $1 }')
awk -v r="$r" 'BEGIN { exit !(r > 1.03) }' || fail "an eye facing a blue wall under D65: ratio $r (expected above 1.03)"
# The surfaces' CSV gains the column; lux itself is what it was without --melanopic.
"$BIN/rad-gather" "$TMP/day.mesh" "$TMP/day.rad" --points "$TMP/day-eyes.txt" "${SKY[@]}" -q > "$TMP/day-lux.txt" || fail "daylight lux"
cmp -s <(awk '{ print $1 }' "$TMP/day-d65.txt") "$TMP/day-lux.txt" || fail "--melanopic changed the lux column"
"$BIN/rad-gather" "$TMP/day.mesh" "$TMP/day.rad" --surfaces "$D/calc.csv" "${SKY[@]}" --melanopic --error -q -o "$TMP/day-s.csv" || fail "daylight surfaces"
head -1 "$TMP/day-s.csv" | grep -q "^surface,index,column,row,x,y,z,lux,lux_error,melanopic,melanopic_error$" || fail "surfaces header: $(head -1 "$TMP/day-s.csv")"
expect_error "--melanopic gives melanopic EDI under one sky" "$TMP/x.ill" "$BIN/rad-gather" "$TMP/day.mesh" "$TMP/day.rad" --points "$TMP/day-eyes.txt" --epw "$SRC/tests/data/denver-tmy3.epw" --annual --melanopic -o "$TMP/x.ill"
expect_error "a daylight solution's light is the sky's, one spectrum" "$TMP/x.txt" "$BIN/rad-gather" "$TMP/day.mesh" "$TMP/day.rad" --points "$TMP/day-eyes.txt" "${SKY[@]}" --melanopic --spectrum sky=a -o "$TMP/x.txt"

# Refusals, before any output.
expect_error "light group 'downlights' has no spectrum" "$TMP/x.txt" "$BIN/rad-gather" "$TMP/brown.mesh" "$TMP/brown.rad" --points "$TMP/eyes.txt" --lux --melanopic -o "$TMP/x.txt"
expect_error "has no light group 'lamps' (its groups: downlights)" "$TMP/x.txt" "$BIN/rad-gather" "$TMP/brown.mesh" "$TMP/brown.rad" --points "$TMP/eyes.txt" --lux --melanopic --spectrum lamps=a -o "$TMP/x.txt"
expect_error "--spectrum weighs light for --melanopic" "$TMP/x.txt" "$BIN/rad-gather" "$TMP/brown.mesh" "$TMP/brown.rad" --points "$TMP/eyes.txt" --lux --spectrum a -o "$TMP/x.txt"
expect_error "--melanopic writes melanopic EDI beside lux: add --lux" "$TMP/x.txt" "$BIN/rad-gather" "$TMP/brown.mesh" "$TMP/brown.rad" --points "$TMP/eyes.txt" --melanopic --spectrum a -o "$TMP/x.txt"
printf '400,1\n380,1\n' > "$TMP/bad.csv"
expect_error "bad.csv:2: wavelength 380 nm does not increase" "$TMP/x.txt" "$BIN/rad-gather" "$TMP/brown.mesh" "$TMP/brown.rad" --points "$TMP/eyes.txt" --lux --melanopic --spectrum "$TMP/bad.csv" -o "$TMP/x.txt"
finish
