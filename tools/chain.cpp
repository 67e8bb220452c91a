// The recommended chain: candidates measured per screen-size band, the cheapest good one chosen.
#include "tools/chain.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "core/error.h"
#include "gl/egl.h"
#include "runtime_gl/camera.h"
#include "tools/any_scene.h"

namespace qf::render {
namespace {

struct Candidate {
  std::string file, kind;
  const std::vector<std::uint8_t>* bytes = nullptr;
  std::vector<ViewMetrics> at_size;  // mean over views, one per ChainOptions::sizes
};

// 1. What the manifest lists: mesh LODs, impostor levels, the point impostor.
std::vector<Candidate> listed_candidates(const nlohmann::json& manifest, const std::vector<OutputFile>& files) {
  std::map<std::string, const std::vector<std::uint8_t>*> by_name;
  for (const OutputFile& f : files) by_name[f.name] = &f.bytes;
  std::vector<Candidate> out;
  auto add = [&](const nlohmann::json& entry, const char* kind) {
    const std::string name = entry.at("file").get<std::string>();
    if (by_name.count(name)) out.push_back({name, kind, by_name[name], {}});
  };
  if (manifest.contains("mesh_lods"))
    for (const nlohmann::json& l : manifest["mesh_lods"]["levels"]) add(l, "mesh_lod");
  for (const nlohmann::json& l : manifest.at("levels")) add(l, "impostor_level");
  if (manifest.contains("point_impostor")) add(manifest["point_impostor"], "point_impostor");
  return out;
}

DrawSettings engine_settings() {
  DrawSettings s;
  s.method = Method::kEngine;
  s.background = {128, 128, 128};  // as qf-render eval
  return s;
}

// One on-screen size: its cameras, the reference drawn from them, a renderer for the candidates.
struct SizeViews {
  int factor = 1;  // drawn at size x factor, then box-filtered down
  std::vector<Camera> cams;
  std::vector<RenderPair> reference;
  std::unique_ptr<Renderer> renderer;
};

RenderPair draw_pair(Renderer& r, const Camera& cam, int factor) {
  const RenderPair p = render_pair(r, cam, engine_settings());
  return RenderPair{box_downsample(p.over_black, factor), box_downsample(p.over_white, factor)};
}

// 2. The reference from every view at every size.
std::vector<SizeViews> reference_views(const AnyScene& reference, const ChainOptions& o) {
  const Sphere sphere = bounding_sphere(reference.bounds());
  std::vector<SizeViews> out;
  for (int size : o.sizes) {
    SizeViews s;
    s.factor = std::max(1, o.supersampled_side / size);
    const int side = size * s.factor;
    Renderer ref_renderer(side, side);
    reference.attach(ref_renderer);
    for (int v = 0; v < o.views; ++v) {
      s.cams.push_back(orbit_camera(sphere, sphere_direction(v, o.views), 0, side, side));
      s.reference.push_back(draw_pair(ref_renderer, s.cams.back(), s.factor));
    }
    s.renderer = std::make_unique<Renderer>(side, side);
    out.push_back(std::move(s));
  }
  return out;
}

// 3. Each candidate (loaded once) drawn from the same views, scored per view and averaged per size.
void measure(std::vector<Candidate>& candidates, std::vector<SizeViews>& sizes) {
  const Rgb8 background = engine_settings().background;
  for (Candidate& c : candidates) {
    const AnyScene scene = load_scene(*c.bytes, c.file);
    for (SizeViews& s : sizes) {
      scene.attach(*s.renderer);
      std::vector<ViewMetrics> per_view;
      for (std::size_t v = 0; v < s.cams.size(); ++v)
        per_view.push_back(compare_renders(s.reference[v], draw_pair(*s.renderer, s.cams[v], s.factor), background));
      c.at_size.push_back(mean_of(per_view));
    }
  }
}

double rounded(double v, double step) { return canonical_double(static_cast<float>(std::round(v / step) * step)); }

// 4. A band's choice among the files of at most `cap` bytes (the nearer band's choice: farther away
// never costs more): the fewest bytes that reach the quality bar there (PSNR and IoU, as the
// manifest rounds them, so that it can be checked from the manifest); where none does, the best
// trade, PSNR less 1 dB per doubling of bytes (the highest PSNR alone took the spider's 933 KB
// impostor level over its 39 KB mesh LOD for 2.2 dB; drawn at 96 px the two look alike). The
// earlier candidate on a tie.
double trade(const Candidate& c, std::size_t band) {
  return rounded(c.at_size[band].psnr, 0.01) - std::log2(static_cast<double>(std::max<std::size_t>(1, c.bytes->size())));
}

std::size_t choose(const std::vector<Candidate>& candidates, std::size_t band, std::size_t cap, const ChainOptions& o) {
  std::size_t pick = candidates.size(), best = candidates.size();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].bytes->size() > cap) continue;
    const double psnr = rounded(candidates[i].at_size[band].psnr, 0.01), iou = rounded(candidates[i].at_size[band].iou, 0.001);
    if (best == candidates.size() || trade(candidates[i], band) > trade(candidates[best], band)) best = i;
    if (psnr >= o.min_psnr && iou >= o.min_iou && (pick == candidates.size() || candidates[i].bytes->size() < candidates[pick].bytes->size()))
      pick = i;
  }
  return pick < candidates.size() ? pick : best;
}

