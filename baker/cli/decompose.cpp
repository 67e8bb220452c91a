// The decompose command: stages 1-5 (analysis, AMG hierarchy, basis functions, domains and
// their neighbour graph) with debug outputs and a JSON summary of every level.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <cstdio>
#include <ostream>

#include "amg/basis.h"
#include "amg/hierarchy.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/file_io.h"
#include "domains/domains.h"
#include "domains/merge.h"
#include "pipeline/bake.h"

namespace qf::cli {
namespace {

// Distinct colours: hues a golden angle apart, so neighbouring indices never look alike.
Rgb8 domain_color(std::size_t d) {
  const double h = std::fmod(double(d) * 0.6180339887498949, 1.0) * 6.0, s = 0.7, v = 0.95;
  const int k = static_cast<int>(h);
  const double f = h - k, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r, g, b;
  switch (k % 6) {
    case 0: r = v, g = t, b = p; break;
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = t; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = t, g = p, b = v; break;
    default: r = v, g = p, b = q; break;
  }
  auto c = [](double x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0, 1.0) * 255)); };
  return {c(r), c(g), c(b)};
}

// Parses --level: an integer (negative counts back from the coarsest), or "L" / "L-5".
long long parse_level(const std::string& text) {
  std::string t = text;
  if (!t.empty() && (t[0] == 'L' || t[0] == 'l')) {
    if (t.size() == 1) return -0;  // the coarsest: handled by the caller as "L"
    t = t.substr(1);
  }
  try {
    std::size_t used = 0;
    const long long v = std::stoll(t, &used);
    if (used != t.size()) throw std::invalid_argument(t);
    return v;
  } catch (const std::exception&) {
    throw UsageError("--level expects an integer (negative: from the coarsest) or L, L-K; got '" + text + "'");
  }
}

nlohmann::json size_stats(const Domains& d) {
  std::vector<std::size_t> sizes;
  for (std::size_t f = 0; f < d.count(); ++f)
    if (d.size(f)) sizes.push_back(d.size(f));
  std::sort(sizes.begin(), sizes.end());
  nlohmann::json j;
  j["min"] = sizes.empty() ? 0 : sizes.front();
  j["median"] = sizes.empty() ? 0 : sizes[sizes.size() / 2];
  j["max"] = sizes.empty() ? 0 : sizes.back();
  return j;
}

void write_basis_dump(const std::string& path, const SparseMatrix& psi, std::size_t level) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# quasiflat basis dump: level " << level << ", " << psi.rows() << " points, " << psi.cols()
        << " basis functions\n# per point: its index, then function:weight for every non-zero weight (weights sum to 1)\n";
    std::string line;
    char num[32];
    for (Eigen::Index i = 0; i < psi.rows(); ++i) {
      line = std::to_string(i);
      for (SparseMatrix::InnerIterator it(psi, i); it; ++it) {
        line += ' ';
        line += std::to_string(it.col());
        line += ':';
        line.append(num, std::to_chars(num, num + sizeof num, it.value()).ptr);
      }
      line += '\n';
      out << line;
    }
  });
}

// The level --level or --primitives names (UsageError when --level names none).
std::size_t chosen_level(const ParsedArgs& args, const AmgHierarchy& h) {
  if (!args.has("level")) return level_by_primitives(h, static_cast<std::size_t>(args.get_int("primitives", 200, 1, 1ll << 40)));
  const std::string text = args.get("level");
  try {
    return (text == "L" || text == "l") ? h.level_count() - 1 : level_by_index(h, parse_level(text));
  } catch (const std::out_of_range& e) {
    throw UsageError(std::string("--level: ") + e.what());
  }
}

// One level's entry in the --summary file.
nlohmann::json level_summary(const AmgHierarchy& h, std::size_t l, const SparseMatrix& psi, const DomainOptions& dopt) {
  const Domains d = make_domains(psi, dopt);
  return {{"level", l},
          {"functions", h.levels[l].size},
          {"ratio", canonical_double(static_cast<float>(h.levels[l].ratio))},
          {"theta", canonical_double(static_cast<float>(h.levels[l].theta))},
          {"weights_per_point", canonical_double(float(psi.nonZeros()) / float(psi.rows()))},
          {"domain_points", size_stats(d)},
          {"empty_domains", d.empty},
          {"uncovered_points", d.uncovered},
          {"shared_points", d.shared_points},
          {"graph_edges", d.edges.size()}};
}

