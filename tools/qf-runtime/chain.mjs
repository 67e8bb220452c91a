// The engine-free half of the runtime loaders (three.mjs, babylon.mjs): a bake's chain of files as
// steps by on-screen size, the pick for a size, and the few GLB reads they need (a part of a
// `_lods.glb` as a file of its own, the bounds of a node from its accessors' min/max).
//
// Sizes: a bake's manifest measures the object's on-screen size as its bounding-box diagonal D in
// pixels; at distance d from the centre, with a vertical field of view fov on a screen H pixels
// high, that is D * H / (2 d tan(fov / 2)) (docs/manifest.md, baker/measure/chain.cpp).

// 1. Steps: [{file, kind, max, node?}] nearest first; step i is shown while the object spans at
// most `max` pixels (null: any size) and more than step i+1's `max`.

// From manifest.json. hasAsset: the app passes its own model for the entries of kind "asset" (the
// input itself, at the sizes where no baked file holds). Without one, those entries leave their
// band to the nearer file (the farther one where no nearer file exists): a baked file is shown
// rather than nothing.
export function stepsFromManifest(manifest, hasAsset) {
  let steps;
  if (manifest.recommended_chain) {
    steps = manifest.recommended_chain.chain.map((e) => ({ file: e.kind === 'asset' ? null : e.file, kind: e.kind, max: e.max_pixels }));
  } else {
    // --no-chain or --no-measure: the impostor levels, finest first, each shown up to the size at which it
    // holds (max_screen_pixels; 0: at none, left out); above the finest one's, the asset where there is one.
    steps = [...manifest.levels].filter((l) => l.max_screen_pixels > 0).sort((a, b) => b.primitives - a.primitives)
      .map((l) => ({ file: l.file, kind: 'impostor_level', max: l.max_screen_pixels }));
    if (steps.length) steps.unshift({ file: null, kind: 'asset', max: null });
  }
  if (!hasAsset) steps = withoutAsset(steps);
  return normalised(steps, manifest.recommended_chain ? 'the recommended chain' : 'the levels');
}

function withoutAsset(steps) {
  const out = [];
  for (const s of steps) {
    if (s.kind !== 'asset') out.push({ ...s });
    // An asset entry's band goes to the nearer file: dropping the entry does that, as a file is
    // shown down to the next step's `max`. Leading asset entries: the first file takes any size.
  }
  if (out.length) out[0].max = null;
  return out;
}

// Merges neighbours of one file (what dropping an asset entry between them leaves), makes `max`
// non-increasing (a farther step never claims a larger size than a nearer one) and checks that
// something is left to show.
function normalised(steps, what) {
  const out = [];
  for (const s of steps) {
    const last = out[out.length - 1];
    if (last && last.file === s.file && last.kind === s.kind && last.node === s.node) continue;
    const prev = out.length ? out[out.length - 1].max : null;
    out.push({ ...s, max: out.length === 0 ? null : prev === null ? s.max : Math.min(s.max, prev) });
  }
  if (!out.length) throw new Error(`${what} holds no file to show: pass the app's own model (assetModel or assetUrl)`);
  return out;
}

// From a `_lods.glb`'s JSON: the scene's root node and the nodes its MSFT_lod names, finest first;
// MSFT_screencoverage[i] is the coverage down to which part i is shown (the last 0): the object's
// pixels over the height of the screen the bake computed it for (qf-bake --lod-screen-height,
// 1080; the manifest's lod_file.screen_height). The pixels are what the bake measured a file to
// hold at, so they, not the fraction of the screen, decide on a screen of another height.
export function stepsFromLodGlb(json, lodScreenHeight = 1080) {
  const scene = json.scenes[json.scene ?? 0];
  if (!scene || scene.nodes.length !== 1) throw new Error('a _lods.glb has one root node in its scene');
  const root = json.nodes[scene.nodes[0]];
  const ids = [scene.nodes[0], ...(root.extensions?.MSFT_lod?.ids ?? [])];
  const coverage = root.extras?.MSFT_screencoverage ?? [];
  if (ids.length > 1 && coverage.length !== ids.length) throw new Error('MSFT_lod without one MSFT_screencoverage per level');
  const steps = ids.map((node, i) => ({ file: null, node, kind: 'lod_node', max: i === 0 ? null : coverage[i - 1] * lodScreenHeight }));
  return normalised(steps, 'the file');
}

