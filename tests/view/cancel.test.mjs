// A build under way is stopped by the library's SylCancel (sylva.h) when it is no longer
// wanted: a save during a long derivation stops it (the files changed under it), and so does
// a newer request of the same tab, and so does stopping the server. No browser: the server's HTTP answers only. The long build
// is a derivation of many cheap steps (the cancel is asked before each), which would run for
// minutes if it were not stopped; stopped, it costs a fraction of a second.
// Usage: node cancel.test.mjs SYLVA.
import { mkdtempSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { serve, stop, tap, getter, edit } from './browser.mjs';

const sylva = process.argv[2];
const { check, done } = tap();

const dir = mkdtempSync(join(tmpdir(), 'sylva-view-cancel-'));
const file = join(dir, 'spin.syl');
// 20,000 modules rewritten at each step (tens of microseconds); a million steps take minutes
const TEXT = (steps) => `lsystem Spin {
  derive ${steps}
  axiom F${' A(0)'.repeat(20000)}
  A(x) -> A(x+1)
}
`;
const LONG = 1000000; // the most steps a request's n may ask for
writeFileSync(file, TEXT(LONG));

const { server, url } = await serve(sylva, file);
const get = getter(url);
const json = async (path) => JSON.parse((await get(path)).body.toString());
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
// until the server has begun a build more than it had (the long one is under way)
const begun = async (n) => { for (;;) { const m = await json('/api/models'); if (m.builds > n) return m; await sleep(20); } };
try {
  // ---- a save while the long build derives: it stops, the new text is built ----
  const m0 = await json('/api/models');
  const first = json('/api/build?model=Spin&tab=1&seq=1');
  await begun(m0.builds);
  edit(file, TEXT(3));
  const stopped = await first;
  check(stopped.superseded === true && stopped.ok === false && !stopped.stats, 'a save during a long derivation stops it (superseded)',
    JSON.stringify(stopped).slice(0, 200));
  const m1 = await json('/api/models');
  check(m1.stopped === m0.stopped + 1 && m1.gen > m0.gen, 'the server counts the stopped build', JSON.stringify({ m0, m1 }));
  const now = await json('/api/build?model=Spin&tab=1&seq=2');
  check(now.ok && now.stats.modules === 20001, 'the saved text is built next', JSON.stringify(now).slice(0, 200));

  // ---- a newer request of the same tab while its long build derives: it stops ----
  const m2 = await json('/api/models');
  const long = json(`/api/build?model=Spin&n=${LONG}&tab=2&seq=1`);
  await begun(m2.builds);
  const newer = await json('/api/build?model=Spin&n=2&tab=2&seq=2');
  const old = await long;
  check(old.superseded === true && !old.ok, 'a newer request of its tab stops a long derivation', JSON.stringify(old).slice(0, 200));
  check(newer.ok && !newer.superseded && newer.stats.modules === 20001, 'and the newer one is built');
  const m3 = await json('/api/models');
  check(m3.stopped === m2.stopped + 1, 'counted as stopped too', JSON.stringify({ m2, m3 }));

  // ---- Ctrl-C (SIGTERM) while a long build derives: the server stops it and exits cleanly ----
  const m4 = await json('/api/models');
  const doomed = json(`/api/build?model=Spin&n=${LONG}&tab=3&seq=1`).catch(() => null);
  await begun(m4.builds);
  const code = await Promise.race([stop(server), sleep(60000).then(() => 'still running after 60 s')]);
  await doomed;
  check(code === 0, 'SIGTERM during a long derivation stops it and the server exits with 0', String(code));
} finally {
  await stop(server);
  rmSync(dir, { recursive: true, force: true });
}
done();
