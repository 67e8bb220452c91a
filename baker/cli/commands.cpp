// The command table, and the convert and generate commands.
#include "cli/commands.h"

#include <omp.h>

#include <cstdlib>
#include <iostream>
#include <limits>

#include "analysis/neighborhoods.h"
#include "core/error.h"
#include "core/file_io.h"
#include "gltf/glb.h"
#include "io/model_io.h"
#include "primitives/billboard.h"
#include "shapes/foliage.h"
#include "shapes/lattice.h"
#include "shapes/machine.h"
#include "shapes/plate.h"
#include "shapes/pylon.h"
#include "shapes/shapes.h"
#include "shapes/tree.h"

namespace qf::cli {

OptionSpec drop_nonfinite_option() {
  return {"drop-nonfinite", 0, "", "",
          "drop points (or mesh vertices and their triangles) with NaN/Inf coordinates and report how many, "
          "instead of rejecting the file"};
}

std::vector<OptionSpec> analysis_option_specs() {
  return {{"k", 'k', "N", "50", "neighbours per point (paper 2.1: 50..100)"},
          {"epsilon", 0, "E", "off", "feature size in model units: neighbourhoods widen to the ball B_E, and E is the eps of eq. 3"},
          {"max-neighbors", 0, "N", "200", "cap on a widened neighbourhood"},
          {"classifier", 0, "paper|variation", "paper", "C = G(|M0-x| l2/(eps l0)) (paper eq. 3), or G(3 sigma) from the surface variation"},
          {"threads", 'j', "N", "all cores", "threads to use (the outputs do not depend on it)"}};
}

AnalysisOptions read_analysis_options(const OptionValues& args) {
  AnalysisOptions o;
  o.neighborhoods.k = static_cast<int>(args.get_int("k", o.neighborhoods.k, 3, 1000));
  o.neighborhoods.max_neighbors = static_cast<int>(args.get_int("max-neighbors", o.neighborhoods.max_neighbors, 3, 100000));
  if (args.has("epsilon")) {
    o.neighborhoods.epsilon = static_cast<float>(args.get_double("epsilon", 0, 0, 1e30));
    o.classifier.epsilon = o.neighborhoods.epsilon;
  }
  if (args.get_choice("classifier", {"paper", "variation"}, "paper") == "variation") o.classifier.kind = ClassifierKind::kVariation;
  if (args.has("threads")) omp_set_num_threads(static_cast<int>(args.get_int("threads", 0, 1, 1024)));
  return o;
}

std::vector<OptionSpec> sample_option_specs() {
  const SampleOptions d;
  return {{"ldi", 0, "N", std::to_string(d.ldi_size),
           "mesh inputs: sampling density, the layered depth image's largest side in pixels\n"
           "(pixel side = the longest bounding-box extent / N; ~1.7 N^2 points on a sphere)"},
          {"sampler", 0, "gl|cpu", d.backend,
           "mesh inputs: depth peeling on the CPU (faster on llvmpipe, independent of the GL driver) or with\n"
           "OpenGL through EGL (the paper's method; falls back to cpu without a context); same points but ~0.01%"},
          {"all-triangles", 0, "", "",
           "mesh inputs: draw every triangle on every axis (the paper's basic method; same points, more layers)\n"
           "instead of each triangle only on the axis its normal is most parallel to"},
          {"visibility-views", 0, "N", std::to_string(d.visibility.views),
           "mesh inputs: keep only the sampled points one of N orthographic views from outside sees (inner parts,\n"
           "the inside of a closed housing: gone); 0 keeps every depth layer"}};
}

SampleOptions read_sample_options(const OptionValues& args) {
  SampleOptions o;
  o.ldi_size = static_cast<int>(args.get_int("ldi", o.ldi_size, 2, 16000));
  o.backend = args.get_choice("sampler", {"gl", "cpu"}, o.backend);
  o.per_axis_triangles = !args.flag("all-triangles");
  o.visibility.views = static_cast<int>(args.get_int("visibility-views", o.visibility.views, 0, 1024));
  return o;
}

PointSet load_points(const std::string& path, const ParsedArgs& args, const std::string& command, ReadReport& report,
                     SampleStats* sampled, TriangleMesh* mesh) {
  ReadOptions ro;
  ro.drop_nonfinite = args.flag("drop-nonfinite");
  const SampleOptions so = read_sample_options(args);  // usage errors before reading
  SampleStats stats;
  PointSet points = load_point_set(path, ro, so, command, report, &stats, mesh);
  if (!stats.fallback.empty()) std::cerr << "qf-bake " << command << ": warning: " << stats.fallback << "\n";
  for (const std::string& w : report.warnings) std::cerr << "qf-bake " << command << ": warning: " << path << ": " << w << "\n";
  if (sampled) *sampled = stats;
  return points;
}

std::vector<OptionSpec> cache_option_specs() {
  return {{"cache", 0, "DIR", "$QF_CACHE or ~/.cache/quasiflat/amg",
           "hierarchy cache: reused when the points and settings are unchanged"},
          {"no-cache", 0, "", "", "neither read nor write the hierarchy cache"}};
}

std::string read_cache_dir(const OptionValues& args) {
  if (args.flag("no-cache")) return "";
  const char* env = std::getenv("QF_CACHE");
  const char* home = std::getenv("HOME");
  return args.get("cache", env && *env ? env : std::string(home ? home : ".") + "/.cache/quasiflat/amg");
}

void append_point_input_options(std::vector<OptionSpec>& options) {
  for (const auto& group : {merge_option_specs(), cache_option_specs(), analysis_option_specs(), sample_option_specs()})
    options.insert(options.end(), group.begin(), group.end());
}

std::vector<OptionSpec> merge_option_specs() {
  return {{"merge", 0, "", "", "merge overlapping flat domains that face the same way (thesis 3.4), biggest overlap first"},
          {"merge-variation", 0, "V", "0.01", "--merge: a domain is flat when its surface variation is at most V"},
          {"merge-angle", 0, "DEG", "10", "--merge: the two domains' planes differ by at most DEG degrees"}};
}

MergeOptions read_merge_options(const OptionValues& args, const DomainOptions& domains) {
  MergeOptions m;
  m.max_variation = args.get_double("merge-variation", m.max_variation, 0.0, 1.0 / 3.0);
  m.max_angle_degrees = args.get_double("merge-angle", m.max_angle_degrees, 0.0, 90.0);
  m.domains = domains;
  return m;
}

static std::vector<OptionSpec> with_sampling(std::vector<OptionSpec> options) {
  for (const OptionSpec& o : sample_option_specs()) options.push_back(o);
  return options;
}

static std::string shape_list() {
  std::string s;
  for (const ShapeInfo& i : shape_catalog()) {
    std::string n = "  " + std::string(i.name);
    n.resize(14, ' ');
    s += n + i.description + "\n";
  }
  return s;
}

const std::vector<Command>& commands() {
  static const std::vector<Command> table{
      {{"info", "FILE [options]", "describe a point set or mesh: format, counts, attributes, bounds, memory",
        "FILE is any supported input: .ply (points or mesh), .qs, .xyz, .pwn, .las, .laz, .off, .obj, .gltf, .glb\n"
        "(glTF compressed by glTF-Transform or gltfpack too: EXT_meshopt_compression, KHR_mesh_quantization,\n"
        "KHR_draco_mesh_compression, KHR_texture_basisu and EXT_texture_webp images).",
        {{"json", 0, "", "", "print a JSON object instead of text (schema: schemas/info.schema.json)"},
         drop_nonfinite_option()},
        1, 1},
       run_info},
      {{"convert", "IN OUT [options]", "convert a point set between .ply, .qs, .xyz and .pwn (by extension), or sample a mesh",
        "Missing splat radii are estimated from local spacing when OUT stores radii (.ply, .qs):\n"
        "the distance to the --radius-k-th nearest neighbour. .qs and .pwn need normals.\n"
        "A mesh IN (.off, .obj, .ply with faces) is sampled by depth peeling along X, Y and Z\n"
        "(normals, colours when the mesh has them, radii from the pixel size).\n"
        "OUT is written to a temporary name and renamed, so it is never left half-written.",
        with_sampling({{"radius-k", 0, "K", "6", "missing radii reach the K-th nearest neighbour"},
                       {"vertices", 0, "", "", "mesh inputs: the mesh's vertices (with their normals and colours when it has them) are the points, instead of sampling its surface"},
                       drop_nonfinite_option(),
                       quiet_option()}),
        2, 2},
       run_convert},
      {{"generate", "SHAPE -o OUT [options]", "write an analytic sample shape as a point set, or a sample game asset as a .glb",
        "SHAPE is one of:\n" + shape_list() +
            "  tree         a trunk, branches and --leaves alpha-masked leaf quads with generated bark and\n"
            "               leaf textures: a textured game asset (OUT must be .glb), where mesh\n"
            "               simplification has nothing to collapse\n"
            "  bush         stems and --leaves (default 1800) small alpha-masked leaves: foliage (.glb)\n"
            "  oak          a broadleaf tree as game assets make one: limbs and --leaves (default 220)\n"
            "               alpha-masked cards of 40 leaves each, cut-away texels black (.glb)\n"
            "  bare-tree    a trunk and limbs branching down to twigs far thinner than a pixel, no leaves\n"
            "               (.glb); --seed sets the branching\n"
            "  lattice      a tower of thin square beams, flat-shaded, one material (.glb); --seed sets\n"
            "               its storeys, taper, bracing and beam width\n"            "  conifer      a trunk and --leaves (default 140) drooping branch cards in tiers round it, a\n"
            "               cone 5-6 tall; each card a twig with dark needles, cut-away texels black (.glb)\n"
            "  grass        a clump of --leaves (default 300) bent alpha-masked blades 0.3-0.8 tall, green\n"
            "               to straw yellow, from one blade atlas (.glb)\n"
            "  pylon        a power pylon 36-44 tall of square beams 1/200 of its height and thinner:\n"
            "               tapering legs, X bracing, two or three tiers of cross arms, insulators (.glb)\n"
            "  machine      a gearbox as a CAD export gives it: one node per part (housing, motor, shafts,\n"
            "               gears, bearings, bolts, pipe, ...), each its own colour, the inner parts seen\n"
            "               only through a window and a shaft port (.glb)\n"
            "  (--seed sets each game asset's random draws: same seed, same bytes)\n"
            "  plate        a 2 x 1 plate whose halves differ in roughness and metallic (a metallic-\n"
            "               roughness texture) and whose right half emits (.glb): material channels\n"
            "Points are spread uniformly by area with a seeded generator (identical output for\n"
            "identical settings), with outward normals, colours, and radii from local spacing.",
        {{"output", 'o', "OUT", "", "output file (.ply, .qs, .xyz or .pwn); required"},
         {"points", 'n', "N", "16000", "number of points"},
         {"seed", 0, "S", "1", "random seed"},
         {"mesh", 0, "", "", "write a closed triangle mesh instead (octahedron, cube, sphere; OUT must be .ply)"},
         {"subdivisions", 0, "N", "16", "--mesh: each face split into N x N triangles"},
         {"leaves", 0, "N", "3000", "tree, bush, oak, conifer, grass: number of leaf quads, cards or blades (bush default: 1800, oak: 220, conifer: 140, grass: 300)"},
         quiet_option()},
        1, 1},
       run_generate},
      {{"billboard", "MESH -o OUT.glb [options]", "write the crossed billboard engines ship for far foliage (a peer)",
        "Three vertical cards through the asset's centre, 60 degrees apart, and one horizontal card, each\n"
        "an orthographic view of the whole asset (its materials, 4 x 4 samples a texel, coverage as alpha),\n"
        "alpha-tested at 0.5 and double-sided: the classic far-foliage LOD that the fidelity league\n"
        "measures the impostor levels against at equal bytes.",
        {{"output", 'o', "OUT.glb", "", "output file; required"},
         {"side", 0, "N", "128", "texels along each card's longer side"},
         {"bytes", 0, "B", "", "instead of --side: the largest side whose file has at most B bytes"},
         drop_nonfinite_option(),
         quiet_option()},
        1, 1},
       run_billboard},
      {analyze_spec(), run_analyze},
      {decompose_spec(), run_decompose},
      {bake_spec(), run_bake},
      {cluster_spec(), run_cluster},
      {simplify_spec(), run_simplify},
      {batch_spec(), run_batch},
      {merge_reports_spec(), run_merge_reports},
      {tile_spec(), run_tile},
      {join_spec(), run_join},
  };
  return table;
}

int run_convert(const ParsedArgs& args) {
  const std::string& in = args.positional[0];
  const std::string& out = args.positional[1];
  const std::string out_ext = file_extension(out);
  bool known = false;
  for (const std::string& e : point_set_extensions()) known = known || e == out_ext;
  if (!known) throw UsageError("cannot write point sets as '." + out_ext + "' (" + out + "); supported: .ply .qs .xyz .pwn");
  RadiusEstimateOptions radius;
  radius.k = static_cast<int>(args.get_int("radius-k", radius.k, 1, 1000));
  ReadReport report;
  SampleStats sampled;
  PointSet points;
  if (args.flag("vertices")) {
    ReadOptions ro;
    ro.drop_nonfinite = args.flag("drop-nonfinite");
    Model model = read_model(in, ro, &report);
    if (model.is_mesh) {
      points.positions = std::move(model.mesh.positions);
      points.normals = std::move(model.mesh.normals);
      points.colors = std::move(model.mesh.colors);
      points.comments = std::move(model.mesh.comments);
    } else {
      points = std::move(model.points);
    }
    if (points.size() == 0) throw InputError("convert.empty", in, "", "holds no points");
  } else {
    points = load_points(in, args, "convert", report, &sampled);
  }
  std::size_t estimated = 0;
  if (out_ext == "ply" || out_ext == "qs") estimated = estimate_radii(points, radius);
  write_point_set(out, points);
  if (!args.flag("quiet")) {
    std::cerr << "qf-bake convert: " << in << " (" << report.format << ") -> " << out << ": " << points.size()
              << " points";
    if (!sampled.backend.empty())
      std::cerr << " sampled (" << sampled.backend << ", pixel " << sampled.pixel << ", layers " << sampled.layers[0] << "/"
                << sampled.layers[1] << "/" << sampled.layers[2] << ", " << sampled.seconds << " s)";
    if (estimated) std::cerr << ", radii estimated for " << estimated << " (distance to neighbour " << radius.k << ")";
    if (report.dropped_nonfinite) std::cerr << ", " << report.dropped_nonfinite << " non-finite points dropped";
    std::cerr << "\n";
  }
  return 0;
}

int run_billboard(const ParsedArgs& args) {
  const std::string out = args.require("output");
  if (file_extension(out) != "glb") throw UsageError("billboard writes a .glb, not '" + out + "'");
  ReadOptions ro;
  ro.drop_nonfinite = args.flag("drop-nonfinite");
  const Model model = read_model(args.positional[0], ro, nullptr);
  if (!model.is_mesh || model.mesh.triangles.empty())
    throw InputError("billboard.needs_mesh", args.positional[0], "", "is not a mesh with triangles; a billboard draws triangles");
  const auto encode = [&](int side) {
    BillboardOptions o;
    o.side = side;
    return encode_textured_mesh_glb(crossed_billboard(model.mesh, o));
  };
  std::vector<std::uint8_t> bytes;
  int side = static_cast<int>(args.get_int("side", 128, 1, 4096));
  if (args.has("bytes")) {
    // The file grows with the side: bisect for the largest side within the budget (at least 1).
    const long long budget = args.get_int("bytes", 0, 1, std::numeric_limits<long long>::max());
    int lo = 1, hi = 2048;
    while (lo < hi) {
      const int mid = (lo + hi + 1) / 2;
      if (static_cast<long long>(encode(mid).size()) <= budget)
        lo = mid;
      else
        hi = mid - 1;
    }
    side = lo;
  }
  bytes = encode(side);
  write_bytes_atomically(out, bytes);
  if (!args.flag("quiet"))
    std::cerr << "qf-bake billboard: " << args.positional[0] << " -> " << out << ": 4 cards of " << side << " texels, " << bytes.size()
              << " bytes\n";
  return 0;
}

namespace {

// The game assets `generate` writes as .glb (the rest are point sets or --mesh .ply meshes).
bool is_game_asset(const std::string& shape) {
  for (const char* name : {"tree", "bush", "oak", "bare-tree", "lattice", "plate", "conifer", "grass", "pylon", "machine"})
    if (shape == name) return true;
  return false;
}

// Generates game asset `shape` (is_game_asset) from the command's --seed and --leaves and returns
// its .glb; `triangles` gets its triangle count.
std::vector<std::uint8_t> game_asset_glb(const std::string& shape, const ParsedArgs& args, std::uint64_t seed, std::size_t& triangles) {
  const auto leaves = [&](std::size_t fallback, long long most) {
    return static_cast<std::size_t>(args.get_int("leaves", static_cast<long long>(fallback), 1, most));
  };
  if (shape == "machine") {
    MachineOptions m;
    m.seed = seed;
    const Machine machine = generate_machine(m);
    triangles = 0;
    for (const MachinePart& p : machine.parts) triangles += p.mesh.triangles.size();
    return encode_machine_glb(machine);
  }
  TriangleMesh asset;
  if (shape == "tree") {
    TreeOptions t;
    t.seed = seed, t.leaves = leaves(t.leaves, 1000000);
    asset = generate_tree(t);
  } else if (shape == "bush") {
    BushOptions b;
    b.seed = seed, b.leaves = leaves(b.leaves, 1000000);
    asset = generate_bush(b);
  } else if (shape == "oak") {
    CardTreeOptions c;
    c.seed = seed, c.cards = leaves(c.cards, 100000);
    asset = generate_card_tree(c);
  } else if (shape == "conifer") {
    ConiferOptions c;
    c.seed = seed, c.cards = leaves(c.cards, 100000);
    asset = generate_conifer(c);
  } else if (shape == "grass") {
    GrassOptions g;
    g.seed = seed, g.blades = leaves(g.blades, 100000);
    asset = generate_grass(g);
  } else if (shape == "bare-tree") {
    asset = generate_bare_tree(seed);
  } else if (shape == "plate") {
    asset = generate_material_plate();
  } else if (shape == "pylon") {
    PylonOptions p;
    p.seed = seed;
    asset = generate_pylon(p);
  } else {
    LatticeOptions l;
    l.seed = seed;
    asset = generate_lattice(l);
  }
  triangles = asset.triangles.size();
  return encode_textured_mesh_glb(asset);
}

}  // namespace

int run_generate(const ParsedArgs& args) {
  args.require("output");
  ShapeOptions o;
  o.points = static_cast<std::size_t>(args.get_int("points", static_cast<long long>(o.points), 1, 100000000));
  o.seed = static_cast<std::uint64_t>(args.get_int("seed", static_cast<long long>(o.seed), 0, (1ll << 62)));
  const std::string out = args.get("output");
  const std::string& shape = args.positional[0];
  if (is_game_asset(shape)) {
    if (file_extension(out) != "glb") throw UsageError("generate " + shape + " writes a .glb, not '" + out + "'");
    std::size_t triangles = 0;
    const std::vector<std::uint8_t> bytes = game_asset_glb(shape, args, o.seed, triangles);
    write_bytes_atomically(out, bytes);
    if (!args.flag("quiet"))
      std::cerr << "qf-bake generate: " << shape << " -> " << out << ": " << triangles << " triangles, " << bytes.size() << " bytes\n";
    return 0;
  }
  if (args.flag("mesh")) {
    if (file_extension(out) != "ply") throw UsageError("generate --mesh writes .ply meshes, not '" + out + "'");
    const TriangleMesh mesh = generate_mesh(args.positional[0], static_cast<int>(args.get_int("subdivisions", 16, 1, 2000)));
    write_ply(out, mesh);
    if (!args.flag("quiet"))
      std::cerr << "qf-bake generate: " << args.positional[0] << " mesh -> " << out << ": " << mesh.triangles.size() << " triangles\n";
    return 0;
  }
  const PointSet points = generate_shape(args.positional[0], o);
  write_point_set(out, points);
  if (!args.flag("quiet"))
    std::cerr << "qf-bake generate: " << args.positional[0] << " -> " << out << ": " << points.size() << " points\n";
  return 0;
}

}  // namespace qf::cli
