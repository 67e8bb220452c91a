// The Babylon.js side of the engine method's conventions, shared by render.mjs and the LOD check:
// an engine and scene whose colours are the material's (no tone mapping, exposure 1, contrast 1,
// exact sRGB), in glTF's right-handed frame, and local Draco decoder files.
import { Engine } from '@babylonjs/core/Engines/engine.js';
import { Scene } from '@babylonjs/core/scene.js';
import { BaseTexture } from '@babylonjs/core/Materials/Textures/baseTexture.js';
import { SceneLoaderFlags } from '@babylonjs/core/Loading/sceneLoaderFlags.js';
import { DracoDecoder } from '@babylonjs/core/Meshes/Compression/dracoDecoder.js';
import '@babylonjs/loaders/glTF';

// The Draco decoder ships in @babylonjs/core/assets; by default Babylon fetches it from its CDN.
// Decoded on the page's thread (numWorkers 0): no worker start-up for a few small files.
DracoDecoder.DefaultConfiguration = {
  wasmUrl: new URL('/babylon/core/assets/Draco/draco_wasm_wrapper_gltf.js', location.href).href,
  wasmBinaryUrl: new URL('/babylon/core/assets/Draco/draco_decoder_gltf.wasm', location.href).href,
  fallbackUrl: new URL('/babylon/core/assets/Draco/draco_decoder_gltf.js', location.href).href,
  numWorkers: 0,
};

// Babylon filters textures 4x anisotropically by default; the engine method (like three.js) does
// not, and at grazing angles the wider footprint moves where the alpha test cuts (the octahedron
// level's IoU 0.0033 off the engine method's, the bush level's renders at IoU 0.981 of each other).
BaseTexture.DEFAULT_ANISOTROPIC_FILTERING_LEVEL = 1;

// No loading screen over the canvas (it is an HTML overlay, and a module of its own to import).
SceneLoaderFlags.ShowLoadingScreen = false;

export function createEngine(canvas) {
  // useExactSrgbConversions: sRGB textures and output by the sRGB curve, as the engine method does,
  // not Babylon's default power-2.2 approximation (which left the bush level 6 levels of 255 bluer
  // and the sphere level 0.6 dB off the engine method's PSNR, against 0.26 dB exact).
  return new Engine(canvas, false, { preserveDrawingBuffer: true, alpha: false, stencil: false, useExactSrgbConversions: true });
}

export function createScene(engine) {
  const scene = new Scene(engine);
  // glTF and the engine method's cameras are right-handed; in Babylon's default left-handed scene
  // the loader would convert the model under its __root__ node, and the cameras would not match.
  scene.useRightHandedSystem = true;
  const ip = scene.imageProcessingConfiguration;
  ip.toneMappingEnabled = false;  // Babylon's defaults, set so that a change of default shows here
  ip.exposure = 1;
  ip.contrast = 1;
  ip.vignetteEnabled = false;
  ip.colorCurvesEnabled = false;
  ip.ditheringEnabled = false;
  return scene;
}
