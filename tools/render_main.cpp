// qf-render: draws baked levels (and reference point sets / meshes) with the GL 1.1 renderer,
// headless to PNG or in a window, and measures an impostor's fidelity against its reference
// (method.md 7-8; paper 4-6). Exit codes as qf-bake: 0 ok, 1 bad input, 2 bad usage, 3 internal.
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "cli/args.h"
#include "cli/program.h"
#include "core/error.h"
#include "core/file_io.h"
#include "io/model_io.h"
#include "measure/any_scene.h"
#include "runtime_gl/draw_gl11.h"
#include "runtime_gl/egl_context.h"
#include "tools/image_ops.h"
#include "measure/measure.h"
#include "runtime_gl/loader.h"

namespace qf::render {
namespace {

using cli::CommandSpec;
using cli::OptionSpec;
using cli::ParsedArgs;
using nlohmann::ordered_json;

// --- option parsing ---------------------------------------------------------------------------

std::pair<int, int> parse_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  in >> w;
  if (in >> x) {
    if (x != 'x' || !(in >> h)) h = -1;
  } else {
    h = w;
  }
  if (w < 1 || h < 1 || w > 8192 || h > 8192 || in.rdbuf()->in_avail() > 0)
    throw UsageError("--size: expected W or WxH with sides in 1..8192, got '" + text + "'");
  return {w, h};
}

Rgb8 parse_color(const std::string& opt, const std::string& text) {
  int c[3];
  char comma1 = 0, comma2 = 0;
  std::istringstream in(text);
  if (!(in >> c[0] >> comma1 >> c[1] >> comma2 >> c[2]) || comma1 != ',' || comma2 != ',' || in.rdbuf()->in_avail() > 0 ||
      std::min({c[0], c[1], c[2]}) < 0 || std::max({c[0], c[1], c[2]}) > 255)
    throw UsageError("--" + opt + ": expected r,g,b with values 0..255, got '" + text + "'");
  return {static_cast<std::uint8_t>(c[0]), static_cast<std::uint8_t>(c[1]), static_cast<std::uint8_t>(c[2])};
}

std::vector<OptionSpec> draw_option_specs() {
  std::string methods;
  for (const std::string& m : method_names()) methods += (methods.empty() ? "" : "|") + m;
  return {
      {"method", 'm', methods, "overlap",
       "how quads blend: overlap = sorted, neighbours blended, lock by depth (the paper's); two-pass = depth "
       "offset; backface-hard/-soft = dark back faces; blend-all; no-blend; engine = the glTF materials as a "
       "standard PBR engine draws them (any file: levels, mesh LODs, point impostors, references)"},
      {"size", 0, "W[xH]", "512", "image size in pixels"},
      {"background", 0, "R,G,B", "0,0,0", "background colour (results are right over any colour)"},
      {"alpha-ref", 0, "V", "the file's (0.1)", "alpha test of the lock pass"},
      {"transparency", 0, "A", "1", "whole-object opacity in 0..1 (scales the basis functions)"},
      {"no-lighting", 0, "", "", "unlit: texture colours as they are (default: headlight, one normal per quad)"},
      {"depth-offset", 0, "D", "half the median quad half-diagonal", "two-pass: depth offset in world units"},
      {"alpha-mode", 0, "OPAQUE|MASK|BLEND", "the material's", "engine method: draw as this glTF alpha mode"},
      {"alpha-cutoff", 0, "V", "the material's", "engine method, MASK: the cutoff"},
      {"no-mips", 0, "", "", "engine method: sample the textures' base level alone (bilinear), not their mip levels;\n"
                              "a level drawn with and without it at a small size shows what its mip levels lose"},
      {"fov", 0, "DEG", "30", "vertical field of view"},
      {"lod", 0, "N", "by screen coverage", "combined LOD files (qf-bake --lod-file): draw level N (0 = finest) instead of the one\n"
                                             "MSFT_screencoverage picks for the (first) camera, as UnityGLTF would"},
      {"normalize", 0, "T", "0.5 for overlap, 0 (off) for two-pass and blend-all",
       "where the quads' summed basis covers a pixel by c >= T, draw their weighted mean colour, opaque;\n"
       "below, that colour at coverage c / T (fills see-through gaps, no saturated overlaps; 0 = the plain sum)"},
  };
}

// Options the method does not read are refused, never silently ignored (-m engine --no-lighting
// drew lit): the engine method draws the glTF materials as an engine does, without the
// lock-by-depth methods' settings.
void refuse_unused_options(const ParsedArgs& a, Method method) {
  if (method != Method::kEngine) return;
  for (const char* name : {"no-lighting", "alpha-ref", "transparency", "depth-offset", "normalize"})
    if (a.has(name)) throw UsageError(std::string("--") + name + " applies to the lock-by-depth methods, not to the engine method");
}

DrawSettings read_draw_settings(const ParsedArgs& a) {
  DrawSettings s;
  s.method = method_from_name(a.get("method", "overlap"));
  if (a.has("background")) s.background = parse_color("background", a.get("background"));
  s.alpha_ref = static_cast<float>(a.get_double("alpha-ref", -1, 0, 1));
  s.transparency = static_cast<float>(a.get_double("transparency", 1, 0, 1));
  s.lighting = !a.flag("no-lighting");
  s.depth_offset = static_cast<float>(a.get_double("depth-offset", 0, 0, 1e30));
  if (a.has("normalize")) s.normalize = static_cast<float>(a.get_double("normalize", 0, 0, 1));
  if (a.has("alpha-mode")) s.alpha_mode = a.get_choice("alpha-mode", {"OPAQUE", "MASK", "BLEND"}, "");
  s.alpha_cutoff = static_cast<float>(a.get_double("alpha-cutoff", -1, 0, 1));
  s.mipmaps = !a.flag("no-mips");
  refuse_unused_options(a, s.method);
  return s;
}

// --- render -------------------------------------------------------------------------------------

CommandSpec render_spec() {
  const std::vector<OptionSpec> draw = draw_option_specs();
  CommandSpec s{"render", "FILE -o OUT.png [options]   (also: qf-render FILE -o OUT.png)", "render a baked level (.glb/.gltf), a point set (as splats) or a mesh to a PNG, headless",
      "The camera orbits the centre of FILE's bounding sphere (or --frame's): azimuth about +Y from +Z,\n"
      "elevation above the XZ plane; the default distance frames the sphere. --view i/N picks view i of\n"
      "N spread evenly over the sphere instead. --turntable N writes a contact sheet of N views around\n"
      "the object at the given elevation; --octahedral F writes the F x F frames of an octahedral impostor\n"
      "(runtime_gl/camera.h octahedral_direction; use a small --fov for near-orthographic frames). A mesh with materials (OBJ + MTL) is drawn with them by the\n"
      "engine method unless --method says otherwise. glTF files as glTF-Transform and gltfpack write them\n"
      "are decoded (EXT_meshopt_compression, KHR_mesh_quantization, KHR_draco_mesh_compression,\n"
      "KHR_texture_basisu, EXT_texture_webp); a file requiring any other extension is refused (exit 1).",
      {{"output", 'o', "OUT.png", "", "the PNG to write (required)"},
       {"azimuth", 0, "DEG", "30", "camera azimuth"},
       {"elevation", 0, "DEG", "20", "camera elevation"},
       {"distance", 0, "D", "framing the bounding sphere", "camera distance from the centre, world units"},
       {"view", 0, "I/N", "", "view I (0-based) of N spread over the sphere (replaces azimuth/elevation)"},
       {"turntable", 0, "N", "", "N views around the object in one contact sheet"},
       {"octahedral", 0, "F", "", "F x F views from the octahedral grid's directions in one contact sheet, F to a row"},
       {"frame", 0, "FILE", "", "frame the camera on this file's bounding sphere (e.g. the reference)"},
       {"mesh", 0, "MESH", "", "point impostors: the mesh they fade to nearer than s Z0 (pixel side x focal length in pixels)"}},
      1, 1, "qf-render"};
  s.options.insert(s.options.end(), draw.begin(), draw.end());
  return s;
}

// A combined LOD file shows one level: --lod's, else the one its screen coverages pick for
// `camera` (the object's bounding sphere's diameter on screen / the image height).
void choose_lod(AnyScene& scene, const ParsedArgs& a, const Camera& camera) {
  if (scene.lods.empty()) {
    if (a.has("lod") && a.get_int("lod", 0, 0, 1000) != 0) throw UsageError("--lod: the file has one level");
    return;
  }
  const Sphere s = bounding_sphere(scene.bounds());
  const double d = std::max(1e-30, static_cast<double>(length(camera.eye - s.center)));
  const double coverage = 2.0 * s.radius * camera.focal_pixels() / d / camera.height;
  scene.select_lod(a.has("lod") ? static_cast<int>(a.get_int("lod", 0, 0, 1000)) : scene.lod_for_coverage(coverage));
  std::cerr << "qf-render: LOD " << scene.lod << " of " << scene.lods.size() << " (" << scene.describe() << ", screen coverage "
            << coverage << ")\n";
}

Sphere framing_sphere(const ParsedArgs& a, const AnyScene& scene) {
  if (!a.has("frame")) return bounding_sphere(scene.bounds());
  return bounding_sphere(load_scene(a.get("frame")).bounds());
}

std::pair<int, int> parse_view(const std::string& text) {
  int i = -1, n = 0;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> i >> slash >> n) || slash != '/' || n < 1 || i < 0 || i >= n)
    throw UsageError("--view: expected I/N with 0 <= I < N, got '" + text + "'");
  return {i, n};
}

