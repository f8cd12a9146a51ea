// make bench's view section (bench/run section_view): `sylva view` in Debian's chromium
// (headless, WebGL in software by SwiftShader), driven by puppeteer-core (tests/view's).
//   node bench/view.mjs SYLVA RUNS
// Prints one line per case:
//   save NAME MODULES TRIANGLES BEST_MS MEDIAN_MS SERVER_MS WRITE_MS   from the file's save (an
//       atomic rename, as editors save) to the first frame drawn with the new build, in the page's
//       clock; SERVER_MS the last build's compile to .glb written in the server, WRITE_MS the .glb writer's;
//       PAGE the best save's page side: build request / .glb fetch / parse / setup / first frame, ms
//       (the .glb comes in the build's answer since stop 40: its fetch is then 0);
//       PREVIEW_MS the best save's time to the preview's first frame (the page's "preview first":
//       a lighter picture drawn before the .glb), PREVIEW its kind (mesh, lines; '-': none drawn);
//       PIXELS_MS the best time from the save to the full frame's pixels read back (its drawing
//       finished: software WebGL fills them after the draw call returns); PREVIEW_PAGE the best
//       save's preview: its request (the server's wait included) / the server's build / parse
//       and setup / its draw call, ms; FRAME_MS one whole frame of the model at rest (drawn and
//       its pixels read back, best of 3); PREVIEW_PIXELS_MS the best time from the save to the
//       preview's pixels read back (the page reads one back right after the preview's first draw
//       call when sylvaView.measurePixels is set: what is on screen, not what was asked for);
//       SETTLED_MS the best time from the save to the full-quality frame's pixels (the page
//       draws the first frame after a change quick, straight onto the canvas without
//       multisampling, and the full frame right after); QUICK_MS one quick frame at rest (drawn
//       and read back, best of 3). PIXELS_MS and PREVIEW_PIXELS_MS are what make bench holds
//       to the targets: a picture on screen, not a draw call returned
//   slider NAME MODULES UPDATES SECONDS FULL FRAME_MS   pictures of new values drawn while a slider
//       is dragged (a new value of the slider every 20 ms; previews and full builds), FULL of them
//       full builds, FRAME_MS a whole frame of the last preview, CPU_MS the server's and the
//       browser's CPU time (user + system) over the drag per picture drawn: what an update costs
//       whatever the machine's load
import { mkdtempSync, writeFileSync, readFileSync, renameSync, rmSync, cpSync, readdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

import { launch, serve as start, stop } from '../tests/view/browser.mjs';

const sylva = process.argv[2];
const runs = +(process.argv[3] || 3);
const dir = mkdtempSync(join(tmpdir(), 'sylva-bench-view-'));

// The cases: a copy of the model (the copy is edited, never the repository's file)
const a11 = readFileSync('bench/models/a.syl', 'utf8').replace(/derive 12/, 'derive 11'); // 1,058,783 modules
const a9 = readFileSync('bench/models/a.syl', 'utf8').replace(/derive 12/, 'derive 9');     // 117,071 modules
cpSync('examples/weberpenn', join(dir, 'weberpenn'), { recursive: true });
cpSync('examples/abop', join(dir, 'abop'), { recursive: true });
writeFileSync(join(dir, 'a11.syl'), a11);
writeFileSync(join(dir, 'a9.syl'), a9);
// VIEW_CASES=fig2.6,aspen,slider (names' beginnings): only those (default: all)
const only = (process.env.VIEW_CASES || '').split(',').filter(Boolean);
const wanted = (name) => !only.length || only.some((o) => name.startsWith(o));
const saves = [
  ['fig2.6 n=10', join(dir, 'abop/fig2_06_monopodial.syl')],
  ['aspen', join(dir, 'weberpenn/quaking_aspen.syl')],
  ['1M modules', join(dir, 'a11.syl')],
  ['weeping willow', join(dir, 'weberpenn/weeping_willow.syl')],
].filter(([name]) => wanted(name));

const serve = (path) => start(sylva, path);
// CPU seconds (user + system) used so far by the processes pids and their descendants (Linux /proc)
function cpuOf(pids) {
  const kids = new Map(); // parent -> children
  for (const d of readdirSync('/proc')) {
    if (!/^\d+$/.test(d)) continue;
    try {
      const st = readFileSync(`/proc/${d}/stat`, 'utf8'), f = st.slice(st.lastIndexOf(')') + 2).split(' ');
      kids.set(+d, { ppid: +f[1], cpu: (+f[11] + +f[12]) / 100 });
    } catch { /* gone */ }
  }
  let total = 0;
  const todo = [...pids];
  while (todo.length) {
    const p = todo.pop();
    if (kids.has(p)) total += kids.get(p).cpu;
    for (const [q, k] of kids) if (k.ppid === p) todo.push(q);
  }
  return total;
}
const browser = await launch(dir);
const median = (xs) => { const s = [...xs].sort((p, q) => p - q); return s[Math.floor(s.length / 2)]; };
try {
  for (const [name, path] of saves) {
    const { server, url } = await serve(path);
    const page = await browser.newPage();
    await page.setViewport({ width: 900, height: 700 });
    await page.goto(url);
    await page.waitForFunction(() => window.sylvaView && window.sylvaView.shownAt > 0, { timeout: 300000, polling: 50 });
    await page.evaluate(() => { window.sylvaView.measurePixels = true; });
    const text = readFileSync(path, 'utf8');
    const times = [], phases = [], previews = [], pixels = [], pvPhases = [], pvPixels = [], settled = [];
    let kind = '-';
    for (let r = 0; r < runs; r++) {
      const n = await page.evaluate(() => window.sylvaView.loads);
      await new Promise((res) => setTimeout(res, 300)); // an idle page
      writeFileSync(path + '.new', text + `# saved ${r + 1}\n`);
      const t0 = Date.now();
      renameSync(path + '.new', path);
      await page.waitForFunction((k) => window.sylvaView.loads > k && window.sylvaView.shownAt > 0,
        { timeout: 300000, polling: 20 }, n);
      times.push(await page.evaluate(() => window.sylvaView.shownWall) - t0);
      // the frame's pixels filled: a pixel read back waits for them (software WebGL may still
      // be drawing when the draw call returns); the next save then starts from a finished frame,
      // as it does for a user who looks at the plant before saving again
      pixels.push(await page.evaluate(() => {
        if (window.sylvaView.pixelsWall) return window.sylvaView.pixelsWall; // read back by the page at once
        const gl = document.querySelector('canvas').getContext('webgl2'), px = new Uint8Array(4);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
        return Date.now();
      }) - t0);
      // the full-quality frame that follows the first one (the page draws a save's first frame
      // quick, without multisampling: web/app.js), its pixels read back by the page
      // (a page before it draws the full frame first: its settled frame is that one)
      await page.waitForFunction(() => !('settled' in window.sylvaView) || window.sylvaView.settledAt > window.sylvaView.shownAt,
        { timeout: 300000, polling: 20 });
      settled.push(await page.evaluate(() => ('settled' in window.sylvaView ? window.sylvaView.settledPixelsWall || window.sylvaView.settledWall
        : window.sylvaView.pixelsWall)) - t0);
      const pv = await page.evaluate(() => ({ at: window.sylvaView.previewShownWall || 0, kind: window.sylvaView.lastPreviewKind,
        timing: window.sylvaView.previewTiming, draw: window.sylvaView.previewMs, pixels: window.sylvaView.previewPixelsWall || 0 }));
      if (pv.at > t0) previews.push(pv.at - t0), kind = pv.kind || kind, pvPhases.push(pv), pv.pixels > t0 && pvPixels.push(pv.pixels - t0);
      else pvPhases.push(null);
      phases.push(await page.evaluate(() => window.sylvaView.timing || null));
    }
    const s = await page.evaluate(() => window.sylvaView.stats);
    // one whole frame of the model on screen (drawn and its pixels read back), best of 3
    const frameMs = await page.evaluate(() => (window.sylvaFrameMs ? window.sylvaFrameMs(3).toFixed(0) : '-'));
    const quickMs = await page.evaluate(() => (window.sylvaFrameMs ? window.sylvaFrameMs(3, true).toFixed(0) : '-'));
    const built = ['compile', 'derive', 'turtle', 'mesh', 'lod', 'write'].reduce((t, k) => t + (s[k + '_time'] || 0), 0) * 1000;
    const ph = phases[times.indexOf(Math.min(...times))];
    const page_ = ph ? ['build', 'fetch', 'parse', 'setup', 'frame'].map((k) => (ph[k] || 0).toFixed(0)).join('/') : '';
    const best = times.indexOf(Math.min(...times)), pp = pvPhases[best];
    const pvPage = pp && pp.timing ? [pp.timing.fetched, pp.timing.server, pp.timing.parse, pp.draw].map((x) => (x || 0).toFixed(0)).join('/') : '-';
    console.log(`save\t${name}\t${s.modules}\t${s.triangles}\t${Math.min(...times)}\t${median(times)}\t${built.toFixed(0)}\t${(s.write_time * 1000).toFixed(0)}\t${page_}\t${previews.length ? Math.min(...previews) : '-'}\t${kind}\t${Math.min(...pixels)}\t${pvPage}\t${frameMs}\t${pvPixels.length ? Math.min(...pvPixels) : '-'}\t${Math.min(...settled)}\t${quickMs}`);
    await page.close();
    await stop(server);
  }
  // A slider dragged for 3 s (a new angle every 20 ms): builds drawn per second
  if (wanted('slider')) {
    const { server, url } = await serve(join(dir, 'a9.syl'));
    const page = await browser.newPage();
    await page.setViewport({ width: 900, height: 700 });
    await page.goto(url);
    await page.waitForFunction(() => window.sylvaView && window.sylvaView.shownAt > 0, { timeout: 300000, polling: 50 });
    // a page at rest: its first frame drawn and the metrics asked for after it measured
    await page.waitForFunction(() => window.sylvaView.metrics, { timeout: 120000, polling: 100 }).catch(() => {});
    const pids = [server.pid, browser.process().pid], cpu0 = cpuOf(pids);
    const r = await page.evaluate(async () => {
      const el = document.querySelector('input[type=range][data-param=angle]');
      if (!el) return null;
      // pictures: frames that drew a new build (a page before them: its previews and loads)
      const v = window.sylvaView, drawn = () => (v.pictures !== undefined ? v.pictures : v.loads + (v.previews || 0));
      const n0 = v.loads, p0 = drawn(), t0 = performance.now();
      let angle = 20;
      while (performance.now() - t0 < 3000) {
        angle = angle >= 40 ? 20 : angle + +el.step; // a new value at every move
        el.value = String(angle); el.dispatchEvent(new Event('input', { bubbles: true }));
        await new Promise((res) => setTimeout(res, 20));
      }
      const t1 = performance.now(), n1 = v.loads, p1 = drawn();
      // a whole frame of what the drag left on screen (its last preview)
      const frame = window.sylvaFrameMs ? window.sylvaFrameMs(3).toFixed(0) : '-';
      return { updates: p1 - p0, full: n1 - n0, seconds: (t1 - t0) / 1000, modules: v.stats.modules, frame };
    });
    const cpu = cpuOf(pids) - cpu0; // the server's and the browser's, over the drag
    if (r) console.log(`slider\t117k modules, angle\t${r.modules}\t${r.updates}\t${r.seconds.toFixed(2)}\t${r.full}\t${r.frame}\t${(cpu * 1000 / Math.max(r.updates, 1)).toFixed(0)}`);
    else console.log('slider\tno angle slider');
    await page.close();
    await stop(server);
  }
} finally {
  await browser.close();
  rmSync(dir, { recursive: true, force: true });
}
