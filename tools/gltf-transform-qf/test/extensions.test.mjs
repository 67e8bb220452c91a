// The QF extensions through glTF-Transform: each survives copy, a safe optimize and meshopt (CLI,
// with our config) and library transforms that renumber accessors, and the data its indices name
// decodes to the same values afterwards; without our extensions the same commands lose it (so
// these tests fail if the extensions stop being registered). Fixtures: tests/data/toolchain/.
// Run: node --test tools/gltf-transform-qf/test/
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { dedup, prune, quantize } from '@gltf-transform/functions';
import { createIO, inspectGlb, compareInspections } from '../src/inspect.mjs';
import { gltfTransform } from '../src/cli.mjs';
import { QF_IMPOSTOR_LEVEL, QF_POINT_IMPOSTOR, MSFT_LOD } from '../src/index.mjs';
import { SAFE_OPTIMIZE } from '../measure.mjs';

const HERE = path.dirname(fileURLToPath(import.meta.url));
const FIXTURES = path.resolve(HERE, '../../../tests/data/toolchain');
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'qf-gltf-transform-'));
process.on('exit', () => fs.rmSync(tmp, { recursive: true, force: true }));

// The fixtures by what they hold (README.md in the folder says how each was baked).
const fixtures = { level: [], points: [], lods: [] };
for (const name of fs.readdirSync(FIXTURES).filter((f) => f.endsWith('.glb')).sort()) {
	const file = path.join(FIXTURES, name);
	const info = await inspectGlb(fs.readFileSync(file));
	if (info.impostorLevel) fixtures.level.push({ file, info });
	if (info.pointImpostor) fixtures.points.push({ file, info });
	if (info.lods.length) fixtures.lods.push({ file, info });
}

test('the fixtures hold every extension, with data to compare', () => {
	assert.ok(fixtures.level.length >= 2, 'impostor levels (PNG and WebP)');
	assert.equal(fixtures.points.length, 1, 'a point impostor');
	assert.equal(fixtures.lods.length, 1, 'a _lods.glb');
	for (const { info } of fixtures.level) {
		assert.ok(info.quads.length >= 10 && info.quadsCanonical, 'a level with quads (0,1,2),(0,2,3)');
		for (const key of ['domain', 'error', 'neighborOffsets', 'neighbors']) {
			assert.ok(info.impostorLevel.arrays[key]?.length > 0, key);
		}
		assert.equal(info.impostorLevel.arrays.domain.length, info.impostorLevel.def.quadCount);
	}
	assert.ok(fixtures.lods[0].info.lods[0].levels.length >= 3, 'MSFT_lod with at least 3 levels');
	assert.ok(fixtures.points[0].info.points.length >= 100);
});

function spawnValidate(file) {
	return gltfTransform('validate', file, undefined, [], { qf: false }).output;
}

let counter = 0;
function runCli(command, input, flags, qf) {
	const output = path.join(tmp, `${counter++}-${command}.glb`);
	const r = gltfTransform(command, input, output, flags, { qf });
	assert.equal(r.status, 0, `gltf-transform ${command} failed:\n${r.output}`);
	return { output, log: r.output };
}