int run_render(const ParsedArgs& a) {
  if (!a.has("output")) throw UsageError("render: -o OUT.png is required");
  const auto [w, h] = parse_size(a.get("size", "512"));
  DrawSettings settings = read_draw_settings(a);
  const float fov = static_cast<float>(a.get_double("fov", 30, 1, 170));
  const float distance = static_cast<float>(a.get_double("distance", 0, 0, 1e30));
  AnyScene scene = load_scene(a.positional[0]);
  // A mesh's materials only the engine method draws (the others show it grey), so it is the
  // default there. glTF files keep the plain-quads default (other tools' LODs are drawn so).
  if (scene.kind == AnyScene::kMesh && scene.asset && !a.has("method")) settings.method = Method::kEngine;
  refuse_unused_options(a, settings.method);
  // Only the engine method reads the material's alpha mode and cutoff (eval's engine pass reads
  // them whatever --method says; a render draws one method).
  if (settings.method != Method::kEngine)
    for (const char* name : {"alpha-mode", "alpha-cutoff", "no-mips"})
      if (a.has(name)) throw UsageError(std::string("--") + name + " applies to the engine method (-m engine) only");
  if (a.has("mesh")) {
    if (scene.kind != AnyScene::kPoints) throw UsageError("--mesh goes with a point impostor (.glb with QF_point_impostor)");
    AnyScene m = load_scene(a.get("mesh"));
    if (m.kind != AnyScene::kMesh) throw UsageError("--mesh: " + a.get("mesh") + " is not a triangle mesh");
    scene.fade_mesh = std::move(m.mesh);
  }
  const Sphere sphere = framing_sphere(a, scene);

  HeadlessContext context;
  Renderer renderer(w, h);
  std::vector<Vec3f> directions;
  const int turntable = static_cast<int>(a.get_int("turntable", 0, 0, 1000));
  const float elevation = static_cast<float>(a.get_double("elevation", 20, -90, 90));
  const float azimuth = static_cast<float>(a.get_double("azimuth", 30, -1e6, 1e6));
  const int octahedral = static_cast<int>(a.get_int("octahedral", 0, 0, 64));
  if (octahedral == 1) throw UsageError("--octahedral: a grid of at least 2 x 2 frames");
  if (octahedral > 0 && (turntable > 0 || a.has("view"))) throw UsageError("--octahedral replaces --turntable and --view");
  if (octahedral > 0) {
    for (int row = 0; row < octahedral; ++row)
      for (int column = 0; column < octahedral; ++column) directions.push_back(octahedral_direction(column, row, octahedral));
  } else if (turntable > 0) {
    for (int i = 0; i < turntable; ++i) directions.push_back(orbit_direction(azimuth + 360.0f * i / turntable, elevation));
  } else if (a.has("view")) {
    const auto [i, n] = parse_view(a.get("view"));
    directions.push_back(sphere_direction(i, n));
  } else {
    directions.push_back(orbit_direction(azimuth, elevation));
  }
  choose_lod(scene, a, orbit_camera(sphere, directions[0], distance, w, h, fov));
  scene.attach(renderer);
  std::vector<Image> frames;
  DrawStats stats;
  for (const Vec3f& d : directions) {
    stats = renderer.draw(orbit_camera(sphere, d, distance, w, h, fov), settings);
    frames.push_back(renderer.read_pixels());
  }
  const int columns = octahedral > 0 ? octahedral : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(frames.size()))));
  const Image out = frames.size() == 1 ? frames[0] : contact_sheet(frames, columns, settings.background);
  save_png(a.get("output"), out);
  std::cerr << "qf-render: " << a.positional[0] << " (" << scene.describe() << ") -> " << a.get("output") << " (" << out.width << "x"
            << out.height << ", " << method_name(settings.method);
  if (settings.method == Method::kEngine) std::cerr << ", " << stats.color_draws << " primitives";
  else if (scene.kind == AnyScene::kImpostor) std::cerr << ", last view: " << stats.color_draws << " colour draws, " << stats.lock_draws << " locks";
  if (scene.kind == AnyScene::kPoints)
    std::cerr << ", last view: " << stats.points << " points drawn, point weight " << stats.points_weight;
  std::cerr << ")\n";
  return 0;
}

