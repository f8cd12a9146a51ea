#!/usr/bin/env node
// Check lindenmayer's output against a straightforward reference derivation.
//
//   node bench/peers/check_contexts.js
//
// 1. ABOP Fig. 1.31(a) as printed (axiom F1F1F1, n = 30): reports the first step at which
//    lindenmayer's string differs from the reference (its right-context scan does not stop
//    at the ']' that ends a branch; it carries on into the parent axis).
// 2. bench model c (end-of-branch `f` markers, plants side by side) on a few plants, n = 30:
//    lindenmayer must equal the reference, and the reference with the f's removed must
//    equal ABOP's string. This one decides the exit status.
// 3. bench model b: its symbols must spell model a's string (small n).
//
// Reference semantics (ABOP §1.8, cpfg, L-Py): the left context looks back towards the
// root, skipping complete branches and ignored symbols and leaving the current branch
// through its '['; the right context skips branches and ignored symbols and fails at the
// ']' that ends the current branch. Contexts here are single symbols.
'use strict';

const path = require('path');
const LSystem = require(path.join(__dirname, 'node_modules', 'lindenmayer'));

function referenceStep(s, rules, ignored) {
  const n = s.length;
  const partner = new Int32Array(n);
  const open = [];
  for (let i = 0; i < n; i++) {
    if (s[i] === '[') open.push(i);
    else if (s[i] === ']') { const o = open.pop(); partner[i] = o; partner[o] = i; }
  }
  const left = (i) => {
    for (let j = i - 1; j >= 0; j--) {
      const c = s[j];
      if (c === '[' || ignored.includes(c)) continue;
      if (c === ']') { j = partner[j]; continue; }
      return c;
    }
    return null;
  };
  const right = (i) => {
    for (let j = i + 1; j < n; j++) {
      const c = s[j];
      if (ignored.includes(c)) continue;
      if (c === '[') { j = partner[j]; continue; }
      if (c === ']') return null;
      return c;
    }
    return null;
  };
  const out = [];
  for (let i = 0; i < n; i++) {
    const c = s[i];
    let succ = c;
    for (const r of rules) {
      if (r.pred !== c) continue;
      if (r.left !== null && left(i) !== r.left) continue;
      if (r.right !== null && right(i) !== r.right) continue;
      succ = r.succ;
      break;
    }
    out.push(succ);
  }
  return out.join('');
}

// classic productions {'0<0>1': '1[+F1F1]', '+': '-'} -> reference rules
function toRules(productions) {
  return Object.entries(productions).map(([k, succ]) => {
    const m = /^(?:(.)<)?(.)(?:>(.))?$/.exec(k);
    return { left: m[1] ?? null, pred: m[2], right: m[3] ?? null, succ };
  });
}

function hoHeProductions(branch) {
  return {
    '0<0>0': '0', '0<0>1': branch, '0<1>0': '1', '0<1>1': '1',
    '1<0>0': '0', '1<0>1': '1F1', '1<1>0': '0', '1<1>1': '0',
    '+': '-', '-': '+',
  };
}

// Derive with both; return {step, lind, ref} at the first difference, or {ref} if none.
function compare(axiom, productions, ignored, n) {
  const lsys = new LSystem({ axiom, productions: { ...productions }, ignoredSymbols: ignored });
  const rules = toRules(productions);
  let ref = axiom;
  for (let step = 1; step <= n; step++) {
    const lind = lsys.iterate(1);
    ref = referenceStep(ref, rules, ignored);
    if (lind !== ref) return { step, lind, ref };
  }
  return { ref };
}

let ok = true;

// 1. the figure as printed
{
  const r = compare('F1F1F1', hoHeProductions('1[+F1F1]'), '+-F', 30);
  if (r.step !== undefined) {
    console.log(`ABOP 1.31(a) as printed: lindenmayer differs from the reference at step ${r.step}`);
    console.log(`  lindenmayer ${r.lind}`);
    console.log(`  reference   ${r.ref}`);
  } else {
    console.log(`ABOP 1.31(a) as printed: lindenmayer equals the reference through step 30 (${r.ref.length} modules)`);
  }
}

// 2. the bench model (same productions and plant as bench/peers/lindenmayer.js, 3 plants)
{
  const plants = 3;
  const r = compare('f[F1F1F1f]'.repeat(plants), hoHeProductions('1[+F1F1f]'), '+-F', 30);
  if (r.step !== undefined) {
    ok = false;
    console.log(`bench model c: lindenmayer DIFFERS from the reference at step ${r.step}`);
  } else {
    let abop = '[F1F1F1]'.repeat(plants);
    const rules = toRules(hoHeProductions('1[+F1F1]'));
    for (let step = 1; step <= 30; step++) abop = referenceStep(abop, rules, '+-F');
    const same = r.ref.replace(/f/g, '') === abop;
    if (!same) ok = false;
    console.log(`bench model c (${plants} plants, n = 30): lindenmayer equals the reference ` +
      `(${r.ref.length / plants} modules per plant); without its f's it ` +
      (same ? 'equals' : 'does NOT equal') + ' ABOP 1.31(a)');
  }
}

// 3. model b spells model a
{
  const a = new LSystem({ axiom: 'X', productions: { X: 'F[+X][-X]FX', F: 'FF' } }).iterate(6);
  const OPEN = { symbol: '[' }, CLOSE = { symbol: ']' };
  const b = new LSystem({
    axiom: [{ symbol: 'X', params: [1] }],
    productions: {
      X: ({ part }) => { const l = part.params[0]; return [
        { symbol: 'F', params: [l] },
        OPEN, { symbol: '+', params: [25.7] }, { symbol: 'X', params: [l / 2] }, CLOSE,
        OPEN, { symbol: '-', params: [25.7] }, { symbol: 'X', params: [l / 2] }, CLOSE,
        { symbol: 'F', params: [l] }, { symbol: 'X', params: [l / 2] }]; },
      F: ({ part }) => [{ symbol: 'F', params: [part.params[0]] }, { symbol: 'F', params: [part.params[0]] }],
    },
  }).iterate(6);
  const same = b.map((m) => m.symbol).join('') === a;
  if (!same) ok = false;
  console.log(`bench model b: symbols ${same ? 'equal' : 'DIFFER from'} model a's string (n = 6)`);
}

process.exit(ok ? 0 : 1);
