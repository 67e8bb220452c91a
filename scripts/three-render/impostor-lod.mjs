// Switching a bake's per-level impostor files with THREE.LOD at the manifest's distances (the
// README shows this file; tests/render/three_lod_test.sh runs it in headless Chromium).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

// baseUrl: the folder holding manifest.json and the .glb files; camera: a PerspectiveCamera;
// screenHeight: the viewport's height in pixels.
export async function loadImpostorLOD(baseUrl, camera, screenHeight) {
  const manifest = await (await fetch(baseUrl + 'manifest.json')).json();
  // Pixels per world unit at distance 1: an object of diagonal D at distance d spans D * z0 / d px.
  const z0 = screenHeight / (2 * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2));
  const levels = [...manifest.levels].sort((a, b) => b.primitives - a.primitives);  // finest first
  const lod = new THREE.LOD();  // THREE.LOD measures from its own position: the object's centre
  const loader = new GLTFLoader();
  const centre = new THREE.Vector3();
  for (const [i, level] of levels.entries()) {
    const gltf = await loader.loadAsync(baseUrl + level.file);
    if (i === 0) new THREE.Box3().setFromObject(gltf.scene).getCenter(centre);
    gltf.scene.position.sub(centre);
    // A level is accurate (error under half a pixel) while the object spans at most
    // max_screen_pixels: from that distance on; the finest from 0.
    const distance = i === 0 ? 0 : manifest.bounding_box_diagonal * z0 / level.max_screen_pixels;
    lod.addLevel(gltf.scene, distance);
  }
  lod.position.copy(centre);
  return lod;
}
