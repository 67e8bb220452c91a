// The engine-free half of the runtime loaders (chain.mjs) under node: steps from a manifest and a
// `_lods.glb`, the pick at its bounds, GLB parts and bounds, the switching's order of load, show
// and free. ctest qf_runtime_chain; the engines themselves: tests/render/runtime_test.sh.
import assert from 'node:assert/strict';
import test from 'node:test';

import { Switcher, glbBounds, glbOfNode, pickStep, pickStepKeeping, readGlb, stepsFromLodGlb, stepsFromManifest, switchDistances } from '../chain.mjs';

const entry = (file, kind, max) => ({ file, kind, max_pixels: max });
const chain = (...entries) => ({ bounding_box_diagonal: 2, levels: [], recommended_chain: { chain: entries } });

test('asset entries: the app model where passed, else their band goes to the nearer file', () => {
  const m = chain(entry('in.ply', 'asset', null), entry('a.glb', 'impostor_level', 256), entry('in.ply', 'asset', 128),
                  entry('b.glb', 'mesh_lod', 64));
  assert.deepEqual(stepsFromManifest(m, false).map((s) => [s.file, s.max]), [['a.glb', null], ['b.glb', 64]]);
  assert.deepEqual(stepsFromManifest(m, true).map((s) => [s.kind, s.max]),
                   [['asset', null], ['impostor_level', 256], ['asset', 128], ['mesh_lod', 64]]);
  // Dropping the asset between two entries of one file leaves one step of it.
  const twice = chain(entry('a.glb', 'impostor_level', null), entry('in.ply', 'asset', 128), entry('a.glb', 'impostor_level', 64));
  assert.deepEqual(stepsFromManifest(twice, false).map((s) => s.file), ['a.glb']);
  // A cheap asset's chain is the asset alone: nothing to show without the app's model.
  assert.throws(() => stepsFromManifest(chain(entry('in.glb', 'asset', null)), false), /assetModel/);
});

test('no chain: the levels finest first up to their max_screen_pixels, never claiming more than a finer one', () => {
  const m = { bounding_box_diagonal: 2, levels: [
    { file: 'L8.glb', primitives: 30, max_screen_pixels: 90 }, { file: 'L6.glb', primitives: 1000, max_screen_pixels: 500 },
    { file: 'L7.glb', primitives: 300, max_screen_pixels: 120 }, { file: 'L9.glb', primitives: 10, max_screen_pixels: 0 }] };
  assert.deepEqual(stepsFromManifest(m, false).map((s) => [s.file, s.max]), [['L6.glb', null], ['L7.glb', 120], ['L8.glb', 90]]);
  assert.deepEqual(stepsFromManifest(m, true).map((s) => [s.kind, s.max]), [['asset', null], ['impostor_level', 500], ['impostor_level', 120], ['impostor_level', 90]]);
  m.levels[0].max_screen_pixels = 200;  // a coarser level claiming more than a finer one is clamped
  assert.deepEqual(stepsFromManifest(m, false).map((s) => s.max), [null, 120, 120]);
});

test('the pick: a step is shown at its max and below, down to the next one\'s max', () => {
  const steps = [{ max: null }, { max: 256 }, { max: 128 }];
  assert.deepEqual([1e9, 257, 256, 200, 128.5, 128, 1, 0].map((px) => pickStep(steps, px)), [0, 0, 1, 1, 1, 2, 2, 2]);
});

test('switch distances: the manifest\'s formula, D * H / (2 tan(fov / 2) * pixels)', () => {
  const d = switchDistances([{ max: null }, { max: 128 }], 3.8816063, 1080, Math.PI / 3);
  assert.equal(d[0], 0);
  assert.ok(Math.abs(d[1] - 28.3632) < 1e-4, d[1]);  // the torus chain's switch_distance at 128 px
});

