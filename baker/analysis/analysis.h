// Surface analysis, stages 1-3 of method.md as one recipe: neighbourhoods -> local frames ->
// orientation -> classifier -> local Delaunay fans -> stiffness matrix. Each step is timed and
// reported.
#pragma once

#include <string>
#include <vector>

#include "analysis/fans.h"
#include "analysis/local_frames.h"
#include "analysis/neighborhoods.h"
#include "analysis/stiffness.h"

namespace qf {

struct AnalysisOptions {
  NeighborhoodOptions neighborhoods;
  ClassifierOptions classifier;
};

struct StepTime {
  std::string step;
  double seconds = 0;
};

struct AnalysisReport {
  std::size_t points = 0;
  NeighborhoodReport neighborhoods;
  std::size_t normals_flipped = 0;    // PCA normals turned to agree with the input's or with their neighbours'
  std::size_t normal_components = 0;  // parts oriented separately (no input normals); 0 when normals were given
  std::size_t isolated = 0;           // points without neighbours
  FanReport fans;
  double mean_fan_size = 0;           // triangles per point
  StiffnessReport stiffness;
  std::size_t nonzeros = 0;           // of A, diagonal included
  std::vector<StepTime> times;        // wall-clock time per step (not written to any output file)
};

struct SurfaceAnalysis {
  Neighborhoods neighborhoods;
  LocalFrames frames;
  Classifier classifier;
  Fans fans;
  SparseMatrix stiffness;
  AnalysisReport report;
};

// What analyze_surface returns: every intermediate (the analyze command writes them), or only the
// stiffness matrix and the oriented normals (frames.normal), for the bake. The lean form frees
// each per-point array as soon as no later step reads it: the neighbourhoods (k x 8 bytes a
// point, 400 at k = 50) after the fans, the frames and the classifier after the stiffness matrix,
// so they are gone before the matrix is assembled and while the AMG hierarchy is built.
enum class AnalysisKeep { kAll, kStiffnessAndNormals };

// Runs stages 1-3 on a point set (normals, when present, orient the frames). A set with fewer
// points than k uses all the others as neighbours; an empty set gives empty results. The report
// is filled in either form.
SurfaceAnalysis analyze_surface(const PointSet& points, const AnalysisOptions& options = {},
                                AnalysisKeep keep = AnalysisKeep::kAll);

// Debug colour of a classifier value, as the paper's figure 1b: red where C = 1/alpha (flat),
// through yellow, green and cyan to blue at C <= 1/(100 alpha) (creases), on a log scale.
Rgb8 classifier_color(float c, const ClassifierOptions& options);

}  // namespace qf
