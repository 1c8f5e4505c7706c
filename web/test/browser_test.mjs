// Headless-Chromium test of the pages `globalvis view` and `globalvis report` write: runs a
// small pipeline (gen, cells, vis, radiosity, view, report), opens both pages from file:// with
// no network, checks the viewer draws a non-blank scene, that clicking a patch and picking an
// interaction change what is drawn and the viewer's state, that the report shows its tables,
// pictures and the framed viewer, and that no page logs an error. Screenshots stay in --work.
//
// Usage: node browser_test.mjs --cli build/globalvis --work DIR [--chromium /usr/bin/chromium]
//        [--run OUT]   (check the pages of an existing run, e.g. `make run`'s out/, unchanged)
import { execFileSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';

/** Generous: two shared cores, a software WebGL rasteriser, and a test suite running beside. */
const TIMEOUT_MS = 180_000;
/** A real render of the scene has far more colours than this; a blank or failed page has ~1. */
const MIN_DISTINCT_COLORS = 200;
/** Fraction of pixels that must change when a selection is drawn. */
const MIN_CHANGED_FRACTION = 0.0005;
const VIEWPORT = { width: 1100, height: 750 };

function parseArgs(argv) {
  const args = { chromium: '/usr/bin/chromium' };
  for (let i = 0; i < argv.length; i += 2) args[argv[i].replace(/^--/, '')] = argv[i + 1];
  if (!args.cli || !args.work) throw new Error('usage: browser_test.mjs --cli GLOBALVIS --work DIR');
  return args;
}

let passed = 0;
let failed = 0;
function check(ok, what, detail = '') {
  if (ok) {
    passed += 1;
    console.log(`ok    ${what}${detail ? ` (${detail})` : ''}`);
  } else {
    failed += 1;
    console.log(`FAIL  ${what}${detail ? ` (${detail})` : ''}`);
  }
  return ok;
}

/** Runs one pipeline stage; its output goes to our log. */
function run(cli, args) {
  const started = Date.now();
  const out = execFileSync(cli, args, { encoding: 'utf8', timeout: TIMEOUT_MS * 2 });
  console.log(`$ globalvis ${args.join(' ')}  [${((Date.now() - started) / 1000).toFixed(1)} s]\n${out.trim()}`);
}

/** Writes a small run directory the way `make run` lays it out. */
function makeRun(cli, dir) {
  rmSync(dir, { recursive: true, force: true });
  mkdirSync(dir, { recursive: true });
  const scene = join(dir, 'office.obj');
  run(cli, ['gen', 'office', '--rows', '1', '--columns', '2', '-o', scene]);
  run(cli, ['cells', scene, '-o', join(dir, 'cells')]);
  run(cli, ['vis', scene, '-o', join(dir, 'vis'), '--min-coverage', '0.3']);
  run(cli, ['radiosity', scene, '-o', join(dir, 'radiosity'), '--quiet', '--max-refinements', '1', '--rays', '4']);
  run(cli, ['view', dir]);
  run(cli, ['report', dir]);
}

/** Decodes a PNG screenshot in the browser: {width, height, data (RGBA)}. */
async function decodePng(page, png) {
  const rgba = await page.evaluate(async (b64) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const ctx = canvas.getContext('2d');
    ctx.drawImage(bitmap, 0, 0);
    const data = ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
    let binary = '';
    for (let i = 0; i < data.length; i += 0x8000) binary += String.fromCharCode(...data.subarray(i, i + 0x8000));
    return { width: bitmap.width, height: bitmap.height, b64: btoa(binary) };
  }, png.toString('base64'));
  return { width: rgba.width, height: rgba.height, data: Buffer.from(rgba.b64, 'base64') };
}

function distinctColors(image) {
  const seen = new Set();
  for (let i = 0; i < image.data.length; i += 4) {
    seen.add((image.data[i] << 16) | (image.data[i + 1] << 8) | image.data[i + 2]);
  }
  return seen.size;
}

