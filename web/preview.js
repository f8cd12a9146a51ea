// The segments of a preview of a big plant (view_preview.c: 6 floats each, then a byte of
// branch order each) as lines coloured as the skeleton mode colours them. The server has
// joined straight runs into one line each, as scene.js's joinStraight does (software WebGL
// spends a frame's time on each line; tests/view/join.test.mjs compares the two); the colours
// come from a table of the orders, a byte each (normalized): a million-module plant's lines
// are made in milliseconds.
import * as THREE from 'three';
import { ORDER_COLOURS } from './scene.js';

export function linesFrom(buf) {
  const n = buf.byteLength / 25, pos = new Float32Array(buf, 0, n * 6), order = new Uint8Array(buf, n * 24, n);
  const last = ORDER_COLOURS.length - 1, table = new Uint8Array(3 * (last + 1)), c = new THREE.Color();
  for (let k = 0; k <= last; k++) {
    c.setHex(ORDER_COLOURS[k]);
    table[3 * k] = Math.round(c.r * 255); table[3 * k + 1] = Math.round(c.g * 255); table[3 * k + 2] = Math.round(c.b * 255);
  }
  const col = new Uint8Array(n * 6);
  for (let i = 0; i < n; i++) {
    const t = 3 * Math.min(order[i], last), at = 6 * i;
    col[at] = col[at + 3] = table[t]; col[at + 1] = col[at + 4] = table[t + 1]; col[at + 2] = col[at + 5] = table[t + 2];
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.setAttribute('color', new THREE.BufferAttribute(col, 3, true));
  return new THREE.LineSegments(g, new THREE.LineBasicMaterial({ vertexColors: true }));
}
