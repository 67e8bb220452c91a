// qf-diff's comparisons: byte identity, the structure of changed .glb files, and renders of both.
#include "tools/diff.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include <tiny_gltf.h>

#include "core/error.h"
#include "core/file_io.h"
#include "core/gltf_keys.h"
#include "core/input_limits.h"
#include "gl/egl.h"
#include "gltf/compressed_gltf.h"
#include "runtime_gl/camera.h"
#include "measure/any_scene.h"
#include "tools/image_ops.h"

namespace qf::render {
namespace {

using Json = nlohmann::json;
using OJson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// --- files -------------------------------------------------------------------------------------

// Files a bake writes that are compared: not the reports (report.json and the batch's hold times;
// report.html shows the files compared here), not hidden staging.
bool compared(const fs::path& rel) {
  for (const fs::path& part : rel)
    if (!part.empty() && part.string()[0] == '.') return false;
  const std::string name = rel.filename().string();
  return name != "report.json" && name != "report.html" && name.rfind("batch-report", 0) != 0 && name.find(".tmp-") == std::string::npos;
}

std::vector<std::string> list_files(const std::string& dir) {
  std::vector<std::string> out;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), dir);
    if (compared(rel)) out.push_back(rel.generic_string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool same_bytes(ByteView a, ByteView b) { return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size()) == 0); }