// What every command below must keep, per kind of file.
function assertKept(before, after, label, { semantics = true } = {}) {
	const cmp = compareInspections(before, after);
	if (before.impostorLevel) {
		assert.ok(cmp.impostorLevel.kept, `${label}: ${QF_IMPOSTOR_LEVEL} dropped`);
		assert.ok(cmp.impostorLevel.arraysEqual, `${label}: ${QF_IMPOSTOR_LEVEL}'s arrays differ`);
		assert.ok(cmp.impostorLevel.quadCountEqual, `${label}: quadCount changed`);
		assert.ok(cmp.quadsInOrder, `${label}: quad k moved`);
		// The block's own values, not only its arrays.
		for (const key of ['level', 'quadCount', 'blend', 'alphaRef', 'alphaExponent']) {
			assert.equal(after.impostorLevel.def[key], before.impostorLevel.def[key], `${label}: ${key}`);
		}
	}
	if (semantics) assert.ok(cmp.semanticsKept, `${label}: lost vertex attributes ${cmp.semanticsLost}`);
	if (before.pointImpostor) {
		assert.ok(cmp.pointImpostor.kept, `${label}: ${QF_POINT_IMPOSTOR} dropped`);
		assert.ok(cmp.pointImpostor.defEqual, `${label}: ${QF_POINT_IMPOSTOR}'s values changed`);
		assert.ok(cmp.pointsInOrder, `${label}: points lost or reordered (${cmp.pointCountAfter})`);
	}
	if (before.lods.length) {
		assert.ok(cmp.lod.kept, `${label}: ${MSFT_LOD} dropped`);
		assert.equal(cmp.lod.levelsAfter, cmp.lod.levelsBefore, `${label}: MSFT_lod levels`);
		assert.deepEqual(cmp.lod.trianglesAfter, cmp.lod.trianglesBefore, `${label}: a level's mesh changed`);
		assert.ok(cmp.lod.levelsAligned, `${label}: a level moved against the others`);
		assert.ok(cmp.lod.screencoverageKept, `${label}: MSFT_screencoverage`);
	}
}

const all = () => [...fixtures.level, ...fixtures.points, ...fixtures.lods];
const COMMANDS = [
	['copy', []],
	['optimize', SAFE_OPTIMIZE], // meshopt compression (reorder + quantize), WebP/PNG re-encode, prune, dedup
	['meshopt', []],
	['prune', ['--keep-attributes', 'true']], // else it drops the point impostor's NORMAL
	['dedup', []],
];

for (const [command, flags] of COMMANDS) {
	test(`gltf-transform ${command} with our config keeps every extension and its data`, async () => {
		for (const { file, info } of all()) {
			const { output } = runCli(command, file, flags, true);
			assertKept(info, await inspectGlb(fs.readFileSync(output)), `${command} ${path.basename(file)}`);
			if (['copy', 'optimize', 'meshopt'].includes(command)) {
				// The Khronos validator (through the CLI) on what we wrote: no error, no warning.
				const v = spawnValidate(output);
				assert.match(v, /No errors found/, `${command} ${path.basename(file)}:\n${v}`);
				assert.match(v, /No warnings found/, `${command} ${path.basename(file)}:\n${v}`);
			}
		}
	});
}

test('without our config the same commands lose the data (so the tests above can fail)', async () => {
	for (const { file, info } of all()) {
		const { output, log } = runCli('copy', file, [], false);
		assert.match(log, /Missing optional extension/);
		const after = await inspectGlb(fs.readFileSync(output));
		assert.equal(after.impostorLevel, undefined);
		assert.equal(after.pointImpostor, undefined);
		assert.equal(after.lods.length, 0);
		if (info.lods.length) {
			// Without MSFT_lod the coarser levels are nodes in no scene, and prune drops them.
			const opt = await inspectGlb(fs.readFileSync(runCli('optimize', file, [], false).output));
			assert.equal(compareInspections(info, opt).lod.levelsAfter, 1);
		}
	}
});

// The library, not the CLI: transforms that renumber accessors must carry our indices along.
test('indices follow their accessors when transforms renumber them', async () => {
	const io = await createIO();
	for (const { file, info } of fixtures.level) {
		const doc = await io.read(file);
		const root = doc.getRoot();
		const level = root.getExtension(QF_IMPOSTOR_LEVEL);
		const domainIndexBefore = root.listAccessors().indexOf(level.getDomain());
		// Drop the tangents (written before our arrays), so every later accessor moves down one,
		// and add a copy of the domain array: dedup must merge it and keep the reference valid.
		for (const prim of root.listMeshes().flatMap((m) => m.listPrimitives())) prim.setAttribute('TANGENT', null);
		const copy = doc.createAccessor().setArray(level.getDomain().getArray().slice()).setBuffer(root.listBuffers()[0]);
		level.setDomain(copy);
		await doc.transform(prune(), dedup(), quantize());
		const glb = await io.writeBinary(doc);
		const after = await inspectGlb(glb);
		const def = after.impostorLevel.def;
		assert.notEqual(def.domain, domainIndexBefore, 'the test has to move the accessors');
		// (TANGENT is gone on purpose; everything else must hold.)
		assertKept(info, after, `prune+dedup+quantize ${path.basename(file)}`, { semantics: false });
	}
});

