// The JSON side of glTF input (gltf_read.cpp): the type checks of the keys the reader uses. Only
// nlohmann::json here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/file_io.h"

namespace qf::io {

// The JSON of a .gltf, or of a .glb's first chunk; null when it does not parse (tinygltf then says why).
nlohmann::json gltf_json(ByteView bytes);

// tinygltf skips values of the wrong JSON type and goes on with defaults, so a malformed file would
// bake as something else. The keys the reader uses are checked first, by the type the glTF schema
// gives them wherever they appear: InputError "gltf.json_type" naming the first wrong one by its
// JSON path ("materials[0].alphaCutoff: expected a number, found a string").
void check_gltf_json_types(const nlohmann::json& j, const std::string& path);

}  // namespace qf::io
