// Runs impostor-lod.mjs (the Babylon.js LOD example of docs/engines.md) in headless Chromium on a bake folder
// and prints, as JSON, the level Babylon draws (0 = finest) with the camera at each distance from
// the object's centre (fov 60, a 512 x 512 viewport): the mesh its LOD selection picked while
// rendering a frame there (onLODLevelSelection).
// usage: node lod-check.mjs BAKE_DIR DISTANCE,DISTANCE... [BAKE_DIR DISTANCE,...]... (one line of JSON each)
import { chromium, babylonPage } from './browser.mjs';
import { lodCheckMain } from '../web-render/jobs.mjs';

const pageScript = `
import { TargetCamera } from '@babylonjs/core/Cameras/targetCamera.js';
import { HemisphericLight } from '@babylonjs/core/Lights/hemisphericLight.js';
import { Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { createEngine, createScene } from 'qf/scene.mjs';
import { loadImpostorLOD } from 'qf/impostor-lod.mjs';
window.qfLevels = async (baseUrl, distances) => {
  const canvas = document.createElement('canvas');
  canvas.width = 512; canvas.height = 512;
  const engine = createEngine(canvas);
  const scene = createScene(engine);
  const camera = new TargetCamera('camera', new Vector3(0, 0, 1), scene);
  camera.fov = Math.PI / 3;
  camera.minZ = 0.01;
  camera.maxZ = 1e6;
  new HemisphericLight('light', new Vector3(0, 1, 0), scene);
  const finest = await loadImpostorLOD(baseUrl, scene, camera, 512);
  await scene.whenReadyAsync();
  // Levels in the order loadImpostorLOD added them: getLODLevels lists the farthest first.
  const levels = [finest, ...finest.getLODLevels().map((l) => l.mesh).reverse()];
  const centre = finest.getBoundingInfo().boundingSphere.centerWorld.clone();
  let picked = null;
  finest.onLODLevelSelection = (distance, mesh, selected) => { picked = selected; };
  const shown = [];
  for (const d of distances) {
    camera.position = centre.add(new Vector3(0, 0, d));
    camera.setTarget(centre);
    picked = undefined;
    scene.render();
    shown.push(levels.indexOf(picked));
  }
  engine.dispose();
  return shown;
};
`;
await lodCheckMain(chromium, babylonPage(pageScript));