test('meshopt compression keeps 1- and 2-byte arrays (glTF-Transform pads them without a stride)', async () => {
	for (const { file, info } of fixtures.level) {
		const narrow = Object.keys(info.impostorLevel.arrays).filter((k) => k !== 'error');
		assert.ok(narrow.length === 3);
		const { output } = runCli('meshopt', file, [], true);
		const after = await inspectGlb(fs.readFileSync(output));
		assert.ok(after.extensionsUsed.includes('EXT_meshopt_compression'));
		for (const key of narrow) assert.deepEqual(after.impostorLevel.arrays[key], info.impostorLevel.arrays[key], key);
	}
});

test('transforms that change the quads or points are reported, not written silently', async () => {
	// Draco reorders an impostor level's triangles; an aggressive simplify collapses quads.
	for (const [command, flags] of [['draco', []], ['simplify', ['--ratio', '0', '--error', '0.1']]]) {
		const { log } = runCli(command, fixtures.level[0].file, flags, true);
		assert.match(log, /warn: QF_impostor_level:/, `${command}:\n${log}`);
	}
	for (const command of ['copy', 'meshopt']) {
		const { log } = runCli(command, fixtures.level[0].file, [], true);
		assert.doesNotMatch(log, /warn: QF_impostor_level:/, `${command}:\n${log}`);
	}
	// simplify on a point impostor drops points (meshoptimizer's simplifyPoints): our writer warns.
	const { file } = fixtures.points[0];
	const warnings = [];
	const io = await createIO({ logger: { warn: (m) => warnings.push(m), info() {}, debug() {}, error() {} } });
	const doc = await io.read(file);
	const prim = doc.getRoot().listMeshes()[0].listPrimitives()[0];
	const position = prim.getAttribute('POSITION');
	// Keep every other point, as a point simplifier would.
	for (const semantic of prim.listSemantics()) {
		const a = prim.getAttribute(semantic);
		const size = a.getElementSize();
		const src = a.getArray();
		const dst = new src.constructor(Math.floor(a.getCount() / 2) * size);
		for (let i = 0; i < dst.length / size; i++) dst.set(src.subarray(2 * i * size, (2 * i + 1) * size), i * size);
		a.setArray(dst);
	}
	assert.ok(position.getCount() < fixtures.points[0].info.points.length);
	await io.writeBinary(doc);
	assert.ok(warnings.some((w) => w.includes('pointCount')), warnings.join('\n'));
});

