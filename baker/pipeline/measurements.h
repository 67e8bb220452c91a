// What a bake's outputs look like on screen: each file drawn as an engine draws it, at a ladder of
// on-screen sizes, scored against the input's truth (tools/measure.h draws them; the baker, which
// does not link the renderer, is handed that as a function). Plain figures, no GL here: the rules
// that read them (pipeline/screen_sizes.h, pipeline/chain.h) are pure and unit-tested.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace qf {

// One file at one size, the mean over the views.
struct Scores {
  double psnr = 0;      // dB over the pixels either image covers (99 when identical)
  double iou = 0;       // silhouette intersection over union (coverage >= 0.5)
  double soft_iou = 0;  // sum min / sum max of fractional coverage
  bool measured = true; // false: not drawn at this size (it cannot be chosen there; Candidate::max_pixels)
};

struct FileScores {
  std::string file;
  std::string kind;             // "impostor_level", "mesh_lod", "point_impostor"
  std::size_t bytes = 0;
  std::vector<Scores> at_size;  // one per Measurements::sizes
};

struct Measurements {
  // On-screen sizes, pixels, largest first: the object's bounding sphere fits a square window of
  // this side (at a 30-degree field of view its bounding-box diagonal spans about 0.97 of it).
  std::vector<int> sizes;
  int views = 0;                 // directions spread over the bounding sphere
  int truth = 0;                 // the truth: the input drawn at truth x the size, box-filtered
  std::vector<FileScores> files; // in the order asked for
};

// A file to measure: its name, kind and bytes (which outlive the call), and the largest size it
// is drawn at: kShownAbove (pipeline/chain.h) x `max_pixels`, the size it is made for, beyond which
// the chain never shows it (0: every size; an impostor level, whose size these figures decide).
struct Candidate {
  std::string file, kind;
  const std::vector<std::uint8_t>* bytes = nullptr;
  double max_pixels = 0;
};

// Draws `candidates` and the input at `input_path` and scores them; throws UsageError when no GL
// context can be made, and the readers' InputErrors.
using MeasureFiles = std::function<Measurements(const std::string& input_path, const std::vector<Candidate>& candidates)>;

}  // namespace qf
