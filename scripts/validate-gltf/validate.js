// Usage: node validate.js FILE.glb...  Prints the Khronos glTF-Validator's counts and messages for each
// file; exits 1 if any file has an error or a warning. Infos and hints are printed, not failed.
const fs = require('fs');
const validator = require('gltf-validator');
(async () => {
  let bad = 0;
  for (const file of process.argv.slice(2)) {
    const data = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(data, { writeTimestamp: false, maxIssues: 100 });
    const i = report.issues;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
    for (const m of i.messages) console.log(`  ${m.severity} ${m.code} ${m.pointer || ''}: ${m.message}`);
    if (i.numErrors || i.numWarnings) bad = 1;
  }
  process.exit(bad);
})();
