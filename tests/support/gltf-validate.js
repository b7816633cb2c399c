// The Khronos glTF-Validator (npm gltf-validator, installed by scripts/setup --test into
// data/npm) on one .glb/.gltf: prints its counts and messages as one JSON line.
//
//   node tests/support/gltf-validate.js FILE [NODE_MODULES]
'use strict';
const fs = require('fs');
const path = require('path');
const [file, modules] = process.argv.slice(2);
if (!file) {
  console.error('usage: gltf-validate.js FILE [NODE_MODULES]');
  process.exit(2);
}
const validator = require(path.join(modules || path.join(__dirname, '../../data/npm/node_modules'), 'gltf-validator'));
const bytes = new Uint8Array(fs.readFileSync(file));
validator.validateBytes(bytes, {
  uri: path.basename(file),
  maxIssues: 100,
  externalResourceFunction: (uri) => Promise.reject(new Error('external resource ' + uri)),
}).then((report) => {
  const i = report.issues;
  console.log(JSON.stringify({
    errors: i.numErrors, warnings: i.numWarnings, infos: i.numInfos, hints: i.numHints,
    messages: i.messages.map((m) => `${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code} ${m.pointer || ''}: ${m.message}`),
    info: report.info,
  }));
}).catch((e) => {
  console.error('gltf-validate: ' + e);
  process.exit(1);
});