function changedFraction(a, b) {
  if (a.width !== b.width || a.height !== b.height) return 1;
  let changed = 0;
  for (let i = 0; i < a.data.length; i += 4) {
    const d = Math.abs(a.data[i] - b.data[i]) + Math.abs(a.data[i + 1] - b.data[i + 1]) + Math.abs(a.data[i + 2] - b.data[i + 2]);
    if (d > 24) changed += 1;
  }
  return changed / (a.width * a.height);
}

/** Pixels whose colour is close to the tube's red or the blockers' orange. */
function countHue(image, test) {
  let n = 0;
  for (let i = 0; i < image.data.length; i += 4) if (test(image.data[i], image.data[i + 1], image.data[i + 2])) n += 1;
  return n;
}
const isRed = (r, g, b) => r > 150 && g < 90 && b < 90;
const isOrange = (r, g, b) => r > 180 && g > 100 && g < 190 && b < 80;

async function screenshot(page, path) {
  const png = await page.screenshot({ path, timeout: TIMEOUT_MS });
  return decodePng(page, png);
}

async function testViewer(context, runDir, work, errors) {
  const page = await context.newPage();
  watch(page, 'viewer', errors);
  await page.goto(pathToFileURL(join(runDir, 'viewer.html')).href, { timeout: TIMEOUT_MS });
  await page.waitForFunction(() => window.viewerState && window.viewerState.ready, null, { timeout: TIMEOUT_MS });
  const state0 = await page.evaluate(() => ({ ...window.viewerState }));
  check(state0.patchCount > 0 && state0.pairCount > 0, 'viewer loaded the scene', `${state0.patchCount} patches, ${state0.pairCount} pairs, shading ${state0.shading}`);
  check(state0.shading === 'radiosity', 'viewer shades by radiosity when the run has it');

  const before = await screenshot(page, join(work, 'viewer-1-scene.png'));
  const colors = distinctColors(before);
  check(colors >= MIN_DISTINCT_COLORS, 'scene screenshot is not blank', `${colors} distinct colours`);

  // A patch with many partners that is in view: click it as a user would.
  const target = await page.evaluate(() => {
    const s = window.viewerState;
    const api = window.viewerApi;
    const order = [...Array(s.patchCount).keys()].sort((a, b) => api.partnerCount(b) - api.partnerCount(a));
    for (const p of order) {
      const point = api.screenPointOfPatch(p);
      if (point) return { p, ...point };
    }
    return null;
  });
  if (!check(target !== null, 'some patch is visible on screen')) return;
  await page.mouse.click(target.x, target.y);
  await page.waitForFunction((p) => window.viewerState.selectedPatch === p, target.p, { timeout: TIMEOUT_MS });
  check(true, 'clicking a patch selects it', `patch ${target.p} at (${target.x.toFixed(0)}, ${target.y.toFixed(0)})`);
  const text = await page.textContent('#gv-selection');
  check(text.includes(`patch ${target.p}`), 'the panel describes the selected patch', text.slice(0, 80));
  const selected = await screenshot(page, join(work, 'viewer-2-patch.png'));
  const changed = changedFraction(before, selected);
  check(changed >= MIN_CHANGED_FRACTION, 'the selection changed what is drawn', `${(100 * changed).toFixed(2)} % of pixels`);

  // Shift-click a partner in the scene: that interaction is selected.
  const partner = await page.evaluate((p) => {
    const api = window.viewerApi;
    for (const q of api.partnersOf(p)) {
      const point = api.screenPointOfPatch(q);
      if (point) return { q, ...point };
    }
    return null;
  }, target.p);
  if (check(partner !== null, 'a partner of the selected patch is on screen')) {
    await page.keyboard.down('Shift');
    await page.mouse.click(partner.x, partner.y);
    await page.keyboard.up('Shift');
    await page.waitForFunction(() => window.viewerState.selectedPair !== null, null, { timeout: TIMEOUT_MS });
    const pair = await page.evaluate(() => window.viewerState.selectedPair);
    const expected = [Math.min(target.p, partner.q), Math.max(target.p, partner.q)];
    check(pair[0] === expected[0] && pair[1] === expected[1], 'shift-clicking a partner selects the interaction', `pair ${pair}`);
    await page.evaluate((p) => window.viewerApi.selectPatch(p), target.p);
  }

  // Pick the patch's interaction with the most blockers from the list: tube and blockers.
  const partners = await page.locator('#gv-partners li').count();
  if (check(partners > 0, 'the selected patch lists its interactions', `${partners}`)) {
    await page.locator('#gv-partners li').first().click();
    await page.waitForFunction(() => window.viewerState.selectedPair !== null, null, { timeout: TIMEOUT_MS });
    const pair = await page.evaluate(() => window.viewerState.selectedPair);
    check(Array.isArray(pair) && pair.length === 2, 'picking an interaction selects it', `pair ${pair}`);
    const tube = await screenshot(page, join(work, 'viewer-3-tube.png'));
    const changedTube = changedFraction(selected, tube);
    check(changedTube >= MIN_CHANGED_FRACTION, 'the interaction drew its tube', `${(100 * changedTube).toFixed(2)} % of pixels changed`);
    const red = countHue(tube, isRed) - countHue(selected, isRed);
    check(red > 20, 'the tube is drawn in red', `${red} more red pixels`);
    const pairText = await page.textContent('#gv-pair');
    const blockers = /PARTIAL, (\d+) blockers/.exec(pairText);
    if (blockers) {
      const orange = countHue(tube, isOrange);
      check(orange > 0, 'blockers are highlighted in orange', `${blockers[1]} blockers, ${orange} orange pixels`);
    }
  }

  // Layer toggles: each one is drawn (the picture changes) when switched on.
  await page.keyboard.press('Escape');
  const cleared = await page.evaluate(() => window.viewerState.selectedPatch === null && window.viewerState.selectedPair === null);
  check(cleared, 'Escape clears the selection');
  let last = await screenshot(page, join(work, 'viewer-4-cleared.png'));
  for (const name of ['visibleLinks', 'partialLinks', 'cells', 'portals']) {
    await page.click(`#gv-toggle-${name}`);
    const on = await page.evaluate((n) => window.viewerState.show[n], name);
    const now = await screenshot(page, join(work, `viewer-5-${name}.png`));
    const fraction = changedFraction(last, now);
    check(on && fraction >= MIN_CHANGED_FRACTION, `toggle ${name} draws its layer`, `${(100 * fraction).toFixed(2)} % of pixels changed`);
    last = now;
  }
  await page.close();
}

