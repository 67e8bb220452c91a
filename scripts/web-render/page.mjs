// Headless Chromium with a WebGL engine served from an npm folder: the page every engine script
// (scripts/three-render, scripts/babylon-render) runs in. Each engine folder pins its own
// playwright-core and passes its `chromium` in, so this folder needs no node_modules of its own.
// The page lives on a fake origin: `roots` maps URL prefixes to local folders, /web/ serves this
// folder (the in-page helpers, capture.mjs), /files/... serves `files(path)`'s files, and an
// import map resolves the engine's bare module names.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const origin = 'http://qf-render.invalid';

const types = { '.js': 'text/javascript', '.mjs': 'text/javascript', '.json': 'application/json', '.glb': 'model/gltf-binary',
                '.wasm': 'application/wasm' };

// Runs `use(page, errors)` on a page whose body runs `moduleScript` (a JS module), then closes the
// browser. `imports`: the import map's entries; `roots`: {'/prefix/': folder}; `files(relative)`
// maps a /files/ path to a local file, or null. Page errors are collected and thrown after `use`
// if it did not throw itself.
export async function withPage(chromium, { imports, roots, moduleScript }, files, use) {
  // SwiftShader: the same software WebGL on every machine, GPU or not (deterministic pixels).
  const browser = await chromium.launch({
    executablePath: process.env.QF_CHROMIUM || '/usr/bin/chromium',
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist', '--no-sandbox'],
  });
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    const html = `<!doctype html><html><head><script type="importmap">
${JSON.stringify({ imports: { ...imports, 'web/': '/web/' } })}
</script></head><body><script type="module">${moduleScript}\nwindow.qfReady = true;</script></body></html>`;
    const allRoots = Object.entries({ ...roots, '/web/': here });
    await page.route(`${origin}/**`, async (route) => {
      const p = decodeURIComponent(new URL(route.request().url()).pathname);
      if (p === '/') return route.fulfill({ body: html, contentType: 'text/html' });
      let file = null;
      if (p.startsWith('/files/')) file = files(p.slice('/files/'.length));
      else for (const [prefix, dir] of allRoots) if (p.startsWith(prefix)) { file = path.join(dir, p.slice(prefix.length)); break; }
      if (!file || !fs.existsSync(file) || !fs.statSync(file).isFile()) return route.fulfill({ status: 404, body: 'not found' });
      return route.fulfill({ body: fs.readFileSync(file), contentType: types[path.extname(file)] || 'application/octet-stream' });
    });
    await page.goto(`${origin}/`);
    await page.waitForFunction(() => window.qfReady === true, null, { timeout: 120000 });
    const result = await use(page, errors);
    if (errors.length) throw new Error(errors.join('; '));
    return result;
  } finally {
    await browser.close();
  }
}
