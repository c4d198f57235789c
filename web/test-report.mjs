// Opens a rad-report page in headless Chromium (puppeteer-core, Debian's chromium) and checks
// it against rad-gather --surfaces' values for the same inputs: no console error and no
// network request; every figure in the tables equals the one computed from rad-gather's values
// to the digits shown; every isoline's ends lie where rad-gather's values, linear between
// sensors, equal its level, and its pixels are drawn there; every line has its label.
//
//   node test-report.mjs --page R.html --values G.csv [--quantity lux|df|da300]
//     lux:   G.csv is rad-gather --surfaces' output (its lux column)
//     df:    rad-gather --surfaces --sky cie-overcast --daylight-factor's (its df column)
//     da300: rad-gather --surfaces --epw F --annual --metrics G.csv's metrics
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import puppeteer from 'puppeteer-core';

function options() {
  const args = process.argv.slice(2);
  const out = {};
  for (let i = 0; i < args.length; i += 2) {
    if (!args[i].startsWith('--') || i + 1 >= args.length) throw new Error(`bad argument ${args[i]}`);
    out[args[i].slice(2)] = args[i + 1];
  }
  if (!out.page || !out.values) throw new Error('give --page and --values');
  return out;
}

// rad-gather's CSV: surface name -> { columns, rows, rows of fields by column name }.
function readValues(file) {
  const surfaces = new Map();
  const lines = readFileSync(file, 'utf8').split('\n').filter((l) => l && !l.startsWith('#'));
  const header = lines[0].split(',');
  if (header.slice(0, 4).join(',') !== 'surface,index,column,row') throw new Error(`${file}: not rad-gather --surfaces output`);
  for (const line of lines.slice(1)) {
    const f = line.split(',');
    const row = Object.fromEntries(header.map((name, k) => [name, f[k] === 'nan' ? NaN : Number(f[k])]));
    if (!surfaces.has(f[0])) surfaces.set(f[0], { columns: 0, rows: 0, sensors: [] });
    const s = surfaces.get(f[0]);
    s.columns = Math.max(s.columns, row.column + 1);
    s.rows = Math.max(s.rows, row.row + 1);
    s.sensors.push(row);
  }
  return surfaces;
}

const mean = (v) => v.reduce((a, b) => a + b, 0) / v.length;
const share = (v, test) => 100 * v.filter(test).length / v.length;