// quasiflat writes MSFT_lod on nodes only; the extension also allows it on materials, and a file
// edited elsewhere may carry both. Built here, since no bake makes one.
test('MSFT_lod on nodes and materials: prune keeps the levels it names, the writer renumbers them', async () => {
	const { Document } = await import('@gltf-transform/core');
	const { MSFTLod } = await import('../src/index.mjs');
	const io = await createIO();
	const doc = new Document();
	const buffer = doc.createBuffer();
	const ext = doc.createExtension(MSFTLod);
	const triangle = (name, material) => doc.createMesh(name).addPrimitive(doc.createPrimitive()
		.setAttribute('POSITION', doc.createAccessor().setType('VEC3').setBuffer(buffer)
			.setArray(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0])))
		.setMaterial(material));
	// An unused node and material first, so that prune renumbers everything after them.
	doc.createNode('unused');
	doc.createMaterial('unused');
	const materials = ['m0', 'm1', 'm2'].map((n) => doc.createMaterial(n));
	const nodes = ['n0', 'n1', 'n2'].map((n, i) => doc.createNode(n).setMesh(triangle(n, materials[i])));
	doc.createScene().addChild(nodes[0]); // the coarser levels are in no scene, as in _lods.glb
	nodes[0].setExtension('MSFT_lod', ext.createLod().addLod(nodes[1]).addLod(nodes[2]));
	materials[0].setExtension('MSFT_lod', ext.createLod().addLod(materials[1]).addLod(materials[2]));
	await doc.transform(prune());
	const json = (await io.writeJSON(doc, { format: 'glb' })).json;
	const nodeIndex = (name) => json.nodes.findIndex((n) => n.name === name);
	const materialIndex = (name) => json.materials.findIndex((m) => m.name === name);
	assert.equal(json.nodes.length, 3, 'prune kept the three levels and dropped the unused node');
	assert.deepEqual(json.nodes[nodeIndex('n0')].extensions.MSFT_lod.ids, [nodeIndex('n1'), nodeIndex('n2')]);
	assert.deepEqual(json.materials[materialIndex('m0')].extensions.MSFT_lod.ids, [materialIndex('m1'), materialIndex('m2')]);
	assert.equal(materialIndex('unused'), -1);
});

// The blocks our writer produces (after meshopt: widened arrays) against the extensions' JSON
// schemas in schemas/, with Debian's python3-jsonschema as tests/gltf/validate_test.sh uses it.
test('written blocks validate against schemas/', async () => {
	const { spawnSync } = await import('node:child_process');
	const blocks = [];
	for (const { file } of [...fixtures.level, ...fixtures.points]) {
		for (const command of ['copy', 'meshopt']) {
			const json = (await (await createIO()).binaryToJSON(fs.readFileSync(runCli(command, file, [], true).output))).json;
			for (const name of [QF_IMPOSTOR_LEVEL, QF_POINT_IMPOSTOR]) {
				if (json.extensions?.[name]) blocks.push({ name, block: json.extensions[name], where: `${command} ${path.basename(file)}` });
			}
		}
	}
	assert.ok(blocks.length >= 6);
	const schemas = path.resolve(HERE, '../../../schemas');
	const script = `
import json, sys, jsonschema
schemas, blocks = sys.argv[1], json.load(sys.stdin)
bad = 0
for b in blocks:
    schema = json.load(open(f"{schemas}/{b['name']}/schema/glTF.{b['name']}.schema.json"))
    for e in jsonschema.Draft202012Validator(schema).iter_errors(b['block']):
        print(b['where'], b['name'], e.message); bad = 1
sys.exit(bad)
`;
	const r = spawnSync('/usr/bin/python3', ['-c', script, schemas], { input: JSON.stringify(blocks), encoding: 'utf8' });
	assert.equal(r.status, 0, `${r.stdout}${r.stderr}`);
});

// Files baked before December 2026 carry `center`, `normal` and `atlasRect` in the block (values a
// reader now ignores); they and other unknown keys pass through unchanged, and extras too.
test('unknown keys and extras of a block are written back as they were', async () => {
	const io = await createIO();
	const jsonDoc = await io.binaryToJSON(fs.readFileSync(fixtures.level[0].file));
	const block = jsonDoc.json.extensions[QF_IMPOSTOR_LEVEL];
	block.center = [0.5, -0.25, 1];
	block.atlasRect = [0, 0.125, 0.5, 1];
	block.extras = { note: 'kept' };
	const doc = await io.readJSON(jsonDoc);
	const written = (await io.writeJSON(doc, { format: 'glb' })).json.extensions[QF_IMPOSTOR_LEVEL];
	assert.deepEqual(written.center, [0.5, -0.25, 1]);
	assert.deepEqual(written.atlasRect, [0, 0.125, 0.5, 1]);
	assert.deepEqual(written.extras, { note: 'kept' });
	assert.equal(written.quadCount, block.quadCount);
});
