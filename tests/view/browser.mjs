// What the browser tests (view, live and preview .test.mjs) and make bench (bench/view.mjs) share: Debian's
// chromium started as issue 30 runs it (headless, WebGL drawn in software by SwiftShader), and
// `sylva view FILE` on a free port of 127.0.0.1 with its printed address.
import { spawn } from 'node:child_process';
import { writeFileSync, renameSync } from 'node:fs';
import { join } from 'node:path';
import http from 'node:http';
import puppeteer from 'puppeteer-core';

export function launch(dir) {
  return puppeteer.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    userDataDir: join(dir, 'profile'),
    args: ['--headless=new', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
      '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run',
      '--window-size=900,700'],
  });
}

// The servers still running: killed when this process ends however it ends (a failed check's
// exception, a timeout, Ctrl-C), not only by a test's own stop() — none is left behind.
const running = new Set();
const killAll = () => { for (const s of running) s.kill('SIGKILL'); };
process.on('exit', killAll);
for (const [sig, n] of [['SIGINT', 2], ['SIGTERM', 15], ['SIGHUP', 1]])
  process.on(sig, () => { killAll(); process.exit(128 + n); });

// Resolves to {server, url}; server.err collects its stderr.
export function serve(sylva, path) {
  const server = spawn(sylva, ['view', path, '--port', '0', '-j', '1'], { stdio: ['ignore', 'pipe', 'pipe'] });
  running.add(server);
  server.err = '';
  server.stderr.on('data', (d) => { server.err += d; });
  return new Promise((resolve, reject) => {
    let out = '';
    const late = setTimeout(() => { server.kill('SIGKILL'); reject(new Error('no address printed')); }, 20000);
    server.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/^(http:\/\/\S+)\n/);
      if (m) { clearTimeout(late); resolve({ server, url: m[1] }); }
    });
    server.on('exit', (c) => { running.delete(server); clearTimeout(late); reject(new Error('sylva view exited ' + c + ': ' + server.err)); });
  });
}

// A GET of a server's path with the token of its printed address: {status, body (a Buffer)},
// status 0 when the request failed.
export function getter(url) {
  const u = new URL(url.replace(/\/\?token=.*/, '')), token = url.replace(/.*token=/, '');
  return (path) => new Promise((resolve) => {
    http.get({ host: u.hostname, port: u.port, path, headers: { 'X-Sylva-Token': token } }, (res) => {
      const parts = []; res.on('data', (d) => parts.push(d)); res.on('end', () => resolve({ status: res.statusCode, body: Buffer.concat(parts) }));
    }).on('error', (e) => resolve({ status: 0, body: Buffer.from(String(e)) }));
  });
}

// A save as an editor makes it: the new text written beside, then renamed over the file.
export function edit(path, text) { writeFileSync(path + '.new', text); renameSync(path + '.new', path); }

// A bush of blades (leaves the preview draws as instanced cards), depth a slider's parameter.
export const BUSH = (depth) => `lsystem Bush {
  param depth = ${depth}
  derive 8
  angle 25
  axiom A(0)
  A(i) : i < depth -> F[+A(i+1)][-A(i+1)]/(90)FA(i+1)
  F -> F ~L
}
`;

// A new tab of the viewer at url, 900x700 as the tests draw it; its page errors go to errors.
// holdEvents: the page's event stream (/api/events) is held back until page.releaseEvents() —
// a save made meanwhile lands before the stream is connected. The page's requests then pass
// through puppeteer for its whole life (turning that off while the page asks races with it).
export async function openPage(browser, url, errors, { holdEvents = false } = {}) {
  const page = await browser.newPage();
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.setViewport({ width: 900, height: 700 });
  if (holdEvents) {
    const held = [];
    let holding = true;
    const onRequest = (r) => (holding && new URL(r.url()).pathname === '/api/events' ? held.push(r) : r.continue());
    await page.setRequestInterception(true);
    page.on('request', onRequest);
    page.eventsHeld = () => held.length;
    page.releaseEvents = async () => {
      holding = false;
      for (const r of held) await r.continue();
      return held.length;
    };
  }
  await page.goto(url);
  return page;
}

// SIGTERM, then its exit code (or the signal's name when it died of one)
export function stop(server) {
  if (server.exitCode !== null || server.signalCode !== null) return Promise.resolve(server.exitCode ?? server.signalCode);
  const done = new Promise((r) => server.on('exit', (c, s) => r(c === null ? s : c)));
  server.kill('SIGTERM');
  return done;
}

// TAP lines: check(ok, what, detail) prints "ok N - what" (the detail when it failed); done()
// prints the plan and exits 1 when a check failed.
export function tap() {
  let failures = 0, count = 0;
  return {
    check(ok, what, detail = '') {
      count++;
      if (!ok) failures++;
      console.log(`${ok ? 'ok' : 'not ok'} ${count} - ${what}${!ok && detail ? ' (' + detail + ')' : ''}`);
    },
    done() { console.log(`1..${count}`); process.exit(failures ? 1 : 0); },
  };
}

// The ecosystem tests' tree: a stick that matures in two years (on tests/oracle's flat terrain),
// its species lines and its model.
export const STICK_SPECIES = `  species stick
    model Stick
    maturity 2
    height_max 6
    growth_rate 0.6
    start_height 0.5
    radius_ratio 0.3
    seeds 2
    dispersal 2
    arrivals 60
    shade_tolerance 0.5
`;
export const STICK_MODEL = `lsystem Stick {
  derive 2
  axiom F
  F -> F[+F]F[-F]F
}
`;
