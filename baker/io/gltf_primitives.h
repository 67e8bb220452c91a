// One glTF primitive's vertex attributes and triangles (for gltf_read.cpp): accessors of any
// component type read as floats after checking that they lie within their buffer views and
// buffers, strips and fans as triangle lists (Draco and meshopt data are decoded before, by
// gltf/compressed_gltf.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace qf::io {

// In the mesh's own space: 3, 3, 4 and 2 floats per vertex (empty when absent); colours RGBA
// linear (RGB ones get alpha 1); uvs of texture-coordinate set `uv_set`, untransformed.
struct PrimitiveData {
  std::vector<float> positions, normals, colors, uvs;
  std::vector<std::uint32_t> corners;  // 3 per triangle, each < the vertex count
};

// Throws InputError "gltf.*" naming `path` and the JSON path `where` (e.g. "meshes[0].primitives[1]").
PrimitiveData read_primitive(const tinygltf::Model& m, const tinygltf::Primitive& p, int uv_set, const std::string& path,
                             const std::string& where);

// What decoding the primitive's KHR_draco_mesh_compression stream would allocate, in bytes, from
// the face and point counts its connectivity header declares (Draco bitstream 2.2, what current
// encoders write): the decoder sizes its corner table and attribute buffers by them before it
// reads the data they describe, so a stream of a few bytes can claim 2^31 faces. 0 for a
// primitive without the extension, or a stream whose counts cannot be read here (another
// bitstream version, metadata first, a bad view): the decoder judges those.
double draco_decoding_bytes(const tinygltf::Model& m, const tinygltf::Primitive& p);

}  // namespace qf::io
