// Draco for KHR_draco_mesh_compression: compression of a triangle list (draco.cpp, gltf-notes.md 2.4)
// and decoding of the glTF readers' input (draco_decode.cpp). Those two files, built into the shared
// library qf_draco, are the only ones that include Draco's headers.
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

// ---- Decoding (draco_decode.cpp): KHR_draco_mesh_compression input ----

// What a Draco stream's header claims, read without Draco (which allocates for the counts before
// it reads the data they describe: a 60-byte stream claiming 2^30 faces asked for 12 GB): its
// faces and, for the sequential method, its points (edgebreaker streams: at most 3 a face).
// Throws std::runtime_error when the header does not read or is not a triangle mesh's.
struct DracoCounts {
  std::uint64_t faces = 0, points = 0;
};
DracoCounts draco_peek_counts(const std::uint8_t* bytes, std::size_t size);

// One attribute asked of a decoded mesh: Draco's unique id, the component count glTF's accessor
// gives it and the accessor's componentType (glTF's code: 5120 .. 5126).
struct DracoRequest {
  int id = -1, components = 0, component_type = 5126;
};
// Its values, one per point, tightly packed little-endian in `component_type`: the type asked for,
// except that an attribute Draco holds as floats (its quantized positions, normals, uvs) comes
// back as floats (5126), not requantized. Integer attributes asked as floats are converted as
// glTF's normalized accessors are (0..1 / -1..1) when Draco marks them normalized.
struct DracoValues {
  int component_type = 5126;
  std::vector<std::uint8_t> bytes;
};
// A decoded mesh: its point count, triangle corners (3 a face, each < points) and the attributes asked for.
struct DracoTypedMesh {
  std::size_t points = 0;
  std::vector<std::uint32_t> corners;
  std::map<int, DracoValues> attributes;
};
// Throws std::runtime_error when the stream does not decode, lacks an attribute asked for, or an
// attribute's values do not convert.
DracoTypedMesh draco_decode_typed(const std::uint8_t* bytes, std::size_t size, const std::vector<DracoRequest>& wanted);

// The positions (3 per point) and triangle corners a Draco reader gets from `bytes`; throws
// std::runtime_error when they do not decode. For checks and tools.
void draco_decode(const std::vector<std::uint8_t>& bytes, std::vector<float>& positions, std::vector<std::uint32_t>& corners);

}  // namespace qf
