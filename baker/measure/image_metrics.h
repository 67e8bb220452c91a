// The fidelity metrics of `qf-render eval` and the bake's measuring (paper section 6: render the
// original and the simplification with the same camera and compare), on 8-bit RGBA frames: plain
// loops, no image library.
#pragma once

#include <vector>

#include "runtime_gl/scene.h"

namespace qf::render {

// One view's comparison. A render's coverage c is recovered from two renders over black (B) and
// white (W): W - B = (1 - c) * 255 for every method, since each is linear in the background. The
// colours compared are both composited over `background`.
//
// Every figure is taken over the footprint, the pixels that either image covers, never over the
// whole frame: a frame that is mostly background would score well whatever the object does. Where
// there is nothing to judge by, a figure is NaN (no evidence), never a match: two empty masks are
// not an IoU of 1, and a truth that covers nothing gives no PSNR, soft IoU or coverage.
struct ViewMetrics {
  // dB over the footprint, each pixel weighted by the larger of the two coverages (a pixel that a
  // thin beam covers a fifth of counts a fifth); 99 when identical.
  double psnr = 0;
  double iou = 1;          // silhouette intersection over union (c >= 0.5); NaN when neither silhouette has a pixel
  // Sum of min(c_ref, c) / sum of max(c_ref, c) over all pixels: the IoU of fractional coverage
  // (a leaf or a beam covers part of a pixel, which the silhouette's 0.5 threshold rounds away).
  double soft_iou = 1;
  // Sum of c / sum of c_ref: how much of what the truth covers the image covers (1: as much; a
  // level that draws nothing is 0, whatever its PSNR).
  double coverage = 1;
  double covered_reference = 0;  // sum of c_ref, pixels: under half a pixel, there is no evidence
  double covered_image = 0;      // sum of c
  double mae = 0;          // mean absolute difference, 0..1, over the same weighted footprint
  double holes = 0;        // share of reference-covered pixels where the impostor's c < 0.5
  double see_through = 0;  // share of reference-covered pixels where the impostor's 0.5 <= c < 0.9
  std::size_t covered = 0; // pixels covered by the reference
  double brightness = 0;   // mean grey (0..255) over the impostor's covered pixels (c >= 0.5)
  double reference_brightness = 0;  // the same over the reference's
};
struct RenderPair {
  Image over_black, over_white;
};
// Whether `m` has anything to judge by: the truth covers at least half a pixel.
bool has_evidence(const ViewMetrics& m);

// `diff` (if given) receives |reference - impostor| as linear floats, RGB, 0..1.
ViewMetrics compare_renders(const RenderPair& reference, const RenderPair& impostor, Rgb8 background,
                            std::vector<float>* diff = nullptr);

// `image` reduced by a whole `factor` (its sides divisible by it), each pixel the mean of a
// factor x factor block of bytes: a resolve in sRGB bytes, so that a pair over black and white
// still gives coverage = 1 - (W - B) / 255.
Image box_downsample(const Image& image, int factor);

// A float RGB image as 8-bit, scaled by `gain` and clamped (difference images made visible).
Image to_8bit(const std::vector<float>& rgb, int width, int height, float gain);

}  // namespace qf::render