/** A page of the files directly in a directory (vis/ alone): material colours, no cells. */
async function testMaterialOnly(context, cli, runDir, work, errors) {
  const pageFile = join(work, 'viewer-vis-only.html');
  run(cli, ['view', join(runDir, 'vis'), '-o', pageFile]);
  const page = await context.newPage();
  watch(page, 'viewer (vis only)', errors);
  await page.goto(pathToFileURL(pageFile).href, { timeout: TIMEOUT_MS });
  await page.waitForFunction(() => window.viewerState && window.viewerState.ready, null, { timeout: TIMEOUT_MS });
  const state = await page.evaluate(() => ({ ...window.viewerState }));
  check(state.shading === 'material' && state.pairCount > 0, 'a run without radiosity is shaded by material colour', `${state.pairCount} pairs`);
  const cellsDisabled = await page.isDisabled('#gv-toggle-cells');
  check(cellsDisabled, 'without cells.obj the cells toggle is disabled');
  const colors = distinctColors(await screenshot(page, join(work, 'viewer-6-material.png')));
  check(colors >= MIN_DISTINCT_COLORS / 4, 'material-shaded screenshot is not blank', `${colors} distinct colours`);
  await page.close();
}

async function testReport(context, runDir, work, errors) {
  const page = await context.newPage();
  watch(page, 'report', errors);
  await page.goto(pathToFileURL(join(runDir, 'report.html')).href, { timeout: TIMEOUT_MS, waitUntil: 'load' });
  for (const id of ['table-7-1', 'table-7-2', 'table-fig13', 'table-7-3', 'table-1-paper', 'table-1-run', 'table-timings']) {
    const rows = await page.locator(`#${id} tbody tr`).count();
    check(rows > 0, `report shows table ${id}`, `${rows} rows`);
  }
  const bars = await page.locator('svg.chart rect.success').count();
  check(bars > 0, 'report draws the Fig. 13 chart', `${bars} length groups`);
  const pngs = [
    ...readdirSync(join(runDir, 'radiosity')).filter((f) => f.endsWith('.png')).map((f) => `radiosity/${f}`),
    ...readdirSync(runDir).filter((f) => f.endsWith('.png')),
  ];
  const images = await page.evaluate(() => [...document.images].map((i) => ({ ok: i.complete && i.naturalWidth > 0, alt: i.alt })));
  check(images.length === pngs.length && images.every((i) => i.ok), 'report shows every picture of the run', `${images.filter((i) => i.ok).length} shown of ${pngs.length} PNG files: ${pngs.join(', ') || 'none'}`);
  const frame = page.frames().find((f) => f.url().endsWith('viewer.html'));
  if (check(!!frame, 'report frames the viewer')) {
    await frame.waitForFunction(() => window.viewerState && window.viewerState.ready, null, { timeout: TIMEOUT_MS });
    check(true, 'the framed viewer starts');
    const framed = page.locator('#viewer-frame');
    await framed.scrollIntoViewIfNeeded();
    const png = await framed.screenshot({ path: join(work, 'report-viewer-frame.png'), timeout: TIMEOUT_MS });
    const colors = distinctColors(await decodePng(page, png));
    check(colors >= MIN_DISTINCT_COLORS, 'the framed viewer draws the scene', `${colors} distinct colours`);
  }
  await page.screenshot({ path: join(work, 'report.png'), fullPage: true, timeout: TIMEOUT_MS });
  await page.close();
}