// The debug point set: colours mixed by weight, the strongest function and its weight.
PointSet domain_point_set(const PointSet& points, const SparseMatrix& chosen, std::size_t level, const AmgHierarchy& h) {
  PointSet dbg;
  dbg.positions = points.positions;
  dbg.normals = points.normals;  // the input's only: the output must not depend on a cache hit
  dbg.radii = points.radii;
  dbg.colors.resize(points.size());
  std::vector<float> strongest(points.size()), weight(points.size());
  for (Eigen::Index i = 0; i < chosen.rows(); ++i) {
    double rgb[3] = {0, 0, 0}, best = -1;
    for (SparseMatrix::InnerIterator it(chosen, i); it; ++it) {
      const Rgb8 c = domain_color(static_cast<std::size_t>(it.col()));
      rgb[0] += it.value() * c.r, rgb[1] += it.value() * c.g, rgb[2] += it.value() * c.b;
      if (it.value() > best) best = it.value(), strongest[static_cast<std::size_t>(i)] = static_cast<float>(it.col());
    }
    weight[static_cast<std::size_t>(i)] = static_cast<float>(best);
    auto q = [](double x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0, 255.0))); };
    dbg.colors[static_cast<std::size_t>(i)] = {q(rgb[0]), q(rgb[1]), q(rgb[2])};
  }
  dbg.scalars = {{"domain", strongest}, {"weight", weight}};
  dbg.comments = {"quasiflat decompose: level " + std::to_string(level) + " of " + std::to_string(h.level_count() - 1) +
                  ", " + std::to_string(chosen.cols()) + " basis functions"};
  return dbg;
}

// What a decompose run found and took, for the terminal.
struct DecomposeRun {
  std::string in, out, cache_dir, cache_state;
  std::size_t level = 0;
  double hierarchy_seconds = 0, basis_seconds = 0;
};

// The --summary file (schemas/levels.schema.json): the hierarchy and every level.
void write_levels_summary(const std::string& path, const DecomposeRun& r, const AmgHierarchy& h, std::size_t points,
                          const nlohmann::json& levels, const MergeReport* merged) {
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(hierarchy_hash(h)));
  nlohmann::json j;
  j["input"] = r.in;
  j["points"] = points;
  j["components"] = h.components;
  j["isolated_points"] = h.isolated;
  j["hierarchy_hash"] = hash;
  j["chosen_level"] = r.level;
  if (merged) j["merged"] = {{"functions_before", merged->before}, {"functions_after", merged->after}};
  j["levels"] = levels;
  // Wall-clock times: the only part of the file that differs between runs.
  j["seconds"] = {{"hierarchy", canonical_double(static_cast<float>(r.hierarchy_seconds))},
                  {"basis", canonical_double(static_cast<float>(r.basis_seconds))}};
  write_file_atomically(path, [&](std::ostream& o) { o << j.dump(2) << "\n"; });
}

void print_decompose_summary(const DecomposeRun& r, const AmgHierarchy& h, const SparseMatrix& chosen, const Domains& domains,
                             const MergeReport* merged) {
  std::fprintf(stderr, "qf-bake decompose: %s -> %s\n", r.in.c_str(), r.out.c_str());
  std::fprintf(stderr, "  hierarchy: %zu levels (", h.level_count());
  for (std::size_t l = 0; l < h.level_count(); ++l) std::fprintf(stderr, "%s%zu", l ? " " : "", h.levels[l].size);
  std::fprintf(stderr, " functions), %zu component(s), %zu isolated point(s)\n", h.components, h.isolated);
  std::fprintf(stderr, "  level %zu: %zu basis functions, %zu domains (%zu empty), %zu points shared, %zu uncovered, %zu graph edges\n",
               r.level, static_cast<std::size_t>(chosen.cols()), domains.count() - domains.empty, domains.empty,
               domains.shared_points, domains.uncovered, domains.edges.size());
  if (merged)
    std::fprintf(stderr, "  merged: %zu -> %zu basis functions (%zu merges)\n", merged->before, merged->after, merged->merges);
  std::fprintf(stderr, "  cache: %s (%s)\n", r.cache_state.c_str(), r.cache_dir.empty() ? "disabled" : r.cache_dir.c_str());
  std::fprintf(stderr, "  time: analysis and hierarchy %.3f s, basis %.3f s\n", r.hierarchy_seconds, r.basis_seconds);
}

}  // namespace