bool leave_image_undecoded(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// Throws InputError ("diff.glb") unless tinygltf reads the .glb as the runtime reads it (the bytes
// it would refuse of a Draco or meshopt file rewritten first, gltf/compressed_gltf.h; images left
// undecoded): a file the runtime rejects is unreadable here too, not compared.
void check_glb(ByteView b, const std::string& path) {
  if (b.size() < 4 || std::memcmp(b.data(), "glTF", 4) != 0)
    throw InputError("diff.glb", path, "byte 0", "not a binary glTF file (no 'glTF' magic)");
  check_gltf_json_depth(b.data(), b.size(), path, "diff");  // before tinygltf's recursive parser
  check_glb_chunks(b.data(), b.size(), path, "diff.glb");
  const std::vector<std::uint8_t> prepared = gltf_input::prepared_for_tinygltf(b, {path, "diff", 0});
  if (!prepared.empty()) b = ByteView(prepared);
  tinygltf::TinyGLTF gltf;
  gltf.SetImageLoader(leave_image_undecoded, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  if (!gltf.LoadBinaryFromMemory(&model, &err, &warn, b.data(), static_cast<unsigned int>(b.size())))
    throw InputError("diff.glb", path, "", "not a readable binary glTF file: " + err);
}

// --- structure ---------------------------------------------------------------------------------

struct Quads {
  long long level = -1;
  std::vector<long long> domain;
  std::vector<Vec3f> center, normal;
  std::vector<double> error;
  std::set<std::pair<long long, long long>> edges;  // by domain, smaller first
};

// The quads of an impostor level as the runtime read them (`scene`: quad k is item k): domains,
// errors and graph from its extension, planes from its vertices.
std::optional<Quads> impostor_quads(const AnyScene& scene) {
  if (scene.kind != AnyScene::kImpostor || !scene.impostor.has_extension) return std::nullopt;
  const ImpostorScene& s = scene.impostor;
  Quads q;
  q.level = s.level;
  if (s.domains.size() != s.items.size()) return q;
  for (std::size_t k = 0; k < s.items.size(); ++k) {
    q.domain.push_back(s.domains[k]);
    q.center.push_back(s.items[k].center);
    q.normal.push_back(s.items[k].normal);
    q.error.push_back(s.errors[k]);
  }
  for (std::size_t k = 0; k + 1 < s.offsets.size() && k < s.items.size(); ++k)
    for (std::uint32_t i = s.offsets[k]; i < s.offsets[k + 1]; ++i) {
      const long long a = q.domain[k], b = q.domain[s.neighbors[i]];
      q.edges.insert({std::min(a, b), std::max(a, b)});
    }
  return q;
}

// Quads matched by domain (the basis function they show): added, removed, and how the matched
// ones moved (centre, normal) and how their errors changed.
OJson quad_diff(const Quads& a, const Quads& b, double diagonal, double& change_share) {
  std::map<long long, std::size_t> in_a, in_b;
  for (std::size_t k = 0; k < a.domain.size(); ++k) in_a[a.domain[k]] = k;
  for (std::size_t k = 0; k < b.domain.size(); ++k) in_b[b.domain[k]] = k;
  std::size_t added = 0, removed = 0, matched = 0;
  double max_shift = 0, sum_shift = 0, max_angle = 0, sum_angle = 0, max_error_change = 0;
  for (const auto& [d, ka] : in_a) {
    const auto it = in_b.find(d);
    if (it == in_b.end()) {
      ++removed;
      continue;
    }
    const std::size_t kb = it->second;
    ++matched;
    const double shift = length(b.center[kb] - a.center[ka]);
    const double angle = std::acos(std::clamp(double(dot(a.normal[ka], b.normal[kb])), -1.0, 1.0)) * 180.0 / M_PI;
    max_shift = std::max(max_shift, shift), sum_shift += shift;
    max_angle = std::max(max_angle, angle), sum_angle += angle;
    max_error_change = std::max(max_error_change, std::abs(b.error[kb] - a.error[ka]));
  }
  for (const auto& [d, kb] : in_b) added += in_a.count(d) ? 0 : 1;
  std::size_t edges_added = 0, edges_removed = 0;
  for (const auto& e : b.edges) edges_added += a.edges.count(e) ? 0 : 1;
  for (const auto& e : a.edges) edges_removed += b.edges.count(e) ? 0 : 1;
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
  };
  change_share = double(added + removed) / double(std::max<std::size_t>(1, a.domain.size()));
  const double m = double(std::max<std::size_t>(1, matched));
  return {{"level", {a.level, b.level}},
          {"quads", {a.domain.size(), b.domain.size()}},
          {"quads_matched", matched},
          {"quads_added", added},
          {"quads_removed", removed},
          {"neighbor_edges", {a.edges.size(), b.edges.size()}},
          {"edges_added", edges_added},
          {"edges_removed", edges_removed},
          {"center_shift_max", round_to(max_shift, 7)},
          {"center_shift_mean", round_to(sum_shift / m, 7)},
          {"center_shift_max_of_diagonal", round_to(diagonal > 0 ? max_shift / diagonal : 0, 7)},
          {"normal_angle_max_degrees", round_to(max_angle, 4)},
          {"normal_angle_mean_degrees", round_to(sum_angle / m, 4)},
          {"mean_error", {round_to(mean(a.error), 8), round_to(mean(b.error), 8)}},
          {"error_change_max", round_to(max_error_change, 8)}};
}

// What a .glb holds, for files without our impostor extension.
OJson contents(const AnyScene& s) {
  if (s.kind == AnyScene::kPoints) return {{"kind", "point impostor"}, {"points", s.points.positions.size()}};
  if (s.kind == AnyScene::kCluster)
    return {{"kind", "cluster LOD"},
            {"cell_width", s.cluster.cell},
            {"triangles", s.cluster.mesh.indices.size() / 3},
            {"thick_edges", s.cluster.thickness.size()},
            {"points", s.cluster.points.size()}};
  return {{"kind", "quads"}, {"quads", s.impostor.items.size()}};
}

// The images of a level's file: the loader appends a white texture of its own (runtime_gl
// loader.cpp) for untextured draws, which no file holds; texels count the file's images alone, as
// the manifest and report.html do.
std::vector<Image> file_images(const ImpostorScene& s) {
  return std::vector<Image>(s.textures.begin(), s.textures.end() - (s.textures.empty() ? 0 : 1));
}

// Texels of a scene's textures: count, covered share (alpha > 0), mean RGBA of covered texels;
// and, when both have the same images, the share of texels changed beyond the tolerance.
OJson texel_stats(const std::vector<Image>& images) {
  std::size_t texels = 0, covered = 0;
  double sum[4] = {0, 0, 0, 0};
  for (const Image& im : images) {
    texels += std::size_t(im.width) * std::size_t(im.height);
    for (std::size_t i = 0; i + 3 < im.rgba.size(); i += 4) {
      if (im.rgba[i + 3] == 0) continue;
      ++covered;
      for (int c = 0; c < 4; ++c) sum[c] += im.rgba[i + c];
    }
  }
  OJson mean = OJson::array();
  for (double s : sum) mean.push_back(round_to(covered ? s / double(covered) : 0.0, 3));
  return {{"images", images.size()}, {"texels", texels}, {"covered_share", round_to(texels ? double(covered) / double(texels) : 0.0, 6)},
          {"mean_rgba_covered", mean}};
}

// Share of texels changed by more than `tolerance` levels in a channel; -1 when the images differ in size.
double texel_change(const std::vector<Image>& a, const std::vector<Image>& b, int tolerance) {
  if (a.size() != b.size()) return -1;
  std::size_t total = 0, changed = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (a[k].width != b[k].width || a[k].height != b[k].height) return -1;
    for (std::size_t i = 0; i + 3 < a[k].rgba.size(); i += 4) {
      ++total;
      for (int c = 0; c < 4; ++c)
        if (std::abs(int(a[k].rgba[i + c]) - int(b[k].rgba[i + c])) > tolerance) {
          ++changed;
          break;
        }
    }
  }
  return total ? double(changed) / double(total) : 0.0;
}

