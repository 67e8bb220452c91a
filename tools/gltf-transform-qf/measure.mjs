#!/usr/bin/env node
// Puts each given .glb through the glTF-Transform CLI's commands (with and without our config)
// and through gltfpack, and prints Markdown tables: bytes before and after, whether each of our
// extensions survives, and whether the data it describes is still the same (docs/toolchain.md
// holds the output for the committed fixtures). Usage:
//   node tools/gltf-transform-qf/measure.mjs tests/data/toolchain/*.glb
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { gltfTransform, gltfpack } from './src/cli.mjs';
import { inspectGlb, compareInspections } from './src/inspect.mjs';

// The flags that keep an impostor level's quads and a point impostor's points as they are in
// `optimize` (docs/toolchain.md says why each is needed).
export const SAFE_OPTIMIZE = ['--simplify', 'false', '--prune-attributes', 'false', '--join', 'false'];

const RUNS = [
	['copy', (i, o) => gltfTransform('copy', i, o, [], { qf: false }), 'no'],
	['copy', (i, o) => gltfTransform('copy', i, o), 'yes'],
	['optimize', (i, o) => gltfTransform('optimize', i, o, [], { qf: false }), 'no'],
	['optimize', (i, o) => gltfTransform('optimize', i, o), 'yes'],
	['optimize + safe flags¹', (i, o) => gltfTransform('optimize', i, o, SAFE_OPTIMIZE), 'yes'],
	['optimize + safe flags¹ --compress draco', (i, o) => gltfTransform('optimize', i, o, [...SAFE_OPTIMIZE, '--compress', 'draco']), 'yes'],
	['optimize + safe flags¹ --compress quantize', (i, o) => gltfTransform('optimize', i, o, [...SAFE_OPTIMIZE, '--compress', 'quantize']), 'yes'],
	['optimize + safe flags¹ --texture-compress webp', (i, o) => gltfTransform('optimize', i, o, [...SAFE_OPTIMIZE, '--texture-compress', 'webp']), 'yes'],
	['meshopt', (i, o) => gltfTransform('meshopt', i, o, [], { qf: false }), 'no'],
	['meshopt', (i, o) => gltfTransform('meshopt', i, o), 'yes'],
	['draco', (i, o) => gltfTransform('draco', i, o), 'yes'],
	['quantize', (i, o) => gltfTransform('quantize', i, o), 'yes'],
	['webp', (i, o) => gltfTransform('webp', i, o), 'yes'],
	['prune', (i, o) => gltfTransform('prune', i, o), 'yes'],
	['dedup', (i, o) => gltfTransform('dedup', i, o), 'yes'],
	['reorder', (i, o) => gltfTransform('reorder', i, o), 'yes'],
	['weld', (i, o) => gltfTransform('weld', i, o), 'yes'],
	['prune --keep-attributes true', (i, o) => gltfTransform('prune', i, o, ['--keep-attributes', 'true']), 'yes'],
	['simplify', (i, o) => gltfTransform('simplify', i, o), 'yes'],
	['simplify --ratio 0.5 --error 0.01', (i, o) => gltfTransform('simplify', i, o, ['--ratio', '0.5', '--error', '0.01']), 'yes'],
	['simplify --ratio 0 --error 0.1', (i, o) => gltfTransform('simplify', i, o, ['--ratio', '0', '--error', '0.1']), 'yes'],
	['join', (i, o) => gltfTransform('join', i, o), 'yes'],
	['flatten', (i, o) => gltfTransform('flatten', i, o), 'yes'],
	['instance', (i, o) => gltfTransform('instance', i, o), 'yes'],
	['center', (i, o) => gltfTransform('center', i, o), 'yes'],
	['unweld', (i, o) => gltfTransform('unweld', i, o), 'yes'],
	['gltfpack', (i, o) => gltfpack(i, o), '—'],
	['gltfpack -kn -km -ke', (i, o) => gltfpack(i, o, ['-kn', '-km', '-ke']), '—'],
	['gltfpack -c', (i, o) => gltfpack(i, o, ['-c']), '—'],
	['gltfpack -noq', (i, o) => gltfpack(i, o, ['-noq']), '—'],
];

