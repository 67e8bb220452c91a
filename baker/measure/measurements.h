// What a bake's outputs look like on screen: each file drawn as an engine draws it, at a ladder of
// on-screen sizes, scored against the input's truth, beside the input itself drawn at each size
// (the asset as drawn, what every file is judged relative to). measure/measure.h draws them. Plain
// figures, no GL here: the rules that read them (measure/screen_sizes.h, measure/chain.h) are pure
// and unit-tested.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace qf {

// One file at one size, the mean over the views (measure/image_metrics.h). A figure is NaN where
// there was nothing to judge by: the truth covers under half a pixel (no PSNR, soft IoU or
// coverage), or neither silhouette has a pixel (no IoU). Such a size is no evidence that a file
// holds, never a match.
struct Scores {
  double psnr = 0;      // dB over the footprint (the pixels either image covers, weighted by coverage)
  double iou = 0;       // silhouette intersection over union (coverage >= 0.5)
  double soft_iou = 0;  // sum min / sum max of fractional coverage
  double coverage = 0;  // the file's summed coverage over the truth's (1: as much as the truth)
  bool measured = true; // false: not drawn at this size
  bool evidence() const { return measured && !std::isnan(psnr) && !std::isnan(soft_iou) && !std::isnan(coverage); }
};

struct FileScores {
  std::string file;
  std::string kind;             // "asset" (the input itself), "impostor_level", "mesh_lod", "point_impostor"
  std::size_t bytes = 0;
  std::vector<Scores> at_size;  // one per Measurements::sizes
};

struct Measurements {
  // On-screen sizes, pixels, largest first: the object's bounding sphere fits a square window of
  // this side (at a 30-degree field of view its bounding-box diagonal spans about 0.97 of it).
  std::vector<int> sizes;
  int views = 0;                 // directions spread over the bounding sphere
  int truth = 0;                 // the truth: the input drawn at truth x the size, box-filtered
  FileScores asset;              // the input drawn at each size as an engine draws it (file, bytes: the caller's)
  std::vector<FileScores> files; // in the order asked for
  // The GL driver that drew them (GL_RENDERER, GL_VERSION): another driver rasterises and filters
  // a little differently, so the figures hold for it (empty when nothing was drawn).
  std::string gl_renderer, gl_version;
};

// A file to measure: its name, kind and bytes (which outlive the call).
struct Candidate {
  std::string file, kind;
  const std::vector<std::uint8_t>* bytes = nullptr;
};


}  // namespace qf
