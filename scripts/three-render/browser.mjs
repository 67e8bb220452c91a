// Headless Chromium with three.js served from node_modules: the page both three.js scripts use.
// The page lives on a fake origin; /three/... serves node_modules/three, /files/... serves
// `serve(path)`'s files, and an import map makes 'three' and 'three/addons/' resolve.
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const threeRoot = path.join(here, 'node_modules', 'three');
export const origin = 'http://qf-three.invalid';

const types = { '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json', '.glb': 'model/gltf-binary' };

// Runs `use(page)` on a page whose body runs `moduleScript` (a JS module), then closes the browser.
// `files(relative)` maps a /files/ path to a local file, or null. Page errors are collected and
// thrown after `use` if it did not throw itself.
export async function withThreePage(moduleScript, files, use) {
  const browser = await chromium.launch({
    executablePath: process.env.QF_CHROMIUM || '/usr/bin/chromium',
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist', '--no-sandbox'],
  });
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    const html = `<!doctype html><html><head><script type="importmap">
{"imports": {"three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/", "qf/": "/qf/"}}
</script></head><body><script type="module">${moduleScript}\nwindow.qfReady = true;</script></body></html>`;
    await page.route(`${origin}/**`, async (route) => {
      const url = new URL(route.request().url());
      const p = decodeURIComponent(url.pathname);
      let file = null;
      if (p === '/') return route.fulfill({ body: html, contentType: 'text/html' });
      if (p.startsWith('/three/')) file = path.join(threeRoot, p.slice('/three/'.length));
      else if (p.startsWith('/qf/')) file = path.join(here, p.slice('/qf/'.length));
      else if (p.startsWith('/files/')) file = files(p.slice('/files/'.length));
      if (file && fs.existsSync(file) && fs.statSync(file).isFile())
        return route.fulfill({ body: fs.readFileSync(file), contentType: types[path.extname(file)] || 'application/octet-stream' });
      return route.fulfill({ status: 404, body: 'not found' });
    });
    await page.goto(`${origin}/`);
    await page.waitForFunction(() => window.qfReady === true);
    const result = await use(page, errors);
    if (errors.length) throw new Error(errors.join('; '));
    return result;
  } finally {
    await browser.close();
  }
}
