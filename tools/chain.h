// The recommended chain from near to far: every candidate a bake made (mesh LODs, impostor levels,
// the point impostor) drawn by the engine method against the input at a ladder of on-screen sizes,
// and for each screen-size band the fewest bytes that look good enough there (a quality bar; else
// the best trade of PSNR against bytes, 1 dB per doubling; never more bytes than nearer), with
// its switch distance. qf-bake hands it to the bake (AssetOptions::measure_chain): the drawing
// needs runtime_gl, which the baker does not link. The figures come from the GL driver's pixels
// (llvmpipe here): the same bytes on every run on one driver, not across drivers.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "pipeline/asset.h"

namespace qf::render {

struct ChainOptions {
  // The bands' upper edges, on-screen pixels (the object's bounding sphere fits a window of this
  // side, at a 30-degree field of view its diagonal spans cos 15 deg = 0.97 of it), largest first:
  // band k shows the object between sizes[k+1] and sizes[k] pixels and is measured at sizes[k],
  // its largest; the first band also takes every size above it, the last every size below.
  std::vector<int> sizes{256, 128, 64, 32, 16};
  int views = 6;               // directions spread over the bounding sphere (sphere_direction)
  // Small sizes are drawn larger, by a whole factor up to this side, and box-filtered down: the
  // picture an engine's multisampling shows, where one aliased sample per pixel would score a
  // sub-pixel shift as a whole pixel's error.
  int supersampled_side = 128;
  // The quality bar: a band takes the smallest file that reaches both at the band's size. A
  // tolerance relative to the band's best would always take the finest mesh LOD (44 dB on the
  // bunny at every size), however small the object is on screen.
  double min_psnr = 30;
  double min_iou = 0.9;
  double screen_height = 1080; // of the switch distances, pixels (qf-bake: --lod-screen-height)
  double fov_degrees = 60;     // vertical field of view of the switch distances
  ReadOptions read;            // how the input is read again as the reference (as the bake read it)
};

// Measures the candidates that `manifest` lists (files by name in `files`) against the input at
// `input_path` and returns the manifest's "recommended_chain": the rule, the measurements of every
// candidate and the chain (consecutive bands with the same file joined; an entry's error is that
// at its nearest band's size), nearest first. A point set is the reference as splats, a mesh as
// triangles, both as an engine draws them. Throws the readers' and loader's InputErrors, and a
// UsageError when no GL context can be made.
nlohmann::json recommend_chain(const std::string& input_path, const nlohmann::json& manifest, const std::vector<OutputFile>& files,
                               const ChainOptions& options = {});

// The distance at which an object of bounding-box diagonal `diagonal` spans `pixels` on a screen of
// `screen_height` pixels with vertical field of view `fov_degrees` (as the point impostor's switch
// distance: diagonal x screen_height / (2 tan(fov / 2) x pixels)).
double distance_for_pixels(double diagonal, double pixels, double screen_height, double fov_degrees);

}  // namespace qf::render