// --- eval ---------------------------------------------------------------------------------------

CommandSpec eval_spec() {
  std::vector<OptionSpec> draw = draw_option_specs();
  for (OptionSpec& o : draw) {
    if (o.name == "size") o.default_text = "256";
    if (o.name == "background") o.default_text = "128,128,128";
  }
  CommandSpec s{"eval", "REFERENCE BAKED [options]", "measure an impostor against its reference (points as splats, or a mesh) from many views",
      "Renders both with the same cameras from N viewpoints (the reference as the truth: drawn at --truth times the size\n"
      "and box-filtered down) spread evenly over the sphere, framing the\n"
      "reference's bounding sphere, once with --method and once with the engine method (both the file and\n"
      "the reference drawn as a standard PBR engine draws glTF: base colour and normal maps, lighting in\n"
      "linear light, double-sided where the material says; three.js r187's MeshStandardMaterial). Per view and on average: PSNR over the pixels covered\n"
      "by either image, silhouette IoU, soft IoU (of fractional coverage), mean absolute error, and the shares of reference pixels that are\n"
      "holes (impostor coverage < 0.5) or see-through (0.5 <= coverage < 0.9). Coverage is measured from\n"
      "renders over black and over white; colours are compared over --background. BAKED is a baked .glb\n"
      "(impostor level, cluster LOD, point impostor), or another point set or mesh: a second sampling of\n"
      "the reference's surface shows the metric's own floor (the splats' ragged edges differ).\n"
      "REFERENCE may also be a glTF asset (textured, as an artist made it) or a mesh with materials (OBJ +\n"
      "MTL, drawn with its textures): it is then drawn, and BAKED scored, by the engine method only.",
      {{"output", 'o', "REPORT.json", "", "write the report here (default: print it)"},
       {"views", 0, "N", "26", "number of viewpoints"},
       {"truth", 0, "F", "8",
        "score against the truth: the reference drawn at F x the size (at most 4096 px a side) and box-filtered\n"
        "down (what its pixels should show); the reference drawn at the size is scored against it too (as_drawn, engine method).\n"
        "1 = against the reference as drawn at the size"},
       {"outliers", 0, "F", "0",
        "a point-set REFERENCE without its outliers, the points farther than F x its median spacing from their 8\n"
        "nearest neighbours, as qf-bake --outliers drops them before baking and measuring (its default: 10); 0 keeps every point"},
       {"diff", 0, "PREFIX", "REPORT's path without .json", "write PREFIX.exr and PREFIX.png: per-view |difference| sheets (PNG x4)"},
       {"no-engine", 0, "", "", "skip the engine-path evaluation"},
       {"cameras", 0, "FILE", "", "write the views' cameras and the engine lights as JSON (for renders made elsewhere)"},
       {"external", 0, "DIR", "",
       "also score renders of BAKED made elsewhere from those cameras (e.g. three.js, scripts/three-render):\n"
       "DIR/view_I_black.png and view_I_white.png, against the reference drawn by the engine method,\n"
       "and against the engine method's own renders of BAKED (engine_vs_external)"}},
      2, 2, "qf-render"};
  s.options.insert(s.options.end(), draw.begin(), draw.end());
  return s;
}

