// The bake's report.html and the batch's page (tools/report_html.h).
#include "tools/report_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "gl/egl.h"
#include "measure/chain.h"
#include "runtime_gl/camera.h"
#include "measure/any_scene.h"
#include "tools/html_page.h"
#include "measure/measure.h"

namespace qf::render {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

// --- the bake's files --------------------------------------------------------------------------

// One output file as the page shows it: its manifest entry, its bytes and what it is made for.
struct PageFile {
  std::string file, kind;  // kind: impostor_level, mesh_lod, point_impostor, lod_file
  const Json* entry = nullptr;
  const std::vector<std::uint8_t>* bytes = nullptr;
  double own_pixels = 0;         // max_screen_pixels (the point impostor's size at its switch distance)
  std::size_t texels = 0;        // of the images in the file, as an engine uploads them
  Image own, near;               // drawn at its own size (capped) and at near_pixels
};

const std::vector<std::uint8_t>* bytes_of(const AssetBake& a, const std::string& name) {
  for (const OutputFile& f : a.files)
    if (f.name == name) return &f.bytes;
  return nullptr;
}

// 1. The files, in the manifest's order: impostor levels (finest first), mesh LODs, the point
// impostor, the combined LOD file (listed, not drawn: it shows its parts).
std::vector<PageFile> page_files(const AssetBake& a) {
  const Json& m = a.manifest;
  std::vector<PageFile> out;
  auto add = [&](const Json& e, const char* kind, double own) {
    const std::string name = e.at("file").get<std::string>();
    if (const auto* b = bytes_of(a, name)) out.push_back({name, kind, &e, b, own, 0, {}, {}});
  };
  std::vector<const Json*> levels;
  for (const Json& l : m.at("levels")) levels.push_back(&l);
  std::stable_sort(levels.begin(), levels.end(), [](const Json* x, const Json* y) { return (*x)["level"] < (*y)["level"]; });
  for (const Json* l : levels) add(*l, "impostor_level", (*l)["max_screen_pixels"].get<double>());
  if (m.contains("mesh_lods"))
    for (const Json& l : m["mesh_lods"]["levels"]) add(l, "mesh_lod", l.value("max_screen_pixels", 0.0));  // none: clustering LODs
  if (m.contains("point_impostor")) {
    // Measured: where it holds; else nearer than its switch distance the points part, so it is
    // made for the sizes below this one.
    const Json& p = m["point_impostor"];
    add(p, "point_impostor", p.contains("measured") ? p["max_screen_pixels"].get<double>()
                                                    : distance_for_pixels(m.at("bounding_box_diagonal").get<double>(), p.at("switch_distance").get<double>(),
                                                                          p.at("switch_screen_height").get<double>(), p.at("switch_fov_degrees").get<double>()));
  }
  if (m.contains("lod_file")) add(m["lod_file"], "lod_file", 0);
  return out;
}

// A file's measured figures, [{pixels, psnr, iou, soft_iou, coverage, holds}] largest size first
// (manifest "measured"; none where the file was not measured).
Json measured_of(const PageFile& f) { return f.entry->value("measured", Json::array()); }

// One measured size's cell: PSNR / coverage, marked where the file holds there.
void measured_cell(std::ostream& h, const Json& s, const Json& at) {
  const bool held = at.value("holds", false);
  h << "<td class=\"measured" << (held ? " holds" : "") << "\" data-pixels=\"" << html::attr(s) << "\" data-psnr=\"" << html::attr(at["psnr"])
    << "\" data-iou=\"" << html::attr(at["iou"]) << "\" data-coverage=\"" << html::attr(at["coverage"]) << "\" data-sort=\"" << html::attr(at["psnr"])
    << "\">" << html::fixed(at["psnr"], 2) << " / " << html::fixed(at["coverage"], 2) << "</td>";
}

// GPU memory of a file's textures: the manifest's figure where it gives one (compressed
// textures), else RGBA8 with a full mip chain (4 bytes a texel, plus a third).
double gpu_bytes(const PageFile& f) {
  if (f.entry->contains("gpu_bytes")) return (*f.entry)["gpu_bytes"].get<double>();
  return double(f.texels) * 16 / 3;
}

// Texels as an engine uploads them: the images in the file.
std::size_t texels_of(const AnyScene& s) {
  std::size_t n = 0;
  for (const Image& im : s.engine.images) n += std::size_t(im.width) * std::size_t(im.height);
  return n;
}

// The side a file is drawn at for its own size: its size rounded, at least 1, at most `near`
// (`near` for a file without a size: the clustering LODs, valid by their cell width).
int own_side(const PageFile& f, int near) {
  return f.own_pixels > 0 ? std::clamp(static_cast<int>(std::lround(f.own_pixels)), 1, near) : near;
}

// --- drawing -----------------------------------------------------------------------------------

// 2. Every file and the input from one view (the input framed, as the measuring frames it): the
// engine method over the measuring's grey; each file loaded once (its texels counted then).
// Returns the input's images by side; empty (with `why`) when there is no GL driver.
// `driver`: the GL driver that drew them, "renderer (version)".
std::map<int, Image> draw_all(std::vector<PageFile>& files, const std::string& input_path, const BakePageOptions& o, std::string& why,
                              std::string& driver) {
  std::map<int, Image> input;
  std::unique_ptr<HeadlessContext> context;
  try {
    context = std::make_unique<HeadlessContext>();
  } catch (const std::runtime_error& e) {
    why = e.what();
    return input;
  }
  driver = context->renderer() + " (" + context->version() + ")";
  DrawSettings settings;
  settings.method = Method::kEngine;
  settings.background = {128, 128, 128};
  // Azimuth 30 degrees, 20 above the horizon: a three-quarter view of a Y-up model.
  const Vec3f direction = orbit_direction(30, 20);
  const AnyScene scene = measured_input(input_path, o.read);
  const Sphere sphere = bounding_sphere(scene.bounds());
  Renderer renderer(1, 1);
  auto draw = [&](int side) {
    renderer.resize(side, side);
    renderer.draw(orbit_camera(sphere, direction, 0, side, side), settings);
    return renderer.read_pixels();
  };
  renderer.set_engine_only(scene.engine);
  input[o.near_pixels] = draw(o.near_pixels);
  for (const PageFile& f : files)
    if (f.kind != "lod_file" && !input.count(own_side(f, o.near_pixels))) input[own_side(f, o.near_pixels)] = draw(own_side(f, o.near_pixels));
  for (PageFile& f : files) {
    if (f.kind == "lod_file") continue;
    const AnyScene s = load_scene(*f.bytes, f.file);
    f.texels = texels_of(s);
    renderer.set_engine_only(s.engine);
    f.near = draw(o.near_pixels);
    f.own = own_side(f, o.near_pixels) < o.near_pixels ? draw(own_side(f, o.near_pixels)) : f.near;
  }
  return input;
}

// --- the bake page's parts ---------------------------------------------------------------------

// "12.3%": `part` of `whole` bytes, "-" without a whole.
std::string share_text(double part, double whole) {
  if (!(whole > 0)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, part < 0.1 * whole ? "%.2f%%" : "%.1f%%", 100 * part / whole);
  return text;
}

// The input's facts (manifest "source") and what the bake makes of its bytes: all it wrote, and
// what the recommended chain ships; the version that baked and the GL driver that measured. The
// figures as data-* attributes, as the JSON has them.
std::string source_line(const AssetBake& a, const std::string& driver) {
  const Json& s = a.manifest.value("source", Json::object());
  const double input = s.value("bytes", 0.0);
  std::ostringstream h;
  h << "<p class=\"meta\" id=\"source\" data-format=\"" << html::attr(s.value("format", Json())) << "\" data-bytes=\"" << html::attr(s.value("bytes", Json()))
    << "\" data-files=\"" << html::attr(s.value("files", Json())) << "\" data-triangles=\"" << html::attr(s.value("triangles", Json()))
    << "\" data-points=\"" << html::attr(s.value("points", Json())) << "\" data-materials=\"" << html::attr(s.value("materials", Json()))
    << "\" data-textures=\"" << html::attr(s.value("textures", Json())) << "\">The input: " << html::escape(s.value("format", std::string("?"))) << ", "
    << html::bytes_text(input) << " in " << s.value("files", 1) << " file(s), ";
  if (s.contains("triangles"))
    h << s["triangles"].dump() << " triangles, " << s.value("materials", Json(0)).dump() << " material(s), " << s.value("textures", Json(0)).dump() << " texture(s).";
  else
    h << s.value("points", Json(0)).dump() << " points.";
  const OutputBytes out = output_bytes(a.manifest, a.files);
  h << " The bake wrote <span id=\"bytes-written\" data-value=\"" << out.written << "\">" << html::bytes_text(double(out.written)) << "</span> ("
    << share_text(double(out.written), input) << " of the input)";
  if (out.chain)
    h << "; its recommended chain ships <span id=\"chain-bytes\" data-value=\"" << *out.chain << "\">" << html::bytes_text(double(*out.chain)) << "</span> ("
      << share_text(double(*out.chain), input) << ")";
  h << ".</p>\n<p class=\"meta\" id=\"generator\" data-version=\"" << html::attr(a.report.value("tool_version", Json())) << "\">quasiflat "
    << html::escape(a.report.value("tool_version", std::string("(version not given)")));
  // The measuring's driver decides the figures; without measuring, the driver that drew this page.
  if (a.gl.is_object())
    h << "; measured with the GL driver <span id=\"gl\" data-renderer=\"" << html::attr(a.gl["renderer"]) << "\" data-version=\""
      << html::attr(a.gl["version"]) << "\">" << html::escape(a.gl["renderer"].get<std::string>()) << ", OpenGL "
      << html::escape(a.gl["version"].get<std::string>()) << "</span> (another driver draws a little differently: the figures are this one's)";
  else if (!driver.empty())
    h << "; not measured; drawn with the GL driver " << html::escape(driver);  // "renderer (version)"
  else
    h << "; not measured";
  h << ".</p>\n";
  return h.str();
}

std::string header(const AssetBake& a, const std::string& driver) {
  const Json& r = a.report;
  std::ostringstream h;
  h << "<h1>" << html::escape(fs::path(r.value("input", std::string())).filename().string()) << "</h1>\n<p class=\"meta\">input <code>"
    << html::escape(r.value("input", std::string())) << "</code> (" << html::escape(r.value("format", std::string())) << ", <span id=\"points\" data-value=\""
    << html::attr(r.value("points", Json())) << "\">" << r.value("points", Json()).dump() << "</span> points";
  if (!a.sampled.backend.empty()) h << " sampled from the mesh";
  h << "), hierarchy of " << r.value("hierarchy_levels", Json()).dump() << " levels; settings:";
  const Json settings = r.value("settings", Json::object());
  for (const auto& [k, v] : settings.items()) h << " " << html::escape(k) << "=" << html::escape(v.dump());
  h << "</p>\n" << source_line(a, driver);
  return h.str();
}

std::string warnings_section(const AssetBake& a) {
  std::ostringstream h;
  h << "<h2>Warnings</h2>\n";
  if (a.result.warnings.empty()) return h.str() + "<p id=\"warnings\" data-count=\"0\">none</p>\n";
  h << "<ul id=\"warnings\" class=\"warn\" data-count=\"" << a.result.warnings.size() << "\">";
  for (const std::string& w : a.result.warnings) h << "<li class=\"warning\">" << html::escape(w) << "</li>";
  h << "</ul>\n";
  return h.str();
}

// One row per file: what it holds, its bytes, texels and GPU bytes, the size it is made for and
// its measured figures at each measured size.
std::string files_table(const AssetBake& a, const std::vector<PageFile>& files) {
  const Json& m = a.manifest;
  const Json sizes = m.contains("measuring") ? m["measuring"].value("sizes", Json::array()) : Json::array();
  const double input_bytes = m.contains("source") ? m["source"].value("bytes", 0.0) : 0.0;
  std::ostringstream h;
  h << "<h2>Files</h2>\n<p class=\"meta\">Each file drawn by the engine method at each measured size against the truth: footprint PSNR "
       "(dB) / coverage (its summed coverage over the truth's); marked where it holds, as good as the input itself as drawn there "
       "(manifest measuring.hold). made for: the largest size at which it holds.</p>\n"
       "<table id=\"files\" class=\"sortable\"><thead><tr><th>file</th><th class=\"text\">kind</th><th class=\"text\">holds</th><th>bytes</th>"
       "<th title=\"its bytes over the input's, with every file the input reads\">of input</th><th>texels</th>"
       "<th>GPU bytes</th><th>made for &le; px</th>";
  for (const Json& s : sizes) h << "<th>at " << s.dump() << " px<br>PSNR dB / coverage</th>";
  h << "</tr></thead><tbody>\n";
  // The input itself as an engine draws it, what every file is judged beside.
  if (m.contains("measuring") && m["measuring"].contains("asset")) {
    h << "<tr data-file=\"\" data-kind=\"asset\"><td>the input, as drawn</td><td class=\"text\">asset</td><td class=\"text\"></td><td data-sort=\""
      << input_bytes << "\">" << (input_bytes ? html::bytes_text(input_bytes) : "-") << "</td><td>" << share_text(input_bytes, input_bytes)
      << "</td><td>-</td><td>-</td><td>-</td>";
    for (const Json& s : sizes)
      for (const Json& x : m["measuring"]["asset"])
        if (x.value("pixels", Json()) == s) measured_cell(h, s, x);
    h << "</tr>\n";
  }
  for (const PageFile& f : files) {
    const Json& e = *f.entry;
    std::string holds = e.contains("primitives")  ? e["primitives"].dump() + " quads"
                        : e.contains("triangles") ? e["triangles"].dump() + " triangles"
                        : e.contains("points")    ? e["points"].dump() + " points"
                        : e.contains("parts")     ? std::to_string(e["parts"].size()) + " parts"
                                                  : "";
    const bool drawn = f.kind != "lod_file";
    h << "<tr data-file=\"" << html::attr(f.file) << "\" data-kind=\"" << f.kind << "\" data-bytes=\"" << f.bytes->size() << "\"";
    if (drawn) h << " data-texels=\"" << f.texels << "\" data-gpu-bytes=\"" << html::attr(std::llround(gpu_bytes(f))) << "\" data-own-pixels=\"" << html::attr(e.value("max_screen_pixels", Json())) << "\"";
    h << "><td><a href=\"#" << html::attr(f.file) << "\">" << html::escape(f.file) << "</a></td><td class=\"text\">" << f.kind << "</td><td class=\"text\">" << holds
      << "</td><td data-sort=\"" << f.bytes->size() << "\">" << html::bytes_text(double(f.bytes->size())) << "</td><td data-sort=\""
      << f.bytes->size() << "\">" << share_text(double(f.bytes->size()), input_bytes) << "</td>";
    if (drawn)
      h << "<td>" << f.texels << "</td><td data-sort=\"" << std::llround(gpu_bytes(f)) << "\">" << html::bytes_text(gpu_bytes(f)) << "</td><td>"
        << (f.own_pixels > 0 ? std::to_string(std::llround(f.own_pixels)) : "-") << "</td>";
    else
      h << "<td>-</td><td>-</td><td>-</td>";
    const Json measured = drawn ? measured_of(f) : Json::array();
    for (const Json& s : sizes) {
      const Json* at = nullptr;
      for (const Json& x : measured)
        if (x.value("pixels", Json()) == s) at = &x;
      if (at) measured_cell(h, s, *at);
      else h << "<td>-</td>";
    }
    h << "</tr>\n";
  }
  h << "</tbody></table>\n";
  if (sizes.empty()) h << "<p class=\"note\">The outputs were not measured (--no-measure, or no GL driver): no measured error.</p>\n";
  return h.str();
}

// A band's width on the screen-size axis: log2 of the pixels it spans, clamped to [4, 1024].
double band_width(double lo, double hi) {
  lo = std::clamp(lo, 4.0, 1024.0), hi = std::clamp(hi, 4.0, 1024.0);
  return std::max(0.0, std::log2(hi / lo));
}

// The recommended chain (else the impostor levels by their max_screen_pixels) as bands along the
// on-screen size, near (large) on the left: the file shown in each, its figures, the switch sizes
// and distances.
std::string chain_section(const AssetBake& a, const std::vector<PageFile>& files) {
  struct Band {
    std::string file;
    double lo = 0, hi = 0;  // pixels; hi < 0: any larger size
    Json psnr, iou, distance;
    bool bar_met = true;
    std::string reason, kind, cost;
  };
  // What drawing a chain entry costs: triangles, and the GPU memory of its textures.
  const auto cost_text = [](const Json& c) {
    if (!c.is_object()) return std::string();
    std::string out = c.contains("triangles") ? c["triangles"].dump() + " triangles" : c.contains("points") ? c["points"].dump() + " points" : "";
    if (c.contains("gpu_bytes")) out += ", " + html::bytes_text(c["gpu_bytes"].get<double>()) + " GPU";
    return out;
  };
  const Json& m = a.manifest;
  std::vector<Band> bands;
  std::ostringstream h;
  const bool chain = m.contains("recommended_chain");
  if (chain) {
    const Json& c = m["recommended_chain"];
    h << "<h2>Recommended chain</h2>\n<p class=\"meta\">From near to far: the file shown while the object spans that many pixels on a screen "
      << html::fixed(c.value("screen_height", Json()), 0) << " px high (" << html::fixed(c.value("fov_degrees", Json()), 0)
      << "&deg; field of view), its measured error at the band's largest size, and where it switches.</p>\n";
    for (const Json& e : c["chain"])
      bands.push_back({e["file"].get<std::string>(), e["min_pixels"].get<double>(), e["max_pixels"].is_null() ? -1 : e["max_pixels"].get<double>(),
                       e["error"].is_object() ? e["error"]["psnr"] : Json(), e["error"].is_object() ? e["error"]["iou"] : Json(),
                       e.value("switch_distance", Json()), e.value("bar_met", true), e.value("reason", std::string()), e.value("kind", std::string()),
                       cost_text(e.value("draw_cost", Json()))});
  } else {
    h << "<h2>Impostor levels by on-screen size</h2>\n<p class=\"note\">No recommended chain (baked with <code>--no-chain</code> or "
         "<code>--no-measure</code>, or without a GL driver to measure): the impostor levels, each shown from its max_screen_pixels down to "
         "the next coarser one's.</p>\n";
    std::vector<const PageFile*> levels;
    for (const PageFile& f : files)
      if (f.kind == "impostor_level") levels.push_back(&f);
    for (std::size_t i = 0; i < levels.size(); ++i)
      bands.push_back({levels[i]->file, i + 1 < levels.size() ? levels[i + 1]->own_pixels : 0, levels[i]->own_pixels, Json(), Json(), Json(), true, "", "", ""});
  }
  if (bands.empty()) return h.str() + "<p>none</p>\n";
  h << "<div id=\"chain\" class=\"chain\" data-kind=\"" << (chain ? "recommended_chain" : "impostor_levels") << "\">";
  for (const Band& b : bands) {
    const PageFile* f = nullptr;
    for (const PageFile& x : files)
      if (x.file == b.file) f = &x;
    const double upper = b.hi < 0 ? 1024 : b.hi;
    h << "<div class=\"band" << (b.bar_met ? "" : " below") << "\" style=\"flex-grow:" << html::fixed(std::max(0.5, band_width(b.lo, upper)), 3)
      << "\" data-file=\"" << html::attr(b.file) << "\" data-min-pixels=\"" << html::attr(b.lo) << "\" data-max-pixels=\""
      << (b.hi < 0 ? std::string("null") : html::attr(b.hi)) << "\"";
    if (chain) h << " data-psnr=\"" << html::attr(b.psnr) << "\" data-iou=\"" << html::attr(b.iou) << "\"";
    h << "><div class=\"range\">" << (b.hi < 0 ? std::string("&infin;") : std::to_string(std::llround(b.hi))) << " &rarr; " << std::llround(b.lo)
      << " px</div>";
    if (f && f->near.width > 0) h << html::img(f->near, b.file, "thumb");
    if (b.kind == "asset") h << "<div>the input itself</div>";
    else h << "<div><a href=\"#" << html::attr(b.file) << "\">" << html::escape(b.file) << "</a></div>";
    if (f) h << "<div>" << html::bytes_text(double(f->bytes->size())) << "</div>";
    if (!b.cost.empty()) h << "<div class=\"meta cost\">" << html::escape(b.cost) << "</div>";
    if (chain)
      h << (b.psnr.is_number() ? "<div>" + html::fixed(b.psnr, 2) + " dB, IoU " + html::fixed(b.iou, 3) + "</div>" : "")
        << (b.reason.empty() ? "" : "<div class=\"" + std::string(b.bar_met ? "meta" : "warn") + " reason\">" + html::escape(b.reason) + "</div>")
        << (b.distance.is_number() ? "<div class=\"meta\">switches at distance " + html::fixed(b.distance, 2) + "</div>" : "");
    h << "</div>";
  }
  h << "</div>\n<div class=\"axis\"><span>near: large on screen</span><span>on-screen size (log scale) &rarr;</span><span>far: small</span></div>\n";
  return h.str();
}

std::string figure(const Image& image, const std::string& caption, const std::string& id = "") {
  std::string out = "<figure" + (id.empty() ? "" : " id=\"" + id + "\"") + ">" + html::img(image, caption);
  // Below 64 px also four times as large, pixels kept, to see what is there.
  if (image.width < 64) {
    out += "<img src=\"" + html::png_data_uri(image) + "\" width=\"" + std::to_string(4 * image.width) + "\" height=\"" +
           std::to_string(4 * image.height) + "\" class=\"px\" alt=\"" + html::escape(caption) + " x4\">";
  }
  return out + "<figcaption>" + html::escape(caption) + "</figcaption></figure>";
}

// Each file beside the input: both at the file's own size, the file at near_pixels (the input at
// near_pixels stays pinned beside them).
std::string gallery(const std::vector<PageFile>& files, const std::map<int, Image>& input, const BakePageOptions& o, const std::string& why) {
  std::ostringstream h;
  h << "<h2>As drawn</h2>\n";
  if (input.empty())
    return h.str() + "<p id=\"no-images\" class=\"note\">No images: drawing needs an EGL/OpenGL driver, and there was none (" + html::escape(why) +
           "). The figures above are complete.</p>\n";
  h << "<p class=\"meta\">The engine method (as a glTF engine draws the file), one view, over grey: each file at its own on-screen size "
       "(what it is made for: max_screen_pixels; the point impostor's size at its switch distance) beside the input at that size, and at "
    << o.near_pixels << " px beside the input at " << o.near_pixels << " px (pinned on the left).</p>\n<div class=\"gallery\"><div class=\"pin\">"
    << figure(input.at(o.near_pixels), "input at " + std::to_string(o.near_pixels) + " px", kThumbnailId) << "</div><div>\n";
  for (const PageFile& f : files) {
    if (f.kind == "lod_file") continue;
    const int side = own_side(f, o.near_pixels);
    h << "<h3 id=\"" << html::attr(f.file) << "\">" << html::escape(f.file) << "</h3><div class=\"row\">";
    if (side < o.near_pixels)
      h << figure(input.at(side), "input at " + std::to_string(side) + " px") << figure(f.own, f.file + " at " + std::to_string(side) + " px");
    const std::string made = side < o.near_pixels || f.own_pixels <= 0 ? "" : " (made for " + std::to_string(std::llround(f.own_pixels)) + ")";
    h << figure(f.near, f.file + " at " + std::to_string(o.near_pixels) + " px" + made) << "</div>\n";
  }
  h << "</div></div>\n";
  return h.str();
}

constexpr const char* kBakeStyle = R"(
.chain{display:flex;gap:2px;margin:8px 0 2px;align-items:stretch}
.band{min-width:110px;flex-basis:0;text-align:center;background:#e8f0fa;border:1px solid #b8cce4;border-radius:4px;padding:6px;font-size:12px;display:flex;flex-direction:column;align-items:center;gap:2px}
.band.below{background:#fdf0e6;border-color:#e9c3a3}.band .range{font-weight:600}.band img.thumb{width:96px;height:96px}
.axis{display:flex;justify-content:space-between;font-size:12px;color:#555;border-top:2px solid #888;padding-top:2px}
.gallery{display:grid;grid-template-columns:auto 1fr;gap:16px}.pin{position:sticky;top:8px;align-self:start}
h3{font-size:14px;margin:12px 0 2px}
td.measured.holds{background:#e6f4e6}.band .reason{max-width:220px}
)";

// --- the batch page ----------------------------------------------------------------------------

// The src of the thumbnail image in an asset's report.html (empty when it has none).
std::string thumbnail_src(const std::string& page_path) {
  std::ifstream in(page_path, std::ios::binary);
  if (!in) return "";
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::string mark = std::string("id=\"") + kThumbnailId + "\"><img src=\"";
  const std::size_t at = text.find(mark);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + mark.size(), end = text.find('"', begin);
  return end == std::string::npos ? "" : text.substr(begin, end - begin);
}

}  // namespace

std::string bake_page(const AssetBake& a, const std::string& input_path, const BakePageOptions& o) {
  std::vector<PageFile> files = page_files(a);
  std::string why, driver;
  const std::map<int, Image> input = draw_all(files, input_path, o, why, driver);
  // Without GL the files were not loaded to be drawn: their texels are counted here.
  if (input.empty())
    for (PageFile& f : files)
      if (f.kind != "lod_file") f.texels = texels_of(load_scene(*f.bytes, f.file));
  const std::string title = fs::path(a.report.value("input", std::string("bake"))).filename().string() + " - quasiflat bake";
  return html::page(title, header(a, driver) + warnings_section(a) + files_table(a, files) + chain_section(a, files) + gallery(files, input, o, why), kBakeStyle);
}

namespace {

// A cell of bytes in a sortable column (class `what`), "-" where there is no figure.
std::string bytes_cell(const char* what, std::optional<std::uintmax_t> bytes) {
  if (!bytes) return std::string("<td class=\"") + what + "\">-</td>";
  const std::string n = std::to_string(*bytes);
  return std::string("<td class=\"") + what + "\" data-sort=\"" + n + "\" data-value=\"" + n + "\">" + html::bytes_text(double(*bytes)) + "</td>";
}

}  // namespace

std::string batch_page(const Json& report, const std::string& page_dir) {
  const std::string root = report.value("output", std::string("."));
  const Json& t = report.value("totals", Json::object());
  std::ostringstream h;
  h << "<h1>Batch: " << html::escape(fs::path(report.value("manifest", std::string())).filename().string()) << "</h1>\n<p class=\"meta\">manifest <code>"
    << html::escape(report.value("manifest", std::string())) << "</code>, output <code>" << html::escape(root) << "</code>, " << report["assets"].size()
    << " asset(s): ";
  for (const char* s : {"baked", "up to date", "failed", "skipped"}) h << "<span id=\"total-" << (s == std::string("up to date") ? "up-to-date" : s) << "\" data-value=\"" << html::attr(t.value(s, Json(0))) << "\">" << t.value(s, Json(0)).dump() << " " << s << "</span>, ";
  // The folder's weight beside what ships: the chains' files (a report from before these totals has neither).
  if (t.contains("bytes") && t.contains("chain_bytes"))
    h << "<span id=\"total-bytes\" data-value=\"" << html::attr(t["bytes"]) << "\">" << html::bytes_text(t["bytes"].get<double>())
      << " written</span>, of which the recommended chains ship <span id=\"total-chain-bytes\" data-value=\"" << html::attr(t["chain_bytes"])
      << "\">" << html::bytes_text(t["chain_bytes"].get<double>()) << "</span>, ";
  h << "in " << html::fixed(report.value("seconds", Json()), 2) << " s. Click a column to sort.</p>\n";
  h << "<table id=\"assets\" class=\"sortable\"><thead><tr><th>asset</th><th>image</th><th>status</th><th>seconds</th><th>peak MB</th><th>points</th>"
       "<th>levels</th><th>primitives</th><th>texels</th><th title=\"the files the recommended chain ships\">chain bytes</th>"
       "<th title=\"every file written, the reports aside\">bytes written</th><th>warnings</th><th class=\"text\">error</th></tr></thead><tbody>\n";
  for (const Json& e : report["assets"]) {
    const std::string name = e.value("name", std::string());
    const std::string status = e.value("status", std::string());
    const fs::path folder = fs::path(root) / name;
    const Json manifest = read_asset_manifest(folder.string());
    // The asset's own figures from its folder (up-to-date assets were not baked in this run).
    std::size_t levels = 0, primitives = 0, texels = 0;
    if (manifest.is_object())
      for (const Json& l : manifest.value("levels", Json::array())) ++levels, primitives += l.value("primitives", std::size_t{0}), texels += l.value("texels", std::size_t{0});
    // Both weights: a point impostor or a mesh LOD that no band of the chain takes is written, not shipped.
    const OutputBytes bytes = output_bytes(manifest);
    const fs::path page = folder / "report.html";
    std::error_code ec;
    const bool has_page = manifest.is_object() && fs::is_regular_file(page, ec);
    const std::string link = fs::relative(page, page_dir, ec).generic_string();
    const std::string thumb = has_page ? thumbnail_src(page.string()) : "";
    const std::string message = e.contains("error") ? e["error"].value("message", std::string()) : "";
    h << "<tr data-name=\"" << html::attr(name) << "\" data-status=\"" << html::attr(status) << "\"><td>"
      << (has_page ? "<a href=\"" + html::attr(link) + "\">" + html::escape(name) + "</a>" : html::escape(name)) << "</td><td>"
      << (thumb.empty() ? "-" : "<img src=\"" + thumb + "\" width=\"64\" height=\"64\" alt=\"" + html::escape(name) + "\">") << "</td><td class=\""
      << (status == "failed" ? "fail" : status == "skipped" ? "" : "ok") << "\">" << html::escape(status) << "</td><td data-value=\""
      << html::attr(e.value("seconds", Json())) << "\">" << html::fixed(e.value("seconds", Json()), 2) << "</td><td>" << html::fixed(e.value("peak_mb", Json()), 0)
      << "</td><td>" << (e.contains("points") ? e["points"].dump() : manifest.is_object() ? manifest.value("points", Json()).dump() : "-") << "</td>";
    if (manifest.is_object())
      h << "<td>" << levels << "</td><td data-value=\"" << primitives << "\">" << primitives << "</td><td data-value=\"" << texels << "\">" << texels
        << "</td>" << bytes_cell("chain-bytes", bytes.chain) << bytes_cell("bytes", bytes.written);
    else
      h << "<td>-</td><td>-</td><td>-</td><td class=\"chain-bytes\">-</td><td class=\"bytes\">-</td>";
    h << "<td>" << (e.contains("warnings") ? std::to_string(e["warnings"].size()) : "-") << "</td><td class=\"fail error\">" << html::escape(message)
      << "</td></tr>\n";
  }
  h << "</tbody></table>\n";
  return html::page("quasiflat batch", h.str(), "td.error{text-align:left;white-space:normal;min-width:320px}");
}

}  // namespace qf::render