// --- images ------------------------------------------------------------------------------------

struct ImageDiff {
  OJson json;
  bool within = true;
};

// A render pair as drawn over `background` (colour = B + (W - B) x background / 255: each method
// is linear in the background).
Image over_background(const RenderPair& p, Rgb8 background) {
  Image out = p.over_black;
  const std::uint8_t bg[3] = {background.r, background.g, background.b};
  for (std::size_t i = 0; i + 3 < out.rgba.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      out.rgba[i + c] = static_cast<std::uint8_t>(std::lround(p.over_black.rgba[i + c] +
                                                              (int(p.over_white.rgba[i + c]) - int(p.over_black.rgba[i + c])) * bg[c] / 255.0));
  return out;
}

ImageDiff image_diff(const AnyScene& a, const AnyScene& b, const std::string& name, const DiffOptions& o) {
  static std::unique_ptr<HeadlessContext> context;  // one GL context for every file of a run
  if (!context) context = std::make_unique<HeadlessContext>();
  const int w = o.size;
  Renderer ra(w, w), rb(w, w);
  a.attach(ra);
  b.attach(rb);
  Bounds both = a.bounds();
  if (!b.bounds().empty()) both.add(b.bounds().min), both.add(b.bounds().max);
  const Sphere sphere = bounding_sphere(both);
  const Rgb8 background{128, 128, 128};
  DrawSettings settings;
  std::vector<ViewMetrics> metrics;
  std::vector<float> exr;
  std::vector<Image> sheet;
  double min_psnr = 1e9, max_changed = 0;
  OJson per_view = OJson::array();
  for (int i = 0; i < o.views; ++i) {
    const Camera cam = orbit_camera(sphere, sphere_direction(i, o.views), 0, w, w);
    std::vector<float> diff;
    const RenderPair pa = render_pair(ra, cam, settings), pb = render_pair(rb, cam, settings);
    const ViewMetrics m = compare_renders(pa, pb, background, &diff);
    if (o.pictures) {
      DiffPictures& p = (*o.pictures)[name];
      p.old_views.push_back(over_background(pa, background));
      p.new_views.push_back(over_background(pb, background));
      p.diff_views.push_back(to_8bit(diff, w, w, 4));
    }
    std::size_t changed = 0;
    const float tol = float(o.thresholds.pixel_tolerance) / 255.0f;
    for (std::size_t p = 0; p + 2 < diff.size(); p += 3) changed += std::max({diff[p], diff[p + 1], diff[p + 2]}) > tol ? 1 : 0;
    const double share = double(changed) / double(std::size_t(w) * std::size_t(w));
    // Two bakes that both draw nothing from a view agree there; the metric has no evidence (NaN).
    const double psnr = !std::isnan(m.psnr) ? m.psnr : changed == 0 ? 99.0 : 0.0;
    metrics.push_back(m);
    metrics.back().psnr = psnr;
    min_psnr = std::min(min_psnr, psnr);
    max_changed = std::max(max_changed, share);
    per_view.push_back({{"psnr", round_to(psnr, 3)}, {"iou", round_to(m.iou, 5)}, {"changed_share", round_to(share, 6)}});
    exr.insert(exr.end(), diff.begin(), diff.end());
    sheet.push_back(to_8bit(diff, w, w, 4));
  }
  ImageDiff out;
  const ViewMetrics mean = mean_of(metrics);
  out.json = {{"views", o.views},
              {"size", w},
              {"psnr_min", round_to(min_psnr, 3)},
              {"psnr_mean", round_to(mean.psnr, 3)},
              {"iou_mean", round_to(mean.iou, 5)},
              {"changed_share_max", round_to(max_changed, 6)},
              {"per_view", per_view}};
  out.within = min_psnr >= o.thresholds.min_psnr && max_changed <= o.thresholds.max_changed;
  if (!o.images.empty()) {
    fs::create_directories(o.images);
    std::string stem = name;
    std::replace(stem.begin(), stem.end(), '/', '_');
    const std::string prefix = o.images + "/" + stem + ".diff";
    save_exr(prefix + ".exr", exr, w, w * o.views);
    save_png(prefix + ".png", contact_sheet(sheet, int(std::ceil(std::sqrt(double(o.views)))), {0, 0, 0}));
    out.json["images"] = {prefix + ".exr", prefix + ".png"};
  }
  return out;
}

// --- one pair of files -------------------------------------------------------------------------

// A bake manifest's impostor levels side by side, matched by file: texels, texel size and bytes
// (null where a manifest lacks the level or the field: one written before qf-bake 0.2.0), and the
// levels' bytes in total. Empty when neither JSON lists levels.
OJson level_changes(const Json& a, const Json& b) {
  const auto levels = [](const Json& m) {
    std::map<std::string, Json> out;
    if (m.is_object() && m.contains("levels") && m["levels"].is_array())
      for (const Json& l : m["levels"])
        if (l.is_object() && l.contains("file") && l["file"].is_string()) out[l["file"].get<std::string>()] = l;
    return out;
  };
  const std::map<std::string, Json> la = levels(a), lb = levels(b);
  std::set<std::string> files;
  for (const auto& [f, l] : la) files.insert(f);
  for (const auto& [f, l] : lb) files.insert(f);
  const auto field = [](const std::map<std::string, Json>& m, const std::string& f, const char* key) {
    const auto it = m.find(f);
    return it != m.end() && it->second.contains(key) ? OJson(it->second[key]) : OJson();
  };
  OJson out = OJson::array();
  std::size_t total[2] = {0, 0};
  for (const std::string& f : files) {
    OJson e{{"file", f}};
    for (const char* key : {"primitives", "texels", "texel", "bytes"}) e[key] = {field(la, f, key), field(lb, f, key)};
    for (int side = 0; side < 2; ++side)
      if (e["bytes"][side].is_number_unsigned()) total[side] += e["bytes"][side].get<std::size_t>();
    out.push_back(e);
  }
  if (out.empty()) return out;
  return OJson{{"levels", out}, {"bytes_total", {total[0], total[1]}}};
}

// Two manifests' recommended chains, one line per side ("FILE to N px, P dB -> ...", null on a side
// without one), when their chains differ in anything; empty when they are the same.
OJson chain_changes(const Json& a, const Json& b) {
  const auto chain = [](const Json& m) {
    return m.is_object() && m.contains("recommended_chain") && m["recommended_chain"].is_object() ? m["recommended_chain"].value("chain", Json())
                                                                                                   : Json();
  };
  if (chain(a) == chain(b)) return OJson();
  const auto line = [](const Json& m) {
    if (!m.is_object() || !m.contains("recommended_chain") || !m["recommended_chain"].is_object()) return OJson();
    std::string text;
    for (const Json& e : m["recommended_chain"].value("chain", Json::array())) {
      if (!e.is_object()) continue;
      if (!text.empty()) text += " -> ";
      // The input's first entry, above the largest size measured, has no figure.
      const Json error = e.contains("error") && e["error"].is_object() ? e["error"] : Json::object();
      text += (e.value("kind", std::string()) == "asset" ? std::string("the input") : e.value("file", std::string("?"))) + " to " +
              e.value("min_pixels", Json(0)).dump() + " px" + (error.contains("psnr") ? ", " + error["psnr"].dump() + " dB" : "");
    }
    return OJson(text);
  };
  return OJson{{"old", line(a)}, {"new", line(b)}};
}

// The measured errors of two manifests, where both sides measured them: each impostor level's
// figure at each size (by file) and each band of the recommended chain (the file shown there and
// its figure), old -> new where they differ, and the largest PSNR drop among them (a regression
// of the look at some on-screen size, which bytes and structure alone do not show). Null when
// nothing measured changed.
OJson error_changes(const Json& a, const Json& b, double& worst_drop) {
  using Figures = std::map<std::string, Json>;  // "what at N px" -> {psnr, iou[, file]}
  const auto figures = [](const Json& m) {
    Figures out;
    if (!m.is_object()) return out;
    for (const Json& l : m.value("levels", Json::array()))
      if (l.is_object() && l.contains("measured") && l["measured"].is_array())
        for (const Json& e : l["measured"])
          if (e.is_object() && e.contains("pixels") && e.contains("psnr"))
            out[l.value("file", std::string("?")) + " at " + e["pixels"].dump() + " px"] = {{"psnr", e["psnr"]}, {"iou", e.value("iou", Json())}};
    const Json c = m.value("recommended_chain", Json());
    if (!c.is_object() || !c.contains("sizes") || !c.contains("chain") || !c.contains("measured")) return out;
    const Json& sizes = c["sizes"];
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      const double size = sizes[k].get<double>(), lower = k + 1 < sizes.size() ? sizes[k + 1].get<double>() : 0;
      for (const Json& e : c["chain"]) {
        const bool covers = (e["max_pixels"].is_null() || size <= e["max_pixels"].get<double>()) && lower >= e["min_pixels"].get<double>();
        if (!covers) continue;
        // The band's file: the input itself (its figures as drawn) or a measured file.
        std::vector<const Json*> sources;
        if (e.value("kind", std::string()) == "asset" && c.contains("asset")) sources.push_back(&c["asset"]);
        for (const Json& f : c["measured"])
          if (f["file"] == e["file"]) sources.push_back(&f);
        for (const Json* f : sources)
          if ((*f)["at_pixels"].size() > k && (*f)["at_pixels"][k].is_object())
            out["chain band " + sizes[k].dump() + " px"] = {{"psnr", (*f)["at_pixels"][k]["psnr"]}, {"iou", (*f)["at_pixels"][k]["iou"]}, {"file", e["file"]}};
      }
    }
    return out;
  };
  const Figures fa = figures(a), fb = figures(b);
  OJson out = OJson::array();
  for (const auto& [what, old] : fa) {
    const auto it = fb.find(what);
    if (it == fb.end() || it->second == old) continue;
    OJson e{{"what", what}, {"psnr", {old["psnr"], it->second["psnr"]}}, {"iou", {old["iou"], it->second["iou"]}}};
    if (old.contains("file")) e["file"] = {old["file"], it->second["file"]};
    if (old["psnr"].is_number() && it->second["psnr"].is_number())
      worst_drop = std::max(worst_drop, old["psnr"].get<double>() - it->second["psnr"].get<double>());
    out.push_back(e);
  }
  return out.empty() ? OJson() : out;
}

