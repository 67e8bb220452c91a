// glTF-Transform extensions for the three extensions quasiflat writes, so that the glTF-Transform
// library and CLI read them into the document graph and write them back instead of dropping them
// ("Missing optional extension") as they do for any extension they do not know.
//
// The point of doing this with ExtensionProperty objects rather than copying the JSON through is
// that every index an extension holds (an accessor of QF_impostor_level, a node or material of
// MSFT_lod) becomes an edge of the graph. Transforms then see the extension as a parent of that
// data: prune keeps it, dedup and other swaps redirect the edge, and the writer renumbers it to
// wherever the data ends up in the output file.
import { Extension, ExtensionProperty, PropertyType, RefList } from '@gltf-transform/core';

export const QF_IMPOSTOR_LEVEL = 'QF_impostor_level';
export const QF_POINT_IMPOSTOR = 'QF_point_impostor';
export const MSFT_LOD = 'MSFT_lod';

// Accessor usage of the per-quad arrays. The writer groups accessors by usage into buffer views and
// gives a target only to vertex and index usages; a usage of our own keeps these arrays in a buffer
// view with no target, as schemas/QF_impostor_level requires, and apart from vertex data.
const IMPOSTOR_ARRAY_USAGE = 'QF_IMPOSTOR_LEVEL_ARRAY';

// The keys of QF_impostor_level that hold accessor indices, in the schema's order.
const IMPOSTOR_ACCESSOR_KEYS = ['domain', 'error', 'neighborOffsets', 'neighbors'];
// Its keys that hold plain values; anything else is carried through verbatim (see `unknown`).
const IMPOSTOR_VALUE_KEYS = ['level', 'quadCount', 'blend', 'alphaRef', 'alphaExponent'];

function plainCopy(value) {
	return value === undefined ? undefined : JSON.parse(JSON.stringify(value));
}

/** Root-level property of QF_impostor_level: the level's values and its four accessors. */
export class ImpostorLevel extends ExtensionProperty {
	static EXTENSION_NAME = QF_IMPOSTOR_LEVEL;

	init() {
		this.extensionName = QF_IMPOSTOR_LEVEL;
		this.propertyType = 'QFImpostorLevel';
		this.parentTypes = [PropertyType.ROOT];
	}

	getDefaults() {
		return Object.assign(super.getDefaults(), {
			level: 0,
			quadCount: 0,
			blend: 'additive_sorted_lock_by_depth',
			alphaRef: 0.1,
			alphaExponent: null, // absent: the schema's default 1
			domain: null,
			error: null,
			neighborOffsets: null,
			neighbors: null,
			// Keys of the JSON this code does not know (e.g. `center`, `normal`, `atlasRect` of files
			// baked before December 2026, which readers ignore). They hold values, not indices, so
			// copying them unchanged cannot leave a stale reference behind.
			unknown: {},
		});
	}

	getLevel() { return this.get('level'); }
	setLevel(v) { return this.set('level', v); }
	getQuadCount() { return this.get('quadCount'); }
	setQuadCount(v) { return this.set('quadCount', v); }
	getBlend() { return this.get('blend'); }
	setBlend(v) { return this.set('blend', v); }
	getAlphaRef() { return this.get('alphaRef'); }
	setAlphaRef(v) { return this.set('alphaRef', v); }
	getAlphaExponent() { return this.get('alphaExponent'); }
	setAlphaExponent(v) { return this.set('alphaExponent', v); }

	/** Per quad: its basis function's index at the level. */
	getDomain() { return this.getRef('domain'); }
	setDomain(accessor) { return this.setRef('domain', accessor, { usage: IMPOSTOR_ARRAY_USAGE }); }
	/** Per quad: mean distance of its domain's points to its plane. */
	getError() { return this.getRef('error'); }
	setError(accessor) { return this.setRef('error', accessor, { usage: IMPOSTOR_ARRAY_USAGE }); }
	/** Compressed rows of the neighbour graph: quadCount + 1 offsets into `neighbors`. */
	getNeighborOffsets() { return this.getRef('neighborOffsets'); }
	setNeighborOffsets(accessor) {
		return this.setRef('neighborOffsets', accessor, { usage: IMPOSTOR_ARRAY_USAGE });
	}
	/** Quad indices of the neighbour graph's rows. */
	getNeighbors() { return this.getRef('neighbors'); }
	setNeighbors(accessor) { return this.setRef('neighbors', accessor, { usage: IMPOSTOR_ARRAY_USAGE }); }

	getUnknown() { return this.get('unknown'); }
	setUnknown(v) { return this.set('unknown', v); }
}

