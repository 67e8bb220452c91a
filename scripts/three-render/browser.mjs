// three.js's page (scripts/web-render/page.mjs): /three/... serves node_modules/three, /qf/... this
// folder, and the import map resolves 'three', 'three/addons/' and 'qf/'.
import { chromium } from 'playwright-core';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

export { chromium };
const here = path.dirname(fileURLToPath(import.meta.url));

export function threePage(moduleScript) {
  return {
    imports: { three: '/three/build/three.module.js', 'three/addons/': '/three/examples/jsm/', 'qf/': '/qf/' },
    roots: { '/three/': path.join(here, 'node_modules', 'three'), '/qf/': here },
    moduleScript,
  };
}
