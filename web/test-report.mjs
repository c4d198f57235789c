// Opens a rad-report page in headless Chromium (puppeteer-core, Debian's chromium) and checks
// it against rad-gather --surfaces' values for the same inputs: no console error and no
// network request; every figure in the tables equals the one computed from rad-gather's values
// to the digits shown; every isoline's ends lie where rad-gather's values, linear between
// sensors, equal its level, and its pixels are drawn there; every line has its label.
//
//   node test-report.mjs --page R.html --values G.csv [--screenshot-dir D]
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

// rad-gather --surfaces' CSV: surface name -> { columns, rows, lux[] } (names here are plain).
function readValues(file) {
  const surfaces = new Map();
  const lines = readFileSync(file, 'utf8').split('\n').filter((l) => l && !l.startsWith('#'));
  if (lines[0] !== 'surface,index,column,row,x,y,z,lux') throw new Error(`${file}: not rad-gather --surfaces output`);
  for (const line of lines.slice(1)) {
    const f = line.split(',');
    const name = f[0];
    if (!surfaces.has(name)) surfaces.set(name, { columns: 0, rows: 0, lux: [] });
    const s = surfaces.get(name);
    s.columns = Math.max(s.columns, Number(f[2]) + 1);
    s.rows = Math.max(s.rows, Number(f[3]) + 1);
    s.lux.push(f[7] === 'nan' ? NaN : Number(f[7]));
  }
  return surfaces;
}

function figures(lux) {
  const v = lux.filter((x) => Number.isFinite(x));
  const min = Math.min(...v), max = Math.max(...v), mean = v.reduce((a, b) => a + b, 0) / v.length;
  return { em: mean, emin: min, emax: max, u0: min / mean, ratio: min / max };
}

// The shown text equals `value` to its digits: within half a unit of its last decimal (and
// the rounding of rad-gather's six significant digits).
function sameToDigits(shown, value) {
  const decimals = (shown.split('.')[1] ?? '').length;
  const half = 0.5 * 10 ** -decimals;
  return Math.abs(Number(shown) - value) <= half + 1e-5 * Math.abs(value);
}

// The value at an isoline's end (sensor coordinates, on a square's edge), linear along it.
function valueAt(s, c, r) {
  const v = (cc, rr) => s.lux[rr * s.columns + cc];
  const near = (x) => Math.abs(x - Math.round(x)) < 1e-3;
  if (near(c)) {
    const cc = Math.round(c), r0 = Math.min(Math.floor(r), s.rows - 2);
    return { value: v(cc, r0) + (r - r0) * (v(cc, r0 + 1) - v(cc, r0)), spread: Math.abs(v(cc, r0 + 1) - v(cc, r0)) };
  }
  const rr = Math.round(r), c0 = Math.min(Math.floor(c), s.columns - 2);
  return { value: v(c0, rr) + (c - c0) * (v(c0 + 1, rr) - v(c0, rr)), spread: Math.abs(v(c0 + 1, rr) - v(c0, rr)) };
}

