// The steps of building a .glb that the impostor levels' writer (glb.cpp) and the mesh writers
// (glb_mesh.cpp: cluster and mesh LODs, point impostors) share. Internal to baker/gltf; include it
// after <tiny_gltf.h>.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gltf/glb.h"

namespace qf::glb_model {

// What a texture holds: how its mip levels are made and how it is encoded.
enum class TextureClass { kColor, kNormal, kData, kEmissive };

// A model with buffer 0, the asset header (the options' generator) and sampler 0 (trilinear, clamped).
tinygltf::Model new_model(const GltfOptions& options);
// Appends raw bytes to buffer 0 (4-byte aligned) and returns a bufferView over them (`target`:
// the bufferView's target, 0 for none).
int add_view(tinygltf::Model& m, const void* data, std::size_t bytes, int target);
// A float VECn accessor with exact min/max where `bounds` (of the float32 values as stored);
// `target`: the bufferView's (vertex data; 0 for other data).
int add_floats(tinygltf::Model& m, const std::vector<float>& v, int components, int type, bool bounds,
               int target = TINYGLTF_TARGET_ARRAY_BUFFER);
// An index accessor of `idx`, uint16 where every index fits, else uint32; returns its index.
int add_indices(tinygltf::Model& m, const std::vector<std::uint32_t>& idx);
// Adds an image and a texture of it in the options' format; returns the texture's index.
int add_texture(tinygltf::Model& m, const std::vector<std::uint8_t>& rgba, int w, int h, const std::string& name,
                TextureClass cls, const GltfOptions& options, TextureCost* cost);
// `mesh` as the model's only mesh, held by its only node, the default scene's one root; returns
// the node.
tinygltf::Node& add_single_node_scene(tinygltf::Model& m, tinygltf::Mesh mesh);
// The model as .glb bytes.
std::vector<std::uint8_t> write_glb(tinygltf::Model& m);

}  // namespace qf::glb_model
