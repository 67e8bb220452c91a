// On-disk cache of AMG hierarchies (thesis 5.2.1: the hierarchy depends only on the input and the
// analysis settings, so choosing another level must not redo analysis and coarsening).
#pragma once

#include <optional>
#include <string>

#include "amg/hierarchy.h"
#include "analysis/analysis.h"
#include "core/file_io.h"

namespace qf {

// 128-bit content key of everything the hierarchy depends on: the format version, positions,
// normals (when present), analysis options and AMG options. Hex, 32 characters.
std::string hierarchy_cache_key(const PointSet& points, const AnalysisOptions& analysis, const AmgOptions& amg);

// "<dir>/<key>.qfamg". A file that is missing, truncated, corrupt (checksum), of another format
// version or for another key yields nullopt, with the reason in `why` ("missing", "corrupt", ...).
// `normals`, if given, receives the normals stored with the hierarchy (empty if none were).
std::optional<AmgHierarchy> load_hierarchy(const std::string& dir, const std::string& key, std::string* why = nullptr,
                                           std::vector<Vec3f>* normals = nullptr);

// load_hierarchy on a file's bytes already in memory (the fuzz target of tests/fuzz calls it).
std::optional<AmgHierarchy> decode_hierarchy(ByteView bytes, const std::string& key, std::string* why = nullptr,
                                             std::vector<Vec3f>* normals = nullptr);

// Writes the hierarchy atomically (temporary name, then rename), creating `dir` if needed, with
// the analysis' estimated normals for inputs that have none (later stages orient and light with
// them, and a cache hit must give the same output as a miss).
void save_hierarchy(const std::string& dir, const std::string& key, const AmgHierarchy& h,
                    const std::vector<Vec3f>& normals = {});

}  // namespace qf
