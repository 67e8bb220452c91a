// Config for the glTF-Transform CLI (4.x):
//   gltf-transform <command> IN OUT --config tools/gltf-transform-qf/gltf-transform.config.mjs
// The CLI imports this file and Object.assign()s its default export over its own defaults, so
// `extensions` replaces the CLI's list rather than adding to it: it has to name the standard
// extensions too, or every KHR_/EXT_ extension (mesh quantization, texture_basisu, webp, draco,
// meshopt) would be dropped instead of ours being kept.
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { QF_EXTENSIONS } from './src/index.mjs';

export default {
	extensions: [...ALL_EXTENSIONS, ...QF_EXTENSIONS],
};
