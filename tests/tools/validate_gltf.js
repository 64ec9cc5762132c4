#!/usr/bin/env node
// Validates glTF / GLB files with the Khronos glTF Validator.
// Usage: node validate_gltf.js FILE...
// Prints every issue; exits 1 when any file has errors (warnings, infos and
// hints are printed but allowed), 2 when the validator is not installed.
'use strict';

const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error(`gltf-validator is not installed: run \`npm ci\` in ${__dirname} once ` +
                '(tests never download at test time).');
  process.exit(2);
}

const SEVERITY = ['error', 'warning', 'info', 'hint'];

async function validateFile(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    writeTimestamp: false,
    // External buffers (a .gltf's .bin) are read beside the file, so a broken
    // reference shows up as an error rather than being skipped.
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      const resource = path.resolve(path.dirname(file), decodeURIComponent(uri));
      fs.readFile(resource, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
    }),
  });
  const issues = report.issues;
  for (const m of issues.messages) {
    console.log(`${file}: ${SEVERITY[m.severity] || m.severity}: ${m.code}: ${m.message}` +
                (m.pointer ? ` (at ${m.pointer})` : ''));
  }
  console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
              `${issues.numInfos} infos, ${issues.numHints} hints`);
  return issues.numErrors;
}

async function main(files) {
  if (files.length === 0) {
    console.error('usage: node validate_gltf.js FILE...');
    return 2;
  }
  let failed = 0;
  for (const file of files) {
    try {
      if ((await validateFile(file)) > 0) failed++;
    } catch (e) {
      console.error(`${file}: cannot validate: ${e}`);
      failed++;
    }
  }
  return failed > 0 ? 1 : 0;
}

main(process.argv.slice(2)).then((code) => process.exit(code));
