// qf-diff: what changed between two bakes (two .glb files, or two output folders of `qf-bake bake`
// or `qf-bake batch`). In order of cost: byte identity; a structural diff of each changed .glb
// (level, quads matched by domain, neighbour-graph edges, plane and error changes, texel
// statistics); an image diff from canonical views drawn by runtime_gl (PSNR, changed-pixel share,
// EXR and PNG difference images). What CI runs to review an asset change.
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "runtime_gl/scene.h"

namespace qf::render {

struct DiffThresholds {
  double min_psnr = 40;          // dB: every view of every changed .glb at least this
  double max_changed = 0.005;    // share of a view's pixels that may change
  int pixel_tolerance = 2;       // 8-bit levels: a pixel changed when a channel differs by more
  double max_quad_change = 0;    // share of a level's quads that may be added or removed
  // dB a manifest's measured figure (a level at a size, a chain band) may fall by: a regression
  // of the look as the bake itself measured it
  double max_error_drop = 0.5;
};

// A changed .glb's renders from the image diff's views, each view in each: the old and the new file
// over the grey the PSNR is computed over, and |old - new| x 4 (the difference images).
struct DiffPictures {
  std::vector<Image> old_views, new_views, diff_views;
};

struct DiffOptions {
  DiffThresholds thresholds;
  int views = 6;            // canonical views (evenly over the sphere), framing both files
  int size = 128;           // square image side, pixels
  bool render = true;       // false: byte and structural diff only (texel changes decide)
  std::string images;       // folder for difference images (NAME.diff.exr / .png); empty = none
  // When set, receives every rendered changed .glb's pictures by name (qf-diff --html).
  std::map<std::string, DiffPictures>* pictures = nullptr;
};

// Compares two .glb files or two folders (files paired by relative path; report.json and
// batch-report*.json hold times and are left out, as are hidden staging files). Returns the
// report: "verdict" is "identical", "within thresholds" or "different". Throws InputError for
// unreadable inputs, UsageError for a file compared with a folder.
nlohmann::ordered_json diff_bakes(const std::string& old_path, const std::string& new_path, const DiffOptions& options);

// The report as text for people.
std::string diff_text(const nlohmann::ordered_json& report);

}  // namespace qf::render
