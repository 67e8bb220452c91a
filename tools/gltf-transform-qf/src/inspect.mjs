// Reads what quasiflat's extensions say about a .glb and what the data they name holds, so that a
// file before and after a transform can be compared (the tests and measure.mjs use it).
//
// It decodes deliberately WITHOUT the QF extensions: it takes the extension blocks from the file's
// JSON as written and looks their indices up in the accessor and node lists of a document read
// with the standard extensions only (meshopt, Draco and quantization decoded). glTF-Transform's
// reader creates accessors and nodes in file order, so index i is the i-th of those lists. A bug
// in our reader or writer therefore cannot hide itself by decoding its own mistake.
import { Logger, NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { MeshoptDecoder, MeshoptEncoder } from 'meshoptimizer';
import draco3d from 'draco3dgltf';
import { QF_EXTENSIONS, QF_IMPOSTOR_LEVEL, QF_POINT_IMPOSTOR, MSFT_LOD } from './index.mjs';

const TRIANGLES = 4;
const POINTS = 0;

/** A NodeIO with the standard extensions and their codecs; `qf` adds ours. */
export async function createIO({ qf = true, logger = new Logger(Logger.Verbosity.ERROR) } = {}) {
	await MeshoptDecoder.ready;
	await MeshoptEncoder.ready;
	const io = new NodeIO()
		.setLogger(logger)
		.registerExtensions(qf ? [...ALL_EXTENSIONS, ...QF_EXTENSIONS] : ALL_EXTENSIONS)
		.registerDependencies({
			'meshopt.decoder': MeshoptDecoder,
			'meshopt.encoder': MeshoptEncoder,
			'draco3d.decoder': await draco3d.createDecoderModule(),
			'draco3d.encoder': await draco3d.createEncoderModule(),
		});
	return io;
}

function transformPoint(m, x, y, z) {
	return [
		m[0] * x + m[4] * y + m[8] * z + m[12],
		m[1] * x + m[5] * y + m[9] * z + m[13],
		m[2] * x + m[6] * y + m[10] * z + m[14],
	];
}

// World-space positions of a primitive, taking the first node that draws its mesh (quantization
// moves the dequantizing scale and offset into that node's transform).
function worldPositions(doc, mesh, prim, drawnBy = null) {
	const node = drawnBy || doc.getRoot().listNodes().find((n) => n.getMesh() === mesh);
	const m = node ? node.getWorldMatrix() : [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
	const position = prim.getAttribute('POSITION');
	const out = [];
	const el = [];
	for (let i = 0; i < position.getCount(); i++) {
		position.getElement(i, el); // normalized integers come back as their float values
		out.push(transformPoint(m, el[0], el[1], el[2]));
	}
	return out;
}

// The quads in the order QF_impostor_level numbers them: primitives in order, then each run of
// 6 indices (2 triangles, 4 distinct vertices). Each quad is given by its centroid; `canonical`
// says whether every quad still has the triangles (0, 1, 2), (0, 2, 3) of its corners that the
// schema promises (a runtime may take the corners in that order).
function quadCentroids(doc) {
	const centroids = [];
	let broken = false;
	let canonical = true;
	for (const mesh of doc.getRoot().listMeshes()) {
		for (const prim of mesh.listPrimitives()) {
			if (prim.getMode() !== TRIANGLES) continue;
			const pos = worldPositions(doc, mesh, prim);
			const indices = prim.getIndices();
			const count = indices ? indices.getCount() : pos.length;
			if (count % 6 !== 0) broken = true;
			for (let q = 0; q + 6 <= count; q += 6) {
				const verts = new Set();
				for (let k = 0; k < 6; k++) verts.add(indices ? indices.getScalar(q + k) : q + k);
				if (verts.size !== 4) broken = true;
				const at = (k) => (indices ? indices.getScalar(q + k) : q + k);
				if (at(3) !== at(0) || at(4) !== at(2)) canonical = false;
				const c = [0, 0, 0];
				for (const v of verts) for (let a = 0; a < 3; a++) c[a] += pos[v][a] / verts.size;
				centroids.push(c);
			}
		}
	}
	return { centroids, broken, canonical };
}

function bboxDiagonal(points) {
	if (!points.length) return 0;
	const lo = [Infinity, Infinity, Infinity];
	const hi = [-Infinity, -Infinity, -Infinity];
	for (const p of points) for (let a = 0; a < 3; a++) { lo[a] = Math.min(lo[a], p[a]); hi[a] = Math.max(hi[a], p[a]); }
	return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

function triangleCount(mesh) {
	let n = 0;
	for (const prim of mesh.listPrimitives()) {
		if (prim.getMode() !== TRIANGLES) continue;
		const idx = prim.getIndices();
		n += (idx ? idx.getCount() : prim.getAttribute('POSITION').getCount()) / 3;
	}
	return n;
}

/** What a .glb's QF_impostor_level, QF_point_impostor and MSFT_lod hold, decoded. */
export async function inspectGlb(bytes) {
	const io = await createIO({ qf: false });
	const jsonDoc = await io.binaryToJSON(bytes);
	const json = structuredClone(jsonDoc.json);
	const doc = await io.readJSON(jsonDoc);
	const accessors = doc.getRoot().listAccessors();
	const nodes = doc.getRoot().listNodes();
	const result = { bytes: bytes.byteLength, extensionsUsed: json.extensionsUsed || [] };

	const levelDef = json.extensions?.[QF_IMPOSTOR_LEVEL];
	if (levelDef) {
		const arrays = {};
		for (const key of ['domain', 'error', 'neighborOffsets', 'neighbors']) {
			if (levelDef[key] === undefined) continue;
			const accessor = accessors[levelDef[key]];
			arrays[key] = accessor ? Array.from(accessor.getArray()) : null;
		}
		result.impostorLevel = { def: levelDef, arrays };
	}
	// The quads, with or without the extension (to tell a dropped block from reordered quads).
	const quads = quadCentroids(doc);
	result.quads = quads.centroids;
	result.quadsBroken = quads.broken;
	result.quadsCanonical = quads.canonical;
	result.quadsDiagonal = bboxDiagonal(quads.centroids);

	const pointDef = json.extensions?.[QF_POINT_IMPOSTOR];
	if (pointDef) result.pointImpostor = { def: pointDef };
	// The points themselves, with or without the extension (to tell a dropped block from lost points).
	const pointPrims = [];
	for (const mesh of doc.getRoot().listMeshes()) {
		for (const prim of mesh.listPrimitives()) {
			if (prim.getMode() !== POINTS) continue;
			// Points are drawn in index order where a transform (join) gave them indices.
			const pos = worldPositions(doc, mesh, prim);
			const indices = prim.getIndices();
			pointPrims.push(indices ? Array.from(indices.getArray(), (i) => pos[i]) : pos);
		}
	}
	result.points = pointPrims.flat();
	// The vertex attributes of every primitive (prune drops a point impostor's NORMAL, which no
	// material asks for, unless told to keep attributes).
	result.semantics = [...new Set(doc.getRoot().listMeshes().flatMap((m) => m.listPrimitives())
		.flatMap((p) => p.listSemantics()))].sort();
	result.pointsDiagonal = bboxDiagonal(result.points);

	const lods = [];
	(json.nodes || []).forEach((nodeDef, i) => {
		const lodDef = nodeDef.extensions?.[MSFT_LOD];
		if (!lodDef) return;
		const chain = [i, ...lodDef.ids].map((id) => {
			const mesh = nodes[id]?.getMesh();
			// Where the level is drawn: the centre of its world-space bounds. A transform that moves
			// the scene but not the LOD nodes outside it (center) shows up as levels apart.
			const pts = mesh ? mesh.listPrimitives().flatMap((p) => worldPositions(doc, mesh, p, nodes[id])) : [];
			const lo = [Infinity, Infinity, Infinity];
			const hi = [-Infinity, -Infinity, -Infinity];
			for (const p of pts) for (let a = 0; a < 3; a++) { lo[a] = Math.min(lo[a], p[a]); hi[a] = Math.max(hi[a], p[a]); }
			return {
				node: id, name: nodes[id]?.getName() ?? null, triangles: mesh ? triangleCount(mesh) : 0,
				center: lo.map((v, a) => (v + hi[a]) / 2), diagonal: bboxDiagonal(pts),
			};
		});
		lods.push({ node: i, levels: chain, screencoverage: nodeDef.extras?.MSFT_screencoverage ?? null });
	});
	result.lods = lods;
	// Every mesh-carrying node, in a scene or not: what a file without MSFT_lod still holds.
	result.meshNodes = nodes.filter((n) => n.getMesh()).length;
	return result;
}

// Whether b[i] is a[i] for every i, to `tol`, after moving both sets' means to the origin: `center`
// moves the whole model, which a runtime does not mind, so only the order and the shape count.
function sameSequence(a, b, tol) {
	if (a.length !== b.length) return false;
	if (!a.length) return true;
	const mean = (s) => s.reduce((m, p) => [m[0] + p[0] / s.length, m[1] + p[1] / s.length, m[2] + p[2] / s.length], [0, 0, 0]);
	const ma = mean(a);
	const mb = mean(b);
	return a.every((p, i) => Math.hypot(p[0] - ma[0] - b[i][0] + mb[0], p[1] - ma[1] - b[i][1] + mb[1],
		p[2] - ma[2] - b[i][2] + mb[2]) <= tol);
}

/**
 * Compares a file after a transform with the file before it: whether each extension is still
 * there, whether its arrays hold the same values, whether quad k (point k) is still where it was
 * (to a tolerance of `tolerance` × the bounding box diagonal, for quantization), and MSFT_lod's
 * level count.
 */
export function compareInspections(before, after, { tolerance = 2e-3 } = {}) {
	const out = {};
	if (before.impostorLevel) {
		const b = before.impostorLevel;
		const a = after.impostorLevel;
		out.impostorLevel = { kept: !!a };
		if (a) {
			out.impostorLevel.arraysEqual = Object.keys(b.arrays).every((key) => {
				const x = b.arrays[key];
				const y = a.arrays[key];
				// error is FLOAT in both files; every transform here copies it bit for bit.
				return Array.isArray(y) && x.length === y.length && x.every((v, i) => v === y[i]);
			}) && Object.keys(a.arrays).length === Object.keys(b.arrays).length;
			out.impostorLevel.quadCountEqual = a.def.quadCount === b.def.quadCount;
		}
		out.quadCountAfter = after.quads.length;
		out.quadsInOrder = !after.quadsBroken && (after.quadsCanonical || !before.quadsCanonical)
			&& sameSequence(before.quads, after.quads, tolerance * before.quadsDiagonal);
	}
	if (before.pointImpostor) {
		out.pointImpostor = { kept: !!after.pointImpostor };
		if (after.pointImpostor) {
			// Key by key: a writer may order the keys differently.
			const a = after.pointImpostor.def;
			const b = before.pointImpostor.def;
			const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
			out.pointImpostor.defEqual = [...keys].every((k) => JSON.stringify(a[k]) === JSON.stringify(b[k]));
		}
		out.pointCountAfter = after.points.length;
		out.pointsInOrder = sameSequence(before.points, after.points, tolerance * before.pointsDiagonal);
	}
	out.semanticsKept = before.semantics.every((sem) => after.semantics.includes(sem));
	out.semanticsLost = before.semantics.filter((sem) => !after.semantics.includes(sem));
	if (before.lods.length) {
		const levelsBefore = before.lods[0].levels.length;
		const levelsAfter = after.lods.length ? after.lods[0].levels.length : (after.meshNodes ? 1 : 0);
		out.lod = {
			kept: after.lods.length === before.lods.length,
			levelsBefore, levelsAfter,
			trianglesBefore: before.lods[0].levels.map((l) => l.triangles),
			trianglesAfter: after.lods.length ? after.lods[0].levels.map((l) => l.triangles) : null,
			// Each level where it was relative to the first, to 1% of the first's size.
			levelsAligned: after.lods.length > 0 && after.lods[0].levels.length === levelsBefore
				&& after.lods[0].levels.every((l, i) => {
					const b0 = before.lods[0].levels[0];
					const a0 = after.lods[0].levels[0];
					const bi = before.lods[0].levels[i];
					const d = [0, 1, 2].map((k) => (l.center[k] - a0.center[k]) - (bi.center[k] - b0.center[k]));
					return Math.hypot(...d) <= 0.01 * b0.diagonal;
				}),
			screencoverageKept: JSON.stringify(after.lods[0]?.screencoverage) === JSON.stringify(before.lods[0].screencoverage),
		};
	}
	return out;
}
