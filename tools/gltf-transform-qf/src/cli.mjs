// Runs the glTF-Transform CLI and gltfpack installed in this package's node_modules, so that the
// tests and measure.mjs exercise exactly the pinned versions, not whatever is on PATH.
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

export const PACKAGE_DIR = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
export const CONFIG = path.join(PACKAGE_DIR, 'gltf-transform.config.mjs');
const BIN = path.join(PACKAGE_DIR, 'node_modules', '.bin');

function run(tool, args) {
	const r = spawnSync(path.join(BIN, tool), args, { encoding: 'utf8', timeout: 300_000 });
	return { status: r.status, output: `${r.stdout || ''}${r.stderr || ''}`, error: r.error };
}

/** `gltf-transform <command> IN OUT ...flags`, with our config when `qf` is true. */
export function gltfTransform(command, input, output, flags = [], { qf = true } = {}) {
	const args = [command, input, ...(output === undefined ? [] : [output]), ...flags];
	if (qf) args.push('--config', CONFIG);
	return run('gltf-transform', args);
}

/** `gltfpack -i IN -o OUT ...flags` (the npm package's WebAssembly build). */
export function gltfpack(input, output, flags = []) {
	return run('gltfpack', ['-i', input, '-o', output, ...flags]);
}