const opts = options();
const values = readValues(opts.values);
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
  const shown = await page.evaluate(() => {
    const text = (el, sel) => el.querySelector(sel)?.textContent.trim();
    const out = [];
    for (const table of document.querySelectorAll('table.figures')) {
      const name = table.dataset.surface;
      const row = [...document.querySelectorAll('table.surfaces tr')].find((r) => r.dataset.surface === name);
      const summary = row ? [...row.querySelectorAll('td')].map((td) => td.textContent.trim()) : [];
      const section = table.closest('section');
      const iso = section.querySelector('g.isolux');
      const [x0, y0] = iso.dataset.sensorOrigin.split(' ').map(Number);
      const [dx, dy] = iso.dataset.sensorStep.split(' ').map(Number);
      const lines = [...iso.querySelectorAll('path.isoline')].map((p) => ({ lux: p.dataset.lux, d: p.getAttribute('d') }));
      const labels = [...iso.querySelectorAll('text.isolabel')].map((t) => ({ lux: t.dataset.lux, text: t.textContent }));
      out.push({
        name, summary, lines, labels, x0, y0, dx, dy,
        em: text(table, 'td.em'), emin: text(table, 'td.emin'), emax: text(table, 'td.emax'),
        u0: text(table, 'td.u0'), ratio: text(table, 'td.ratio'),
      });
    }
    return out;
  });
  if (shown.length !== values.size) fail(`the page has ${shown.length} surfaces, rad-gather wrote ${values.size}`);
  let checked = 0, ends = 0, drawn = 0, sampled = 0;
  for (const s of shown) {
    const v = values.get(s.name);
    if (!v) { fail(`surface '${s.name}' is not in ${opts.values}`); continue; }
    const f = figures(v.lux);
    for (const key of ['em', 'emin', 'emax', 'u0', 'ratio']) {
      if (!sameToDigits(s[key], f[key])) fail(`${s.name}: ${key} shown ${s[key]}, rad-gather's values give ${f[key]}`);
      ++checked;
    }
    // The summary row: Em, Emin, Emax, U0, Emin/Emax in columns 2 to 6.
    ['em', 'emin', 'emax', 'u0', 'ratio'].forEach((key, k) => {
      if (s.summary[2 + k] !== s[key]) fail(`${s.name}: the summary shows ${s.summary[2 + k]} for ${key}, the section ${s[key]}`);
    });
    // Isolines: every end at its level; every level labelled, with its own value.
    const element = await page.$(`section:has(table.figures[data-surface="${s.name}"]) svg.plan`);
    const box = await element.boundingBox();
    const shot = await element.screenshot({ encoding: 'base64' });
    const pixels = await page.evaluate(async (src) => {
      const image = new Image();
      image.src = `data:image/png;base64,${src}`;
      await image.decode();
      const canvas = document.createElement('canvas');
      canvas.width = image.width; canvas.height = image.height;
      const context = canvas.getContext('2d');
      context.drawImage(image, 0, 0);
      return { width: image.width, data: Array.from(context.getImageData(0, 0, image.width, image.height).data) };
    }, shot);
    const dark = (x, y) => {
      for (let j = -1; j <= 1; ++j) for (let i = -1; i <= 1; ++i) {
        const k = 4 * ((Math.round(y) + j) * pixels.width + Math.round(x) + i);
        if (pixels.data[k] + pixels.data[k + 1] + pixels.data[k + 2] < 200) return true;
      }
      return false;
    };
    for (const line of s.lines) {
      const level = Number(line.lux);
      if (!s.labels.some((l) => l.lux === line.lux)) fail(`${s.name}: the ${line.lux} lx line has no label`);
      const numbers = line.d.match(/-?[0-9.]+/g).map(Number);
      for (let k = 0; k + 3 < numbers.length; k += 4) {
        for (const [x, y] of [[numbers[k], numbers[k + 1]], [numbers[k + 2], numbers[k + 3]]]) {
          const at = valueAt(v, (x - s.x0) / s.dx, (s.y0 - y) / s.dy);
          const tolerance = at.spread * 0.006 / Math.min(s.dx, s.dy) + 1e-4 * level;
          if (!(Math.abs(at.value - level) <= tolerance)) fail(`${s.name}: an end of the ${line.lux} lx line at (${x}, ${y}) lies at ${at.value.toFixed(3)} lx`);
          ++ends;
        }
        const mx = (numbers[k] + numbers[k + 2]) / 2, my = (numbers[k + 1] + numbers[k + 3]) / 2;
        ++sampled;
        if (dark(mx - 0 * box.x, my)) ++drawn;
      }
    }
    for (const label of s.labels) if (label.text !== label.lux) fail(`${s.name}: a label reads ${label.text} on the ${label.lux} lx line`);
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