// 2. The pick: the farthest step whose `max` the object's size in pixels does not exceed.
export function pickStep(steps, size) {
  let i = 0;
  while (i + 1 < steps.length && size <= steps[i + 1].max) ++i;
  return i;
}

// The pick with hysteresis h (a fraction, 0: none): the step shown stays while the size is within a
// factor 1 + h of its band, so a camera that hovers at a switch distance does not load and free the
// two files at every crossing. h = 0 switches exactly at the manifest's distances.
export function pickStepKeeping(steps, size, current, h) {
  const i = pickStep(steps, size);
  if (h <= 0 || current < 0 || i === current) return i;
  const nearest = pickStep(steps, size * (1 + h)), farthest = pickStep(steps, size / (1 + h));
  return current >= nearest && current <= farthest ? current : i;
}

// The object's size on screen in pixels, D at distance d (model units) with a vertical field of view
// fovRadians on a screen heightPixels high. d = 0 (the camera at the centre): any size.
export function pixelsAt(diagonal, distance, heightPixels, fovRadians) {
  return distance > 0 ? (diagonal * heightPixels) / (2 * distance * Math.tan(fovRadians / 2)) : Infinity;
}

// Where step i (i >= 1) takes over: the distance at which the object spans its `max`.
export function switchDistances(steps, diagonal, heightPixels, fovRadians) {
  return steps.map((s, i) => {
    if (i === 0) return 0;
    return s.max > 0 ? (diagonal * heightPixels) / (2 * s.max * Math.tan(fovRadians / 2)) : Infinity;
  });
}

// 3. GLB reading. Returns {json, bin} (bin: the BIN chunk's bytes, or null).
export function readGlb(buffer) {
  const view = new DataView(buffer);
  if (buffer.byteLength < 20 || view.getUint32(0, true) !== 0x46546c67 || view.getUint32(4, true) !== 2)
    throw new Error('not a glTF 2.0 binary file');
  let json = null, bin = null;
  for (let at = 12; at + 8 <= buffer.byteLength;) {
    const length = view.getUint32(at, true), type = view.getUint32(at + 4, true);
    const bytes = new Uint8Array(buffer, at + 8, length);
    if (type === 0x4e4f534a) json = JSON.parse(new TextDecoder().decode(bytes));
    else if (type === 0x004e4942 && bin === null) bin = bytes;
    at += 8 + length + ((4 - (length % 4)) % 4);
  }
  if (!json) throw new Error('a GLB without a JSON chunk');
  return { json, bin };
}

// A GLB whose scene is node `node` of `json` alone, the same BIN chunk: one part of a `_lods.glb`
// as a file of its own, for an engine's ordinary glTF loader (three.js reads no MSFT_lod, and
// Babylon.js would load every level at once). MSFT_lod is taken off every node (a valid file
// names every extension its nodes use).
export function glbOfNode(json, bin, node) {
  const part = structuredClone(json);
  part.scenes = [{ nodes: [node] }];
  part.scene = 0;
  for (const n of part.nodes) {
    if (!n.extensions) continue;
    delete n.extensions.MSFT_lod;
    if (!Object.keys(n.extensions).length) delete n.extensions;
  }
  if (part.extensionsUsed) part.extensionsUsed = part.extensionsUsed.filter((e) => e !== 'MSFT_lod');
  const text = new TextEncoder().encode(JSON.stringify(part));
  const jsonLength = text.length + ((4 - (text.length % 4)) % 4);
  const binLength = bin ? bin.length + ((4 - (bin.length % 4)) % 4) : 0;
  const total = 12 + 8 + jsonLength + (bin ? 8 + binLength : 0);
  const out = new Uint8Array(total);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true);
  view.setUint32(4, 2, true);
  view.setUint32(8, total, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, 0x4e4f534a, true);
  out.set(text, 20);
  out.fill(0x20, 20 + text.length, 20 + jsonLength);  // JSON pads with spaces
  if (bin) {
    view.setUint32(20 + jsonLength, binLength, true);
    view.setUint32(24 + jsonLength, 0x004e4942, true);
    out.set(bin, 28 + jsonLength);
  }
  return out.buffer;
}