const yes = (v) => (v ? 'yes' : '**no**');

function describe(before, after, cmp) {
	const cells = [];
	if (cmp.impostorLevel) {
		const e = cmp.impostorLevel;
		cells.push(e.kept ? `kept, arrays ${e.arraysEqual ? 'equal' : '**differ**'}` : '**dropped**');
		cells.push(cmp.quadsInOrder ? 'yes' : `**no** (${cmp.quadCountAfter} quads)`);
	}
	if (cmp.pointImpostor) {
		cells.push(cmp.pointImpostor.kept ? 'kept' : '**dropped**');
		cells.push(`${cmp.pointCountAfter}${cmp.pointsInOrder ? ', in order' : ', **not in order**'}`);
	}
	if (!cmp.lod) cells.push(cmp.semanticsKept ? 'kept' : `**lost ${cmp.semanticsLost.join(', ')}**`);
	if (cmp.lod) {
		const l = cmp.lod;
		cells.push(l.kept ? 'kept' : '**dropped**');
		cells.push(`${l.levelsAfter} of ${l.levelsBefore}`);
		cells.push(l.trianglesAfter ? l.trianglesAfter.join(' / ') : '—');
		cells.push(l.kept ? yes(l.levelsAligned) : '—');
	}
	return cells;
}

function header(before) {
	const h = ['command', 'our config', 'bytes'];
	if (before.impostorLevel) h.push('QF_impostor_level', 'quad k in place');
	if (before.pointImpostor) h.push('QF_point_impostor', 'points');
	if (!before.lods.length) h.push('attributes');
	if (before.lods.length) h.push('MSFT_lod', 'levels', 'triangles per level', 'levels aligned');
	h.push('warned');
	return h;
}

async function measure(file) {
	const input = fs.readFileSync(file);
	const before = await inspectGlb(input);
	const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'qf-measure-'));
	const rows = [];
	const head = header(before);
	const first = [path.basename(file), '', String(before.bytes)];
	rows.push(`| ${head.join(' | ')} |`, `|${head.map(() => '---').join('|')}|`);
	for (const [label, fn, qf] of RUNS) {
		const out = path.join(tmp, 'out.glb');
		fs.rmSync(out, { force: true });
		const r = fn(file, out);
		if (r.status !== 0 || !fs.existsSync(out)) {
			const msg = (r.output.match(/error: (.*)/) || r.output.match(/Error: (.*)/) || [null, `exit ${r.status}`])[1];
			rows.push(`| ${label} | ${qf} | failed: ${msg.trim().slice(0, 60)} |${head.slice(3).map(() => ' |').join('')}`);
			continue;
		}
		const bytes = fs.readFileSync(out);
		const after = await inspectGlb(bytes);
		const cells = describe(before, after, compareInspections(before, after));
		// Our writer's warning that the quads or points no longer match the block (src/index.mjs).
		const warned = /warn: QF_(impostor_level|point_impostor):/.test(r.output) ? 'yes' : '—';
		rows.push(`| ${label} | ${qf} | ${bytes.byteLength} | ${cells.join(' | ')} | ${warned} |`);
	}
	fs.rmSync(tmp, { recursive: true, force: true });
	const extra = before.lods.length ? `, MSFT_lod levels' triangles ${before.lods[0].levels.map((l) => l.triangles).join(' / ')}` : '';
	const pts = before.pointImpostor ? `, ${before.points.length} points` : '';
	const quads = before.impostorLevel ? `, ${before.quads.length} quads` : '';
	return `**${first[0]}** (${first[2]} bytes${quads}${pts}${extra})\n\n${rows.join('\n')}\n`;
}

for (const file of process.argv.slice(2)) {
	console.log(await measure(file));
}
