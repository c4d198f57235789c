// Opens a rad-bake --html page in headless Chromium (puppeteer-core, Debian's chromium), sets
// its sliders if asked, reads the rendered pixels and compares them with a reference PNG
// (rad-shade's image of the same view): mean absolute difference on sRGB values, pixels at
// edges of the reference left out. Exits 1 when the difference is at or over --max-difference.
//
//   node test-viewer.mjs --page P.html --reference R.png [--set '{"weights":{"g":0}}']
//        [--screenshot S.png] [--width 512] [--height 512] [--max-difference 0.03]
//        [--probe X,Y]  (print the pixel at X,Y and what the page shows outside; no reference needed)
//        [--glb G.glb: show this glb in the page instead of its own]
//        [--slide name=value,...: move the page's sliders, as a user would]
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import puppeteer from 'puppeteer-core';

function options() {
  const args = process.argv.slice(2);
  const out = { width: 512, height: 512, 'max-difference': 0.03 };
  for (let i = 0; i < args.length; i += 2) {
    if (!args[i].startsWith('--') || i + 1 >= args.length) throw new Error(`bad argument ${args[i]}`);
    out[args[i].slice(2)] = args[i + 1];
  }
  if (!out.page || (!out.reference && !out.probe)) throw new Error('give --page and --reference (or --probe X,Y)');
  return out;
}

// The reference as RGBA rows, top first, decoded by the browser itself.
async function decodePng(page, file) {
  const url = `data:image/png;base64,${readFileSync(file).toString('base64')}`;
  return page.evaluate(async (src) => {
    const image = new Image();
    image.src = src;
    await image.decode();
    const canvas = document.createElement('canvas');
    canvas.width = image.width;
    canvas.height = image.height;
    const context = canvas.getContext('2d', { colorSpace: 'srgb' });
    context.drawImage(image, 0, 0);
    return { width: image.width, height: image.height, rgba: Array.from(context.getImageData(0, 0, image.width, image.height).data) };
  }, url);
}

// Mean |a - b| over RGB in [0, 1], leaving out pixels where the reference changes by more than
// 0.1 to a neighbour (edges: a one-pixel shift there is not a shading error).
function compare(shown, reference) {
  const { width: w, height: h } = reference;
  if (shown.width !== w || shown.height !== h) throw new Error(`page is ${shown.width}x${shown.height}, reference ${w}x${h}`);
  const ref = (x, y, c) => reference.rgba[4 * (y * w + x) + c];
  const page = (x, y, c) => shown.rgba[4 * ((h - 1 - y) * w + x) + c]; // GL rows: bottom first
  let sum = 0, counted = 0, edges = 0;
  for (let y = 1; y < h - 1; ++y) {
    for (let x = 1; x < w - 1; ++x) {
      let edge = false;
      for (let dy = -1; dy <= 1 && !edge; ++dy)
        for (let dx = -1; dx <= 1 && !edge; ++dx)
          for (let c = 0; c < 3; ++c) if (Math.abs(ref(x + dx, y + dy, c) - ref(x, y, c)) > 25.5) edge = true;
      if (edge) { ++edges; continue; }
      for (let c = 0; c < 3; ++c) sum += Math.abs(page(x, y, c) - ref(x, y, c)) / 255;
      ++counted;
    }
  }
  return { difference: sum / (3 * counted), counted, edges };
}

const opts = options();
const profile = mkdtempSync(join(tmpdir(), 'radiosity-chromium-'));
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  userDataDir: profile,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync', '--disable-quic'],
});
let status = 0;
try {
  const page = await browser.newPage();
  const problems = [];
  page.on('pageerror', (error) => problems.push(String(error)));
  page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()}`));
  await page.setViewport({ width: Number(opts.width), height: Number(opts.height), deviceScaleFactor: 1 });
  if (opts.glb) {
    // The same page showing another glb (rad-bake --engine's): its embedded glb replaced.
    const html = readFileSync(opts.page, 'utf8').replace(
      /(<script id="radiosity-glb" type="application\/octet-stream">)[^<]*(<\/script>)/,
      (_, open, close) => `${open}\n${readFileSync(opts.glb).toString('base64')}\n${close}`);
    await page.setContent(html, { waitUntil: 'load' });
  } else {
    await page.goto(pathToFileURL(resolve(opts.page)).href, { waitUntil: 'load' });
  }
  await page.waitForFunction(() => document.body.dataset.ready || document.body.dataset.error, { timeout: 120000 });
  const error = await page.evaluate(() => document.body.dataset.error);
  if (error) throw new Error(`the page failed: ${error}`);
  if (problems.length > 0) throw new Error(`the page reported: ${problems.join('; ')}`);
  if (opts.set) await page.evaluate((s) => window.radiosity.set(s), JSON.parse(opts.set));
  if (opts.slide) {
    // As a user would: move the sliders (name=value,...) and let their input events relight.
    for (const setting of opts.slide.split(',')) {
      const [name, value] = setting.split('=');
      const moved = await page.evaluate((n, v) => {
        const input = document.querySelector(`#panel input[data-name="${n}"]`);
        if (!input) return false;
        input.value = v;
        input.dispatchEvent(new Event('input'));
        return true;
      }, name, value);
      if (!moved) throw new Error(`the page has no slider '${name}'`);
    }
  }
  const shown = await page.evaluate(() => window.radiosity.pixels());
  if (opts.screenshot) await page.screenshot({ path: opts.screenshot });
  if (opts.probe) {
    // The canvas pixel at X,Y (from the top left), with what the page says is outside.
    const [x, y] = opts.probe.split(',').map(Number);
    const at = 4 * ((shown.height - 1 - y) * shown.width + x);
    const outside = await page.evaluate(() => ({ outside: window.radiosity.outside(), panes: window.radiosity.panes() }));
    console.log(`probe: ${JSON.stringify({ pixel: shown.rgba.slice(at, at + 3), ...outside })}`);
  }
  if (opts.reference) {
    const result = compare(shown, await decodePng(page, opts.reference));
    const limit = Number(opts['max-difference']);
    console.log(`${opts.page}: mean absolute difference ${(100 * result.difference).toFixed(2)}% of full scale over ${result.counted} pixels (${result.edges} edge pixels left out), limit ${(100 * limit).toFixed(2)}%`);
    if (!(result.difference < limit)) status = 1;
  }
} catch (error) {
  console.error(`test-viewer: ${error.message}`);
  status = 2;
} finally {
  await browser.close();
  rmSync(profile, { recursive: true, force: true });
}
process.exit(status);