/** The QF_impostor_level extension: reads and writes the document's ImpostorLevel. */
export class QFImpostorLevel extends Extension {
	static EXTENSION_NAME = QF_IMPOSTOR_LEVEL;
	extensionName = QF_IMPOSTOR_LEVEL;

	// glTF-Transform 4.5.1's EXT_meshopt_compression writer stores every accessor it claims in
	// meshopt's ATTRIBUTES mode, which needs a byte stride divisible by 4: it pads a 1- or 2-byte
	// SCALAR to 4 bytes an element but writes `byteStride` on the buffer view only for vertex data.
	// A reader then takes our UNSIGNED_BYTE / UNSIGNED_SHORT arrays as tightly packed and reads
	// [0, 1, 2, 3] back as [0, 0, 0, 0] (measured; docs/toolchain.md). The writer claims accessors
	// in its "Accessor" prewrite hook, which runs before ours (hooks run in extension-name order),
	// so the only point where we can act first is `install`, which the writer calls for every
	// extension's writeDependencies before any prewrite. There, when the document is going to be
	// meshopt-compressed, our integer arrays become UNSIGNED_INT: the same values, 4 bytes each,
	// which meshopt then compresses without padding (the high zero bytes cost little).
	writeDependencies = ['qf.widen-for-meshopt'];

	install(key, dependency) {
		if (key === 'qf.widen-for-meshopt') this.widenForMeshopt();
		return super.install(key, dependency);
	}

	widenForMeshopt() {
		const root = this.document.getRoot();
		const meshopt = root.listExtensionsUsed().some((ext) => ext.extensionName === 'EXT_meshopt_compression');
		const level = root.getExtension(QF_IMPOSTOR_LEVEL);
		if (!meshopt || !level) return;
		for (const key of ['domain', 'neighborOffsets', 'neighbors']) {
			const accessor = level.getRef(key);
			if (!accessor || accessor.getComponentSize() >= 4 || accessor.getNormalized()) continue;
			// An accessor shared with mesh data (dedup can merge equal arrays) keeps its type: the
			// vertex or index data decides it, and meshopt writes those with a proper stride.
			const shared = accessor.listParents().some((p) => p !== root && p !== level);
			if (!shared) accessor.setArray(Uint32Array.from(accessor.getArray()));
		}
	}

	createImpostorLevel() {
		return new ImpostorLevel(this.document.getGraph());
	}

	read(context) {
		const def = context.jsonDoc.json.extensions?.[QF_IMPOSTOR_LEVEL];
		if (!def) return this;
		const level = this.createImpostorLevel();
		const unknown = {};
		for (const [key, value] of Object.entries(def)) {
			if (IMPOSTOR_VALUE_KEYS.includes(key)) level.set(key, value);
			else if (IMPOSTOR_ACCESSOR_KEYS.includes(key)) {
				const accessor = context.accessors[value];
				// An index past the accessors is a broken file; refusing it here beats writing a
				// reference to whatever accessor happens to get that index later.
				if (!accessor) throw new Error(`${QF_IMPOSTOR_LEVEL}: "${key}" names accessor ${value}, which does not exist.`);
				level.setRef(key, accessor, { usage: IMPOSTOR_ARRAY_USAGE });
			} else if (key === 'extras') level.setExtras(plainCopy(value));
			else if (key !== 'extensions') unknown[key] = plainCopy(value);
		}
		level.setUnknown(unknown);
		this.document.getRoot().setExtension(QF_IMPOSTOR_LEVEL, level);
		return this;
	}

	write(context) {
		const level = this.document.getRoot().getExtension(QF_IMPOSTOR_LEVEL);
		if (!level) return this;
		const def = { ...plainCopy(level.getUnknown()) };
		for (const key of IMPOSTOR_VALUE_KEYS) {
			const value = level.get(key);
			if (value !== null && value !== undefined) def[key] = value;
		}
		for (const key of IMPOSTOR_ACCESSOR_KEYS) {
			const accessor = level.getRef(key);
			if (accessor) def[key] = context.accessorIndexMap.get(accessor);
		}
		const extras = level.getExtras();
		if (extras && Object.keys(extras).length) def.extras = plainCopy(extras);
		this.checkQuads(level, context.logger);
		const json = context.jsonDoc.json;
		json.extensions = json.extensions || {};
		json.extensions[QF_IMPOSTOR_LEVEL] = def;
		return this;
	}