// Keys whose values differ between two JSON values, as JSON pointers (at most `limit`).
void json_changes(const Json& a, const Json& b, const std::string& at, OJson& out, std::size_t limit) {
  if (out.size() >= limit || a == b) return;
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (const auto& [k, v] : a.items()) keys.insert(k);
    for (const auto& [k, v] : b.items()) keys.insert(k);
    for (const std::string& k : keys)
      json_changes(a.contains(k) ? a[k] : Json(), b.contains(k) ? b[k] : Json(), at + "/" + k, out, limit);
  } else if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (std::size_t i = 0; i < a.size(); ++i) json_changes(a[i], b[i], at + "/" + std::to_string(i), out, limit);
  } else {
    out.push_back(at.empty() ? "/" : at);
  }
}

// A changed .glb the runtime draws: its structure (quads matched by domain, else what it holds),
// its texels and its renders, into `r`. Returns whether it stays within the thresholds.
bool drawn_glb_diff(OJson& r, const std::string& name, const std::string& pa, const std::string& pb, const DiffOptions& o) {
  bool within = true;
  const AnyScene sa = load_scene(pa), sb = load_scene(pb);
  const std::optional<Quads> qa = impostor_quads(sa), qb = impostor_quads(sb);
  if (qa && qb) {
    double change = 0;
    r["structure"] = quad_diff(*qa, *qb, sa.bounds().diagonal(), change);
    within = within && qa->level == qb->level && change <= o.thresholds.max_quad_change;
  } else {
    r["structure"] = {{"old", contents(sa)}, {"new", contents(sb)}};
    within = within && contents(sa) == contents(sb);
  }
  if (sa.kind == AnyScene::kImpostor && sb.kind == AnyScene::kImpostor) {
    const std::vector<Image> ia = file_images(sa.impostor), ib = file_images(sb.impostor);
    const double changed = texel_change(ia, ib, o.thresholds.pixel_tolerance);
    r["texels"] = {{"old", texel_stats(ia)}, {"new", texel_stats(ib)}};
    if (changed >= 0) r["texels"]["changed_share"] = round_to(changed, 6);
    if (!o.render) within = within && changed >= 0 && changed <= o.thresholds.max_changed;
  }
  if (o.render) {
    const ImageDiff im = image_diff(sa, sb, name, o);
    r["images"] = im.json;
    within = within && im.within;
  }
  return within;
}