// A figure without evidence (NaN: nothing covered to judge by) is null.
ordered_json figure(double v) { return std::isnan(v) ? ordered_json(nullptr) : ordered_json(canonical_double(static_cast<float>(v))); }

ordered_json metrics_json(const ViewMetrics& m) {
  return {{"psnr", figure(m.psnr)},
          {"iou", figure(m.iou)},
          {"soft_iou", figure(m.soft_iou)},
          {"coverage", figure(m.coverage)},
          {"mae", canonical_double(static_cast<float>(m.mae))},
          {"holes", canonical_double(static_cast<float>(m.holes))},
          {"see_through", canonical_double(static_cast<float>(m.see_through))},
          {"brightness", canonical_double(static_cast<float>(m.brightness))},
          {"reference_brightness", canonical_double(static_cast<float>(m.reference_brightness))}};
}

// The eval's cameras as JSON, for renderers outside qf-render (scripts/three-render): per view
// the eye, target, up, vertical field of view, near/far planes and both matrices (column-major),
// and the engine method's lights.
ordered_json cameras_json(const std::vector<Camera>& cams, const EngineLights& lights, Rgb8 background) {
  ordered_json views = ordered_json::array();
  for (const Camera& c : cams) {
    auto vec = [](Vec3f v) { return ordered_json{v.x, v.y, v.z}; };
    const Mat4 view = c.view(), proj = c.projection();
    views.push_back({{"eye", vec(c.eye)}, {"target", vec(c.target)}, {"up", vec(c.up)}, {"fovy_degrees", c.fovy_degrees},
                     {"near", c.near_plane}, {"far", c.far_plane}, {"width", c.width}, {"height", c.height},
                     {"view", std::vector<float>(view.begin(), view.end())}, {"projection", std::vector<float>(proj.begin(), proj.end())}});
  }
  return {{"lights", {{"directional", lights.directional}, {"ambient", lights.ambient}}},
          {"background", {background.r, background.g, background.b}},
          {"views", views}};
}

