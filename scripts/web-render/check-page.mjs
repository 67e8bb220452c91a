// Opens one of quasiflat's pages (a bake's report.html, a batch's page, qf-diff's page) in headless
// Chromium and checks what a user relies on: it loads with no console error and asks for nothing
// over the network (every request but the page itself fails), every image decodes, and the figures
// it shows equal the JSON they come from (the pages carry them as data-* attributes). Prints one
// JSON line: the page's bytes, its load time, its images; with --shot, saves a full-page screenshot.
// usage: node check-page.mjs bake PAGE.html            (manifest.json, report.json beside it)
//        node check-page.mjs batch PAGE.html REPORT.json
//        node check-page.mjs diff PAGE.html DIFF.json  (qf-diff --json of the same run)
//        [--shot OUT.png]
// playwright-core is scripts/three-render's (pinned by its package-lock.json).
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { chromium } from '../three-render/browser.mjs';

const args = process.argv.slice(2);
const shotAt = args.indexOf('--shot');
const shot = shotAt >= 0 ? args.splice(shotAt, 2)[1] : null;
const [kind, pagePath, jsonPath] = args;
const problems = [];
const check = (ok, what) => { if (!ok) problems.push(what); };
const readJson = (p) => JSON.parse(fs.readFileSync(p, 'utf8'));

// What the page shows, read in the page: every element with data-* attributes, by a CSS selector.
async function figures(page, selector) {
  return page.$$eval(selector, (els) => els.map((e) => ({ ...e.dataset, text: e.textContent })));
}
// A WebP image's width x height from its first chunk: VP8X (the extended header: 24-bit sizes less
// one), VP8L (lossless: 14-bit sizes less one after the 0x2f signature) or VP8 (lossy: the key
// frame's 14-bit sizes); null for another chunk.
function webpTexels(data) {
  const chunk = data.subarray(12, 16).toString('latin1');
  if (chunk === 'VP8X') return (data.readUIntLE(24, 3) + 1) * (data.readUIntLE(27, 3) + 1);
  if (chunk === 'VP8L') {
    const bits = data.readUInt32LE(21);
    return ((bits & 0x3fff) + 1) * (((bits >>> 14) & 0x3fff) + 1);
  }
  if (chunk === 'VP8 ') return (data.readUInt16LE(26) & 0x3fff) * (data.readUInt16LE(28) & 0x3fff);
  return null;
}
// The texels of a .glb's images, read from their headers (PNG IHDR; KTX2 level 0; WebP).
function glbTexels(file) {
  const b = fs.readFileSync(file);
  const jsonLength = b.readUInt32LE(12);
  const gltf = JSON.parse(b.subarray(20, 20 + jsonLength).toString('utf8'));
  const bin = b.subarray(20 + jsonLength + 8);
  let texels = 0;
  for (const image of gltf.images || []) {
    const view = gltf.bufferViews[image.bufferView];
    const data = bin.subarray(view.byteOffset || 0, (view.byteOffset || 0) + view.byteLength);
    if (data.readUInt32BE(0) === 0x89504e47) texels += data.readUInt32BE(16) * data.readUInt32BE(20);
    else if (data.subarray(1, 7).toString('latin1') === 'KTX 20') texels += data.readUInt32LE(20) * data.readUInt32LE(24);
    else if (data.subarray(0, 4).toString('latin1') === 'RIFF' && data.subarray(8, 12).toString('latin1') === 'WEBP' && webpTexels(data) !== null)
      texels += webpTexels(data);
    else problems.push(`${file}: an image neither PNG, KTX2 nor WebP`);
  }
  return texels;
}
const num = (v) => (v === undefined || v === 'null' ? null : Number(v));

