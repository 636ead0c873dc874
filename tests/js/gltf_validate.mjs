// Validates glTF files with the Khronos glTF-Validator (npm package gltf-validator, which is a
// library only: this is its command line). Prints each file's report as JSON on stdout and a
// summary line per file on stderr; exits 1 when any file has an error or a warning (infos and
// hints are reported, and allowed), 2 on bad usage or a file that cannot be read.
//
//   node gltf_validate.mjs walk.glb [more.glb ...] > report.json
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';

import validator from 'gltf-validator';

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node gltf_validate.mjs FILE.glb [FILE.glb ...]');
  process.exit(2);
}

let failed = false;
const reports = [];
for (const file of files) {
  let bytes;
  try {
    bytes = new Uint8Array(readFileSync(file));
  } catch (error) {
    console.error(`${file}: ${error.message}`);
    process.exit(2);
  }
  // No external resources: a .glb holds everything; a reference out of it is an error.
  const report = await validator.validateBytes(bytes, {
    uri: basename(file),
    maxIssues: 1000,
    writeTimestamp: false,
    externalResourceFunction: (uri) =>
      Promise.reject(new Error(`external resource ${uri} requested by ${file}`)),
  });
  reports.push(report);
  const { numErrors, numWarnings, numInfos, numHints, messages } = report.issues;
  console.error(`${file}: glTF-Validator ${report.validatorVersion}: ${numErrors} errors, ` +
    `${numWarnings} warnings, ${numInfos} infos, ${numHints} hints; ${bytes.length} bytes`);
  const severities = ['error', 'warning', 'info', 'hint'];
  for (const m of messages) {
    console.error(`  ${severities[m.severity] ?? m.severity} ${m.code}` +
      `${m.pointer ? ' at ' + m.pointer : ''}: ${m.message}`);
  }
  if (numErrors > 0 || numWarnings > 0) failed = true;
}
process.stdout.write(JSON.stringify(reports.length === 1 ? reports[0] : reports, null, 2) + '\n');
process.exit(failed ? 1 : 0);
