// Loading what runtime_gl draws: a baked .glb (tinygltf, with the QF_impostor_level extension when
// present). References made from input files are measure/reference_scene.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "runtime_gl/engine_scene.h"
#include "runtime_gl/scene.h"

namespace qf::render {

// Reads a .glb or .gltf. With the extension, item k is the extension's quad k (its centre, normal
// and neighbours); without it every pair of triangles (or lone triangle) is an item with its own
// centroid and normal, and no neighbours. Throws InputError ("render.gltf.*") naming the file.
ImpostorScene load_gltf(const std::string& path);

// Any .glb/.gltf the baker writes, parsed once: a point impostor (QF_point_impostor), a
// vertex-clustering LOD (node extras cellWidth, from `qf-bake cluster`), else an impostor level as
// load_gltf reads it. Throws InputError ("render.gltf.*") naming the file.
struct BakedScene {
  enum Kind { kImpostor, kPoints, kCluster } kind = kImpostor;
  bool asset = false;  // kImpostor without QF_impostor_level: a game asset, not a baked level
  ImpostorScene impostor;
  PointImpostorScene points;
  ClusterScene cluster;
  EngineScene engine;  // the whole file as a standard engine draws it (any kind)
  // A combined LOD file (MSFT_lod): every level alone, finest first (the fields above hold the
  // finest), and down to which screen coverage each is shown (MSFT_screencoverage).
  std::vector<BakedScene> lods;
  std::vector<double> lod_coverage;
};
BakedScene load_baked(const std::string& path);
// The same from a .glb file's bytes in memory (images embedded); errors name `name`.
BakedScene load_baked(const std::vector<std::uint8_t>& glb, const std::string& name);

}  // namespace qf::render