// The bake's page against manifest.json and report.json: every file's bytes, texels, GPU bytes,
// size and measured figures; the chain's bands; the warnings.
async function checkBake(page) {
  const dir = path.dirname(pagePath);
  const m = readJson(path.join(dir, 'manifest.json')), r = readJson(path.join(dir, 'report.json'));
  const rows = await figures(page, '#files tbody tr');
  const row = (file) => rows.find((x) => x.file === file);
  const listed = Object.fromEntries(m.files.map((f) => [f.name, f.bytes]));
  const entries = [...m.levels.map((e) => ['impostor_level', e]), ...(m.mesh_lods ? m.mesh_lods.levels.map((e) => ['mesh_lod', e]) : []),
                   ...(m.point_impostor ? [['point_impostor', m.point_impostor]] : [])];
  // The input itself as drawn heads the table where the bake measured: its figures are measuring.asset.
  const asset = m.measuring && m.measuring.asset ? 1 : 0;
  check(rows.length === entries.length + (m.lod_file ? 1 : 0) + asset, `files table has ${rows.length} rows, manifest ${entries.length} files`);
  const cells = await page.$$eval('#files tbody tr', (trs) => trs.map((tr) => [...tr.querySelectorAll('td.measured')].map((td) => ({ ...td.dataset }))));
  const sameFigures = (what, shown, measured) => {
    check(shown.length === measured.length, `${what}: ${shown.length} measured cells, manifest ${measured.length}`);
    for (const s of measured) {
      const c = shown.find((y) => num(y.pixels) === s.pixels);
      check(c && num(c.psnr) === s.psnr && num(c.iou) === s.iou && num(c.coverage) === s.coverage,
            `${what} at ${s.pixels} px: shown ${JSON.stringify(c)}, manifest ${s.psnr} dB / ${s.iou} / ${s.coverage}`);
    }
  };
  if (asset) {
    const k = rows.findIndex((x) => x.kind === 'asset');
    check(k === 0, `the input's row is row ${k}, not the first`);
    if (k >= 0) sameFigures('the input as drawn', cells[k], m.measuring.asset);
  }
  for (const [kindName, e] of entries) {
    const x = row(e.file);
    if (!x) { problems.push(`no row for ${e.file}`); continue; }
    check(x.kind === kindName, `${e.file}: kind ${x.kind}, expected ${kindName}`);
    check(num(x.bytes) === listed[e.file], `${e.file}: bytes ${x.bytes}, manifest ${listed[e.file]}`);
    if (e.bytes !== undefined) check(num(x.bytes) === e.bytes, `${e.file}: bytes ${x.bytes}, entry ${e.bytes}`);
    if (e.max_screen_pixels !== undefined) check(num(x.ownPixels) === e.max_screen_pixels, `${e.file}: max_screen_pixels ${x.ownPixels}, manifest ${e.max_screen_pixels}`);
    const texels = glbTexels(path.join(dir, e.file));
    check(num(x.texels) === texels, `${e.file}: texels ${x.texels}, its images ${texels}`);
    const gpu = e.gpu_bytes ?? Math.round(num(x.texels) * 16 / 3);
    check(num(x.gpuBytes) === gpu, `${e.file}: GPU bytes ${x.gpuBytes}, expected ${gpu}`);
    // Measured figures: the file's own (every measured file has them).
    sameFigures(e.file, cells[rows.indexOf(x)], e.measured || []);
  }
  // The chain's bands (or the impostor levels' when there is no chain).
  const bands = await figures(page, '#chain .band');
  if (m.recommended_chain) {
    const chain = m.recommended_chain.chain;
    check(bands.length === chain.length, `chain: ${bands.length} bands, manifest ${chain.length}`);
    chain.forEach((e, k) => {
      const b = bands[k] || {};
      const error = e.error || {};  // the input's first entry, above the largest size measured, has none
      check(b.file === e.file && num(b.minPixels) === e.min_pixels && num(b.maxPixels) === e.max_pixels && num(b.psnr) === (error.psnr ?? null) &&
            num(b.iou) === (error.iou ?? null), `chain band ${k}: shown ${JSON.stringify(b)}, manifest ${JSON.stringify(e)}`);
    });
  } else {
    check(bands.length === m.levels.length, `level bands: ${bands.length}, manifest ${m.levels.length} levels`);
  }
  const warnings = await page.$$eval('#warnings li.warning', (li) => li.map((x) => x.textContent));
  check(JSON.stringify(warnings) === JSON.stringify(r.warnings), `warnings shown ${JSON.stringify(warnings)}, report.json ${JSON.stringify(r.warnings)}`);
  check(num(await page.$eval('#points', (e) => e.dataset.value)) === r.points, 'points differ from report.json');
  // The input's facts (manifest source), what the bake wrote and what its chain ships, the
  // version and the measuring's GL driver (report.json).
  const source = await page.$eval('#source', (e) => ({ ...e.dataset }));
  for (const k of ['bytes', 'files', 'triangles', 'points', 'materials', 'textures'])
    check(num(source[k]) === (m.source[k] ?? null), `source ${k}: shown ${source[k]}, manifest ${m.source[k]}`);
  check(source.format === m.source.format, `source format: shown ${source.format}, manifest ${m.source.format}`);
  const written = m.files.reduce((n, f) => n + f.bytes, 0);
  check(num(await page.$eval('#bytes-written', (e) => e.dataset.value)) === written, `bytes written differ from the manifest's ${written}`);
  if (m.recommended_chain) {
    const shipped = [...new Set(m.recommended_chain.chain.filter((e) => e.kind !== 'asset').map((e) => e.file))];
    const chainBytes = shipped.reduce((n, f) => n + m.files.find((x) => x.name === f).bytes, 0);
    check(num(await page.$eval('#chain-bytes', (e) => e.dataset.value)) === chainBytes, `chain bytes differ from the manifest's ${chainBytes}`);
  }
  check((await page.$eval('#generator', (e) => e.dataset.version)) === r.tool_version, 'version differs from report.json');
  if (r.gl) {
    const gl = await page.$eval('#gl', (e) => ({ ...e.dataset }));
    check(gl.renderer === r.gl.renderer && gl.version === r.gl.version, `GL driver shown ${JSON.stringify(gl)}, report.json ${JSON.stringify(r.gl)}`);
  }
}

