// Runs tools/qf-runtime/babylon.mjs (loadImpostorLOD) in headless Chromium on bake folders and prints, per
// case, a line of JSON: the file shown and the engine's memory (its GPU textures, the scene's
// geometries and meshes) with the camera at each distance from lod.centre (fov 60, a SIZE x SIZE
// canvas), first outward, then back. Each position is drawn (lod.update runs before the frame), then
// drawn again once lod.ready() says the file for it is shown. tests/render/runtime_test.sh writes the
// cases (the same CASES.json as scripts/three-render/runtime-check.mjs) and checks the answers.
// usage: node runtime-check.mjs CASES.json
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { chromium, babylonPage } from './browser.mjs';
import { withPage } from '../web-render/page.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const pageScript = `
import { TargetCamera } from '@babylonjs/core/Cameras/targetCamera.js';
import { HemisphericLight } from '@babylonjs/core/Lights/hemisphericLight.js';
import { PBRMaterial } from '@babylonjs/core/Materials/PBR/pbrMaterial.js';
import { Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { CreateBox } from '@babylonjs/core/Meshes/Builders/boxBuilder.js';
import { createEngine, createScene } from 'qf/scene.mjs';
import { loadImpostorLOD } from 'qf-runtime/babylon.mjs';
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
const engines = new Map();
async function run(size, c) {
  // One engine for every case (its compiled shaders are kept: SwiftShader takes seconds per PBR
  // variant), a scene of its own per case.
  if (!engines.has(size)) {
    const canvas = document.createElement('canvas');
    canvas.width = size; canvas.height = size;
    engines.set(size, createEngine(canvas));
  }
  const engine = engines.get(size);
  const scene = createScene(engine);
  // A left-handed scene (Babylon's default): the glTF loader turns each file under its __root__.
  if (c.leftHanded) scene.useRightHandedSystem = false;
  const camera = new TargetCamera('camera', new Vector3(0, 0, 1), scene);
  camera.fov = Math.PI / 3;
  camera.minZ = 0.01;
  camera.maxZ = 1e6;
  new HemisphericLight('light', new Vector3(0, 1, 0), scene);
  // Babylon keeps a texture of its own for PBR materials (the BRDF lookup table): drawn once first,
  // so that 'before' counts it.
  const warm = CreateBox('warm', {}, scene);
  warm.material = new PBRMaterial('warm', scene);
  await scene.whenReadyAsync();
  scene.render();
  warm.material.dispose();
  warm.dispose();
  const memory = () => ({ textures: engine.getLoadedTexturesCache().length, geometries: scene.geometries.length, meshes: scene.meshes.length });
  const before = memory();
  // The app's own model for the chain's "asset" entries: a box it owns (never disposed by the loader).
  const asset = c.asset ? CreateBox('app-asset', { size: 2 }, scene) : null;
  const t0 = performance.now();
  // The toolchain's decoders: the copies @babylonjs/core ships, from /babylon/core/assets/.
  const here = (p) => new URL(p, location.href).href;
  const decoders = c.decoders ? {
    meshopt: { url: here('/babylon/core/assets/meshopt/meshopt_decoder.js') },
    draco: { wasmUrl: here('/babylon/core/assets/Draco/draco_wasm_wrapper_gltf.js'), wasmBinaryUrl: here('/babylon/core/assets/Draco/draco_decoder_gltf.wasm'),
             fallbackUrl: here('/babylon/core/assets/Draco/draco_decoder_gltf.js'), numWorkers: 0 },
  } : {};
  const lod = await loadImpostorLOD(c.url, { scene, camera, assetModel: asset, assetUrl: c.assetUrl, diagonal: c.diagonal, ...decoders });
  const loadMs = performance.now() - t0;
  live = lod;
  const samples = [];
  const at = async (d) => {
    camera.position = lod.centre.add(new Vector3(0, 0, d));
    camera.setTarget(lod.centre.clone());
    scene.render();  // lod.update runs before the frame (onBeforeRenderObservable)
    await lod.ready();
    scene.render();
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
  scene.render();
  const after = memory();
  const assetAlive = asset ? !asset.isDisposed() && asset.getTotalVertices() > 0 : null;
  scene.dispose();
  // appAsset: what the app's box holds (it stays: the app owns it).
  return { samples, switches, before, after, loadMs, ms, assetAlive, appAsset: { textures: 0, geometries: 1, meshes: 1 },
           steps: lod.steps.map((s) => s.kind === 'asset' ? 'asset' : s.file ?? 'node ' + s.node) };
}
`;

const spec = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
const page = babylonPage(pageScript);
page.imports['qf-runtime/'] = '/qf-runtime/';
page.roots['/qf-runtime/'] = path.join(here, '..', '..', 'tools', 'qf-runtime');
const files = (p) => {
  const [name, ...rest] = p.split('/');
  return spec.dirs[name] === undefined ? null : path.join(spec.dirs[name], ...rest);
};
await withPage(chromium, page, files, async (tab) => {
  for (const c of spec.cases) console.log(JSON.stringify(await tab.evaluate(([s, k]) => window.qfRun(s, k), [spec.size, c])));
});
