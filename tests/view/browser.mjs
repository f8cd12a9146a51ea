// What the browser tests (view.test.mjs) and make bench (bench/view.mjs) share: Debian's
// chromium started as issue 30 runs it (headless, WebGL drawn in software by SwiftShader), and
// `sylva view FILE` on a free port of 127.0.0.1 with its printed address.
import { spawn } from 'node:child_process';
import { join } from 'node:path';
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

// Resolves to {server, url}; server.err collects its stderr.
export function serve(sylva, path) {
  const server = spawn(sylva, ['view', path, '--port', '0', '-j', '1'], { stdio: ['ignore', 'pipe', 'pipe'] });
  server.err = '';
  server.stderr.on('data', (d) => { server.err += d; });
  return new Promise((resolve, reject) => {
    let out = '';
    server.stdout.on('data', (d) => { out += d; const m = out.match(/^(http:\/\/\S+)\n/); if (m) resolve({ server, url: m[1] }); });
    server.on('exit', (c) => reject(new Error('sylva view exited ' + c + ': ' + server.err)));
    setTimeout(() => reject(new Error('no address printed')), 20000);
  });
}

// SIGTERM, then its exit code (or the signal's name when it died of one)
export function stop(server) {
  const done = new Promise((r) => server.on('exit', (c, s) => r(c === null ? s : c)));
  server.kill('SIGTERM');
  return done;
}