// The axis-aligned bounds {min, max} of the scene of `json` (or of node `node` and its children),
// in the file's frame, from the POSITION accessors' min/max (which glTF requires) through the node
// transforms. null where no mesh has positions.
export function glbBounds(json, node = null) {
  const box = { min: [Infinity, Infinity, Infinity], max: [-Infinity, -Infinity, -Infinity] };
  const roots = node === null ? json.scenes[json.scene ?? 0].nodes : [node];
  const visit = (index, parent) => {
    const n = json.nodes[index];
    const m = multiply(parent, nodeMatrix(n));
    if (n.mesh !== undefined)
      for (const p of json.meshes[n.mesh].primitives) {
        const a = json.accessors[p.attributes.POSITION];
        if (!a || !a.min || !a.max) continue;
        const [lo, hi] = [dequantised(a, a.min), dequantised(a, a.max)];
        for (let c = 0; c < 8; ++c) {
          const v = transform(m, [c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]]);
          for (let k = 0; k < 3; ++k) box.min[k] = Math.min(box.min[k], v[k]), box.max[k] = Math.max(box.max[k], v[k]);
        }
      }
    for (const child of n.children ?? []) visit(child, m);
  };
  for (const r of roots) visit(r, identity());
  return box.min[0] <= box.max[0] ? box : null;
}

// KHR_mesh_quantization: a normalized integer accessor's min/max are stored integers.
function dequantised(accessor, v) {
  if (!accessor.normalized) return v;
  const scale = { 5120: 127, 5121: 255, 5122: 32767, 5123: 65535 }[accessor.componentType] ?? 1;
  return v.map((x) => Math.max(x / scale, -1));
}

// Column-major 4x4 matrices, as glTF stores them.
const identity = () => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
function multiply(a, b) {
  const out = new Array(16).fill(0);
  for (let c = 0; c < 4; ++c) for (let r = 0; r < 4; ++r) for (let k = 0; k < 4; ++k) out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
  return out;
}
function nodeMatrix(n) {
  if (n.matrix) return n.matrix;
  const [x, y, z, w] = n.rotation ?? [0, 0, 0, 1];
  const [sx, sy, sz] = n.scale ?? [1, 1, 1];
  const [tx, ty, tz] = n.translation ?? [0, 0, 0];
  return [(1 - 2 * (y * y + z * z)) * sx, 2 * (x * y + z * w) * sx, 2 * (x * z - y * w) * sx, 0,
          2 * (x * y - z * w) * sy, (1 - 2 * (x * x + z * z)) * sy, 2 * (y * z + x * w) * sy, 0,
          2 * (x * z + y * w) * sz, 2 * (y * z - x * w) * sz, (1 - 2 * (x * x + y * y)) * sz, 0, tx, ty, tz, 1];
}
function transform(m, v) {
  return [0, 1, 2].map((r) => m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r]);
}

// The diagonal and the centre of a bounds.
export function diagonalOf(box) {
  return Math.hypot(box.max[0] - box.min[0], box.max[1] - box.min[1], box.max[2] - box.min[2]);
}
export function centreOf(box) {
  return [0, 1, 2].map((k) => (box.min[k] + box.max[k]) / 2);
}

// The required extensions of a file that the caller passed no decoder for, as a message naming the
// option to pass; '' where there is none. `have`: {extension: whether its decoder was passed}.
export function missingDecoders(json, have, file) {
  const missing = (json.extensionsRequired ?? []).filter((e) => e in have && !have[e].passed);
  return missing.length ? `${file} requires ${missing.join(', ')}: pass ${missing.map((e) => have[e].option).join(', ')}` : '';
}

// 4. The switching, engine-free: `engine` loads a step (load(i) -> a shown-able thing), shows and
// hides it (show(thing), hide(thing)) and frees it (free(thing): its GPU memory and references).
// One load at a time; the step shown stays shown until the wanted one has arrived (no frame
// without the object); a step that is no longer shown is freed at once ("unloading what is not
// shown": coming back to it loads it again).
export class Switcher {
  constructor(engine) {
    this.engine = engine;
    this.current = -1;  // the step shown
    this.wanted = -1;  // the step the last pick asked for
    this.loading = -1;  // the step being loaded
    this.error = null;  // the last load's error (the step shown stays)
    this.failed = -1;  // the step whose load failed: not tried again every frame
    this.shown = null;
    this.waiters = [];
    this.disposed = false;
  }

  want(i) {
    this.wanted = i;
    if (i !== this.current && this.loading < 0 && i !== this.failed) this.run();
  }

