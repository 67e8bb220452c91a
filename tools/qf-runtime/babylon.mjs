// A quasiflat bake in Babylon.js in one call: loadImpostorLOD(url, options) reads a bake's
// manifest.json (or a `_lods.glb` with MSFT_lod), shows the file of the recommended chain for the
// object's on-screen size, switches at the chain's distances and disposes what is not shown
// (docs/engines.md; tests/render/runtime_test.sh runs it in headless Chromium). The same steps and
// switching as three.mjs (chain.mjs); Babylon's own LOD (Mesh.addLODLevel) is not used: it keeps
// every level loaded and switches single meshes only.
import { Camera } from '@babylonjs/core/Cameras/camera.js';
import { LoadAssetContainerAsync } from '@babylonjs/core/Loading/sceneLoader.js';
import { Matrix, Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { DracoDecoder } from '@babylonjs/core/Meshes/Compression/dracoDecoder.js';
import { MeshoptCompression } from '@babylonjs/core/Meshes/Compression/meshoptCompression.js';
import { TransformNode } from '@babylonjs/core/Meshes/transformNode.js';
import { KhronosTextureContainer2 } from '@babylonjs/core/Misc/khronosTextureContainer2.js';
import '@babylonjs/loaders/glTF';

import { Switcher, openBake, pickStepKeeping, pixelsAt, switchDistances } from './chain.mjs';

// url: a manifest.json or a STEM_lods.glb (relative to the page or absolute). options:
//   scene         the Scene to load into (required); lod.object is a TransformNode in it
//   camera        the camera to pick by (default: scene.activeCamera at each frame)
//   autoUpdate    switch by itself before each frame (scene.onBeforeRenderObservable; default true)
//   ktx2          Babylon's KTX2 decoder files, {jsDecoderModule, wasmMSCTranscoder, ...}: set as
//                 KhronosTextureContainer2.URLConfig (default: Babylon's CDN), for --textures ktx2 bakes
//   meshopt       {url} of the meshopt decoder: MeshoptCompression.Configuration.decoder
//   draco         {wasmUrl, wasmBinaryUrl, fallbackUrl, numWorkers}: DracoDecoder.DefaultConfiguration
//                 (Babylon's decoders are settings of the whole page: these set them before loading)
//   assetModel    the app's own model (a TransformNode or Mesh) for the chain's entries of kind
//                 "asset": parented under lod.object and enabled where shown, disabled where not,
//                 never disposed (the app owns it)
//   assetUrl      or a glTF of the model, loaded where shown and disposed where not
//   screenHeight  the screen's height in pixels (default: the engine's render height)
//   diagonal, lodScreenHeight   for a `_lods.glb`, as in three.mjs
//   hysteresis    as in three.mjs (default 0: switch exactly at the manifest's distances)
// Without an asset, the "asset" entries' bands go to the nearest baked file. Resolves once the first
// file is shown.
export async function loadImpostorLOD(url, options = {}) {
  const { scene, camera = null, autoUpdate = true, ktx2 = null, meshopt = null, draco = null, assetModel = null,
          assetUrl = null, screenHeight = null, diagonal = null, lodScreenHeight = 1080, hysteresis = 0 } = options;
  if (!scene) throw new Error('loadImpostorLOD: pass the scene');
  if (ktx2) KhronosTextureContainer2.URLConfig = { ...KhronosTextureContainer2.URLConfig, ...ktx2 };
  if (meshopt) MeshoptCompression.Configuration = { decoder: { ...MeshoptCompression.Configuration.decoder, ...meshopt } };
  if (draco) DracoDecoder.DefaultConfiguration = { ...DracoDecoder.DefaultConfiguration, ...draco };
  const absolute = new URL(url, globalThis.location?.href).href;
  const bake = await openBake(absolute, { hasAsset: Boolean(assetModel || assetUrl), diagonal, lodScreenHeight });
  const rootUrl = new URL('.', absolute).href;
  const assetAbsolute = assetUrl && new URL(assetUrl, globalThis.location?.href).href;
  const object = new TransformNode('impostorLOD', scene);

  // A loaded file: an AssetContainer whose root nodes go under lod.object (the glTF loader's
  // __root__, which turns glTF's right-handed frame into a left-handed scene's).
  // A baked file comes as bytes (a GLB, its images inside), the app's model by its URL (any format
  // Babylon.js reads, found by its extension).
  const loadContainer = async (source, name) => {
    const options = typeof source === 'string' ? {} : { rootUrl, pluginExtension: '.glb', name };
    const container = await LoadAssetContainerAsync(source, scene, options);
    const roots = [...container.meshes, ...container.transformNodes].filter((n) => !n.parent);
    return { container, roots, owned: true };
  };
  const switcher = new Switcher({
    async load(i) {
      const step = bake.steps[i];
      if (step.kind === 'asset') {
        if (assetModel) return { roots: [assetModel], owned: false };
        return loadContainer(assetAbsolute);
      }
      const { buffer, name } = await bake.glb(i);
      return loadContainer(new Uint8Array(buffer), name);
    },
    show(t) {
      t.container?.addAllToScene();
      for (const n of t.roots) {
        n.parent = object;
        n.setEnabled(true);
      }
    },
    hide(t) {
      for (const n of t.roots) n.setEnabled(false);
    },
    // Disposing the container disposes its meshes, geometries, materials and textures.
    free: (t) => t.owned && t.container.dispose(),
  });

  // The centre in lod.object's frame: a left-handed scene's __root__ turns glTF's x.
  let centre;
  if (bake.centre) {
    const [x, y, z] = bake.centre;
    centre = scene.useRightHandedSystem ? new Vector3(x, y, z) : new Vector3(-x, y, z);
  } else {
    // Every step the app's model: the centre of its bounds.
    const loaded = assetModel ? null : await loadContainer(assetAbsolute);
    const { min, max } = (assetModel ?? loaded.roots[0]).getHierarchyBoundingVectors(true);
    centre = Vector3.TransformCoordinates(min.add(max).scale(0.5), Matrix.Invert(object.computeWorldMatrix(true)));
    loaded?.container.dispose();
  }
  const engine = scene.getEngine();
  const heightOf = (cam) => screenHeight ?? engine.getRenderHeight() * cam.viewport.height;
  // The vertical field of view in radians (Babylon's fov is horizontal in FOVMODE_HORIZONTAL_FIXED).
  const fovOf = (cam) => {
    if (cam.fovMode !== Camera.FOVMODE_HORIZONTAL_FIXED) return cam.fov;
    return 2 * Math.atan(Math.tan(cam.fov / 2) / engine.getAspectRatio(cam));
  };

  const lod = {
    object,
    steps: bake.steps,
    diagonal: bake.diagonal,
    centre,
    // The object's size on screen in pixels (its bounding-box diagonal) seen from `cam`.
    pixels(cam) {
      const eye = cam.getWorldMatrix().getTranslation();
      const local = Vector3.TransformCoordinates(eye, Matrix.Invert(object.computeWorldMatrix(true)));
      const h = heightOf(cam);
      // Orthographic: Babylon's extents default to the render size in world units.
      if (cam.mode === Camera.ORTHOGRAPHIC_CAMERA) return (bake.diagonal * h) / ((cam.orthoTop ?? h / 2) - (cam.orthoBottom ?? -h / 2));
      return pixelsAt(bake.diagonal, Vector3.Distance(local, centre), h, fovOf(cam));
    },
    // Picks the step for `cam` and starts loading it where it is not shown; returns its index.
    update(cam = camera ?? scene.activeCamera) {
      if (!cam) return switcher.wanted;
      const i = pickStepKeeping(bake.steps, lod.pixels(cam), switcher.current, hysteresis);
      switcher.want(i);
      return i;
    },
    // The distances from lod.centre (in lod.object's units) at which each step takes over (step 0: 0).
    switchDistances(cam = camera ?? scene.activeCamera) {
      return switchDistances(bake.steps, bake.diagonal, heightOf(cam), fovOf(cam));
    },
    ready: () => switcher.ready(),
    dispose() {
      scene.onBeforeRenderObservable.remove(observer);
      switcher.dispose();
      if (assetModel?.parent === object) assetModel.parent = null;  // the app's, kept
      object.dispose(true);
    },
  };
  // The step shown (an index into lod.steps; -1 before the first arrives) and the last load's error.
  Object.defineProperties(lod, {
    level: { get: () => switcher.current, enumerable: true },
    error: { get: () => switcher.error, enumerable: true },
  });
  const observer = autoUpdate ? scene.onBeforeRenderObservable.add(() => lod.update()) : null;
  if (camera ?? scene.activeCamera) lod.update();
  else switcher.want(bake.steps.length - 1);
  await switcher.ready();
  return lod;
}
