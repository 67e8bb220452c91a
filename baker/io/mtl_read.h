// Wavefront MTL material libraries, for the OBJ reader (text_read.cpp): Kd and map_Kd.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/file_io.h"
#include "core/types.h"
#include "io/model_io.h"

namespace qf::io {

// The materials of one mesh by name, filled from the MTL files its OBJ names, and what their
// files may use: the folder they must stay inside and the memory their images may take.
struct MaterialLibrary {
  std::map<std::string, std::uint32_t> by_name;  // into mesh.materials
  std::filesystem::path root;                    // canonical (io/asset_files.h asset_root)
  std::size_t memory_limit = 0;                  // ReadOptions::memory_limit
  std::uint64_t image_bytes = 0;                 // decoded so far, RGBA8
};

// Reads `mtl_path` (as written in the OBJ at `obj_line`: relative to the OBJ's folder, '\' taken
// as '/') into mesh.materials and mesh.textures: per `newmtl`, Kd (sRGB, like the texture) and
// map_Kd (the image through OpenImageIO; a missing or undecodable image is an InputError naming
// the MTL line). The MTL and its images must resolve inside library.root and be regular files
// (InputError "obj.outside_asset" / "mtl.outside_asset", "...not_regular_file"); each image's
// decoded size is read from its header and the images' total checked against the memory limit
// before it is decoded ("mtl.memory"). A missing MTL file is only a warning in the report: the
// geometry still bakes, uncoloured.
void read_mtl(const std::string& obj_path, const std::string& mtl_path, std::size_t obj_line, TriangleMesh& mesh,
              MaterialLibrary& library, ReadReport* report);

// Words of the rest of a line joined by single spaces (material names may hold spaces).
std::string join_words(const std::vector<std::string_view>& words);

}  // namespace qf::io
