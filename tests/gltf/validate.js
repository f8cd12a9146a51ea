#!/usr/bin/env node
// Validate .glb/.gltf files with the Khronos glTF validator (npm package gltf-validator).
// One line per file: "ok FILE: W warnings, I infos" or "FAIL FILE: N errors" followed by the
// errors. Exit status 1 if any file has an error (or cannot be read), 0 otherwise.
//   node tests/gltf/validate.js [--verbose] FILE...
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function main(args) {
  const verbose = args[0] === '--verbose';
  if (verbose) args = args.slice(1);
  if (args.length === 0) {
    console.error('usage: validate.js [--verbose] FILE...');
    return 2;
  }
  let failed = 0;
  for (const file of args) {
    let report;
    try {
      const bytes = new Uint8Array(fs.readFileSync(file));
      report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 100,
        externalResourceFunction: (uri) => Promise.resolve(
          new Uint8Array(fs.readFileSync(path.resolve(path.dirname(file), decodeURIComponent(uri))))),
      });
    } catch (e) {
      console.log(`FAIL ${file}: ${e}`);
      failed++;
      continue;
    }
    const n = report.issues;
    if (n.numErrors > 0) {
      failed++;
      console.log(`FAIL ${file}: ${n.numErrors} errors, ${n.numWarnings} warnings`);
    } else {
      console.log(`ok ${file}: ${n.numWarnings} warnings, ${n.numInfos} infos`);
    }
    for (const m of n.messages) {
      if (m.severity === 0 || (verbose && m.severity <= 2)) {
        const sev = ['error', 'warning', 'info', 'hint'][m.severity];
        console.log(`    ${sev} ${m.code} ${m.pointer || ''}: ${m.message}`);
      }
    }
  }
  return failed ? 1 : 0;
}

main(process.argv.slice(2)).then((code) => process.exit(code), (e) => {
  console.error(e);
  process.exit(1);
});
