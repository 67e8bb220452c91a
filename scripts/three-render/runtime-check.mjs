// Runs tools/qf-runtime/three.mjs (loadImpostorLOD) in headless Chromium on bake folders and prints, per
// case, a line of JSON: the file shown and renderer.info.memory's geometries and textures with the
// camera at each distance from lod.centre (fov 60, a SIZE x SIZE canvas), first outward, then back.
// Each position is drawn (the renderer calls lod.update), then drawn again once lod.ready() says
// the file for it is shown. tests/render/runtime_test.sh writes the cases and checks the answers.
// usage: node runtime-check.mjs CASES.json
//   CASES.json: {"size": px, "dirs": {"NAME": folder}, "cases": [{"url": "/files/NAME/manifest.json",
//                "asset": bool (the app's own box), "assetUrl": url|null, "ktx2": bool, "decoders": bool
//                (meshopt, Draco), "diagonal": number|null, "distances": [d, ...]}]}
//   A case whose load or switch fails prints {"error": message}.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { chromium, threePage } from './browser.mjs';
import { withPage } from '../web-render/page.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const pageScript = `
import * as THREE from 'three';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';
import { DRACOLoader } from 'three/addons/loaders/DRACOLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
import { loadImpostorLOD } from 'qf-runtime/three.mjs';
window.qfRun = async (size, c) => {
  try {
    return await run(size, c);
  } catch (e) {
    live?.dispose();  // a case that failed half-way frees its files: the next case's count starts clean
    live = null;
    return { error: String(e.message ?? e) };
  }
};
let live = null;
const renderers = new Map();
async function run(size, c) {
  // One renderer for every case (its compiled programs are kept), the memory counted per case.
  if (!renderers.has(size)) {
    const r = new THREE.WebGLRenderer({ antialias: false });
    r.setSize(size, size, false);
    renderers.set(size, r);
  }
  const renderer = renderers.get(size);
  const camera = new THREE.PerspectiveCamera(60, 1, 0.01, 1e6);
  const scene = new THREE.Scene();
  scene.add(new THREE.AmbientLight(0xffffff, 1));
  // The app's own model for the chain's "asset" entries: a box it owns (never disposed by the loader).
  const asset = c.asset ? new THREE.Mesh(new THREE.BoxGeometry(2, 2, 2), new THREE.MeshBasicMaterial()) : null;
  if (asset) asset.name = 'app-asset';
  const ktx2Loader = c.ktx2 ? new KTX2Loader().setTranscoderPath('/three/examples/jsm/libs/basis/') : null;
  // three.js keeps one texture of its own for every physically based material (the DFG lookup
  // table): drawn once first, so that 'before' counts it.
  const warm = new THREE.Mesh(new THREE.PlaneGeometry(), new THREE.MeshStandardMaterial());
  renderer.render(warm, camera);
  warm.geometry.dispose();
  warm.material.dispose();
  const memory = () => ({ geometries: renderer.info.memory.geometries, textures: renderer.info.memory.textures });
  const before = memory();
  const t0 = performance.now();
  // The toolchain's decoders: three.js's own copies, from /three/.
  const dracoLoader = c.decoders ? new DRACOLoader().setDecoderPath('/three/examples/jsm/libs/draco/gltf/') : null;
  const meshoptDecoder = c.decoders ? MeshoptDecoder : null;
  const lod = await loadImpostorLOD(c.url, { renderer, camera, ktx2Loader, dracoLoader, meshoptDecoder, assetModel: asset, assetUrl: c.assetUrl, diagonal: c.diagonal });
  const loadMs = performance.now() - t0;
  live = lod;
  scene.add(lod.object);
  const samples = [];
  const at = async (d) => {
    camera.position.copy(lod.centre).add(new THREE.Vector3(0, 0, d));
    camera.lookAt(lod.centre);
    renderer.render(scene, camera);  // the renderer calls lod.object.update(camera)
    await lod.ready();
    renderer.render(scene, camera);
    const step = lod.steps[lod.level];
    samples.push({ d, file: step.kind === 'asset' ? 'asset' : step.file ?? 'level ' + lod.level, memory: memory() });
  };
  const t1 = performance.now();
  for (const d of c.distances) await at(d);
  for (const d of [...c.distances].reverse()) await at(d);
  const ms = performance.now() - t1;
  const switches = lod.switchDistances(camera);
  lod.dispose();
  live = null;
  renderer.render(scene, camera);
  const after = memory();
  const assetAlive = asset ? asset.geometry.attributes.position.count > 0 : null;
  ktx2Loader?.dispose();
  dracoLoader?.dispose();
  asset?.geometry.dispose();  // the app's, after the count
  // appAsset: what the app's box holds (it stays: the app owns it).
  return { samples, switches, before, after, loadMs, ms, assetAlive, appAsset: { geometries: 1, textures: 0 }, steps: lod.steps.map((s) => s.kind === 'asset' ? 'asset' : s.file ?? 'node ' + s.node) };
}
`;

const spec = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
const page = threePage(pageScript);
page.imports['qf-runtime/'] = '/qf-runtime/';
page.roots['/qf-runtime/'] = path.join(here, '..', '..', 'tools', 'qf-runtime');
const files = (p) => {
  const [name, ...rest] = p.split('/');
  return spec.dirs[name] === undefined ? null : path.join(spec.dirs[name], ...rest);
};
await withPage(chromium, page, files, async (tab) => {
  for (const c of spec.cases) console.log(JSON.stringify(await tab.evaluate(([s, k]) => window.qfRun(s, k), [spec.size, c])));
});
