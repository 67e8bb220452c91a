// Renders .glb files with Babylon.js (@babylonjs/loaders' glTF loader, PBRMaterial) in headless
// Chromium from the cameras `qf-render eval --cameras` writes, with the engine method's lights,
// over black and over white: the renders `qf-render eval --external` scores (command line and
// outputs: scripts/web-render/jobs.mjs). No antialiasing.
// Matching the engine method (engine_scene.h EngineLights, three.js r187's units):
// - the directional headlight keeps its intensity (pi x 0.7): Babylon's PBR lights multiply the
//   BRDF (albedo / pi: its default diffuse, Oren-Nayar at diffuse roughness 0, is Lambert's; GGX)
//   by intensity x N.L, as three.js does;
// - the ambient light (pi x 0.3) is a HemisphericLight with the same sky and ground colour (so the
//   normal does not matter) at intensity 0.3: Babylon adds a hemispheric light's colour to the
//   diffuse sum without the BRDF's 1 / pi, so three.js's ambient intensity is divided by pi;
// - no tone mapping, exposure or contrast, exact sRGB, no anisotropic filtering: scene.mjs;
// - the camera is Babylon's own TargetCamera from the eye, target, up, vertical fov and near/far;
//   its view and projection matrices are checked against the engine method's.
//
// usage: node render.mjs FILE.glb CAMERAS.json OUTDIR | --jobs JOBS.json
import { chromium, babylonPage } from './browser.mjs';
import { renderMain } from '../web-render/jobs.mjs';

const pageScript = `
import { AppendSceneAsync, SceneLoader } from '@babylonjs/core/Loading/sceneLoader.js';
import { TargetCamera } from '@babylonjs/core/Cameras/targetCamera.js';
import { Camera } from '@babylonjs/core/Cameras/camera.js';
import { Material } from '@babylonjs/core/Materials/material.js';
import { DirectionalLight } from '@babylonjs/core/Lights/directionalLight.js';
import { HemisphericLight } from '@babylonjs/core/Lights/hemisphericLight.js';
import { Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { Color3, Color4 } from '@babylonjs/core/Maths/math.color.js';
import { captureViews, collectWarnings } from 'web/capture.mjs';
import { createEngine, createScene } from 'qf/scene.mjs';

// Largest difference between a Babylon matrix and the engine method's (both column-major, GL's
// layout), relative to the largest entry.
function matrixGap(m, want) {
  let gap = 0, size = 0;
  for (let i = 0; i < 16; ++i) { gap = Math.max(gap, Math.abs(m[i] - want[i])); size = Math.max(size, Math.abs(want[i])); }
  return gap / size;
}

// One engine for every job: it keeps the shaders it compiled for the files before (SwiftShader
// compiles Babylon's PBR shaders slowly).
let engine = null;
window.qfRender = async (url, cams) => {
  const first = cams.views[0];
  if (!engine) engine = createEngine(document.createElement('canvas'));
  engine.setSize(first.width, first.height);
  const scene = createScene(engine);
  const { warnings } = await collectWarnings(async () => {
    // The load resolves once the first MSFT_lod level is shown; the glTF loader's whenCompleteAsync
    // once every level it loads progressively has replaced the one before: what a user then sees.
    let complete = null;
    SceneLoader.OnPluginActivatedObservable.addOnce((loader) => { complete = loader.whenCompleteAsync(); });
    await AppendSceneAsync(url, scene, { pluginExtension: '.glb' });
    await complete;
  });
  // Points and lines unlit, as the engine method (and three.js's PointsMaterial, LineBasicMaterial)
  // draws them; Babylon lights them by their NORMAL (the point impostor has normals).
  const unlit = [Material.PointListDrawMode, Material.PointFillMode, Material.LineListDrawMode, Material.LineStripDrawMode, Material.LineLoopDrawMode];
  for (const m of scene.materials) if (unlit.includes(m.fillMode)) m.unlit = true;
  const camera = new TargetCamera('camera', new Vector3(0, 0, 0), scene);
  camera.fovMode = Camera.FOVMODE_VERTICAL_FIXED;
  const sun = new DirectionalLight('headlight', new Vector3(0, 0, -1), scene);
  sun.intensity = cams.lights.directional;
  sun.diffuse = new Color3(1, 1, 1);
  sun.specular = new Color3(1, 1, 1);
  const sky = new HemisphericLight('ambient', new Vector3(0, 1, 0), scene);
  sky.intensity = cams.lights.ambient / Math.PI;
  sky.diffuse = new Color3(1, 1, 1);
  sky.groundColor = new Color3(1, 1, 1);
  sky.specular = new Color3(0, 0, 0);
  await scene.whenReadyAsync();
  const setView = (v) => {
    camera.position = Vector3.FromArray(v.eye);
    camera.upVector = Vector3.FromArray(v.up);
    camera.setTarget(Vector3.FromArray(v.target));
    camera.fov = v.fovy_degrees * Math.PI / 180;
    camera.minZ = v.near;
    camera.maxZ = v.far;
    sun.direction = Vector3.FromArray(v.target).subtract(Vector3.FromArray(v.eye)).normalize();
    const gap = Math.max(matrixGap(camera.getViewMatrix(true).m, v.view), matrixGap(camera.getProjectionMatrix(true).m, v.projection));
    if (!(gap < 1e-4)) throw new Error('Babylon camera differs from the engine method: relative matrix gap ' + gap);
  };
  const draw = (bg) => {
    scene.clearColor = new Color4(bg[0], bg[1], bg[2], 1);
    scene.render();
  };
  const images = captureViews(engine._gl, cams, setView, draw);
    // What the engine drew: the active meshes that have geometry (not the loader's __root__).
  const active = scene.getActiveMeshes();
  const drawn = active.data.slice(0, active.length).filter((m) => m.getTotalVertices() > 0).map((m) => m.name);
  // What the scene holds at all: a combined file's other levels, were they kept to switch to.
  const loaded = scene.meshes.filter((m) => m.getTotalVertices() > 0).map((m) => m.name);
  scene.dispose();
  return { images, warnings, drawn, loaded };
};
`;

await renderMain('babylon-render', chromium, babylonPage(pageScript));
