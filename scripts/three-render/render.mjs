// Renders .glb files with three.js (GLTFLoader, WebGLRenderer) in headless Chromium from the cameras
// `qf-render eval --cameras` writes, with the same lights (a white directional headlight and ambient
// light, engine_scene.h EngineLights), over black and over white, as
// OUT/view_I_black.png and OUT/view_I_white.png: the renders `qf-render eval --external OUT` scores.
// No antialiasing, no tone mapping, sRGB output: what three.js does by default, minus MSAA.
//
// usage: node render.mjs FILE.glb CAMERAS.json OUTDIR
//        node render.mjs --jobs JOBS.json     (a JSON array of {"file", "cameras", "out"}: one browser for all)
// env:   QF_CHROMIUM  the Chromium executable (default /usr/bin/chromium)
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';

import { withThreePage } from './browser.mjs';

// A PNG of RGB rows (colour type 2, 8 bits, filter 0 on every row).
function encodePng(width, height, rgba) {
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

const pageScript = `
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
window.qfRender = async (url, cams) => {
  const first = cams.views[0];
  const canvas = document.createElement('canvas');
  canvas.width = first.width; canvas.height = first.height;
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, alpha: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(first.width, first.height, false);
  const warnings = [];
  const warn = console.warn;
  console.warn = (...a) => { warnings.push(a.join(' ')); warn(...a); };
  const gltf = await new GLTFLoader().loadAsync(url);
  console.warn = warn;
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  const sun = new THREE.DirectionalLight(0xffffff, cams.lights.directional);
  scene.add(sun, sun.target, new THREE.AmbientLight(0xffffff, cams.lights.ambient));
  const camera = new THREE.PerspectiveCamera();
  camera.matrixAutoUpdate = false;
  const gl = renderer.getContext();
  const out = [];
  for (const v of cams.views) {
    camera.matrix.fromArray(v.view).invert();
    camera.projectionMatrix.fromArray(v.projection);
    camera.projectionMatrixInverse.copy(camera.projectionMatrix).invert();
    camera.updateMatrixWorld(true);
    sun.position.fromArray(v.eye);
    sun.target.position.fromArray(v.target);
    sun.updateMatrixWorld(true);
    sun.target.updateMatrixWorld(true);
    const pair = [];
    for (const bg of [0x000000, 0xffffff]) {
      renderer.setClearColor(bg, 1);
      renderer.render(scene, camera);
      const px = new Uint8Array(v.width * v.height * 4);
      gl.readPixels(0, 0, v.width, v.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
      // GL rows are bottom-up; send top-down rows as a plain array.
      const rows = new Uint8Array(px.length), stride = v.width * 4;
      for (let y = 0; y < v.height; ++y) rows.set(px.subarray((v.height - 1 - y) * stride, (v.height - y) * stride), y * stride);
      pair.push(Array.from(rows));
    }
    out.push(pair);
  }
  renderer.dispose();
  return { images: out, warnings };
};
`;

async function main() {
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
  await withThreePage(pageScript, (p) => (p === 'model.glb' ? current : null), async (page, errors) => {
    for (const job of jobs) {
      current = job.file;
      const cams = JSON.parse(fs.readFileSync(job.cameras, 'utf8'));
      try {
        const { images, warnings } = await page.evaluate(([u, c]) => window.qfRender(u, c), [`/files/model.glb?${encodeURIComponent(job.file)}`, cams]);
        fs.mkdirSync(job.out, { recursive: true });
        images.forEach((pair, i) => {
          const v = cams.views[i];
          fs.writeFileSync(path.join(job.out, `view_${i}_black.png`), encodePng(v.width, v.height, pair[0]));
          fs.writeFileSync(path.join(job.out, `view_${i}_white.png`), encodePng(v.width, v.height, pair[1]));
        });
        fs.writeFileSync(path.join(job.out, 'warnings.json'), JSON.stringify(warnings, null, 1) + '\n');
        console.log(`three-render: ${job.file}: ${images.length} views -> ${job.out}` + (warnings.length ? ` (${warnings.length} warnings)` : ''));
      } catch (e) {
        ++failed;
        console.error(`three-render: ${job.file}: ${e.message.split('\n')[0]} ${errors.splice(0).join('; ')}`);
      }
    }
  });
  process.exit(failed ? 1 : 0);
}

main().catch((e) => { console.error(`three-render: ${e.stack || e}`); process.exit(1); });