	// The extension's arrays are per quad, and quad k is the k-th run of 6 indices of the mesh. A
	// transform that changes the number of quads (simplify at a large error) keeps the arrays
	// intact but breaks that pairing, and nothing else would notice: warn. One that only reorders
	// the quads keeps the counts; of those, Draco is recognised by its extension.
	checkQuads(level, logger) {
		const quadCount = level.getQuadCount();
		if (this.document.getRoot().listExtensionsUsed().some((ext) => ext.extensionName === 'KHR_draco_mesh_compression')) {
			logger.warn(`${QF_IMPOSTOR_LEVEL}: Draco stores the triangles in its own order, so quad k is no longer `
				+ `the k-th pair of triangles that the per-quad arrays describe (use meshopt or quantize).`);
		}
		const meshes = this.document.getRoot().listMeshes();
		let indexCount = 0;
		for (const mesh of meshes) {
			for (const prim of mesh.listPrimitives()) {
				const indices = prim.getIndices();
				indexCount += indices ? indices.getCount() : (prim.getAttribute('POSITION')?.getCount() ?? 0);
			}
		}
		if (meshes.length !== 1 || indexCount !== 6 * quadCount) {
			logger.warn(`${QF_IMPOSTOR_LEVEL}: quadCount is ${quadCount} but the document has ${meshes.length} mesh(es) `
				+ `with ${indexCount} indices (expected one mesh, ${6 * quadCount}); a transform changed the quads, `
				+ `so the per-quad arrays no longer match them.`);
		}
		const perQuad = [['domain', quadCount], ['error', quadCount], ['neighborOffsets', quadCount + 1]];
		for (const [key, count] of perQuad) {
			const accessor = level.getRef(key);
			if (accessor && accessor.getCount() !== count) {
				logger.warn(`${QF_IMPOSTOR_LEVEL}: "${key}" has ${accessor.getCount()} elements, expected ${count}.`);
			}
		}
	}
}

const POINT_KEYS = ['pixelSize', 'pointCount', 'seed', 'switchDistance', 'switchScreenHeight', 'switchFovDegrees'];

/** Root-level property of QF_point_impostor. It holds values only, no indices. */
export class PointImpostor extends ExtensionProperty {
	static EXTENSION_NAME = QF_POINT_IMPOSTOR;

	init() {
		this.extensionName = QF_POINT_IMPOSTOR;
		this.propertyType = 'QFPointImpostor';
		this.parentTypes = [PropertyType.ROOT];
	}

	getDefaults() {
		return Object.assign(super.getDefaults(), {
			pixelSize: 0,
			pointCount: 0,
			seed: 0,
			switchDistance: 0,
			switchScreenHeight: 1080,
			switchFovDegrees: 60,
			unknown: {},
		});
	}

	getPixelSize() { return this.get('pixelSize'); }
	setPixelSize(v) { return this.set('pixelSize', v); }
	getPointCount() { return this.get('pointCount'); }
	setPointCount(v) { return this.set('pointCount', v); }
	getSeed() { return this.get('seed'); }
	setSeed(v) { return this.set('seed', v); }
	getSwitchDistance() { return this.get('switchDistance'); }
	setSwitchDistance(v) { return this.set('switchDistance', v); }
	getSwitchScreenHeight() { return this.get('switchScreenHeight'); }
	setSwitchScreenHeight(v) { return this.set('switchScreenHeight', v); }
	getSwitchFovDegrees() { return this.get('switchFovDegrees'); }
	setSwitchFovDegrees(v) { return this.set('switchFovDegrees', v); }
	getUnknown() { return this.get('unknown'); }
	setUnknown(v) { return this.set('unknown', v); }
}

/** The QF_point_impostor extension. */
export class QFPointImpostor extends Extension {
	static EXTENSION_NAME = QF_POINT_IMPOSTOR;
	extensionName = QF_POINT_IMPOSTOR;

	createPointImpostor() {
		return new PointImpostor(this.document.getGraph());
	}

	read(context) {
		const def = context.jsonDoc.json.extensions?.[QF_POINT_IMPOSTOR];
		if (!def) return this;
		const points = this.createPointImpostor();
		const unknown = {};
		for (const [key, value] of Object.entries(def)) {
			if (POINT_KEYS.includes(key)) points.set(key, value);
			else if (key === 'extras') points.setExtras(plainCopy(value));
			else if (key !== 'extensions') unknown[key] = plainCopy(value);
		}
		points.setUnknown(unknown);
		this.document.getRoot().setExtension(QF_POINT_IMPOSTOR, points);
		return this;
	}

