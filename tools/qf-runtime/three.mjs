// A quasiflat bake in three.js in one call: loadImpostorLOD(url, options) reads a bake's
// manifest.json (or a `_lods.glb` with MSFT_lod), shows the file of the recommended chain for the
// object's on-screen size, switches at the chain's distances and frees what is not shown
// (docs/engines.md; tests/render/runtime_test.sh runs it in headless Chromium).
import { Box3, MathUtils, Object3D, Vector2, Vector3 } from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

import { Switcher, missingDecoders, openBake, pickStepKeeping, pixelsAt, switchDistances } from './chain.mjs';

// The object the renderer switches by itself: three.js's renderer calls update(camera) on every
// object with isLOD and autoUpdate while it walks the scene (as it does for THREE.LOD).
class ImpostorLODObject extends Object3D {
  constructor(lod) {
    super();
    this.type = 'ImpostorLOD';
    this.isLOD = true;
    this.autoUpdate = true;
    this.lod = lod;
  }

  update(camera) {
    this.lod.update(camera);
  }
}

// url: a manifest.json or a STEM_lods.glb (relative to the page or absolute). options:
//   renderer      the WebGLRenderer: its drawing-buffer height gives the screen's pixels (or screenHeight)
//                 and KTX2Loader.detectSupport is called with it
//   camera        a camera to pick the first file for (without one: the farthest step first)
//   ktx2Loader    a KTX2Loader with its transcoder path: needed by --textures ktx2 bakes
//   meshoptDecoder, dracoLoader   for files that glTF-Transform or gltfpack compressed
//   assetModel    the app's own model (an Object3D) for the chain's entries of kind "asset": added
//                 under lod.object where shown, removed where not, never disposed (the app owns it)
//   assetUrl      or a glTF of the model, loaded where shown and disposed where not
//   screenHeight  the screen's height in pixels, where no renderer is passed
//   diagonal      a `_lods.glb`'s input diagonal (the manifest's bounding_box_diagonal), which the
//                 file does not carry; without it, its finest level's bounds
//   lodScreenHeight  the screen height a `_lods.glb`'s MSFT_screencoverage was computed for
//                 (qf-bake --lod-screen-height; default 1080, as qf-bake's)
//   hysteresis    keep the file shown while the size is within this fraction of its band (default 0:
//                 switch exactly at the manifest's distances; 0.05 stops a camera that hovers at a
//                 switch distance from loading and freeing two files at every crossing)
//   manager       a LoadingManager for the GLTFLoader
// Without an asset, the "asset" entries' bands go to the nearest baked file. A `_lods.glb` carries
// no asset entries (pass the manifest to use the app's model). Resolves once the first file is shown.
export async function loadImpostorLOD(url, options = {}) {
  const { renderer = null, camera = null, ktx2Loader = null, meshoptDecoder = null, dracoLoader = null,
          assetModel = null, assetUrl = null, screenHeight = null, diagonal = null, lodScreenHeight = 1080, hysteresis = 0,
          manager } = options;
  if (!renderer && !screenHeight) throw new Error('loadImpostorLOD: pass renderer (or screenHeight) for the screen\'s pixels');
  const absolute = new URL(url, globalThis.location?.href).href;
  const bake = await openBake(absolute, { hasAsset: Boolean(assetModel || assetUrl), diagonal, lodScreenHeight });
  const loader = new GLTFLoader(manager);
  if (ktx2Loader) {
    loader.setKTX2Loader(ktx2Loader);
    if (renderer) ktx2Loader.detectSupport(renderer);
  }
  if (meshoptDecoder) loader.setMeshoptDecoder(meshoptDecoder);
  if (dracoLoader) loader.setDRACOLoader(dracoLoader);
  const decoders = {
    KHR_texture_basisu: { passed: Boolean(ktx2Loader), option: 'ktx2Loader (a KTX2Loader)' },
    EXT_meshopt_compression: { passed: Boolean(meshoptDecoder), option: 'meshoptDecoder (MeshoptDecoder)' },
    KHR_draco_mesh_compression: { passed: Boolean(dracoLoader), option: 'dracoLoader (a DRACOLoader)' },
  };

  const lod = {};
  const object = new ImpostorLODObject(lod);
  const resourcePath = new URL('.', absolute).href;
  const switcher = new Switcher({
    async load(i) {
      const step = bake.steps[i];
      if (step.kind === 'asset') return assetModel ? { object: assetModel, owned: false } : { object: (await loader.loadAsync(assetUrl)).scene, owned: true };
      const { buffer, json, name } = await bake.glb(i);
      const missing = missingDecoders(json, decoders, name);
      if (missing) throw new Error(missing);
      return { object: (await loader.parseAsync(buffer, resourcePath)).scene, owned: true, file: name };
    },
    show: (t) => object.add(t.object),
    hide: (t) => object.remove(t.object),
    free: (t) => t.owned && disposeTree(t.object),
  });

  // Every step the app's model alone: the centre is its bounds' (in lod.object's frame).
  let centre;
  if (bake.centre) centre = new Vector3(...bake.centre);
  else {
    const model = assetModel ?? (await loader.loadAsync(assetUrl)).scene;
    centre = new Box3().setFromObject(model).getCenter(new Vector3());
    if (!assetModel) disposeTree(model);
  }
  const size = new Vector2();
  const eye = new Vector3();
  const heightOf = () => screenHeight ?? renderer.getDrawingBufferSize(size).y;
  // The vertical field of view in radians (zoom included); an orthographic camera: null.
  const fovOf = (cam) => (cam.isPerspectiveCamera ? MathUtils.degToRad(cam.getEffectiveFOV()) : null);

  Object.assign(lod, {
    object,
    steps: bake.steps,
    diagonal: bake.diagonal,
    centre,
    // The object's size on screen in pixels (its bounding-box diagonal) seen from `cam`.
    pixels(cam) {
      object.updateWorldMatrix(true, false);
      const local = object.worldToLocal(cam.getWorldPosition(eye));
      const h = heightOf();
      if (cam.isOrthographicCamera) return (bake.diagonal * h * cam.zoom) / (cam.top - cam.bottom);
      return pixelsAt(bake.diagonal, local.distanceTo(centre), h, fovOf(cam));
    },
    // Picks the step for `cam` and starts loading it where it is not shown; returns its index.
    update(cam) {
      const px = lod.pixels(cam);
      const i = pickStepKeeping(bake.steps, px, switcher.current, hysteresis);
      switcher.want(i);
      return i;
    },
    // The distances from lod.centre (in lod.object's units) at which each step takes over, for
    // `cam`'s field of view and this screen (step 0: 0).
    switchDistances(cam) {
      return switchDistances(bake.steps, bake.diagonal, heightOf(), fovOf(cam));
    },
    ready: () => switcher.ready(),
    dispose() {
      switcher.dispose();
      object.removeFromParent();
    },
  });
  // The step shown (an index into lod.steps; -1 before the first arrives) and the last load's error.
  Object.defineProperties(lod, {
    level: { get: () => switcher.current, enumerable: true },
    error: { get: () => switcher.error, enumerable: true },
  });
  if (camera) lod.update(camera);
  else switcher.want(bake.steps.length - 1);
  await switcher.ready();
  return lod;
}

// Frees what a loaded file holds on the GPU and in the page: geometries, materials, their textures
// (and the ImageBitmaps three.js's GLTFLoader decodes images into, which the garbage collector
// does not free).
function disposeTree(root) {
  const textures = new Set(), materials = new Set();
  root.traverse((o) => {
    o.geometry?.dispose();
    for (const m of [o.material].flat()) if (m) materials.add(m);
  });
  for (const m of materials) {
    for (const v of Object.values(m)) if (v && v.isTexture) textures.add(v);
    m.dispose();
  }
  for (const t of textures) {
    t.dispose();
    const data = t.source?.data;
    if (typeof ImageBitmap !== 'undefined' && data instanceof ImageBitmap) data.close();
  }
  root.removeFromParent();
}
