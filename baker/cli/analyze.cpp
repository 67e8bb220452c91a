// The analyze command: stages 1-3 (neighbourhoods, classifier, fans, stiffness) with debug outputs.
#include <cstdio>
#include <iostream>

#include "analysis/analysis.h"
#include "cli/commands.h"
#include "core/error.h"
#include "io/matrix_market.h"
#include "io/model_io.h"

namespace qf::cli {

CommandSpec analyze_spec() {
  CommandSpec spec{"analyze", "IN -o OUT.ply [options]",
          "surface analysis: neighbourhoods, moment classifier, local Delaunay fans, stiffness matrix",
          "Writes the points with the classifier as colours (smooth = red, creases = blue, as the paper's\n"
          "figure 1b), the classifier and the surface variation as extra float properties (classifier,\n"
          "variation), and the oriented normals. Prints a summary with the time per step.",
          {{"output", 'o', "OUT.ply", "", "output point set (.ply); required"},
           {"matrix", 0, "A.mtx", "", "also write the stiffness matrix A (Matrix Market coordinate format)"},
           drop_nonfinite_option(),
           quiet_option()},
          1, 1};
  for (OptionSpec& o : analysis_option_specs()) spec.options.push_back(o);
  for (OptionSpec& o : sample_option_specs()) spec.options.push_back(o);
  return spec;
}

int run_analyze(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  const std::string out = args.require("output");
  if (file_extension(out) != "ply") throw UsageError("analyze writes .ply, not '" + out + "'");
  const AnalysisOptions o = read_analysis_options(args);
  const std::string kind = args.get("classifier", "paper");
  ReadReport read_report;
  const PointSet points = load_points(in, args, "analyze", read_report);
  const SurfaceAnalysis a = analyze_surface(points, o);

  // The debug point set: classifier colours, oriented normals, classifier and variation values.
  PointSet dbg;
  dbg.positions = points.positions;
  dbg.normals = points.has_normals() ? points.normals : a.frames.normal;
  dbg.radii = points.radii;
  dbg.colors.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) dbg.colors[i] = classifier_color(a.classifier.value[i], o.classifier);
  dbg.scalars = {{"classifier", a.classifier.value}, {"variation", a.classifier.variation}};
  dbg.comments = {"quasiflat analyze: k " + std::to_string(o.neighborhoods.k) + ", classifier " + kind};
  write_ply(out, dbg);
  if (args.has("matrix"))
    write_matrix_market(args.get("matrix"), a.stiffness, "quasiflat stiffness matrix of " + in);

  if (!args.flag("quiet")) {
    const AnalysisReport& r = a.report;
    std::fprintf(stderr, "qf-bake analyze: %s -> %s\n", in.c_str(), out.c_str());
    std::fprintf(stderr, "  points %zu, k %d, neighbourhoods widened %zu, capped %zu, isolated %zu\n", r.points,
                 o.neighborhoods.k, r.neighborhoods.widened, r.neighborhoods.capped, r.isolated);
    if (points.has_normals())
      std::fprintf(stderr, "  normals: from the input; %zu PCA normals flipped to agree\n", r.normals_flipped);
    else
      std::fprintf(stderr, "  normals: estimated (PCA), %zu flipped for a consistent orientation (%zu part(s))\n",
                   r.normals_flipped, r.normal_components);
    std::fprintf(stderr, "  fans: mean %.2f triangles, %zu open, %zu empty, %zu duplicate neighbours skipped\n",
                 r.mean_fan_size, r.fans.open, r.fans.empty, r.fans.duplicates);
    std::fprintf(stderr, "  stiffness: %zu non-zeros (%.2f per row), %zu zero-area triangles skipped, %zu one-sided pairs, %zu empty rows\n",
                 r.nonzeros, r.points ? double(r.nonzeros) / r.points : 0.0, r.stiffness.zero_area_triangles,
                 r.stiffness.one_sided_pairs, r.stiffness.empty_rows);
    double total = 0;
    std::string times;
    for (const StepTime& t : r.times) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s%s %.3f s", times.empty() ? "" : ", ", t.step.c_str(), t.seconds);
      times += buf;
      total += t.seconds;
    }
    std::fprintf(stderr, "  time: %s; total %.3f s (%.0f points/s)\n", times.c_str(), total,
                 total > 0 ? r.points / total : 0.0);
  }
  return 0;
}

}  // namespace qf::cli