CommandSpec decompose_spec() {
  CommandSpec spec{"decompose", "IN -o OUT.ply [options]",
                   "AMG decomposition: basis functions, domains and their neighbour graph at one level",
                   "Writes the points coloured by domain (each basis function a colour, mixed by the weights\n"
                   "where domains overlap, as the paper's figure 5c/d), with the strongest function's index as\n"
                   "the float property 'domain' and its weight as 'weight'. Levels are numbered from the finest:\n"
                   "0 is the points themselves; a negative number or L-K counts back from the coarsest level L.\n"
                   "The points are taken, and written, in the bake's order (along a Morton curve), so each level\n"
                   "is the decomposition the bake's file of that level is made from.",
                   {{"output", 'o', "OUT.ply", "", "output point set (.ply); required"},
                    {"level", 0, "K", "", "the level to decompose at (0 = points, -K or L-K from the coarsest)"},
                    {"primitives", 'n', "N", "200", "instead of --level: the level with the number of basis functions nearest N"},
                    {"tau", 0, "T", "0.05", "domain threshold: D = {x : Psi(x) > T} (paper; the thesis used 0.01)"},
                    {"strict", 0, "", "", "strict domains: each point only in its strongest function's domain"},
                    {"neighbor-share", 0, "S", "0.05", "domains i, j are neighbours when they share more than S of either's points"},
                    {"prune", 0, "W", "0.001", "drop basis weights below W after each product (rows renormalised); 0 = exact"},
                    {"summary", 0, "levels.json", "", "write a JSON summary of every level"},
                    {"basis-dump", 0, "FILE", "", "write every point's non-zero basis weights at the chosen level (text)"},
                    drop_nonfinite_option(), quiet_option()},
                   1, 1};
  append_point_input_options(spec.options);
  return spec;
}

int run_decompose(const ParsedArgs& args) {
  // 1. Options.
  DecomposeRun r;
  r.in = args.positional[0];
  r.out = args.require("output");
  if (file_extension(r.out) != "ply") throw UsageError("decompose writes .ply, not '" + r.out + "'");
  if (args.has("level") && args.has("primitives")) throw UsageError("give --level or --primitives, not both");
  const AnalysisOptions ao = read_analysis_options(args);
  DomainOptions dopt;
  dopt.tau = args.get_double("tau", dopt.tau, 0.0, 1.0);
  dopt.strict = args.flag("strict");
  dopt.neighbor_share = args.get_double("neighbor-share", dopt.neighbor_share, 0.0, 1.0);
  const MergeOptions mopt = read_merge_options(args, dopt);
  BasisOptions bopt;
  bopt.prune = args.get_double("prune", bopt.prune, 0.0, 0.5);

  // 2. The hierarchy: it depends only on the points and the settings, so it is reused when cached.
  ReadReport read_report;
  // In the bake's order (Morton), so that a level here is the decomposition the bake's file of
  // that level was made from; the output lists the points in that order.
  const PointSet points = [&] {
    const PointSet loaded = load_points(r.in, args, "decompose", read_report);
    return permuted(loaded, morton_order(loaded.positions));
  }();
  r.cache_dir = read_cache_dir(args);
  const auto t0 = std::chrono::steady_clock::now();
  const AmgHierarchy h = cached_hierarchy(points, ao, AmgOptions{}, r.cache_dir, r.cache_state);
  r.hierarchy_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.level = chosen_level(args, h);

  // 3. Every level's basis and domains for the summary (only up to the chosen level without one).
  const bool summary = args.has("summary");
  nlohmann::json levels = nlohmann::json::array();
  levels.push_back({{"level", 0}, {"functions", h.levels[0].size}});
  SparseMatrix chosen;
  if (r.level == 0) chosen = basis_at_level(h, 0);
  auto tb = std::chrono::steady_clock::now();
  for_each_basis(h, summary ? h.level_count() - 1 : r.level, bopt, [&](std::size_t l, const SparseMatrix& psi) {
    r.basis_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - tb).count();
    if (l == r.level) chosen = psi;
    if (summary) levels.push_back(level_summary(h, l, psi, dopt));
    tb = std::chrono::steady_clock::now();
  });
  MergeReport merge_report;
  if (args.flag("merge")) chosen = merge_domains(chosen, points.positions, mopt, &merge_report);
  const Domains domains = make_domains(chosen, dopt);

  // 4. The outputs.
  write_ply(r.out, domain_point_set(points, chosen, r.level, h));
  if (args.has("basis-dump")) write_basis_dump(args.get("basis-dump"), chosen, r.level);
  if (summary) write_levels_summary(args.get("summary"), r, h, points.size(), levels, args.flag("merge") ? &merge_report : nullptr);
  if (!args.flag("quiet")) print_decompose_summary(r, h, chosen, domains, args.flag("merge") ? &merge_report : nullptr);
  return 0;
}

}  // namespace qf::cli