// Renders of BAKED made elsewhere (DIR/view_I_black.png and view_I_white.png, over black and
// white, from the cameras --cameras wrote).
RenderPair external_pair(const std::string& dir, int view, int w, int h) {
  RenderPair p;
  const std::string stem = dir + "/view_" + std::to_string(view);
  p.over_black = load_image(stem + "_black.png");
  p.over_white = load_image(stem + "_white.png");
  for (const Image* img : {&p.over_black, &p.over_white})
    if (img->width != w || img->height != h)
      throw InputError("render.image", stem, "", "external render is " + std::to_string(img->width) + "x" + std::to_string(img->height) +
                                                     ", expected " + std::to_string(w) + "x" + std::to_string(h));
  return p;
}

// What an eval measured: per view and method, the metrics, cameras and difference images.
struct EvalViews {
  std::vector<ViewMetrics> main, engine, external, agreement;  // agreement: engine method vs external renders
  std::vector<ViewMetrics> as_drawn;  // the reference drawn at the size (engine method) vs the truth
  std::vector<Camera> cams;
  std::vector<Image> diff_sheet;
  std::vector<float> exr_sheet;  // views stacked vertically
  ordered_json per_view = ordered_json::array();
};

// The reference as the pixels should show it: drawn `factor` times larger and box-filtered down
// (the truth), or drawn at the size where factor is 1.
struct ReferenceViews {
  Renderer& at_size;
  Renderer* supersampled;  // factor x the size; null when factor is 1
  int factor = 1;
  RenderPair draw(const Sphere& sphere, Vec3f d, int w, int h, const DrawSettings& s) const {
    if (factor <= 1) return render_pair(at_size, orbit_camera(sphere, d, 0, w, h), s);
    const RenderPair p = render_pair(*supersampled, orbit_camera(sphere, d, 0, w * factor, h * factor), s);
    return {box_downsample(p.over_black, factor), box_downsample(p.over_white, factor)};
  }
};

