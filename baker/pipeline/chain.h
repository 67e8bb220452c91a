// The recommended chain from near to far: for each screen-size band, the fewest bytes that look
// good enough there (a quality bar; else the best trade of PSNR against bytes, 1 dB per doubling;
// never more bytes than nearer), with its switch distance, chosen from the bake's measurements of
// every candidate (mesh LODs, impostor levels, the point impostor; pipeline/measurements.h).
#pragma once

#include <nlohmann/json.hpp>

#include "pipeline/measurements.h"

namespace qf {

struct ChainRule {
  // The quality bar: a band takes the smallest file that reaches both at the band's size. A
  // tolerance relative to the band's best would always take the finest mesh LOD (44 dB on the
  // bunny at every size), however small the object is on screen.
  double min_psnr = 30;
  double min_iou = 0.9;
  double screen_height = 1080; // of the switch distances, pixels (qf-bake: --lod-screen-height)
  double fov_degrees = 60;     // vertical field of view of the switch distances
};

// A file is a candidate for a band only where it is valid: at most `kShownAbove` x its own
// max_screen_pixels (a level far above the size it was made for shows its flaws: CGAL's building
// scan's 28-quad level, made for 26 px, was recommended from 0 to 256 px and beyond).
constexpr double kShownAbove = 2;

// The manifest's "recommended_chain" from `m` (band k shows the object between sizes[k+1] and
// sizes[k] pixels and is measured at sizes[k], its largest; the first band also takes every size
// above it, the last every size below): the rule, the candidates' figures and the chain
// (consecutive bands with the same file joined; an entry's error is that at its nearest band's
// size), nearest first. `max_pixels` gives each file's max_screen_pixels (one per m.files; 0 or
// missing: valid at any size); a band takes only files valid at its size (the nearer band's cap
// on bytes kept where it leaves one), and an entry says whether it met the bar (`bar_met`). Null
// when nothing was measured.
nlohmann::json recommend_chain(const Measurements& m, double diagonal, const ChainRule& rule = {}, const std::vector<double>& max_pixels = {});

// The distance at which an object of bounding-box diagonal `diagonal` spans `pixels` on a screen of
// `screen_height` pixels with vertical field of view `fov_degrees` (as the point impostor's switch
// distance: diagonal x screen_height / (2 tan(fov / 2) x pixels)).
double distance_for_pixels(double diagonal, double pixels, double screen_height, double fov_degrees);

// A score as the manifest rounds it: PSNR to 0.01 dB, IoU and soft IoU to 0.001.
nlohmann::json scores_entry(const Scores& s);

}  // namespace qf