OJson diff_pair(const std::string& name, const std::string& pa, const std::string& pb, const DiffOptions& o) {
  const InputFile fa(pa), fb(pb);
  OJson r{{"name", name}};
  if (same_bytes(fa.bytes(), fb.bytes())) {
    r["status"] = "identical";
    r["within_thresholds"] = true;
    return r;
  }
  r["status"] = "changed";
  r["bytes"] = {fa.bytes().size(), fb.bytes().size()};
  const std::string ext = file_extension(name);
  if (ext == "json") {
    const ByteView a = fa.bytes(), b = fb.bytes();
    const Json ja = Json::parse(a.data(), a.data() + a.size(), nullptr, false), jb = Json::parse(b.data(), b.data() + b.size(), nullptr, false);
    OJson changes = OJson::array();
    json_changes(ja, jb, "", changes, 50);
    r["changed_keys"] = changes;
    const OJson levels = level_changes(ja, jb);
    if (!levels.empty()) r["impostor_levels"] = levels;
    const OJson chain = chain_changes(ja, jb);
    if (!chain.is_null()) r["recommended_chain"] = chain;
    double drop = 0;
    const OJson errors = error_changes(ja, jb, drop);
    if (!errors.is_null()) r["measured_errors"] = {{"changes", errors}, {"worst_psnr_drop", round_to(drop, 2)}};
    // A manifest changes with its levels, which decide, unless a measured look got worse.
    r["within_thresholds"] = drop <= o.thresholds.max_error_drop;
    return r;
  }
  if (ext != "glb") {
    r["within_thresholds"] = false;  // nothing to measure it by: any change counts
    return r;
  }
  // Readable as the runtime reads them (Draco and meshopt files included, decoded by the loader).
  check_glb(fa.bytes(), pa), check_glb(fb.bytes(), pb);
  r["within_thresholds"] = drawn_glb_diff(r, name, pa, pb, o);
  return r;
}