  // Resolves when the step wanted is the step shown (or rejects with the load's error).
  ready() {
    if (this.failed >= 0 && this.failed === this.wanted) return Promise.reject(this.error);
    if (this.loading < 0 && this.current === this.wanted) return Promise.resolve(this.current);
    return new Promise((resolve, reject) => this.waiters.push({ resolve, reject }));
  }

  async run() {
    while (!this.disposed && this.wanted !== this.current) {
      const i = this.wanted;
      this.loading = i;
      let thing;
      try {
        thing = await this.engine.load(i);
      } catch (e) {
        this.loading = -1;
        this.error = e;
        this.failed = i;
        for (const w of this.waiters.splice(0)) w.reject(e);
        return;
      }
      this.error = null;
      this.failed = -1;
      // Shown even where the wanted step moved on meanwhile (it was wanted a moment ago, and a
      // camera that keeps moving would otherwise never see a new step), unless the shown one is
      // wanted again.
      if (this.disposed || this.wanted === this.current) {
        this.engine.free(thing);
        continue;
      }
      if (this.shown) {
        this.engine.hide(this.shown);
        this.engine.free(this.shown);
      }
      this.engine.show(thing);
      this.shown = thing;
      this.current = i;
    }
    this.loading = -1;
    for (const w of this.waiters.splice(0)) w.resolve(this.current);
  }

  dispose() {
    this.disposed = true;
    if (this.shown) {
      this.engine.hide(this.shown);
      this.engine.free(this.shown);
    }
    this.shown = null;
    this.current = -1;
  }
}

// 5. A bake opened from its URL: a manifest.json (the recommended chain's files, each fetched when
// shown) or a `_lods.glb` (fetched once; each MSFT_lod level parsed as a file of its own when
// shown). Returns {steps, diagonal, centre, glb(i) -> {buffer, json, name}}: centre is the
// bounds' centre of a baked file's positions in its frame (null where every step is the app's
// model), the point distances are measured from.
export async function openBake(url, { hasAsset = false, diagonal = null, lodScreenHeight = 1080, fetchImpl = globalThis.fetch } = {}) {
  const get = async (u) => {
    const r = await fetchImpl(u);
    if (!r.ok) throw new Error(`${u}: HTTP ${r.status}`);
    return r;
  };
  if (/\.glb$/i.test(new URL(url).pathname)) {
    const buffer = await (await get(url)).arrayBuffer();
    const { json, bin } = readGlb(buffer);
    const steps = stepsFromLodGlb(json, lodScreenHeight);
    // The coverages were computed with the input's diagonal (the manifest's bounding_box_diagonal),
    // which the file does not carry: the caller's, else the finest level's own bounds (an impostor
    // level's quads reach past the input's: the torus's finest level spans 4.28 where the input
    // spans 3.88, and switches 10% farther out).
    const box = glbBounds(json, steps[0].node);
    if (!box) throw new Error(`${url}: its finest level has no positions`);
    const name = new URL(url).pathname.split('/').pop();
    return { steps, diagonal: diagonal ?? diagonalOf(box), centre: centreOf(box),
             glb: async (i) => ({ buffer: glbOfNode(json, bin, steps[i].node), json, name: `${name} (MSFT_lod level ${i})` }) };
  }
  const manifest = await (await get(url)).json();
  if (typeof manifest.bounding_box_diagonal !== 'number' || !Array.isArray(manifest.levels))
    throw new Error(`${url}: not a quasiflat manifest.json (no bounding_box_diagonal or levels)`);
  const steps = stepsFromManifest(manifest, hasAsset);
  let kept = null;  // the file the centre was read from, until the first load takes it
  const glb = async (i) => {
    const k = kept;
    kept = null;
    if (k && k.i === i) return k;
    const buffer = await (await get(new URL(steps[i].file, url).href)).arrayBuffer();
    return { i, buffer, json: readGlb(buffer).json, name: steps[i].file };
  };
  // The centre from the farthest baked file: usually the smallest, and the one shown first where
  // no camera is passed.
  let centre = null;
  const probe = [...steps.keys()].reverse().find((i) => steps[i].kind !== 'asset');
  if (probe !== undefined) {
    const k = await glb(probe);
    const box = glbBounds(k.json);
    if (box) centre = centreOf(box);
    kept = k;
  }
  return { steps, diagonal: manifest.bounding_box_diagonal, centre, glb };
}
