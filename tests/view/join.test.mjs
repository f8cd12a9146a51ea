// joinStraight (web/scene.js), which draws the skeleton mode in fewer lines (the server joins a
// segments preview the same way: preview.test.mjs compares the two): the lines it keeps
// cover every segment it was given (both ends on a line of the same branch order), their total
// length is the segments', and a straight run becomes one line. The segments are made here by
// a small turtle of this test's own (runs of collinear steps, branches, turns). No browser:
// node imports scene.js with web/node_modules' three.js. Usage: node join.test.mjs. TAP lines.
import { joinStraight } from '../../web/scene.js';
import { tap } from './browser.mjs';

const { check, done } = tap();

// A deterministic pseudo-random turtle: depth-first, as a skeleton's nodes come
let seed = 12345;
const rnd = () => ((seed = (Math.imul(seed, 1103515245) + 12345) >>> 0) / 2 ** 32);
const segs = [], orders = [];
function grow(p, d, order, depth) {
  for (let run = 0; run < 3; run++) {
    const steps = 1 + Math.floor(rnd() * 5), len = 0.5 + rnd();
    for (let k = 0; k < steps; k++) { // collinear steps, as F → FF makes them
      const q = [p[0] + d[0] * len, p[1] + d[1] * len, p[2] + d[2] * len];
      segs.push(...p, ...q); orders.push(order);
      p = q;
    }
    if (depth < 4 && rnd() < 0.7) { // a branch from here, then the axis turns a little
      const b = [d[0] + rnd() - 0.5, d[1], d[2] + rnd() - 0.5], n = Math.hypot(...b);
      grow(p, b.map((x) => x / n), order + 1, depth + 1);
    }
    const t = [d[0] + 0.3 * (rnd() - 0.5), d[1], d[2] + 0.3 * (rnd() - 0.5)], m = Math.hypot(...t);
    d = t.map((x) => x / m);
  }
}
grow([0, 0, 0], [0, 1, 0], 0, 0);
const pos = new Float32Array(segs), order = new Uint8Array(orders);
const j = joinStraight(pos, order);

const length = (a, n) => { let s = 0; for (let i = 0; i < n; i++) s += Math.hypot(a[6 * i + 3] - a[6 * i], a[6 * i + 4] - a[6 * i + 1], a[6 * i + 5] - a[6 * i + 2]); return s; };
// point x on line k (within float noise of the line's length)?
const on = (x, k) => {
  const a = j.pos.subarray(6 * k, 6 * k + 3), b = j.pos.subarray(6 * k + 3, 6 * k + 6);
  const ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], ax = [x[0] - a[0], x[1] - a[1], x[2] - a[2]];
  const L2 = ab[0] ** 2 + ab[1] ** 2 + ab[2] ** 2, t = (ab[0] * ax[0] + ab[1] * ax[1] + ab[2] * ax[2]) / L2;
  const d2 = (ax[0] - t * ab[0]) ** 2 + (ax[1] - t * ab[1]) ** 2 + (ax[2] - t * ab[2]) ** 2;
  return t >= -1e-5 && t <= 1 + 1e-5 && d2 <= 1e-8 * L2;
};
let uncovered = 0;
for (let i = 0; i < order.length; i++) {
  const p = pos.subarray(6 * i, 6 * i + 3), q = pos.subarray(6 * i + 3, 6 * i + 6);
  let found = false;
  for (let k = 0; k < j.n && !found; k++) found = j.order[k] === order[i] && on(p, k) && on(q, k);
  if (!found) uncovered++;
}
check(j.n < order.length && uncovered === 0, 'every segment lies on a kept line of its order, and there are fewer lines',
  `${order.length} segments, ${j.n} lines, ${uncovered} not covered`);
const l0 = length(pos, order.length), l1 = length(j.pos, j.n);
check(Math.abs(l0 - l1) <= 1e-5 * l0, 'the lines are as long as the segments together', `${l0} vs ${l1}`);

// 2^16 steps in a row: one line; a reversal and an order change are kept apart
const run = new Float32Array(6 * 65536), ro = new Uint8Array(65536);
for (let i = 0; i < 65536; i++) run.set([0, i * 0.25, 0, 0, (i + 1) * 0.25, 0], 6 * i);
const one = joinStraight(run, ro);
check(one.n === 1 && one.pos[1] === 0 && one.pos[4] === 65536 * 0.25, 'a straight run of 65,536 segments is one line', JSON.stringify([...one.pos]));
const back = joinStraight(new Float32Array([0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0.5, 0, 0, 0.5, 0, 0, 2, 0]), new Uint8Array([0, 0, 1]));
check(back.n === 3, 'a segment going back, or of another order, is not joined', `${back.n} lines`);
done();
