// Renders .glb files with three.js (GLTFLoader, WebGLRenderer) in headless Chromium from the cameras
// `qf-render eval --cameras` writes, with the same lights (a white directional headlight and ambient
// light, engine_scene.h EngineLights), over black and over white: the renders `qf-render eval
// --external` scores (command line and outputs: scripts/web-render/jobs.mjs).
// No antialiasing, no tone mapping, sRGB output: what three.js does by default, minus MSAA.
//
// usage: node render.mjs FILE.glb CAMERAS.json OUTDIR | --jobs JOBS.json
import { chromium, threePage } from './browser.mjs';
import { renderMain } from '../web-render/jobs.mjs';

const pageScript = `
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { DRACOLoader } from 'three/addons/loaders/DRACOLoader.js';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';
import { captureViews, collectWarnings } from 'web/capture.mjs';
// Draco-compressed files (cluster --draco): the decoder three.js ships, fetched from /three/.
const draco = new DRACOLoader().setDecoderPath('/three/examples/jsm/libs/draco/gltf/');
// KTX2 textures (bake --textures ktx2, KHR_texture_basisu): three.js's Basis transcoder, from /three/,
// transcoding to what the GPU supports (detectSupport: SwiftShader's formats here); the files' own
// mip levels are used as they are.
const ktx2 = new KTX2Loader().setTranscoderPath('/three/examples/jsm/libs/basis/');
window.qfRender = async (url, cams) => {
  const first = cams.views[0];
  const canvas = document.createElement('canvas');
  canvas.width = first.width; canvas.height = first.height;
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, alpha: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(first.width, first.height, false);
  ktx2.detectSupport(renderer);
  const { result: gltf, warnings } = await collectWarnings(() => new GLTFLoader().setDRACOLoader(draco).setKTX2Loader(ktx2).loadAsync(url));
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  const sun = new THREE.DirectionalLight(0xffffff, cams.lights.directional);
  scene.add(sun, sun.target, new THREE.AmbientLight(0xffffff, cams.lights.ambient));
  const camera = new THREE.PerspectiveCamera();
  camera.matrixAutoUpdate = false;
  const setView = (v) => {
    camera.matrix.fromArray(v.view).invert();
    camera.projectionMatrix.fromArray(v.projection);
    camera.projectionMatrixInverse.copy(camera.projectionMatrix).invert();
    camera.updateMatrixWorld(true);
    sun.position.fromArray(v.eye);
    sun.target.position.fromArray(v.target);
    sun.updateMatrixWorld(true);
    sun.target.updateMatrixWorld(true);
  };
  const draw = (bg) => {
    renderer.setClearColor(new THREE.Color().setRGB(bg[0], bg[1], bg[2], THREE.SRGBColorSpace), 1);
    renderer.render(scene, camera);
  };
  const images = captureViews(renderer.getContext(), cams, setView, draw);
  const drawn = [];
  gltf.scene.traverseVisible((o) => { if (o.isMesh || o.isPoints || o.isLine) drawn.push(o.name); });
  // What the scene holds at all: a combined file's other levels, were they kept to switch to.
  const loaded = [];
  gltf.scene.traverse((o) => { if (o.isMesh || o.isPoints || o.isLine) loaded.push(o.name); });
  renderer.dispose();
  return { images, warnings, drawn, loaded };
};
`;

await renderMain('three-render', chromium, threePage(pageScript));