	write(context) {
		const points = this.document.getRoot().getExtension(QF_POINT_IMPOSTOR);
		if (!points) return this;
		const def = { ...plainCopy(points.getUnknown()) };
		for (const key of POINT_KEYS) def[key] = points.get(key);
		const extras = points.getExtras();
		if (extras && Object.keys(extras).length) def.extras = plainCopy(extras);
		// pointCount is the POINTS primitive's vertex count, and a runtime draws a prefix of the
		// points in their stored (random) order. A transform that drops, merges or reorders points
		// (simplify, weld, reorder) leaves this block stale; say so rather than write it silently.
		const counts = [];
		for (const mesh of this.document.getRoot().listMeshes()) {
			for (const prim of mesh.listPrimitives()) {
				if (prim.getMode() === 0 /* POINTS */) counts.push(prim.getAttribute('POSITION')?.getCount() ?? 0);
			}
		}
		const total = counts.reduce((a, b) => a + b, 0);
		if (counts.length !== 1 || total !== points.getPointCount()) {
			context.logger.warn(`${QF_POINT_IMPOSTOR}: pointCount is ${points.getPointCount()} but the document has `
				+ `${counts.length} POINTS primitive(s) with ${total} points; a transform changed the points.`);
		}
		const json = context.jsonDoc.json;
		json.extensions = json.extensions || {};
		json.extensions[QF_POINT_IMPOSTOR] = def;
		return this;
	}
}

/**
 * MSFT_lod on a node or a material: the coarser stand-ins of its owner, finest first. The list
 * holds Node (or Material) references, so the LOD nodes, which are in no scene, have a parent and
 * prune keeps them, and their indices are rewritten when the output renumbers nodes.
 */
export class Lod extends ExtensionProperty {
	static EXTENSION_NAME = MSFT_LOD;

	init() {
		this.extensionName = MSFT_LOD;
		this.propertyType = 'MSFTLod';
		this.parentTypes = [PropertyType.NODE, PropertyType.MATERIAL];
	}

	getDefaults() {
		return Object.assign(super.getDefaults(), { lods: new RefList(), unknown: {} });
	}

	listLods() { return this.listRefs('lods'); }
	addLod(property) { return this.addRef('lods', property); }
	removeLod(property) { return this.removeRef('lods', property); }
	getUnknown() { return this.get('unknown'); }
	setUnknown(v) { return this.set('unknown', v); }
}

/** The MSFT_lod extension (Microsoft's vendor extension), for nodes and materials. */
export class MSFTLod extends Extension {
	static EXTENSION_NAME = MSFT_LOD;
	extensionName = MSFT_LOD;

	createLod() {
		return new Lod(this.document.getGraph());
	}

	read(context) {
		const json = context.jsonDoc.json;
		const readList = (defs, owners, targets, what) => {
			(defs || []).forEach((def, index) => {
				const lodDef = def.extensions?.[MSFT_LOD];
				if (!lodDef) return;
				const lod = this.createLod();
				for (const id of lodDef.ids || []) {
					const target = targets[id];
					if (!target) throw new Error(`${MSFT_LOD}: ${what} ${index} names ${what} ${id}, which does not exist.`);
					lod.addLod(target);
				}
				const unknown = {};
				for (const [key, value] of Object.entries(lodDef)) {
					if (key === 'extras') lod.setExtras(plainCopy(value));
					else if (key !== 'ids' && key !== 'extensions') unknown[key] = plainCopy(value);
				}
				lod.setUnknown(unknown);
				owners[index].setExtension(MSFT_LOD, lod);
			});
		};
		readList(json.nodes, context.nodes, context.nodes, 'node');
		readList(json.materials, context.materials, context.materials, 'material');
		return this;
	}

	write(context) {
		const json = context.jsonDoc.json;
		const root = this.document.getRoot();
		const writeList = (owners, defs, indexMap, what) => {
			for (const owner of owners) {
				const lod = owner.getExtension(MSFT_LOD);
				if (!lod) continue;
				const ids = [];
				for (const target of lod.listLods()) {
					const id = indexMap.get(target);
					// Every referenced node or material is written (it is in the root's lists), so a
					// missing index would mean a bug here rather than in the input.
					if (id === undefined) throw new Error(`${MSFT_LOD}: a ${what} LOD was not written.`);
					ids.push(id);
				}
				const def = defs[indexMap.get(owner)];
				const lodDef = { ...plainCopy(lod.getUnknown()), ids };
				const extras = lod.getExtras();
				if (extras && Object.keys(extras).length) lodDef.extras = plainCopy(extras);
				def.extensions = def.extensions || {};
				def.extensions[MSFT_LOD] = lodDef;
			}
		};
		writeList(root.listNodes(), json.nodes, context.nodeIndexMap, 'node');
		writeList(root.listMaterials(), json.materials, context.materialIndexMap, 'material');
		return this;
	}
}

/** The three extensions, to register with an I/O object or the CLI's config. */
export const QF_EXTENSIONS = [QFImpostorLevel, QFPointImpostor, MSFTLod];