// --- text --------------------------------------------------------------------------------------

// A manifest's levels: quads, texels and bytes before -> after ("-" where a side has none).
void levels_text(std::ostream& out, const OJson& il) {
  const auto text = [](const OJson& v) { return v.is_null() ? std::string("-") : v.dump(); };
  for (const OJson& l : il["levels"])
    out << "    " << l["file"].get<std::string>() << ": quads " << text(l["primitives"][0]) << " -> " << text(l["primitives"][1])
        << ", texels " << text(l["texels"][0]) << " -> " << text(l["texels"][1]) << ", bytes " << text(l["bytes"][0]) << " -> "
        << text(l["bytes"][1]) << "\n";
  out << "    impostor levels: " << il["bytes_total"][0] << " -> " << il["bytes_total"][1] << " bytes\n";
}

// A .glb's structure: quads matched by domain and the neighbour graph when both sides are impostor
// levels, else what each side holds.
void structure_text(std::ostream& out, const OJson& st) {
  if (st.contains("quads")) {
    out << "    level " << st["level"][0] << " -> " << st["level"][1] << ", quads " << st["quads"][0] << " -> " << st["quads"][1] << " (+"
        << st["quads_added"] << " -" << st["quads_removed"] << " by domain), neighbour edges " << st["neighbor_edges"][0] << " -> "
        << st["neighbor_edges"][1] << " (+" << st["edges_added"] << " -" << st["edges_removed"] << ")\n";
    out << "    planes of matched quads: centre shift max " << st["center_shift_max"] << " (" << st["center_shift_max_of_diagonal"]
        << " of the diagonal), normal angle max " << st["normal_angle_max_degrees"] << " deg; mean error " << st["mean_error"][0]
        << " -> " << st["mean_error"][1] << "\n";
  } else {
    out << "    " << st["old"].dump() << " -> " << st["new"].dump() << "\n";
  }
}