nlohmann::json metrics_entry(const ViewMetrics& m) { return {{"psnr", rounded(m.psnr, 0.01)}, {"iou", rounded(m.iou, 0.001)}}; }

// 5. The chain, nearest first: one entry per run of bands with the same file, shown from the
// object's on-screen size max_pixels (null: any larger) down to min_pixels (0: any smaller), that
// is out to switch_distance (null: the last entry).
nlohmann::json chain_entries(const std::vector<Candidate>& candidates, double diagonal, const ChainOptions& o) {
  nlohmann::json chain = nlohmann::json::array();
  for (std::size_t band = 0; band < o.sizes.size(); ++band) {
    const std::size_t cap = chain.empty() ? std::numeric_limits<std::size_t>::max() : chain.back()["bytes"].get<std::size_t>();
    const std::size_t pick = choose(candidates, band, cap, o);
    const Candidate& c = candidates[pick];
    const int min_pixels = band + 1 < o.sizes.size() ? o.sizes[band + 1] : 0;
    const nlohmann::json far = min_pixels > 0 ? nlohmann::json(rounded(distance_for_pixels(diagonal, min_pixels, o.screen_height, o.fov_degrees), 1e-4))
                                              : nlohmann::json(nullptr);
    if (!chain.empty() && chain.back()["file"] == c.file) {
      chain.back()["min_pixels"] = min_pixels;
      chain.back()["switch_distance"] = far;
      continue;
    }
    chain.push_back({{"file", c.file},
                     {"kind", c.kind},
                     {"bytes", c.bytes->size()},
                     {"max_pixels", band == 0 ? nlohmann::json(nullptr) : nlohmann::json(o.sizes[band])},
                     {"min_pixels", min_pixels},
                     {"switch_distance", far},
                     {"measured_at_pixels", o.sizes[band]},
                     {"error", metrics_entry(c.at_size[band])}});
  }
  return chain;
}

}  // namespace

double distance_for_pixels(double diagonal, double pixels, double screen_height, double fov_degrees) {
  return diagonal * screen_height / (2 * std::tan(0.5 * fov_degrees * 3.14159265358979323846 / 180) * pixels);
}

nlohmann::json recommend_chain(const std::string& input_path, const nlohmann::json& manifest, const std::vector<OutputFile>& files,
                               const ChainOptions& o) {
  std::vector<Candidate> candidates = listed_candidates(manifest, files);
  if (candidates.empty() || o.sizes.empty() || o.views < 1) return nullptr;
  std::unique_ptr<HeadlessContext> context;
  try {
    context = std::make_unique<HeadlessContext>();
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--chain draws the candidates, which needs an EGL/OpenGL driver: ") + e.what());
  }
  std::vector<SizeViews> sizes = reference_views(load_input(input_path, o.read), o);
  measure(candidates, sizes);
  nlohmann::json measured = nlohmann::json::array();
  for (const Candidate& c : candidates) {
    nlohmann::json at = nlohmann::json::array();
    for (const ViewMetrics& m : c.at_size) at.push_back(metrics_entry(m));
    measured.push_back({{"file", c.file}, {"kind", c.kind}, {"bytes", c.bytes->size()}, {"at_pixels", at}});
  }
  return {{"rule", "per band, nearest first, among files no larger than the nearer band's: the smallest with PSNR >= min_psnr and IoU >= "
                   "min_iou (else the highest PSNR - log2(bytes)), drawn by "
                   "the engine method against the input at the band's largest size from `views` directions"},
          {"sizes", o.sizes},
          {"views", o.views},
          {"min_psnr", rounded(o.min_psnr, 0.01)},
          {"min_iou", rounded(o.min_iou, 0.001)},
          {"screen_height", o.screen_height},
          {"fov_degrees", rounded(o.fov_degrees, 0.01)},
          {"chain", chain_entries(candidates, manifest.at("bounding_box_diagonal").get<double>(), o)},
          {"measured", measured}};
}

}  // namespace qf::render
