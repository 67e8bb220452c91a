// Runs impostor-lod.mjs (the THREE.LOD example of docs/engines.md) in headless Chromium on a bake folder and
// prints, as JSON, the level THREE.LOD shows (0 = finest) with the camera at each distance from the
// object's centre (fov 60, a 512 x 512 viewport), after drawing a frame there.
// usage: node lod-check.mjs BAKE_DIR DISTANCE,DISTANCE... [BAKE_DIR DISTANCE,...]... (one line of JSON each)
import { chromium, threePage } from './browser.mjs';
import { lodCheckMain } from '../web-render/jobs.mjs';

const pageScript = `
import * as THREE from 'three';
import { loadImpostorLOD } from 'qf/impostor-lod.mjs';
window.qfLevels = async (baseUrl, distances) => {
  const renderer = new THREE.WebGLRenderer({ antialias: false });
  renderer.setSize(512, 512, false);
  const camera = new THREE.PerspectiveCamera(60, 1, 0.01, 1e6);
  const lod = await loadImpostorLOD(baseUrl, camera, 512);
  const centre = lod.position;
  const scene = new THREE.Scene();
  scene.add(lod, new THREE.AmbientLight(0xffffff, 1));
  const shown = [];
  for (const d of distances) {
    camera.position.copy(centre).add(new THREE.Vector3(0, 0, d));
    camera.lookAt(centre);
    camera.updateMatrixWorld();
    renderer.render(scene, camera);  // updates the LOD (autoUpdate) and draws it
    shown.push(lod.getCurrentLevel());
  }
  return shown;
};
`;
await lodCheckMain(chromium, threePage(pageScript));