// Draws both from `views` directions spread over the reference's bounding sphere and compares them:
// with `settings`, with the engine method (unless off), and against external renders (if any);
// with a supersampled truth, the reference as drawn at the size is scored against it too.
EvalViews measure_views(const Sphere& sphere, int views, int w, int h, const ReferenceViews& ref, Renderer& imp_renderer,
                        const DrawSettings& settings, bool with_engine, const std::string& external, Rgb8 background) {
  DrawSettings engine = settings;
  engine.method = Method::kEngine;
  EvalViews e;
  for (int i = 0; i < views; ++i) {
    const Vec3f d = sphere_direction(i, views);
    const Camera cam = orbit_camera(sphere, d, 0, w, h);
    e.cams.push_back(cam);
    const RenderPair truth = ref.draw(sphere, d, w, h, settings);
    std::vector<float> diff;
    e.main.push_back(compare_renders(truth, render_pair(imp_renderer, cam, settings), background, &diff));
    ordered_json v{{"view", i}, {"direction", {canonical_double(d.x), canonical_double(d.y), canonical_double(d.z)}}};
    v[method_name(settings.method)] = metrics_json(e.main.back());
    const bool engine_views = with_engine || !external.empty() || ref.factor > 1;
    const RenderPair engine_ref = !engine_views ? RenderPair{} : settings.method == Method::kEngine ? truth : ref.draw(sphere, d, w, h, engine);
    const RenderPair engine_baked = with_engine || !external.empty() ? render_pair(imp_renderer, cam, engine) : RenderPair{};
    if (with_engine) {
      e.engine.push_back(compare_renders(engine_ref, engine_baked, background));
      v["engine"] = metrics_json(e.engine.back());
    }
    if (ref.factor > 1) {
      e.as_drawn.push_back(compare_renders(engine_ref, render_pair(ref.at_size, cam, engine), background));
      v["as_drawn"] = metrics_json(e.as_drawn.back());
    }
    if (!external.empty()) {
      const RenderPair ext = external_pair(external, i, w, h);
      e.external.push_back(compare_renders(engine_ref, ext, background));
      e.agreement.push_back(compare_renders(engine_baked, ext, background));
      v["external"] = metrics_json(e.external.back());
      v["engine_vs_external"] = metrics_json(e.agreement.back());
    }
    e.per_view.push_back(v);
    e.diff_sheet.push_back(to_8bit(diff, w, h, 4));
    e.exr_sheet.insert(e.exr_sheet.end(), diff.begin(), diff.end());
  }
  return e;
}

// The eval report (docs/cli.md: qf-render eval): inputs, settings, the means and every view.
ordered_json eval_report(const ParsedArgs& a, const AnyScene& baked, const EvalViews& e, int views, int w, int h, int truth,
                         const DrawSettings& settings, Rgb8 background) {
  const ImpostorScene& s = baked.impostor;
  ordered_json report{{"reference", a.positional[0]}, {"baked", a.positional[1]}, {"baked_contents", baked.describe()}};
  if (baked.kind == AnyScene::kImpostor) report["level"] = s.level, report["quads"] = s.items.size();
  report.update(ordered_json{{"views", views},
                      {"size", {w, h}},
                      {"background", {background.r, background.g, background.b}},
                      {"method", method_name(settings.method)},
                      {"truth_supersampling", truth}});
  if (baked.kind == AnyScene::kImpostor) report["engine_alpha_mode"] = settings.alpha_mode ? *settings.alpha_mode : s.alpha_mode;
  report["mean"][method_name(settings.method)] = metrics_json(mean_of(e.main));
  if (!e.engine.empty()) report["mean"]["engine"] = metrics_json(mean_of(e.engine));
  if (!e.as_drawn.empty()) report["mean"]["as_drawn"] = metrics_json(mean_of(e.as_drawn));
  if (!e.external.empty()) {
    report["mean"]["external"] = metrics_json(mean_of(e.external));
    report["mean"]["engine_vs_external"] = metrics_json(mean_of(e.agreement));
  }
  report["per_view"] = e.per_view;
  return report;
}