// The rest of a changed file's block, after its name: its verdict, then each part diff_pair measured.
void changed_file_text(std::ostream& out, const OJson& f) {
  out << (f["within_thresholds"].get<bool>() ? " (within thresholds)" : " (BEYOND thresholds)") << "\n";
  if (f.contains("note")) out << "    " << f["note"].get<std::string>() << "\n";
  if (f.contains("changed_keys")) {
    out << "    keys:";
    for (const OJson& k : f["changed_keys"]) out << " " << k.get<std::string>();
    out << "\n";
  }
  if (f.contains("impostor_levels")) levels_text(out, f["impostor_levels"]);
  if (f.contains("recommended_chain")) {
    const auto side = [](const OJson& v) { return v.is_null() ? std::string("none") : v.get<std::string>(); };
    out << "    recommended chain: " << side(f["recommended_chain"]["old"]) << "\n      now: " << side(f["recommended_chain"]["new"]) << "\n";
  }
  if (f.contains("measured_errors")) {
    const OJson& me = f["measured_errors"];
    out << "    measured errors (worst PSNR drop " << me["worst_psnr_drop"] << " dB):\n";
    std::size_t shown = 0;
    for (const OJson& e : me["changes"]) {
      if (++shown > 12) {
        out << "      ... " << me["changes"].size() - 12 << " more\n";
        break;
      }
      out << "      " << e["what"].get<std::string>() << ": " << e["psnr"][0] << " -> " << e["psnr"][1] << " dB, IoU " << e["iou"][0] << " -> "
          << e["iou"][1];
      if (e.contains("file") && e["file"][0] != e["file"][1]) out << " (" << e["file"][0].get<std::string>() << " -> " << e["file"][1].get<std::string>() << ")";
      out << "\n";
    }
  }
  if (f.contains("structure")) structure_text(out, f["structure"]);
  if (f.contains("texels")) {
    const OJson& t = f["texels"];
    out << "    texels " << t["old"]["texels"] << " -> " << t["new"]["texels"] << ", covered " << t["old"]["covered_share"] << " -> "
        << t["new"]["covered_share"];
    if (t.contains("changed_share")) out << ", changed " << t["changed_share"];
    out << "\n";
  }
  if (f.contains("images")) {
    const OJson& im = f["images"];
    out << "    images (" << im["views"] << " views, " << im["size"] << " px): PSNR min " << im["psnr_min"] << " dB, mean " << im["psnr_mean"]
        << " dB; changed pixels max " << im["changed_share_max"];
    if (im.contains("images")) out << "; " << im["images"][1].get<std::string>();
    out << "\n";
  }
}

}  // namespace

