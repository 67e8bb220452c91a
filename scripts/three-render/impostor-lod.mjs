// Switching a bake's per-level files with THREE.LOD at the manifest's distances (docs/engines.md shows
// this file; tests/render/lod_test.sh runs it in headless Chromium).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

// baseUrl: the folder holding manifest.json and the .glb files; camera: a PerspectiveCamera;
// screenHeight: the viewport's height in pixels; asset: the app's own model (an Object3D, as it
// draws it), or null. The chain starts at the asset itself (its entries of kind "asset": the
// nearest sizes, where no baked file looks as good); without it those entries are left out and the
// nearest baked file is shown from 0.
export async function loadImpostorLOD(baseUrl, camera, screenHeight, asset = null) {
  const manifest = await (await fetch(baseUrl + 'manifest.json')).json();
  // Pixels per world unit at distance 1: an object of diagonal D at distance d spans D * z0 / d px.
  const z0 = screenHeight / (2 * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2));
  // The recommended chain (every bake but --no-chain or --no-measure: nearest first, each file
  // shown while the object spans at most max_pixels, null = any size); else the impostor levels,
  // finest first, each shown up to its max_screen_pixels (where its measured look holds; a level
  // that holds at no size measured, 0, is left out).
  const steps = manifest.recommended_chain
    ? manifest.recommended_chain.chain.filter((e, i) => e.kind !== 'asset' || (i === 0 && asset))
        .map((e) => ({ file: e.kind === 'asset' ? null : e.file, pixels: e.max_pixels }))
    : [...manifest.levels].filter((l) => l.max_screen_pixels > 0).sort((a, b) => b.primitives - a.primitives)
        .map((l) => ({ file: l.file, pixels: l.max_screen_pixels }));
  const lod = new THREE.LOD();  // THREE.LOD measures from its own position: the object's centre
  const loader = new GLTFLoader();
  const centre = new THREE.Vector3();
  for (const [i, step] of steps.entries()) {
    const object = step.file === null ? asset : (await loader.loadAsync(baseUrl + step.file)).scene;
    if (i === 0) new THREE.Box3().setFromObject(object).getCenter(centre);
    object.position.sub(centre);
    // Shown from the distance at which the object spans step.pixels on; the first from 0.
    const distance = i === 0 ? 0 : manifest.bounding_box_diagonal * z0 / step.pixels;
    lod.addLevel(object, distance);
  }
  lod.position.copy(centre);
  return lod;
}
