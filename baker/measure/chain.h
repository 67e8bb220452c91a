// The recommended chain from near to far, starting at the asset itself: for each screen-size band,
// the fewest bytes that hold there (measure/screen_sizes.h: about as good as the asset as drawn at
// that size), never more bytes than a nearer derived file; where no derived file holds, the asset
// itself, or, where the asset costs more than the nearer band's file, the best file per byte among
// those that hold at half the band's size or more, with the reason (else the asset after all). Chosen from the bake's measurements of every candidate (mesh LODs, impostor levels,
// the point impostor; measure/measurements.h) and of the asset as drawn.
#pragma once

#include <nlohmann/json.hpp>

#include "measure/measurements.h"
#include "measure/screen_sizes.h"

namespace qf {

struct ChainRule {
  HoldBar bar;                 // where a file holds (qf-bake: --hold-psnr)
  double screen_height = 1080; // of the switch distances, pixels (qf-bake: --lod-screen-height)
  double fov_degrees = 60;     // vertical field of view of the switch distances
};

// The manifest's "recommended_chain" from `m`, whose asset has its file name and bytes set. Bands:
// above sizes[0] (the asset, always: no file is measured there), then band k shows the object
// between sizes[k+1] and sizes[k] pixels and is judged at sizes[k], its largest; the last takes
// every size below. Consecutive bands with the same file are one entry (its error that at its
// nearest band's size); an entry says whether it met the bar (`bar_met`) and, where the rule fell
// back, why. A derived file larger than the asset takes part only at sizes where it draws better
// than the asset (higher PSNR or soft IoU). Null when nothing was measured.
nlohmann::json recommend_chain(const Measurements& m, double diagonal, const ChainRule& rule = {});

// The distance at which an object of bounding-box diagonal `diagonal` spans `pixels` on a screen of
// `screen_height` pixels with vertical field of view `fov_degrees` (as the point impostor's switch
// distance: diagonal x screen_height / (2 tan(fov / 2) x pixels)).
double distance_for_pixels(double diagonal, double pixels, double screen_height, double fov_degrees);

// A score as the manifest rounds it: PSNR to 0.01 dB, IoU, soft IoU and coverage to 0.001; a figure
// without evidence (measure/measurements.h) is null.
nlohmann::json scores_entry(const Scores& s);

// The manifest's words for a HoldBar.
nlohmann::json hold_entry(const HoldBar& bar);

}  // namespace qf
