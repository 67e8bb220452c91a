// Babylon.js's page (scripts/web-render/page.mjs): /babylon/core/... and /babylon/loaders/... serve
// the npm packages' ES modules, /qf/... this folder; the import map resolves '@babylonjs/core/...',
// '@babylonjs/loaders/...' and the bundler-style '@babylonjs/loaders/glTF' (its index) and 'qf/'.
import { chromium } from 'playwright-core';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export { chromium };
const here = path.dirname(fileURLToPath(import.meta.url));
const modules = path.join(here, 'node_modules', '@babylonjs');

export function babylonPage(moduleScript) {
  return {
    imports: {
      '@babylonjs/core/': '/babylon/core/',
      '@babylonjs/loaders/': '/babylon/loaders/',
      '@babylonjs/loaders/glTF': '/babylon/loaders/glTF/index.js',
      'qf/': '/qf/',
    },
    roots: { '/babylon/core/': path.join(modules, 'core'), '/babylon/loaders/': path.join(modules, 'loaders'), '/qf/': here },
    moduleScript,
  };
}
