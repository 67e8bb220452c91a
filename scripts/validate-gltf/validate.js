// Usage: node validate.js FILE.glb...  Prints the Khronos glTF-Validator's counts and messages for each
// file; exits 1 if any file has an error or a warning. Infos and hints are printed, not failed.
//
// KHR_texture_basisu: the released validator (2.0.0-dev.3.10, the newest on npm) does not know the
// extension (KhronosGroup/glTF-Validator#177, open), so it warns about every KTX2 image of a file
// that requires it: its mimeType 'image/ktx2' (VALUE_NOT_IN_LIST) and its bytes
// (IMAGE_UNRECOGNIZED_FORMAT). Exactly those two warnings, on images that a texture's
// KHR_texture_basisu names and whose mimeType is image/ktx2, in a file that lists the extension in
// extensionsRequired, are printed as "known gap" and not counted; any other message counts. The
// test checks the KTX2 images itself (tests/gltf/validate_test.sh).
const fs = require('fs');
const validator = require('gltf-validator');

function glbJson(data) {
  if (data.length < 20 || data[0] !== 0x67 || data[1] !== 0x6c || data[2] !== 0x54 || data[3] !== 0x46) return null;
  const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
  const length = view.getUint32(12, true);
  try { return JSON.parse(Buffer.from(data.subarray(20, 20 + length)).toString('utf8')); } catch (e) { return null; }
}

function ktx2Images(doc) {
  const images = new Set();
  if (!doc || !(doc.extensionsRequired || []).includes('KHR_texture_basisu')) return images;
  for (const t of doc.textures || []) {
    const s = t.extensions && t.extensions.KHR_texture_basisu && t.extensions.KHR_texture_basisu.source;
    if (Number.isInteger(s) && doc.images && doc.images[s] && doc.images[s].mimeType === 'image/ktx2') images.add(s);
  }
  return images;
}

function knownGap(m, ktx2) {
  let match;
  if (m.code === 'VALUE_NOT_IN_LIST' && (match = /^\/images\/(\d+)\/mimeType$/.exec(m.pointer || '')) && /'image\/ktx2'/.test(m.message))
    return ktx2.has(Number(match[1]));
  if (m.code === 'IMAGE_UNRECOGNIZED_FORMAT' && (match = /^\/images\/(\d+)$/.exec(m.pointer || ''))) return ktx2.has(Number(match[1]));
  return false;
}

(async () => {
  let bad = 0;
  for (const file of process.argv.slice(2)) {
    const data = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(data, { writeTimestamp: false, maxIssues: 100 });
    const i = report.issues;
    const ktx2 = ktx2Images(glbJson(data));
    let gaps = 0;
    for (const m of i.messages) if (m.severity === 1 && knownGap(m, ktx2)) gaps++;
    const warnings = i.numWarnings - gaps;
    console.log(`${file}: ${i.numErrors} errors, ${warnings} warnings${gaps ? ` (+${gaps} known gaps: KTX2 images)` : ''}, ${i.numInfos} infos, ${i.numHints} hints`);
    for (const m of i.messages)
      console.log(`  ${m.severity} ${m.code} ${m.pointer || ''}: ${m.message}${m.severity === 1 && knownGap(m, ktx2) ? ' (known gap)' : ''}`);
    if (i.numErrors || warnings) bad = 1;
  }
  process.exit(bad);
})();
