// The notebook view in a real browser (docs/python.md): a notebook exported to HTML by
// nbconvert, opened from disk in Debian's chromium (headless, WebGL by SwiftShader) with the
// network cut off (nbconvert's page aside). Every sylva view must draw from its inlined assets alone: its canvas shown,
// its picture hidden, the plant's pixels unlike the sky's, and no request but data: and blob:.
//   node tests/view/notebook.test.mjs FILE.html
import { createRequire } from 'node:module';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const require = createRequire(import.meta.url);
const puppeteer = require('puppeteer-core');
const file = process.argv[2];
const chromium = process.env.CHROMIUM || '/usr/bin/chromium';
let failed = 0;
const check = (ok, what) => { console.log(`${ok ? 'ok' : 'not ok'} ${what}`); if (!ok) failed++; };

const dir = mkdtempSync(join(tmpdir(), 'sylva-nbview-'));
const browser = await puppeteer.launch({
  executablePath: chromium, headless: true, userDataDir: join(dir, 'profile'),
  args: ['--headless=new', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
    '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run',
    '--window-size=900,700'],
});
try {
  const page = await browser.newPage();
  const fetched = [];
  await page.setRequestInterception(true);
  page.on('request', (r) => {
    const u = r.url();
    // nbconvert's own page loads Debian's require.js and MathJax from /usr/share/javascript
    const ours = u.startsWith('data:') || u.startsWith('blob:') || u === pathToFileURL(file).href;
    if (ours || u.startsWith('file:///usr/share/javascript/')) r.continue();
    else { fetched.push(u); r.abort(); }
  });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(pathToFileURL(file).href, { waitUntil: 'load' });
  const n = await page.$$eval('.sylva-view', (v) => v.length);
  check(n > 0, `the exported notebook holds sylva views (${n})`);
  // a guard, not a timing: SwiftShader draws each view in a few seconds
  await page.waitForFunction((k) => document.querySelectorAll('.sylva-view[data-drawn]').length === k ||
    [...document.querySelectorAll('.sylva-msg')].some((m) => m.textContent.includes('failed')), { timeout: 120000 }, n);
  const views = await page.$$eval('.sylva-view', (vs) => vs.map((v) => {
    const c = v.querySelector('canvas');
    const t = document.createElement('canvas');
    t.width = c.width; t.height = c.height;
    const g = t.getContext('2d');
    g.drawImage(c, 0, 0);
    const px = g.getImageData(0, 0, t.width, t.height).data;
    let other = 0; // the sky (#dce6ef) and the ground (#a3a39a) are greys; the plants are coloured
    for (let i = 0; i < px.length; i += 4)
      if (Math.abs(px[i] - 0xdc) + Math.abs(px[i + 1] - 0xe6) + Math.abs(px[i + 2] - 0xef) > 24 &&
          Math.max(px[i], px[i + 1], px[i + 2]) - Math.min(px[i], px[i + 1], px[i + 2]) > 14) other++;
    return { drawn: v.dataset.drawn === '1', shown: c.style.display === 'block',
      hidden: v.querySelector('img').style.display === 'none', msg: v.querySelector('.sylva-msg').textContent,
      share: other / (px.length / 4), size: [c.width, c.height] };
  }));
  if (process.env.SHOTS) { const els = await page.$$('.sylva-view'); for (let i = 0; i < els.length; i++) await els[i].screenshot({ path: join(process.env.SHOTS, `view${i + 1}.png`) }); }
  views.forEach((v, i) => {
    check(v.drawn && v.shown && v.hidden, `view ${i + 1} drew in its canvas, its picture hidden (${v.msg})`);
    check(v.share > 0.001, `view ${i + 1} shows coloured plants, not only sky and ground (${(100 * v.share).toFixed(1)} % of ${v.size.join('x')})`);
  });
  check(fetched.length === 0, `nothing fetched from outside the file (${fetched.slice(0, 3).join(' ') || 'none'})`);
  check(errors.length === 0, `no error on the page (${errors.slice(0, 2).join('; ') || 'none'})`);
} finally {
  await browser.close();
  rmSync(dir, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