// What the page shows of a surface, by the table cells' classes, from rad-gather's values; and
// the values its plan is drawn from.
const quantities = {
  lux: {
    plan: (s) => s.sensors.map((r) => r.lux),
    figures(s) {
      const v = s.sensors.map((r) => r.lux).filter((x) => Number.isFinite(x));
      const min = Math.min(...v), max = Math.max(...v), m = mean(v);
      return { em: m, emin: min, emax: max, u0: min / m, ratio: min / max };
    },
  },
  df: {
    plan: (s) => s.sensors.map((r) => r.df),
    figures(s) {
      const v = s.sensors.map((r) => r.df).sort((a, b) => a - b), n = v.length;
      const median = n % 2 ? v[(n - 1) / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
      return { 'df-mean': mean(v), 'df-median': median, 'df-min': v[0], 'df-max': v[n - 1], 'df-above2': share(v, (x) => x >= 2) };
    },
  },
  da300: {
    plan: (s) => s.sensors.map((r) => 100 * r.da300),
    figures(s) {
      const da = s.sensors.map((r) => r.da300);
      return {
        sda: share(da, (x) => x >= 0.5), ase: share(s.sensors, (r) => r.sun_hours > 250),
        da300: 100 * mean(da), udi: 100 * mean(s.sensors.map((r) => r.udi_useful)),
      };
    },
  },
};

// The shown text equals `value` to its digits: within half a unit of its last decimal (and
// the rounding of rad-gather's six significant digits).
function sameToDigits(shown, value) {
  const decimals = (shown.split('.')[1] ?? '').length;
  const half = 0.5 * 10 ** -decimals;
  return Math.abs(Number(shown) - value) <= half + 1e-5 * Math.abs(value) + 1e-9;
}

// The value at an isoline's end (sensor coordinates): the plan's field, bilinear between the
// four sensors around it (the plan draws its lines on a finer grid of that field; along any
// grid line the field is linear). `spread`: the four's range, for the tolerance of the end's
// rounding to 0.01 px.
function valueAt(s, c, r) {
  const v = (cc, rr) => s.plan[rr * s.columns + cc];
  const c0 = Math.max(0, Math.min(Math.floor(c), s.columns - 2)), r0 = Math.max(0, Math.min(Math.floor(r), s.rows - 2));
  const c1 = Math.min(c0 + 1, s.columns - 1), r1 = Math.min(r0 + 1, s.rows - 1);
  const fu = c - c0, fv = r - r0;
  const a = v(c0, r0), b = v(c1, r0), cc = v(c0, r1), d = v(c1, r1);
  const value = (1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * cc + fu * d);
  return { value, spread: Math.max(a, b, cc, d) - Math.min(a, b, cc, d) };
}

const opts = options();
const values = readValues(opts.values);
const quantity = quantities[opts.quantity ?? 'lux'];
if (!quantity) throw new Error(`--quantity: lux, df or da300, not ${opts.quantity}`);
const profile = mkdtempSync(join(tmpdir(), 'radiosity-chromium-'));
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  userDataDir: profile,
  args: ['--no-sandbox', '--no-first-run', '--disable-background-networking', '--disable-component-update',
    '--disable-sync', '--disable-quic'],
});
const failures = [];
const fail = (message) => failures.push(message);
let status = 0;
try {
  const page = await browser.newPage();
  const pageUrl = pathToFileURL(resolve(opts.page)).href;
  page.on('pageerror', (error) => fail(`page error: ${error}`));
  page.on('console', (message) => { if (message.type() === 'error') fail(`console error: ${message.text()}`); });
  // data: URLs are the test's own screenshots decoded in the page, not the network.
  page.on('request', (request) => {
    const url = request.url();
    if (url !== pageUrl && !url.startsWith('data:')) fail(`network request: ${url.slice(0, 100)}`);
  });
  await page.setViewport({ width: 900, height: 1200, deviceScaleFactor: 1 });
  await page.goto(pageUrl, { waitUntil: 'load' });
  // Plans at their own size (the page may shrink two side by side): lines one pixel wide or more.
  await page.addStyleTag({ content: '.plans figure, .plans svg { max-width: none !important; }' });
  const shown = await page.evaluate((q) => {
    const out = [];
    for (const table of document.querySelectorAll('table.figures')) {
      const name = table.dataset.surface;
      const row = [...document.querySelectorAll('table.surfaces tr')].find((r) => r.dataset.surface === name);
      const summary = row ? [...row.querySelectorAll('td.num')].map((td) => td.textContent.trim()) : [];
      const cells = {};
      for (const td of table.querySelectorAll('td.num')) cells[[...td.classList].find((c) => c !== 'num')] = td.textContent.trim();
      const iso = table.closest('section').querySelector(`g.isolux[data-quantity="${q}"]`);
      if (!iso) { out.push({ name, missing: true }); continue; }
      const svg = iso.closest('svg');
      const [x0, y0] = iso.dataset.sensorOrigin.split(' ').map(Number);
      const [dx, dy] = iso.dataset.sensorStep.split(' ').map(Number);
      const lines = [...iso.querySelectorAll('path.isoline')].map((p) => ({ level: p.dataset.level, d: p.getAttribute('d') }));
      const labels = [...iso.querySelectorAll('text.isolabel')].map((t) => ({ level: t.dataset.level, text: t.textContent }));
      const zoom = svg.getBoundingClientRect().width / svg.viewBox.baseVal.width;
      svg.id = svg.id || `plan-${out.length}-${q}`;
      out.push({ name, summary, cells, lines, labels, x0, y0, dx, dy, zoom, svg: svg.id });
    }
    return out;
  }, opts.quantity ?? 'lux');
  if (shown.length !== values.size) fail(`the page has ${shown.length} surfaces, rad-gather wrote ${values.size}`);
  let checked = 0, ends = 0, drawn = 0, sampled = 0;
  for (const s of shown) {
    const v = values.get(s.name);
    if (!v) { fail(`surface '${s.name}' is not in ${opts.values}`); continue; }
    if (s.missing) { fail(`${s.name}: no ${opts.quantity ?? 'lux'} plan`); continue; }
    const f = quantity.figures(v);
    for (const [key, value] of Object.entries(f)) {
      if (s.cells[key] === undefined) { fail(`${s.name}: the table has no ${key}`); continue; }
      if (!sameToDigits(s.cells[key], value)) fail(`${s.name}: ${key} shown ${s.cells[key]}, rad-gather's values give ${value}`);
      else ++checked;
      // The summary row shows the same text.
      if (!s.summary.includes(s.cells[key]) && (opts.quantity ?? 'lux') !== 'da300')
        fail(`${s.name}: the summary row (${s.summary.join(' ')}) lacks ${key} ${s.cells[key]}`);
    }
    v.plan = quantity.plan(v);
    // Isolines: every end at its level; every level labelled, with its own value.
    const element = await page.$(`#${s.svg}`);
    const shot = await element.screenshot({ encoding: 'base64' });
    const pixels = await page.evaluate(async (src) => {
      const image = new Image();
      image.src = `data:image/png;base64,${src}`;
      await image.decode();
      const canvas = document.createElement('canvas');
      canvas.width = image.width; canvas.height = image.height;
      const context = canvas.getContext('2d');
      context.drawImage(image, 0, 0);
      return { width: image.width, height: image.height, data: Array.from(context.getImageData(0, 0, image.width, image.height).data) };
    }, shot);
    const dark = (x, y) => {
      const px = Math.round(x * s.zoom), py = Math.round(y * s.zoom);
      for (let j = -1; j <= 1; ++j) for (let i = -1; i <= 1; ++i) {
        const k = 4 * ((py + j) * pixels.width + px + i);
        if (pixels.data[k] + pixels.data[k + 1] + pixels.data[k + 2] < 200) return true;
      }
      return false;
    };
    for (const line of s.lines) {
      const level = Number(line.level);
      if (!s.labels.some((l) => l.level === line.level)) fail(`${s.name}: the ${line.level} line has no label`);
      const numbers = line.d.match(/-?[0-9.]+/g).map(Number);
      for (let k = 0; k + 3 < numbers.length; k += 4) {
        for (const [x, y] of [[numbers[k], numbers[k + 1]], [numbers[k + 2], numbers[k + 3]]]) {
          const at = valueAt(v, (x - s.x0) / s.dx, (s.y0 - y) / s.dy);
          // The ends' pixels are written to 0.01 px, and rad-gather's values rounded (six
          // digits; the metrics' shares to 0.0001, 0.01 in %).
          const rounding = (opts.quantity === 'da300' ? 0.0051 : 0) + 2e-5 * Math.abs(level) + 1e-6;
          const tolerance = at.spread * 0.006 / Math.min(Math.abs(s.dx), Math.abs(s.dy)) + rounding;
          if (!(Math.abs(at.value - level) <= tolerance)) fail(`${s.name}: an end of the ${line.level} line at (${x}, ${y}) lies at ${at.value.toPrecision(7)} (tolerance ${tolerance.toPrecision(2)})`);
          ++ends;
        }
        ++sampled;
        if (dark((numbers[k] + numbers[k + 2]) / 2, (numbers[k + 1] + numbers[k + 3]) / 2)) ++drawn;
      }
    }
    for (const label of s.labels) if (label.text !== label.level) fail(`${s.name}: a label reads ${label.text} on the ${label.level} line`);
  }
  if (sampled === 0) fail('no isoline in the page');
  else if (drawn < 0.9 * sampled) fail(`only ${drawn} of ${sampled} isoline pieces are drawn dark at their place`);
  console.log(`${opts.page}: ${checked} figures equal rad-gather's to the digits shown; ${ends} isoline ends at their level; ${drawn} of ${sampled} pieces drawn`);
  if (failures.length) { console.error(failures.slice(0, 20).join('\n')); status = 1; }
} catch (error) {
  console.error(`test-report: ${error.message}`);
  status = 2;
} finally {
  await browser.close();
  rmSync(profile, { recursive: true, force: true });
}
process.exit(status);