OJson diff_bakes(const std::string& old_path, const std::string& new_path, const DiffOptions& o) {
  const bool da = fs::is_directory(old_path), db = fs::is_directory(new_path);
  if (da != db) throw UsageError("qf-diff compares two files or two folders, not a file with a folder");
  OJson report{{"old", old_path}, {"new", new_path}, {"kind", da ? "folders" : "files"}};
  report["thresholds"] = {{"min_psnr", o.thresholds.min_psnr},
                          {"max_changed_share", o.thresholds.max_changed},
                          {"pixel_tolerance", o.thresholds.pixel_tolerance},
                          {"max_quad_change_share", o.thresholds.max_quad_change},
                          {"max_error_drop", o.thresholds.max_error_drop},
                          {"render", o.render}};
  OJson files = OJson::array();
  std::size_t identical = 0, changed = 0, added = 0, removed = 0;
  bool within = true;
  if (!da) {
    files.push_back(diff_pair(fs::path(new_path).filename().string(), old_path, new_path, o));
  } else {
    const std::vector<std::string> a = list_files(old_path), b = list_files(new_path);
    std::set<std::string> all(a.begin(), a.end());
    all.insert(b.begin(), b.end());
    for (const std::string& name : all) {
      const bool in_a = std::binary_search(a.begin(), a.end(), name), in_b = std::binary_search(b.begin(), b.end(), name);
      if (in_a && in_b) files.push_back(diff_pair(name, old_path + "/" + name, new_path + "/" + name, o));
      else files.push_back({{"name", name}, {"status", in_a ? "removed" : "added"}, {"within_thresholds", false}});
    }
  }
  for (const OJson& f : files) {
    const std::string s = f["status"];
    identical += s == "identical", changed += s == "changed", added += s == "added", removed += s == "removed";
    within = within && f["within_thresholds"].get<bool>();
  }
  report["summary"] = {{"identical", identical}, {"changed", changed}, {"added", added}, {"removed", removed}};
  report["verdict"] = changed + added + removed == 0 ? "identical" : within ? "within thresholds" : "different";
  report["files"] = files;
  return report;
}

// The summary line, one block per file that is not identical (a changed file with what changed,
// as far as diff_pair measured it), and the verdict with its thresholds.
std::string diff_text(const OJson& r) {
  std::ostringstream out;
  const OJson& s = r["summary"];
  out << "qf-diff: " << r["old"].get<std::string>() << " -> " << r["new"].get<std::string>() << ": " << s["identical"] << " identical, "
      << s["changed"] << " changed, " << s["added"] << " added, " << s["removed"] << " removed\n";
  for (const OJson& f : r["files"]) {
    const std::string status = f["status"];
    if (status == "identical") continue;
    out << "  " << status << " " << f["name"].get<std::string>();
    if (status != "changed") {
      out << "\n";
      continue;
    }
    changed_file_text(out, f);
  }
  const OJson& t = r["thresholds"];
  out << "verdict: " << r["verdict"].get<std::string>() << " (thresholds: PSNR >= " << t["min_psnr"] << " dB, changed pixels <= "
      << t["max_changed_share"] << ", quads added/removed <= " << t["max_quad_change_share"] << ", measured PSNR drop <= "
      << t["max_error_drop"] << " dB)\n";
  return out.str();
}

}  // namespace qf::render
