#!/usr/bin/env node
// Peer benchmark: derive one of the bench models with the npm package `lindenmayer`
// (nylki/lindenmayer 1.5.x) and print one line of JSON:
//   {"model":"a","n":12,"modules":3179648,"seconds":0.41,"peak_mb":215.3}
//
//   node bench/peers/lindenmayer.js a|b|c|d N
//
// seconds  best of 3 in-process derivations; only LSystem.iterate(N) is timed
//          (building the LSystem object, i.e. its "parsing", is not)
// modules  length of the final string (string mode) or of the final array (object mode)
// peak_mb  whole-process peak RSS at the end (process.resourceUsage().maxRSS, KiB / 1024)
//
// The models must stay the same L-systems as bench/models/{a,b,c,d}.syl.
'use strict';

const fs = require('fs');
const path = require('path');
const LSystem = require(path.join(__dirname, 'node_modules', 'lindenmayer'));

const RUNS = 3;

// (a) ABOP Fig. 1.24(e), string mode.
function modelA() {
  return new LSystem({
    axiom: 'X',
    productions: { X: 'F[+X][-X]FX', F: 'FF' },
  });
}

// (b) The same plant with a parameter on every module: object symbols and
// function successors, the way lindenmayer does parametric L-systems.
// Brackets carry no parameter, so one shared object stands for every '[' / ']'.
function modelB() {
  const OPEN = { symbol: '[' };
  const CLOSE = { symbol: ']' };
  return new LSystem({
    axiom: [{ symbol: 'X', params: [1] }],
    productions: {
      X: ({ part }) => {
        const l = part.params[0];
        return [
          { symbol: 'F', params: [l] },
          OPEN, { symbol: '+', params: [25.7] }, { symbol: 'X', params: [l / 2] }, CLOSE,
          OPEN, { symbol: '-', params: [25.7] }, { symbol: 'X', params: [l / 2] }, CLOSE,
          { symbol: 'F', params: [l] },
          { symbol: 'X', params: [l / 2] },
        ];
      },
      F: ({ part }) => {
        const l = part.params[0];
        return [{ symbol: 'F', params: [l] }, { symbol: 'F', params: [l] }];
      },
    },
  });
}

// (d) L-Py's context-free parametric tree `lsystem1.9`, R = 1.456, the same way as (b).
function modelD() {
  const OPEN = { symbol: '[' };
  const CLOSE = { symbol: ']' };
  const R = 1.456;
  return new LSystem({
    axiom: [{ symbol: 'A', params: [1] }],
    productions: {
      A: ({ part }) => {
        const s = part.params[0];
        return [
          { symbol: 'F', params: [s] },
          OPEN, { symbol: '+', params: [85] }, { symbol: 'A', params: [s / R] }, CLOSE,
          OPEN, { symbol: '-', params: [85] }, { symbol: 'A', params: [s / R] }, CLOSE,
        ];
      },
    },
  });
}

// (c) Hogeweg–Hesper plant, ABOP Fig. 1.31(a), COPIES plants side by side, classic
// context syntax with ignored symbols + - F. Every branch ends in `f` and every plant is
// preceded by `f`: a non-ignored module that no context names, so a context scan stops at
// the end of a branch as ABOP §1.8 prescribes (lindenmayer's right-context scan otherwise
// walks out of the branch, see bench/peers/check_contexts.js) and the scans of one plant
// never walk into its neighbours. Without the f's the string is exactly ABOP's.
const C_COPIES = 400;
const C_PLANT = 'f[F1F1F1f]';
const C_AXIOM = C_PLANT.repeat(C_COPIES);
const C_PRODUCTIONS = {
  '0<0>0': '0',
  '0<0>1': '1[+F1F1f]',
  '0<1>0': '1',
  '0<1>1': '1',
  '1<0>0': '0',
  '1<0>1': '1F1',
  '1<1>0': '0',
  '1<1>1': '0',
  '+': '-',
  '-': '+',
};

function modelC() {
  return new LSystem({
    axiom: C_AXIOM,
    productions: C_PRODUCTIONS,
    ignoredSymbols: '+-F',
  });
}

// Warn (stderr) if bench/models/c.syl no longer has the axiom this file derives.
function checkAxiomC() {
  const syl = path.join(__dirname, '..', 'models', 'c.syl');
  let text;
  try { text = fs.readFileSync(syl, 'utf8'); } catch { return; }
  const line = text.split('\n').find((l) => /^\s*axiom\s/.test(l));
  const axiom = line && line.replace(/#.*/, '').trim().replace(/^axiom\s+/, '').replace(/\s+/g, '');
  if (axiom !== C_AXIOM)
    process.stderr.write('lindenmayer.js: warning: axiom of bench/models/c.syl differs from C_AXIOM\n');
}

const MODELS = { a: modelA, b: modelB, c: modelC, d: modelD };

function main(argv) {
  const [model, nText] = argv;
  const n = Number(nText);
  if (!MODELS[model] || !Number.isInteger(n) || n < 0) {
    process.stderr.write('usage: node bench/peers/lindenmayer.js a|b|c|d N\n');
    process.exit(2);
  }
  if (model === 'c') checkAxiomC();

  let best = Infinity;
  let modules = -1;
  for (let run = 0; run < RUNS; run++) {
    const lsys = MODELS[model]();
    const t0 = process.hrtime.bigint();
    const result = lsys.iterate(n);
    const t1 = process.hrtime.bigint();
    best = Math.min(best, Number(t1 - t0) / 1e9);
    modules = result.length; // string: characters = modules; array: one object per module
  }

  const peakMb = process.resourceUsage().maxRSS / 1024;
  process.stdout.write(JSON.stringify({
    model, n, modules,
    seconds: Number(best.toFixed(6)),
    peak_mb: Number(peakMb.toFixed(1)),
  }) + '\n');
}

main(process.argv.slice(2));