// The batch's page against its report: one row per asset with its status, time and error; the
// totals; a link to every baked asset's page and its thumbnail.
async function checkBatch(page) {
  const r = readJson(jsonPath);
  const rows = await page.$$eval('#assets tbody tr', (trs) => trs.map((tr) => ({
    ...tr.dataset, seconds: tr.cells[3].dataset.value, link: tr.querySelector('a') ? tr.querySelector('a').getAttribute('href') : null,
    thumb: !!tr.querySelector('img'), error: tr.querySelector('td.error').textContent,
    bytes: tr.querySelector('td.bytes').dataset.value, chainBytes: tr.querySelector('td.chain-bytes').dataset.value })));
  check(rows.length === r.assets.length, `${rows.length} rows, report ${r.assets.length} assets`);
  for (const a of r.assets) {
    const x = rows.find((y) => y.name === a.name);
    if (!x) { problems.push(`no row for ${a.name}`); continue; }
    check(x.status === a.status, `${a.name}: status ${x.status}, report ${a.status}`);
    check(num(x.seconds) === (a.seconds ?? null), `${a.name}: seconds ${x.seconds}, report ${a.seconds}`);
    if (a.error) check(x.error.includes(a.error.message), `${a.name}: error message not shown`);
    // What the asset wrote and what its chain ships: the page reads the folder, the report the bake.
    check(num(x.bytes) === (a.bytes ?? null), `${a.name}: bytes ${x.bytes}, report ${a.bytes}`);
    check(num(x.chainBytes) === (a.chain_bytes ?? null), `${a.name}: chain bytes ${x.chainBytes}, report ${a.chain_bytes}`);
    if (a.status === 'baked') {
      check(x.link && fs.existsSync(path.join(path.dirname(pagePath), x.link)), `${a.name}: no link to an existing report.html (${x.link})`);
      check(x.thumb, `${a.name}: no thumbnail`);
    }
  }
  for (const [id, key] of [['baked', 'baked'], ['failed', 'failed'], ['up-to-date', 'up to date'], ['bytes', 'bytes'], ['chain-bytes', 'chain_bytes']])
    check(num(await page.$eval(`#total-${id}`, (e) => e.dataset.value)) === r.totals[key], `total ${key} differs`);
}

