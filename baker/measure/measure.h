// The measuring library: a bake's files drawn as an engine draws them (the engine method) at a
// ladder of on-screen sizes, scored against the truth, what the input's pixels should show there
// (the input drawn at `truth` x the size and box-filtered down, as `qf-render eval --truth`), with
// the input itself drawn at the size beside them (the asset as an engine shows it). The bake
// measures every output with it (qf-bake hands it over as measure/measurements.h MeasureFiles:
// the baker does not link the renderer); its figures for a file at a size are `qf-render eval
// BAKED --size S --views N -m engine`'s. They come from the GL driver's pixels (llvmpipe here):
// the same bytes on every run on one driver, not across drivers.
#pragma once

#include <string>
#include <vector>

#include "io/model_io.h"
#include "measure/measurements.h"
#include "measure/screen_sizes.h"

namespace qf::render {

struct MeasureOptions {
  // On-screen sizes, largest first (see Measurements::sizes), every file drawn at each; above them,
  // doubling up to `largest`, the files that hold at the size below (measure_files).
  std::vector<int> sizes{256, 128, 64, 32, 16};
  int largest = kLargestMeasuredPixels;
  // Directions spread over the bounding sphere (sphere_direction), 4 for the bake's time, and the
  // truth's supersampling of the largest size (truth_side): 2, so 4 x for half the largest size
  // (on bunny00, the generated tree, a bush and the octahedron 2 against 8 moved every figure by
  // at most 0.23 dB and no level's screen size).
  int views = 4;
  int truth = 2;
  ReadOptions read;  // how the input is read again (as the bake read it)
};

// The largest side the truth is drawn at (8 x 512 px would be 4096; 4 x is as good a box filter).
constexpr int kMaxTruthSide = 4096;

// The truth's supersampling at `size` pixels, as qf-render eval draws it: `truth`, capped by
// kMaxTruthSide (at least 1).
int truth_factor(int size, int truth);

// The side the truth is drawn at: `truth` x the largest size, capped by kMaxTruthSide; every
// size's truth is it box-filtered down (so `qf-render eval --size S --truth SIDE/S` scores the
// same). UsageError when a size does not divide it.
int truth_side(const std::vector<int>& sizes, int truth);

// The input as the measuring draws it (the truth; the bake's report.html draws it so too): a glTF
// file through the loader, as its file says; other files, and glTF files the loader does not take
// (Draco), as the baker's readers read them with `read`. Throws their InputErrors.
struct AnyScene;
AnyScene measured_input(const std::string& input_path, const ReadOptions& read);

// Draws the input at `input_path` (the truth once per view; the asset itself at every size, as
// Measurements::asset, its bytes left 0 for the caller) and every candidate (loaded once, drawn from
// the same views) at every size of options.sizes; then at twice the largest size, up to
// options.largest, the asset and the candidates that hold (measure/screen_sizes.h, by `bar`) at
// the largest size so far, the others not (Scores::measured false), while any does. Returns the
// mean scores per size, largest first. Makes its own headless GL context: throws UsageError when
// there is none, and the readers' and loader's InputErrors.
Measurements measure_files(const std::string& input_path, const std::vector<Candidate>& candidates, const HoldBar& bar,
                           const MeasureOptions& options = {});

}  // namespace qf::render
