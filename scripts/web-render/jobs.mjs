// The command line both engines' render.mjs share: render .glb files from the cameras
// `qf-render eval --cameras` writes, over black and over white, as OUT/view_I_black.png and
// OUT/view_I_white.png (the renders `qf-render eval --external OUT` scores), plus OUT/load.json:
// the loader's warnings, the names of the meshes the engine drew and of all it loaded.
//
// usage: node render.mjs FILE.glb CAMERAS.json OUTDIR
//        node render.mjs --jobs JOBS.json     (a JSON array of {"file", "cameras", "out"}: one browser for all)
// env:   QF_CHROMIUM  the Chromium executable (default /usr/bin/chromium)
//
// The engine's page must define window.qfRender(url, cams) -> {images, warnings, drawn, loaded}
// (images from capture.mjs captureViews).
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';

import { withPage } from './page.mjs';

// A PNG of RGB rows (colour type 2, 8 bits, filter 0 on every row).
export function encodePng(width, height, rgba) {
  const raw = Buffer.alloc((width * 3 + 1) * height);
  for (let y = 0; y < height; ++y) {
    raw[y * (width * 3 + 1)] = 0;
    for (let x = 0; x < width; ++x)
      for (let c = 0; c < 3; ++c) raw[y * (width * 3 + 1) + 1 + x * 3 + c] = rgba[(y * width + x) * 4 + c];
  }
  const chunk = (type, data) => {
    const len = Buffer.alloc(4);
    len.writeUInt32BE(data.length);
    const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    const crc = Buffer.alloc(4);
    crc.writeUInt32BE(zlib.crc32(body) >>> 0);
    return Buffer.concat([len, body, crc]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr[8] = 8; ihdr[9] = 2; ihdr[10] = 0; ihdr[11] = 0; ihdr[12] = 0;
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
                        chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}

// A load or render the engine never finishes (a loader waiting on a promise that never settles)
// fails its job after QF_RENDER_TIMEOUT seconds (default 180) instead of holding the caller until
// it is killed.
const limitMs = Number(process.env.QF_RENDER_TIMEOUT || 180) * 1000;
function within(promise) {
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`the engine did not finish loading and drawing within ${limitMs / 1000} s`)), limitMs);
  });
  return Promise.race([promise, late]).finally(() => clearTimeout(timer));
}

// label: the engine's name in messages; chromium: its playwright-core's; page: withPage's options.
export async function renderMain(label, chromium, page) {
  const args = process.argv.slice(2);
  let jobs;
  if (args[0] === '--jobs' && args.length === 2) jobs = JSON.parse(fs.readFileSync(args[1], 'utf8'));
  else if (args.length === 3) jobs = [{ file: args[0], cameras: args[1], out: args[2] }];
  else {
    console.error('usage: node render.mjs FILE.glb CAMERAS.json OUTDIR | --jobs JOBS.json');
    process.exit(2);
  }
  let failed = 0;
  let current = null;
  try {
    await withPage(chromium, page, (p) => (p === 'model.glb' ? current : null), async (tab, errors) => {
      for (const job of jobs) {
        current = job.file;
        const cams = JSON.parse(fs.readFileSync(job.cameras, 'utf8'));
        try {
          // The file's path rides in the query so that each job's URL differs (no cached file).
          const { images, warnings, drawn, loaded } = await within(tab.evaluate(([u, c]) => window.qfRender(u, c),
            [`/files/model.glb?${encodeURIComponent(job.file)}`, cams]));
          fs.mkdirSync(job.out, { recursive: true });
          images.forEach((pair, i) => {
            const v = cams.views[i];
            fs.writeFileSync(path.join(job.out, `view_${i}_black.png`), encodePng(v.width, v.height, Buffer.from(pair[0], 'base64')));
            fs.writeFileSync(path.join(job.out, `view_${i}_white.png`), encodePng(v.width, v.height, Buffer.from(pair[1], 'base64')));
          });
          fs.writeFileSync(path.join(job.out, 'load.json'), JSON.stringify({ warnings, drawn, loaded }, null, 1) + '\n');
          console.log(`${label}: ${job.file}: ${images.length} views -> ${job.out}` + (warnings.length ? ` (${warnings.length} warnings)` : ''));
        } catch (e) {
          ++failed;
          console.error(`${label}: ${job.file}: ${e.message.split('\n')[0]} ${errors.splice(0).join('; ')}`);
        }
      }
    });
  } catch (e) {
    console.error(`${label}: ${e.stack || e}`);
    process.exit(1);
  }
  process.exit(failed ? 1 : 0);
}
