// Wavefront MTL material libraries, for the OBJ reader (text_read.cpp): Kd and map_Kd.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/file_io.h"
#include "core/types.h"
#include "io/model_io.h"

namespace qf::io {

// The materials of one mesh by name, filled from the MTL files its OBJ names.
struct MaterialLibrary {
  std::map<std::string, std::uint32_t> by_name;  // into mesh.materials
};

// Reads `mtl_path` (as written in the OBJ: relative to the OBJ's folder, '\' taken as '/') into
// mesh.materials and mesh.textures: per `newmtl`, Kd (sRGB, like the texture) and map_Kd (the
// image through OpenImageIO; a missing or undecodable image is an InputError naming the MTL line).
// A missing MTL file is only a warning in the report: the geometry still bakes, uncoloured.
void read_mtl(const std::string& obj_path, const std::string& mtl_path, TriangleMesh& mesh, MaterialLibrary& library,
              ReadReport* report);

// Words of the rest of a line joined by single spaces (material names may hold spaces).
std::string join_words(const std::vector<std::string_view>& words);

}  // namespace qf::io