/** Records console errors, uncaught exceptions and any request that is not file: or data:. */
function watch(page, name, errors) {
  page.on('console', (msg) => {
    if (msg.type() === 'error') errors.push(`${name}: console error: ${msg.text()}`);
  });
  page.on('pageerror', (e) => errors.push(`${name}: uncaught: ${e.message}`));
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  const work = resolve(args.work);
  const runDir = args.run ? resolve(args.run) : join(work, 'run');
  if (!existsSync(args.chromium)) throw new Error(`${args.chromium} not found: apt-get install -y chromium (make deps does)`);
  mkdirSync(work, { recursive: true });
  if (!args.run) makeRun(resolve(args.cli), runDir);

  const profile = mkdtempSync(join(tmpdir(), 'globalvis-chromium-'));
  const errors = [];
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: args.chromium,
    headless: true,
    viewport: VIEWPORT,
    timeout: TIMEOUT_MS,
    args: [
      '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      // WebGL without a GPU: ANGLE on SwiftShader, Chromium's software rasteriser.
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    ],
  });
  context.setDefaultTimeout(TIMEOUT_MS);
  // The pages must be self-contained: any request that leaves file: and data: fails the test.
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:') || url.startsWith('data:')) return route.continue();
    errors.push(`network request: ${url}`);
    return route.abort();
  });
  try {
    await testViewer(context, runDir, work, errors);
    await testMaterialOnly(context, resolve(args.cli), runDir, work, errors);
    if (!args.run) {
      // The report embeds every PNG of the run; make sure there is one (besides whatever the
      // radiosity stage draws) by adding the viewer's screenshot, then write the report again.
      copyFileSync(join(work, 'viewer-1-scene.png'), join(runDir, 'viewer_screenshot.png'));
      run(resolve(args.cli), ['report', runDir]);
    }
    await testReport(context, runDir, work, errors);
  } finally {
    await context.close();
    rmSync(profile, { recursive: true, force: true, maxRetries: 5, retryDelay: 200 });
  }
  check(errors.length === 0, 'no console errors, exceptions or network requests', errors.join('; '));
  writeFileSync(join(work, 'result.txt'), `${passed} passed, ${failed} failed\n`);
  console.log(`screenshots in ${work}`);
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed === 0 ? 0 : 1);
}

main().catch((e) => {
  console.log(`FAIL  ${e.stack || e}`);
  console.log(`${passed} passed, ${failed + 1} failed`);
  process.exit(1);
});