// The diff page against qf-diff --json: the verdict, the summary, one row per file that differs
// with its PSNR, one section with old / new / difference images per view of each changed .glb.
async function checkDiff(page) {
  const r = readJson(jsonPath);
  check((await page.$eval('#verdict', (e) => e.dataset.value)) === r.verdict, 'verdict differs');
  for (const k of ['identical', 'changed', 'added', 'removed'])
    check(num(await page.$eval(`#summary-${k}`, (e) => e.dataset.value)) === r.summary[k], `summary ${k} differs`);
  const rows = await figures(page, '#files tbody tr');
  const differ = r.files.filter((f) => f.status !== 'identical');
  check(rows.length === differ.length, `${rows.length} rows, report ${differ.length} files that differ`);
  for (const f of differ) {
    const x = rows.find((y) => y.file === f.name);
    if (!x) { problems.push(`no row for ${f.name}`); continue; }
    check(x.status === f.status && (x.within === 'true') === f.within_thresholds, `${f.name}: status or verdict differs`);
    if (f.images) {
      check(num(x.psnrMin) === f.images.psnr_min && num(x.psnrMean) === f.images.psnr_mean, `${f.name}: PSNR shown ${x.psnrMin}/${x.psnrMean}`);
      const views = await page.$$eval(`section.changed[data-file="${f.name}"] .view`, (els) => els.map((e) => ({
        psnr: e.dataset.psnr, images: e.querySelectorAll('img').length })));
      check(views.length === f.images.per_view.length, `${f.name}: ${views.length} views shown, report ${f.images.per_view.length}`);
      views.forEach((v, k) => check(v.images === 3 && num(v.psnr) === f.images.per_view[k].psnr, `${f.name} view ${k}: ${JSON.stringify(v)}`));
    }
  }
  check((await page.$$('section.changed')).length === r.summary.changed, 'one section per changed file');
  // The chain's change, as the report words it.
  for (const f of differ.filter((x) => x.recommended_chain)) {
    for (const side of ['old', 'new']) {
      const shown = await page.$eval(`section.changed[data-file="${f.name}"] td[data-chain="${side}"]`, (e) => e.textContent);
      check(shown === (f.recommended_chain[side] ?? 'none'), `${f.name}: chain (${side}) shown "${shown}", report "${f.recommended_chain[side]}"`);
    }
  }
}

const browser = await chromium.launch({
  executablePath: process.env.QF_CHROMIUM || '/usr/bin/chromium',
  args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  const url = pathToFileURL(path.resolve(pagePath)).href;
  page.on('console', (msg) => { if (msg.type() === 'error' || msg.type() === 'warning') problems.push(`console ${msg.type()}: ${msg.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e}`));
  // Self-contained: nothing but the page itself (and the data: URIs in it) may be asked for.
  await page.route('**/*', (route) => {
    const u = route.request().url();
    if (u === url || u.startsWith('data:')) return route.continue();
    problems.push(`request outside the page: ${u}`);
    return route.abort();
  });
  const start = Date.now();
  await page.goto(url, { waitUntil: 'load' });
  const loadMs = Date.now() - start;
  const images = await page.$$eval('img', (imgs) => imgs.map((i) => ({ ok: i.complete && i.naturalWidth > 0, alt: i.alt })));
  for (const i of images) check(i.ok, `image does not decode: ${i.alt}`);
  const outside = await page.$$eval('[src], link[href]', (els) => els.map((e) => e.getAttribute('src') || e.getAttribute('href')).filter((u) => !u.startsWith('data:')));
  for (const u of outside) problems.push(`refers to a file outside the page: ${u}`);
  if (kind === 'bake') await checkBake(page);
  else if (kind === 'batch') await checkBatch(page);
  else if (kind === 'diff') await checkDiff(page);
  else problems.push(`unknown page kind ${kind}`);
  if (shot) await page.screenshot({ path: shot, fullPage: true });
  console.log(JSON.stringify({ page: pagePath, bytes: fs.statSync(pagePath).size, load_ms: loadMs, images: images.length }));
} finally {
  await browser.close();
}
if (problems.length) {
  console.error(`FAIL: ${pagePath}:\n  ${problems.join('\n  ')}`);
  process.exit(1);
}
