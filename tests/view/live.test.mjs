// Browser tests of what issue 30's speed work added to `sylva view` (docs/view.md): the
// Numbers panel's form figures are `sylva compare`'s; a .glb built with the server's kept
// textures is byte for byte `sylva mesh`'s; a slider dragged faster than builds finish draws
// its last value (stale values dropped). Usage: node live.test.mjs SYLVA. TAP lines.
import { spawnSync } from 'node:child_process';
import { mkdtempSync, writeFileSync, readFileSync, rmSync, copyFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { launch, serve, stop, tap, getter, edit, openPage, BUSH, STICK_SPECIES, STICK_MODEL } from './browser.mjs';

const sylva = process.argv[2];
const { check, done } = tap();

const dir = mkdtempSync(join(tmpdir(), 'sylva-view-live-'));
const file = join(dir, 'mono.syl');
copyFileSync('examples/abop/fig2_06_monopodial.syl', file); // bark: a procedural texture in the .glb
const ECO = `ecosystem Patch {
  terrain "flat.asc"
  years 4
  seed 7
${STICK_SPECIES}}
${STICK_MODEL}`;
const eco = join(dir, 'eco.syl');
writeFileSync(eco, ECO);
writeFileSync(join(dir, 'flat.asc'), spawnSync('python3', ['tests/oracle/ecosystem.py', 'flat', '30', '1']).stdout);
const bush = join(dir, 'bush.syl');
writeFileSync(bush, BUSH(4));

const ahead = join(dir, 'ahead.syl'); // a server no page talks to: what a save builds by itself
writeFileSync(ahead, BUSH(3));

const { server, url } = await serve(sylva, file);
const s2 = await serve(sylva, bush);
const s3 = await serve(sylva, eco);
const s4 = await serve(sylva, ahead);
const servers = [server, s2.server, s3.server, s4.server];
const get = getter(url);
const browser = await launch(dir);
const errors = [];
try {
  const page = await openPage(browser, url, errors);
  await page.waitForFunction(() => window.sylvaView && window.sylvaView.loads >= 1 && window.sylvaView.metrics, { timeout: 60000 });

  // ---- the Numbers panel: sylva compare's metrics of the model ----
  const cmp = JSON.parse(spawnSync(sylva, ['compare', file, '--json', '-j', '1']).stdout.toString());
  const want = cmp.models[0];
  const got = await page.evaluate(() => window.sylvaView.metrics);
  const near = (a, b) => (a === null && b === undefined) || (a === null && b === null) ||
    Math.abs(a - b) <= 1e-5 * Math.max(1, Math.abs(b));
  const keys = got.metrics.map((m) => m.key);
  const bad = got.metrics.filter((m) => !near(m.value, want.values[m.key])).map((m) => `${m.key}: ${m.value} vs ${want.values[m.key]}`);
  check(JSON.stringify(keys) === JSON.stringify(Object.keys(want.values)) && bad.length === 0,
    'the numbers panel\'s metrics are sylva compare --json\'s, key by key', bad.join('; ') || JSON.stringify(keys));
  check(JSON.stringify(got.stems_by_order) === JSON.stringify(want.stems_by_order) && got.leaves === want.leaves,
    'stems by branch order and leaves are compare\'s counts', JSON.stringify({ got: got.stems_by_order, want: want.stems_by_order }));
  const shown = await page.evaluate(() => [...document.querySelectorAll('#stats tr')].map((r) => r.textContent));
  check(shown.some((t) => t === `stems of order 0${want.stems_by_order[0]}`) && shown.some((t) => t.startsWith('Strahler order')),
    'the panel shows them (stems of each order, Strahler order, …)', shown.slice(-6).join(' | '));

  // ---- saves: every build's .glb (textures kept by the server) is sylva mesh's ----
  const text = readFileSync(file, 'utf8');
  const tex0 = await page.evaluate(() => window.sylvaTextures());
  let same = true, detail = '';
  for (let k = 1; k <= 2; k++) {
    const n = await page.evaluate(() => window.sylvaView.loads);
    edit(file, text.replace(/const a0 = 45/, `const a0 = ${45 + k}`));
    await page.waitForFunction((c) => window.sylvaView.loads > c, { timeout: 60000 }, n);
    const id = await page.evaluate(() => window.sylvaView.build.id);
    const served = (await get('/api/glb?id=' + id)).body;
    const out = join(dir, `cli${k}.glb`);
    spawnSync(sylva, ['mesh', file, '-o', out, '-j', '1']);
    if (!served.equals(readFileSync(out))) { same = false; detail += `save ${k}: ${served.length} vs ${readFileSync(out).length} bytes; `; }
  }
  const tex2 = await page.evaluate(() => window.sylvaTextures());
  check(tex0.kept.length === 1 && JSON.stringify(tex2.drawn) === JSON.stringify(tex0.kept) && JSON.stringify(tex2.kept) === JSON.stringify(tex0.kept),
    'after saves, the bark texture drawn is the one already on the GPU (same PNG bytes: not decoded into a new texture)', JSON.stringify({ tex0, tex2 }));
  check(same, 'after saves, the .glb drawn (bark texture from the server\'s cache) is byte for byte sylva mesh\'s', detail);
  check((await get('/api/metrics?id=0')).status === 404, 'metrics of no build: 404');

  // ---- a save's first frame is drawn quick (no multisampling), the full frame right after ----
  {
    const n = await page.evaluate(() => { window.sylvaView.keepQuick = true; window.sylvaView.quickPicture = null; return window.sylvaView.loads; });
    const programs = await page.evaluate(() => window.sylvaScene.renderer.info.programs.map((q) => q.id).sort().join(','));
    edit(file, text.replace(/const a0 = 45/, 'const a0 = 50'));
    await page.waitForFunction((c) => window.sylvaView.loads > c && window.sylvaView.shownAt > 0 &&
      window.sylvaView.settledAt > window.sylvaView.shownAt, { timeout: 60000 }, n);
    const r = await page.evaluate(() => {
      const v = window.sylvaView, q = v.quickPicture, f = window.sylvaCanvasPixels();
      v.keepQuick = false; v.quickPicture = null;
      if (!q || q.length !== f.length) return null;
      let plantQ = 0, plantF = 0, differ = 0, far = 0;
      for (let i = 0; i < f.length; i += 4) {
        if (q[i] > q[i + 2] + 25 && q[i] > 40) plantQ++; // bark: red over blue (view.test.mjs's picture())
        if (f[i] > f[i + 2] + 25 && f[i] > 40) plantF++;
        const d = Math.max(Math.abs(q[i] - f[i]), Math.abs(q[i + 1] - f[i + 1]), Math.abs(q[i + 2] - f[i + 2]));
        if (d > 0) differ++;
        if (d > 64) far++;
      }
      return { plantQ, plantF, differ, far, pixels: f.length / 4, programs: window.sylvaScene.renderer.info.programs.map((q) => q.id).sort().join(',') };
    });
    // the same picture (sky, ground and plant where they were), its edges smoothed: some pixels
    // change, few by much (the thin branches' edges, blended with the sky, count less as bark:
    // measured 8,269 bark pixels quick, 6,792 full, 0.4 % of the pixels changed by over 64)
    check(r && r.plantQ > 200 && r.plantF > 0.6 * r.plantQ && r.plantF < 1.2 * r.plantQ && r.differ > 0 && r.far < 0.02 * r.pixels,
      'a save\'s first frame shows the new plant drawn quick, and the full (multisampled) frame of the same picture follows', JSON.stringify(r));
    // the new build's materials are the kinds drawn before: their shader programs (three.js's, by
    // id: a program let go and made again has a new one) are kept, none compiled
    check(r && r.programs === programs, 'a save compiles no shader program (the quick and the full frame\'s are kept)', `${programs} -> ${r && r.programs}`);
  }

  // ---- a slider dragged faster than builds finish: the last value is drawn ----
  const p2 = await browser.newPage();
  p2.on('pageerror', (e) => errors.push(String(e)));
  await p2.goto(s2.url);
  await p2.waitForFunction(() => window.sylvaView && window.sylvaView.loads >= 1, { timeout: 60000 });
  const drag = await p2.evaluate(async () => {
    const el = document.querySelector('input[type=range][data-param=depth]');
    const v = window.sylvaView, n0 = v.loads, values = [5, 6, 7, 6, 5, 4, 5, 6, 7, 8, 7, 6];
    for (const x of values) { el.value = x; el.dispatchEvent(new Event('input', { bubbles: true })); await new Promise((r) => setTimeout(r, 5)); }
    return { n0, moves: values.length };
  });
  await p2.waitForFunction(() => window.sylvaView.sets.depth === 6 && window.sylvaView.idle, { timeout: 60000 }).catch(() => {});
  const after = await p2.evaluate(() => ({ loads: window.sylvaView.loads, depth: window.sylvaView.sets.depth, key: window.sylvaView.drawnQuery }));
  check(/set=depth%3D6(&|$)/.test(after.key) && after.loads - drag.n0 < drag.moves,
    'a fast drag draws its last value, stale values dropped (fewer builds than moves)', JSON.stringify({ ...after, ...drag }));

  // ---- a burst of moves (faster than any build): only the first and the last value are built ----
  const asked = [];
  p2.on('request', (r) => { const m = /\/api\/build\?(.*)/.exec(r.url()); if (m) asked.push(new URLSearchParams(m[1]).getAll('set').join(' ')); });
  const burst = [7, 8, 2, 5, 8, 2, 7, 5, 8, 3];
  const moved = await p2.evaluate((values) => { // the values as the slider's steps have them
    const el = document.querySelector('input[type=range][data-param=depth]'), got = [];
    for (const x of values) { el.value = x; got.push(el.value); el.dispatchEvent(new Event('input', { bubbles: true })); } // one task: no build ends between
    return got;
  }, burst);
  await p2.waitForFunction(() => window.sylvaView.idle && /set=depth%3D3(&|$)/.test(window.sylvaView.drawnQuery), { timeout: 60000 }).catch(() => {});
  // (a value's build may be its preview, then its full mesh)
  check(JSON.stringify([...new Set(asked)]) === JSON.stringify([`depth=${moved[0]}`, `depth=${moved[moved.length - 1]}`]) && asked.length <= 4,
    'a burst of 10 slider moves builds the first value (started at once) and the last, none between', JSON.stringify({ asked, moved }));
  const last = await p2.evaluate(() => ({ id: window.sylvaView.build.id, triangles: window.sylvaView.stats.triangles }));
  const g2 = getter(s2.url);
  const drawnGlb = (await g2('/api/glb?id=' + last.id)).body;
  spawnSync(sylva, ['mesh', bush, '--set', 'depth=3', '-o', join(dir, 'depth3.glb'), '-j', '1']);
  check(drawnGlb.equals(readFileSync(join(dir, 'depth3.glb'))), 'the picture left on screen is the last value\'s: its .glb is sylva mesh --set depth=3\'s, byte for byte',
    `${drawnGlb.length} bytes drawn`);

  // ---- a save builds ahead once: the build the last request asked for, before anyone asks again ----
  const g4 = getter(s4.url);
  const ask = '/api/build?set=depth%3D4';
  const first = JSON.parse((await g4(ask)).body);
  edit(ahead, BUSH(5));
  let built = 0;
  for (let k = 0; k < 600 && built !== 200; k++) { // until the build ahead is there (60 s at most)
    built = (await g4(`/api/glb?id=${first.id + 1}`)).status;
    if (built !== 200) await new Promise((r) => setTimeout(r, 100));
  }
  check(built === 200, 'a save builds the last request\'s build ahead, nobody asking', `id ${first.id + 1}: ${built}`);
  const again = JSON.parse((await g4(ask)).body);
  const none = (await g4(`/api/glb?id=${first.id + 2}`)).status;
  spawnSync(sylva, ['mesh', ahead, '--set', 'depth=4', '-o', join(dir, 'ahead.glb'), '-j', '1']);
  const aheadGlb = (await g4(`/api/glb?id=${again.id}`)).body;
  check(again.id === first.id + 1 && none === 404 && aheadGlb.equals(readFileSync(join(dir, 'ahead.glb'))),
    'the request after the save gets that build (one build, no second) and it is sylva mesh\'s of the saved file',
    JSON.stringify({ first: first.id, again: again.id, next: none, bytes: aheadGlb.length }));

  // ---- an ecosystem's far level: each batch's look's impostor (crossed billboards) ----
  const p3 = await browser.newPage();
  p3.on('pageerror', (e) => errors.push(String(e)));
  await p3.setViewport({ width: 900, height: 700 });
  await p3.goto(s3.url);
  await p3.waitForFunction(() => window.sylvaView && window.sylvaView.loads >= 1 && window.sylvaView.forest, { timeout: 120000 });
  await p3.select('#forcelod', '1');
  await p3.waitForFunction(() => window.sylvaView.forest.full === 0, { timeout: 10000 }).catch(() => {});
  const far = await p3.evaluate(() => ({ batches: window.sylvaForestFar(), forest: window.sylvaView.forest,
    label: document.querySelector('#forcelod option[value="1"]').textContent }));
  // sylva mesh --billboards 3: three crossed quads, each face two triangles, front and back
  check(far.batches.length > 0 && far.batches.every((b) => b.triangles === 12 && b.textured && b.look >= 0) &&
    far.forest.coarse > 0 && /impostor/.test(far.label),
  'an ecosystem\'s far level is each look\'s impostor: 3 crossed textured quads (12 triangles) per plant, not cones',
  JSON.stringify(far).slice(0, 400));
  check(far.batches.reduce((a, b) => a + b.count, 0) === far.forest.instances, 'the impostors are drawn once per plant of the batch');
  check(errors.length === 0, 'no error in the pages', errors.join('; '));
} catch (e) {
  check(false, 'the tests ran to the end', String(e && e.stack || e));
} finally {
  await browser.close();
  for (const s of servers) check(await stop(s) === 0, 'SIGTERM stops the server cleanly (exit 0)');
  rmSync(dir, { recursive: true, force: true });
}
done();