// A GLB of one buffer: two nodes (the second under MSFT_lod), each a mesh of one triangle.
function lodGlb() {
  const bin = new Uint8Array(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer);
  const json = {
    asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], extensionsUsed: ['MSFT_lod'],
    nodes: [{ mesh: 0, extensions: { MSFT_lod: { ids: [1] } }, extras: { MSFT_screencoverage: [0.25, 0] } },
            { mesh: 1, translation: [10, 0, 0], scale: [2, 2, 2] }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }, { primitives: [{ attributes: { POSITION: 1 } }] }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] },
                { bufferView: 0, componentType: 5123, normalized: true, count: 3, type: 'VEC3', min: [0, 0, 0], max: [65535, 32767.5, 0] }],
    bufferViews: [{ buffer: 0, byteLength: bin.length }], buffers: [{ byteLength: bin.length }],
  };
  const { json: back, bin: b } = readGlb(glbOfNode(json, bin, 0));
  assert.deepEqual(back.scenes, [{ nodes: [0] }]);
  return { json, bin, glbJson: back, glbBin: b };
}

test('a _lods.glb: its levels by coverage of the bake\'s screen; each a file of its own; bounds through transforms', () => {
  const { json, bin, glbBin } = lodGlb();
  assert.deepEqual(glbBin, bin);
  assert.deepEqual(stepsFromLodGlb(json, 1080).map((s) => [s.node, s.max]), [[0, null], [1, 270]]);
  const part = readGlb(glbOfNode(json, bin, 1)).json;
  assert.deepEqual(part.scenes, [{ nodes: [1] }]);
  assert.deepEqual(part.extensionsUsed, []);
  assert.equal(part.nodes[0].extensions, undefined);  // MSFT_lod off the (former) root
  assert.deepEqual(glbBounds(json, 0), { min: [0, 0, 0], max: [1, 1, 0] });
  // Node 1: a quantized accessor (1 and 0.5 once normalised) scaled by 2 and moved by 10 in x.
  const b = glbBounds(json, 1);
  assert.deepEqual(b.min, [10, 0, 0]);
  assert.ok(Math.abs(b.max[0] - 12) < 1e-9 && Math.abs(b.max[1] - 1) < 1e-4, JSON.stringify(b));
});

test('switching: the shown step stays until the next arrives, then is freed; a failed load is not retried each frame', async () => {
  const log = [];
  const pending = new Map();
  const engine = {
    load: (i) => new Promise((resolve, reject) => pending.set(i, { resolve, reject })),
    show: (t) => log.push(`show ${t}`),
    hide: (t) => log.push(`hide ${t}`),
    free: (t) => log.push(`free ${t}`),
  };
  const s = new Switcher(engine);
  s.want(0);
  s.want(0);
  assert.equal(pending.size, 1);  // one load at a time
  pending.get(0).resolve('f0');
  await s.ready();
  assert.equal(s.current, 0);
  s.want(2);
  assert.equal(s.current, 0);  // still shown while 2 loads
  s.want(1);  // moved on: 2 is shown when it arrives, then 1 loads
  pending.get(2).resolve('f2');
  await new Promise((r) => setTimeout(r, 0));
  assert.equal(s.current, 2);
  pending.get(1).resolve('f1');
  await s.ready();
  assert.deepEqual(log, ['show f0', 'hide f0', 'free f0', 'show f2', 'hide f2', 'free f2', 'show f1']);
  pending.clear();
  s.want(0);
  pending.get(0).reject(new Error('404'));
  await assert.rejects(s.ready(), /404/);
  pending.clear();
  s.want(0);
  assert.equal(pending.size, 0);  // not fetched again at every frame
  assert.equal(s.current, 1);  // and what was shown stays
  s.dispose();
  assert.deepEqual(log.slice(-2), ['hide f1', 'free f1']);
});

test('hysteresis: the step shown stays within a factor 1 + h of its band, and moves beyond it', () => {
  const steps = [{ max: null }, { max: 100 }, { max: 50 }];
  assert.equal(pickStepKeeping(steps, 99, 0, 0), 1);  // none: exactly at the bounds
  assert.equal(pickStepKeeping(steps, 99, 0, 0.05), 0);  // 99 * 1.05 > 100: 0 stays
  assert.equal(pickStepKeeping(steps, 95, 0, 0.05), 1);
  assert.equal(pickStepKeeping(steps, 101, 1, 0.05), 1);  // 101 / 1.05 <= 100: 1 stays
  assert.equal(pickStepKeeping(steps, 106, 1, 0.05), 0);
  assert.equal(pickStepKeeping(steps, 30, 0, 0.05), 2);  // a jump over a band
  assert.equal(pickStepKeeping(steps, 99, -1, 0.05), 1);  // nothing shown yet: the plain pick
});