// The report (to -o, else stdout) and the difference images (--diff PREFIX, else beside -o).
void write_eval_outputs(const ParsedArgs& a, const ordered_json& report, const EvalViews& e, int views, int w, int h) {
  const std::string text = report.dump(2) + "\n";
  std::string diff_prefix = a.get("diff");
  if (a.has("output")) {
    write_file_atomically(a.get("output"), [&](std::ostream& out) { out << text; });
    if (diff_prefix.empty()) {
      diff_prefix = a.get("output");
      if (file_extension(diff_prefix) == "json") diff_prefix.resize(diff_prefix.size() - 5);
      diff_prefix += "_diff";
    }
  } else {
    std::cout << text;
  }
  if (!diff_prefix.empty()) {
    save_exr(diff_prefix + ".exr", e.exr_sheet, w, h * views);
    save_png(diff_prefix + ".png", contact_sheet(e.diff_sheet, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(views)))), {0, 0, 0}));
  }
}

void print_eval_summary(const EvalViews& e, int views, Method method) {
  auto say = [&](const std::string& what, const std::vector<ViewMetrics>& v) {
    const ViewMetrics m = mean_of(v);
    std::cerr << "qf-render eval: " << what << ": PSNR " << m.psnr << " dB, IoU " << m.iou << ", soft IoU " << m.soft_iou << ", coverage " << m.coverage << ", holes " << 100 * m.holes
              << "%, see-through " << 100 * m.see_through << "%\n";
  };
  say(std::to_string(views) + " views, " + method_name(method), e.main);
  if (!e.engine.empty()) say("engine method", e.engine);
  if (!e.as_drawn.empty()) say("the reference as drawn (engine method)", e.as_drawn);
  if (!e.external.empty()) say("external renders", e.external), say("engine method vs external renders", e.agreement);
}

int run_eval(const ParsedArgs& a) {
  // 1. Options and the two scenes, framed by the reference.
  const auto [w, h] = parse_size(a.get("size", "256"));
  DrawSettings settings = read_draw_settings(a);
  const Rgb8 background = a.has("background") ? settings.background : Rgb8{128, 128, 128};
  const int views = static_cast<int>(a.get_int("views", 26, 1, 10000));
  ReadOptions read;
  read.outlier_factor = static_cast<float>(a.get_double("outliers", 0, 0, 1e6));
  const AnyScene reference = load_scene(a.positional[0], read);
  AnyScene baked = load_scene(a.positional[1]);
  // A glTF reference (a textured game asset) has one look: its materials as an engine draws them,
  // so both sides are drawn and scored by the engine method alone.
  if (reference.kind == AnyScene::kImpostor && !reference.asset)
    throw UsageError("eval: REFERENCE must be a point set, a mesh or a glTF asset, not a baked level");
  if (reference.asset) settings.method = Method::kEngine;
  const Sphere sphere = bounding_sphere(reference.bounds());
  choose_lod(baked, a, orbit_camera(sphere, sphere_direction(0, views), 0, w, h));
  // The truth's side is capped (kMaxTruthSide), as the bake's measuring caps it.
  const int truth = truth_factor(std::max(w, h), static_cast<int>(a.get_int("truth", 8, 1, 256)));
  HeadlessContext context;
  Renderer ref_renderer(w, h), imp_renderer(w, h);
  std::unique_ptr<Renderer> truth_renderer = truth > 1 ? std::make_unique<Renderer>(w * truth, h * truth) : nullptr;
  reference.attach(ref_renderer);
  if (truth_renderer) reference.attach(*truth_renderer);
  baked.attach(imp_renderer);
  // 2. Every view. The engine path: both drawn as an engine draws glTF (the reference as if exported).
  const bool with_engine = !a.flag("no-engine") && settings.method != Method::kEngine;
  const ReferenceViews ref{ref_renderer, truth_renderer.get(), truth};
  const EvalViews e = measure_views(sphere, views, w, h, ref, imp_renderer, settings, with_engine, a.get("external"), background);
  // 3. The outputs.
  if (a.has("cameras")) {
    const std::string text = cameras_json(e.cams, settings.lights, background).dump(1) + "\n";
    write_file_atomically(a.get("cameras"), [&](std::ostream& out) { out << text; });
  }
  write_eval_outputs(a, eval_report(a, baked, e, views, w, h, truth, settings, background), e, views, w, h);
  print_eval_summary(e, views, settings.method);
  return 0;
}

