// Browser tests of `sylva view`'s preview (docs/view.md, "Speed"): a plant quick to build is drawn
// without one; a build's answer carries its .glb (with=part); after a save the page first
// draws a lighter preview, then the .glb of `sylva mesh` (byte for byte); a plant too big to
// mesh quickly is previewed by its segments, those of `sylva skeleton`, straight runs joined by
// the server into the very lines web/scene.js's joinStraight makes of them; a full build a tab's
// newer request has replaced is not built (and another tab's is); a slider dragged draws
// previews and ends on the full mesh of its last value. Usage: node preview.test.mjs SYLVA.
import { spawnSync } from 'node:child_process';
import { mkdtempSync, writeFileSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { launch, serve, stop, tap, getter, edit, openPage, BUSH } from './browser.mjs';
import { joinStraight } from '../../web/scene.js';

const sylva = process.argv[2];
const { check, done } = tap();

const dir = mkdtempSync(join(tmpdir(), 'sylva-view-preview-'));
const file = join(dir, 'plants.syl');
// Bush first (the page's model: blades of leaves, so its preview has instanced cards); Line:
// 2^16 segments in a row, beyond the preview's mesh limit (20,000 nodes); Tree: ABOP Fig.
// 1.24(e) at n = 9, 38,342 segments, branched and turning (bench/models/a.syl)
const TEXT = (depth) => `${BUSH(depth)}lsystem Line {
  derive 16
  axiom F
  F -> FF
}
lsystem Tree {
  derive 9
  angle 25.7
  axiom X
  X -> F[+X][-X]FX
  F -> FF
}
`;
writeFileSync(file, TEXT(4));

const { server, url } = await serve(sylva, file);
const get = getter(url);
const json = async (path) => JSON.parse((await get(path)).body.toString());
const browser = await launch(dir);
const errors = [];
try {
  // the page's event stream held back until the first save has landed: a save the page was
  // never told of (it came before the stream connected) must still be drawn (the stream's
  // hello says the files' generation, newer than the one drawn)
  const page = await openPage(browser, url, errors, { holdEvents: true });
  await page.waitForFunction(() => window.sylvaView && window.sylvaView.loads >= 1, { timeout: 60000 });

  // ---- a plant whose last full mesh had at most previewAbove triangles: no preview first ----
  const quick = await page.evaluate(() => { const v = window.sylvaView; v.previewAbove = 1e9; return { loads: v.loads, previews: v.previews || 0 }; });
  const until = async (f) => { for (let t = Date.now(); !(await f()) && Date.now() - t < 30000;) await new Promise((r) => setTimeout(r, 20)); };
  await until(() => page.eventsHeld() > 0); // the page asked for its stream (after its first build)
  const gen0 = (await json('/api/models')).gen;
  edit(file, TEXT(3));
  await until(async () => (await json('/api/models')).gen !== gen0); // the server saw the save
  const gen1 = (await json('/api/models')).gen;
  const held = await page.releaseEvents();
  const redrawn = await page.waitForFunction((c) => window.sylvaView.loads > c && window.sylvaView.shownAt > 0, { timeout: 60000 }, quick.loads)
    .then(() => true, () => false);
  const drawnGen = await page.evaluate(() => window.sylvaView.builtGen);
  check(held === 1 && redrawn && drawnGen === gen1, 'a save before the page\'s event stream connected is drawn once it connects',
    `${held} held, redrawn: ${redrawn}, generation drawn ${drawnGen} of ${gen1}`);
  const quickAfter = await page.evaluate(() => ({ previews: window.sylvaView.previews || 0, preview: window.sylvaView.preview }));
  check(quickAfter.previews === quick.previews && quickAfter.preview === null, 'a plant quick to build: its save draws the full mesh, no preview',
    JSON.stringify({ quick, quickAfter }));
  // the build's answer with its .glb in one request (with=part): the same bytes as /api/glb's
  const both = (await get('/api/build?model=Bush&with=part')).body;
  const jlen = both.readUInt32LE(0), head = JSON.parse(both.subarray(4, 4 + jlen).toString());
  check(head.ok && both.subarray(4 + jlen).equals((await get('/api/glb?id=' + head.id)).body),
    'a build asked for with its part: the JSON, then the .glb of /api/glb', `${both.length - 4 - jlen} bytes`);

  // ---- a save: the preview's frame, then the full .glb's (sylva mesh's bytes) ----
  await page.evaluate(() => { window.sylvaView.previewAbove = 0; }); // a preview before every full build
  const before = await page.evaluate(() => ({ loads: window.sylvaView.loads, previews: window.sylvaView.previews || 0 }));
  edit(file, TEXT(5));
  await page.waitForFunction((c) => window.sylvaView.loads > c && window.sylvaView.shownAt > 0, { timeout: 60000 }, before.loads);
  const after = await page.evaluate(() => { const v = window.sylvaView; return { previews: v.previews, kind: v.lastPreviewKind,
    previewAt: v.previewShownAt, fullAt: v.shownAt, stats: v.stats, preview: v.preview, id: v.build.id }; });
  check(after.previews === before.previews + 1 && after.kind === 'mesh', 'a save draws one preview (a mesh) first',
    JSON.stringify({ before, previews: after.previews, kind: after.kind }));
  check(after.previewAt > 0 && after.previewAt < after.fullAt, 'the preview\'s frame comes before the full mesh\'s',
    `${after.previewAt} vs ${after.fullAt}`);
  check(after.preview === null && after.stats.preview === '' && after.stats.triangles > 0, 'then the full mesh is on screen (no preview left)');
  const served = (await get('/api/glb?id=' + after.id)).body;
  const out = join(dir, 'cli.glb');
  spawnSync(sylva, ['mesh', file + ':Bush', '-o', out, '-j', '1']);
  check(served.equals(readFileSync(out)), 'the .glb drawn last is byte for byte sylva mesh\'s', `${served.length} vs ${readFileSync(out).length} bytes`);

  // the preview's build, as the server answers it: instanced leaf cards, fewer triangles
  const pv = await json('/api/build?model=Bush&preview=1');
  const full = await json('/api/build?model=Bush');
  check(pv.ok && pv.stats.preview === 'mesh' && pv.stats.leaf_instances === full.stats.organs && pv.stats.triangles < full.stats.triangles,
    'a preview: every leaf one instanced card, fewer triangles than the mesh',
    JSON.stringify({ pv: [pv.stats.leaf_instances, pv.stats.triangles], full: [full.stats.organs, full.stats.triangles] }));

  // ---- a big plant's preview: its segments, those of sylva skeleton ----
  const lines = await json('/api/build?model=Line&preview=1');
  const seg = (await get('/api/lines?id=' + lines.id)).body;
  const csv = spawnSync(sylva, ['skeleton', file + ':Line', '-o', '-'], { maxBuffer: 1 << 28 }).stdout.toString().trim().split('\n').slice(1);
  const internodes = csv.filter((l) => l.split(',')[7] === 'internode');
  const top = Math.max(...internodes.map((l) => +l.split(',')[3]));
  const raw = (await get('/api/export?format=segments&model=Line&preview=1')).body;
  const f = new Float32Array(seg.buffer.slice(seg.byteOffset, seg.byteOffset + seg.length), 0, (seg.length / 25) * 6);
  let ymax = -Infinity;
  for (let i = 4; i < f.length; i += 6) ymax = Math.max(ymax, f[i]);
  check(lines.ok && lines.lines && raw.length === 25 * internodes.length && internodes.length === 65536 && seg.length === 25,
    'a plant beyond the mesh limit is previewed by its segments, as many as sylva skeleton\'s internodes, joined: 65,536 in a row are one line',
    `${raw.length / 25} segments, ${internodes.length} internodes, ${seg.length / 25} lines`);
  check(Math.abs(ymax - top) <= 1e-4 * Math.abs(top), 'and they reach as high', `${ymax} vs ${top}`);
  // the server's lines are joinStraight's of the same segments, byte for byte (a branched plant)
  const tree = await json('/api/build?model=Tree&preview=1');
  const treeLines = (await get('/api/lines?id=' + tree.id)).body;
  const tr = (await get('/api/export?format=segments&model=Tree&preview=1')).body, nt = tr.length / 25;
  const ab = tr.buffer.slice(tr.byteOffset, tr.byteOffset + tr.length);
  const js = joinStraight(new Float32Array(ab, 0, nt * 6), new Uint8Array(ab, nt * 24, nt));
  const theirs = Buffer.concat([Buffer.from(js.pos.buffer, js.pos.byteOffset, js.n * 24), Buffer.from(js.order.buffer, js.order.byteOffset, js.n)]);
  check(tree.lines && nt === 38342 && js.n < nt && treeLines.equals(theirs),
    'the server joins straight runs into the lines joinStraight makes of the same segments, byte for byte',
    `${nt} segments, ${treeLines.length / 25} lines from the server, ${js.n} from joinStraight`);
  check((await get('/api/glb?id=' + lines.id)).status === 404, 'a segments preview has no .glb');
  // the page's lines of them (web/preview.js): straight runs joined, coloured as the skeleton mode colours order 0
  const drawn = await page.evaluate(async (id) => {
    const { linesFrom } = await import('/app/preview.js'), { ORDER_COLOURS } = await import('/app/scene.js');
    const l = linesFrom(await (await fetch('/api/lines?id=' + id)).arrayBuffer());
    const p = l.geometry.attributes.position, c = l.geometry.attributes.color;
    let ymax = -Infinity;
    for (let i = 0; i < p.count; i++) ymax = Math.max(ymax, p.getY(i));
    const t = new (await import('three')).Color().setHex(ORDER_COLOURS[0]), trunk = [t.r, t.g, t.b].map((x) => Math.round(x * 255));
    return { segments: p.count / 2, ymax, first: [c.getX(0), c.getY(0), c.getZ(0)].map((x) => Math.round(x * 255)), trunk };
  }, lines.id);
  check(drawn.segments === 1 && Math.abs(drawn.ymax - top) <= 1e-4 * Math.abs(top) && drawn.first.join() === drawn.trunk.join(),
    'the page draws the line, as high, the trunk in the skeleton mode\'s colour', JSON.stringify(drawn));

  // ---- a full build that a newer request of its tab replaced is not built ----
  await json('/api/build?model=Line&preview=1&tab=7&seq=2');
  const stale = await json('/api/build?model=Line&n=15&tab=7&seq=1');
  check(stale.superseded === true && stale.ok === false && !stale.stats, 'an older full build of a tab is stopped (superseded)', JSON.stringify(stale).slice(0, 200));
  const other = await json('/api/build?model=Bush&n=3&tab=8&seq=1');
  check(other.ok && !other.superseded, 'another tab\'s full build is not stopped by it');
  const newer = await json('/api/build?model=Bush&n=3&tab=7&seq=3');
  check(newer.ok && !newer.superseded && newer.id === other.id, 'the tab\'s newest request is built (the same build: from the cache)');
  const again = await json('/api/build?model=Line&n=15&tab=7&seq=3');
  check(again.ok && again.id !== stale.id, 'a stopped build is not kept in the cache');

  // ---- a slider dragged: previews while it moves, the full mesh of the last value at rest ----
  const drag = await page.evaluate(async () => {
    const el = document.querySelector('input[type=range][data-param=depth]');
    const v = window.sylvaView, p0 = v.previews, n0 = v.loads;
    for (const d of [5, 4, 5, 6, 5, 4, 3, 4, 5, 4, 3, 2]) {
      el.value = d; el.dispatchEvent(new Event('input', { bubbles: true }));
      await new Promise((r) => setTimeout(r, 30));
    }
    return { p0, n0, last: 'set=depth%3D' + el.value }; // the slider's own step rounds the values
  });
  await page.waitForFunction((last) => window.sylvaView.idle && window.sylvaView.shownAt > 0 &&
    (window.sylvaView.drawnQuery + '&').includes(last + '&'), { timeout: 60000 }, drag.last).catch(() => {});
  const end = await page.evaluate(() => ({ previews: window.sylvaView.previews, loads: window.sylvaView.loads,
    key: window.sylvaView.drawnQuery, preview: window.sylvaView.preview, stats: window.sylvaView.stats }));
  check(end.previews > drag.p0, 'a drag draws previews', JSON.stringify({ drag, previews: end.previews }));
  check((end.key + '&').includes(drag.last + '&') && end.preview === null && end.stats.preview === '',
    'it ends on the full mesh of the last value', JSON.stringify({ key: end.key, last: drag.last, preview: end.preview }));
  check(errors.length === 0, 'no page errors', errors.join('; '));
} finally {
  await browser.close().catch(() => {});
  await stop(server);
  rmSync(dir, { recursive: true, force: true });
}
done();
