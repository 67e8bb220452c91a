// Switching a bake's per-level files with Babylon.js's Mesh.addLODLevel at the manifest's distances
// (docs/engines.md shows this file; tests/render/lod_test.sh runs it in headless Chromium).
import { LoadAssetContainerAsync } from '@babylonjs/core/Loading/sceneLoader.js';
import '@babylonjs/loaders/glTF';

// baseUrl: the folder holding manifest.json and the .glb files; scene: a Scene with
// useRightHandedSystem = true (glTF's frame); camera: its camera (fov vertical, Babylon's default);
// screenHeight: the viewport's height in pixels; asset: the app's own model (one Mesh, as it draws
// it), or null. The chain starts at the asset itself (its entries of kind "asset": the nearest
// sizes, where no baked file looks as good); without it those entries are left out and the nearest
// baked file is shown from 0. Returns the nearest level's mesh, the others its LODs.
export async function loadImpostorLOD(baseUrl, scene, camera, screenHeight, asset = null) {
  const manifest = await (await fetch(baseUrl + 'manifest.json')).json();
  // Pixels per world unit at distance 1: an object of diagonal D at distance d spans D * z0 / d px.
  const z0 = screenHeight / (2 * Math.tan(camera.fov / 2));
  // The recommended chain (every bake but --no-chain or --no-measure: nearest first, each file
  // shown while the object spans at most max_pixels, null = any size); else the impostor levels,
  // finest first, each shown up to its max_screen_pixels (where its measured look holds; a level
  // that holds at no size measured, 0, is left out).
  const steps = manifest.recommended_chain
    ? manifest.recommended_chain.chain.filter((e, i) => e.kind !== 'asset' || (i === 0 && asset))
        .map((e) => ({ file: e.kind === 'asset' ? null : e.file, pixels: e.max_pixels }))
    : [...manifest.levels].filter((l) => l.max_screen_pixels > 0).sort((a, b) => b.primitives - a.primitives)
        .map((l) => ({ file: l.file, pixels: l.max_screen_pixels }));
  let finest = null;
  for (const step of steps) {
    if (step.file === null) {
      finest = asset;
      continue;
    }
    const container = await LoadAssetContainerAsync(baseUrl + step.file, scene);
    container.addAllToScene();
    // Babylon switches single meshes (measuring from the finest one's bounding-sphere centre);
    // every level file of a bake is one, a textured mesh LOD may be several (merge them first).
    const meshes = container.meshes.filter((m) => m.getTotalVertices() > 0);
    if (meshes.length !== 1) throw new Error(`${step.file}: ${meshes.length} meshes, addLODLevel takes one`);
    // Shown from the distance at which the object spans step.pixels on; the first from 0.
    if (finest === null) finest = meshes[0];
    else finest.addLODLevel(manifest.bounding_box_diagonal * z0 / step.pixels, meshes[0]);
  }
  return finest;
}
