// Draco compression of a triangle list for KHR_draco_mesh_compression (gltf-notes.md 2.4): the only
// file that includes Draco's headers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace qf {

// Per-vertex attributes of an unindexed triangle list (3 vertices per triangle).
struct DracoInput {
  std::vector<float> positions;       // 3 per vertex
  std::vector<float> normals;         // 3 per vertex, or empty
  std::vector<std::uint16_t> colors;  // 4 per vertex (normalized 16-bit linear RGBA), or empty
};

// The compressed bytes and what the glTF accessors must say: Draco renumbers and merges vertices,
// so the count and the POSITION bounds come from decoding the result. Attribute ids are Draco's
// unique ids (-1 when absent). Same input, same bytes.
struct DracoOutput {
  std::vector<std::uint8_t> bytes;
  std::size_t vertices = 0, indices = 0;
  std::array<double, 3> min{}, max{};
  int position_id = -1, normal_id = -1, color_id = -1;
};

// Quantisation: positions 14 bits, normals 10 bits; colours are stored losslessly. Throws
// std::runtime_error when Draco fails.
DracoOutput draco_compress(const DracoInput& in);

// A decoded Draco mesh (KHR_draco_mesh_compression input): its point count, triangle corners, and
// the attributes asked for by unique id with the component count glTF's accessor gives them,
// converted to floats (normalized integers scaled to 0..1 or -1..1). Throws std::runtime_error
// when the stream does not decode or lacks an attribute.
struct DracoMesh {
  std::size_t points = 0;
  std::vector<std::uint32_t> corners;
  std::map<int, std::vector<float>> attributes;
};
DracoMesh draco_decode_mesh(const std::uint8_t* bytes, std::size_t size, const std::vector<std::pair<int, int>>& wanted);

// The positions (3 per point) and triangle corners a Draco reader gets from `bytes`; throws
// std::runtime_error when they do not decode. For checks and tools.
void draco_decode(const std::vector<std::uint8_t>& bytes, std::vector<float>& positions, std::vector<std::uint32_t>& corners);

}  // namespace qf