// --- view (window) ------------------------------------------------------------------------------

CommandSpec view_spec() {
  const std::vector<OptionSpec> draw = draw_option_specs();
  CommandSpec s{"view", "FILE [options]", "open a window (needs DISPLAY) and orbit FILE with the mouse",
      "Drag with the left button to orbit, wheel to zoom, q or Esc to quit.",
      {{"frames", 0, "N", "0 (until closed)", "quit after N frames (scripts and tests)"},
       {"output", 'o', "OUT.png", "", "save the last frame"},
       {"azimuth", 0, "DEG", "30", "initial azimuth"},
       {"elevation", 0, "DEG", "20", "initial elevation"}},
      1, 1, "qf-render"};
  s.options.insert(s.options.end(), draw.begin(), draw.end());
  return s;
}

int run_view(const ParsedArgs& a) {
  auto [w, h] = parse_size(a.get("size", "512"));
  const DrawSettings settings = read_draw_settings(a);
  const long long frames = a.get_int("frames", 0, 0, 1LL << 40);
  AnyScene scene = load_scene(a.positional[0]);
  const Sphere sphere = bounding_sphere(scene.bounds());
  choose_lod(scene, a, orbit_camera(sphere, orbit_direction(30, 20), 0, w, h));
  WindowContext window(w, h, "qf-render: " + a.positional[0]);
  Renderer renderer(w, h, /*offscreen=*/false);
  scene.attach(renderer);
  float az = static_cast<float>(a.get_double("azimuth", 30, -1e6, 1e6)), el = static_cast<float>(a.get_double("elevation", 20, -90, 90));
  float zoom = 1;
  Image last;
  for (long long f = 0; frames == 0 || f < frames; ++f) {
    const WindowEvents e = window.poll();
    if (e.close) break;
    if (e.width != w || e.height != h) w = e.width, h = e.height, renderer.resize(w, h);
    az -= 0.5f * static_cast<float>(e.drag_dx);
    el = std::clamp(el + 0.5f * static_cast<float>(e.drag_dy), -89.0f, 89.0f);
    zoom *= std::pow(0.9f, static_cast<float>(e.wheel));
    const Camera base = orbit_camera(sphere, orbit_direction(az, el), 0, w, h);
    const Camera cam = orbit_camera(sphere, orbit_direction(az, el), length(base.eye - base.target) * zoom, w, h);
    renderer.draw(cam, settings);
    if (a.has("output") && frames > 0 && f + 1 == frames) last = renderer.read_pixels();
    window.swap();
    if (frames == 0) std::this_thread::sleep_for(std::chrono::milliseconds(8));
  }
  if (a.has("output") && !last.rgba.empty()) save_png(a.get("output"), last);
  return 0;
}

}  // namespace
}  // namespace qf::render

constexpr const char* kUsage =
    "usage: qf-render FILE -o OUT.png [options]   render (see qf-render render --help)\n"
    "       qf-render COMMAND [arguments] [options]\n"
    "       qf-render COMMAND --help\n";

// qf-render FILE -o OUT.png: any first argument that names no command is the file to render.
bool always(const std::string&) { return true; }

int main(int argc, char** argv) {
  using namespace qf::render;
  const qf::cli::Program program{"qf-render", "the GL 1.1 renderer of quasiflat's baked levels (headless through EGL)", kUsage,
                                 "exit codes: 0 ok, 1 bad input, 2 bad usage, 3 internal error (including no GL context),\n"
                                 "4 an output that cannot be written (disk full, read-only, no permission).\n",
                                 {{render_spec(), run_render}, {eval_spec(), run_eval}, {view_spec(), run_view}},
                                 10, "render", always};
  return qf::cli::run_program(program, argc, argv);
}
