// Loading scenes for runtime_gl: .glb/.gltf through tinygltf (with engine_loader.cpp, which reads
// the engine's view of a file, the runtime files that include it; shared accessors in
// gltf_read.h). References made from input files are baker/measure/reference_scene.
#include "runtime_gl/loader.h"
#include "runtime_gl/gltf_read.h"

#include "core/weight_alpha.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <type_traits>

#include "core/color.h"
#include "core/error.h"
#include "core/gltf_keys.h"
#include "core/input_limits.h"
#include "gltf/compressed_gltf.h"
#include "io/asset_files.h"

namespace qf::render {
namespace {

using namespace gltf;

// A 1x1 white texture for materials without a base colour texture.
Image white_image() { return Image{1, 1, {255, 255, 255, 255}}; }


// tinygltf 2.7.0 hands an image's bufferView to stb_image without checking that it lies within its
// buffer (a crafted byteLength read past the end, found by the glb fuzz target): this image loader
// checks the view first (tinygltf has checked that the view and its buffer exist), then decodes with
// tinygltf's own stb_image loader and its default options (user data null: RGBA, as before).
bool load_image_checked(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int width,
                        int height, const unsigned char* bytes, int size, void* user) {
  if (image->bufferView >= 0) {
    const tinygltf::Model& m = *static_cast<const tinygltf::Model*>(user);
    const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(image->bufferView));
    const std::size_t buffer = m.buffers.at(static_cast<std::size_t>(v.buffer)).data.size();
    if (v.byteOffset > buffer || v.byteLength > buffer - v.byteOffset || size < 0 ||
        static_cast<std::size_t>(size) != v.byteLength) {
      if (err) *err += "image[" + std::to_string(index) + "] bufferView reaches past the end of its buffer";
      return false;
    }
  }
  // Every image's size from its header first, against the memory available: a 1 MB PNG can decode
  // to 16384 x 16384 texels (1 GB), and a 6 KB KTX2 or WebP header can claim as much (it cost
  // 1.18 GB before it was refused when decoded).
  if (const std::optional<ImageHeader> h = image_header(bytes, static_cast<std::size_t>(std::max(size, 0)))) {
    try {
      check_memory_need(decoded_image_bytes(*h), 0, "", "render.gltf.memory", "",
                        "image[" + std::to_string(index) + "] of " + std::to_string(h->width) + " x " + std::to_string(h->height) + " texels");
    } catch (const InputError& e) {
      if (err) *err += e.detail();
      return false;
    }
  }
  // KTX2 (KHR_texture_basisu): kept as bytes, transcoded with its mip levels by to_image.
  if (bytes && size > 0 && is_ktx2(bytes, static_cast<std::size_t>(size))) {
    image->image.assign(bytes, bytes + size);
    image->mimeType = gltf::kKtx2Mime;
    image->width = image->height = -1;
    return true;
  }
  // WebP (EXT_texture_webp): kept as bytes too, decoded by to_image (stb_image does not read WebP),
  // so that a malformed image is refused naming the file.
  if (bytes && size > 0 && is_webp(bytes, static_cast<std::size_t>(size))) {
    image->image.assign(bytes, bytes + size);
    image->mimeType = gltf::kWebpMime;
    image->width = image->height = -1;
    return true;
  }
  // PNG and JPEG: decoded here by stb_image.
  return tinygltf::LoadImageData(image, index, err, warn, width, height, bytes, size, nullptr);
}

// tinygltf opens a .gltf and its external buffers and images through these instead of its
// defaults: no "~" or "$VAR" expansion (the default runs wordexp on the file's text); only paths
// that stay inside the file's folder, every ".." and symlink followed (io/asset_files.h, the rule
// the baker applies: an outside file must not become a texture or a buffer); and only regular
// files, opened without blocking (a FIFO named as a buffer hung the reader), within the memory
// limit. `user` is the FsContext.
constexpr const char* kOutside = "leads outside the file's folder: refused (a glTF file reads only the files in its folder)";

struct FsContext {
  std::filesystem::path root;  // canonical; empty: nothing outside the bytes given may be read
  std::string main;            // the file itself, as named on the command line (a symlink may lead anywhere)
};

std::optional<std::filesystem::path> inside_root(const std::string& abs, void* user) {
  const FsContext& c = *static_cast<const FsContext*>(user);
  if (!c.main.empty() && abs == c.main) return std::filesystem::path(abs);
  if (c.root.empty()) return std::nullopt;
  return io::resolve_inside(c.root, "/", abs);
}

// Every path tinygltf asks about is absolute (the file's folder joined to a URI) but for its
// fallback to the working folder, which is never searched. An outside path and a folder or FIFO
// inside "exist", so that read_regular_file says why they are refused (for an outside path the
// same words whether the file exists or not: nothing about it is given away).
bool regular_file_exists(const std::string& abs, void* user) {
  if (abs.empty() || abs[0] != '/') return false;
  const std::optional<std::filesystem::path> p = inside_root(abs, user);
  struct stat st {};
  return !p || ::stat(p->c_str(), &st) == 0;
}

std::string path_as_written(const std::string& path, void*) { return path; }

bool read_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& abs, void* user) {
  const std::optional<std::filesystem::path> p = inside_root(abs, user);
  if (!p) {
    if (err) *err += std::string(kOutside) + "\n";
    return false;
  }
  // The references' symlinks were resolved inside the root; one swapped in since is not followed.
  const int nofollow = abs == static_cast<const FsContext*>(user)->main ? 0 : O_NOFOLLOW;
  const int fd = ::open(p->c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | nofollow);
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    if (fd >= 0) ::close(fd);
    if (err) *err += "not a readable regular file\n";
    return false;
  }
  // An empty file is refused here: tinygltf's binary loader indexes its first byte unchecked
  // (std::out_of_range escaped the loader; its own file reader refuses an empty file too).
  if (st.st_size == 0 || static_cast<std::uint64_t>(st.st_size) > memory_limit(0)) {
    ::close(fd);
    if (err) *err += st.st_size == 0 ? "empty\n" : "larger than the memory available\n";
    return false;
  }
  out->resize(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  for (ssize_t n = 1; done < out->size() && n > 0; done += static_cast<std::size_t>(std::max<ssize_t>(n, 0)))
    n = ::read(fd, out->data() + done, out->size() - done);
  ::close(fd);
  out->resize(std::min(done, out->size()));
  return true;
}

bool write_no_file(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// The extensions a file may require: what the runtime draws (KHR_texture_transform: the engine
// view applies it) and what it decodes (gltf/compressed_gltf.h). Any other required one is refused
// by name: an engine that does not know an extension it requires must not draw the file.
void check_required(const tinygltf::Model& m, const std::string& path) {
  std::vector<std::string> known = gltf_input::decoded_extensions();
  known.push_back("KHR_texture_transform");
  for (const std::string& e : m.extensionsRequired)
    if (std::find(known.begin(), known.end(), e) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError("render.gltf.unsupported_extension", path, "extensionsRequired",
                       "requires the extension " + e + ", which qf-render does not read (it reads: " + list + ")");
    }
}

// Parses a glTF file, or (`glb`, a .glb file's bytes) the same from memory; errors name `path`.
// The bytes go through gltf_input::prepared_for_tinygltf first (what tinygltf refuses of a Draco or
// meshopt file), and the parsed model through decode_compressed.
tinygltf::Model parse_gltf(const std::string& path, const std::vector<std::uint8_t>* glb) {
  if (!glb && !std::filesystem::is_regular_file(path)) throw InputError("file.unreadable", path, "", "cannot open: no such file");
  // A file's references stay in its folder (bytes in memory, the baker's own, read none). tinygltf
  // joins each to the base folder given: the file's canonical folder, so every path it opens is
  // absolute and goes through the callbacks.
  FsContext fs;
  if (!glb) {
    fs.root = io::asset_root(path, "");
    fs.main = (fs.root / std::filesystem::path(path).filename()).string();
  }
  std::vector<std::uint8_t> contents;
  if (!glb) {
    std::string err;
    if (!read_regular_file(&contents, &err, fs.main, &fs)) fail(path, "parse", err.empty() ? "not a readable file" : err.substr(0, err.size() - 1));
  }
  const std::vector<std::uint8_t>& raw = glb ? *glb : contents;
  // The JSON's depth before any parser (tinygltf's recurses per level: ~14,500 levels in 30 KB
  // overflowed the stack): a .gltf's whole text, a .glb's JSON chunk.
  check_gltf_json_depth(raw.data(), raw.size(), path, "render.gltf");
  check_glb_chunks(raw.data(), raw.size(), path, "render.gltf.parse");
  const std::vector<std::uint8_t> prepared = gltf_input::prepared_for_tinygltf(raw, {path, "render.gltf", 0});
  const std::vector<std::uint8_t>& bytes = prepared.empty() ? raw : prepared;
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&load_image_checked, &m);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&regular_file_exists, &path_as_written, &read_regular_file, &write_no_file, &fs});
  std::string err, warn;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const std::string base = fs.root.string();
  const bool ok = binary ? loader.LoadBinaryFromMemory(&m, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), base)
                         : loader.LoadASCIIFromString(&m, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                                      static_cast<unsigned int>(bytes.size()), base);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    fail(path, "parse", err.empty() ? "not a readable glTF file" : err);
  }
  // tinygltf takes an image it could not read as a warning and goes on without it: one refused
  // for leading outside is an error, in its own words.
  if (warn.find(kOutside) != std::string::npos) {
    while (!warn.empty() && (warn.back() == '\n' || warn.back() == ' ')) warn.pop_back();
    fail(path, "outside_file", warn);
  }
  check_required(m, path);
  gltf_input::decode_compressed(m, {path, "render.gltf", 0});
  return m;
}

tinygltf::Model read_gltf(const std::string& path) { return parse_gltf(path, nullptr); }

// COLOR_0 as the baker writes it (normalized 16-bit linear RGBA) -> sRGB bytes; the base colour
// when absent. Other types glTF allows for it (normalized 8-bit, as glTF-Transform's meshopt and
// quantize rewrite it; float; RGB) are read as linear floats.
std::vector<Rgb8> read_colors(const AccessorReader& read, const tinygltf::Primitive& prim, std::size_t n) {
  const auto col = prim.attributes.find("COLOR_0");
  if (col == prim.attributes.end()) return std::vector<Rgb8>(n, kBaseColor);
  const tinygltf::Accessor& a = read.accessor(col->second);
  const bool rgba16 = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && a.type == TINYGLTF_TYPE_VEC4;
  const bool normalized = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || a.normalized;
  if ((a.type != TINYGLTF_TYPE_VEC4 && a.type != TINYGLTF_TYPE_VEC3) || !normalized || a.count != n)
    fail(read.path, "colors", "COLOR_0 must be normalized RGB or RGBA (or float), one per vertex");
  std::vector<Rgb8> out;
  if (!rgba16) {
    const int k = a.type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    const std::vector<float> f = read.floats(col->second, k);
    for (std::size_t i = 0; i + 2 < f.size(); i += static_cast<std::size_t>(k))
      out.push_back({linear_to_srgb8(f[i]), linear_to_srgb8(f[i + 1]), linear_to_srgb8(f[i + 2])});
    return out;
  }
  std::size_t stride = 0;
  const unsigned char* b = read.base(a, 8, stride);
  for (std::size_t i = 0; i < a.count; ++i) {
    std::uint16_t c[4];
    std::memcpy(c, b + i * stride, 8);
    out.push_back({linear16_to_srgb(c[0]), linear16_to_srgb(c[1]), linear16_to_srgb(c[2])});
  }
  return out;
}

std::vector<Vec3f> read_vec3(const AccessorReader& read, const tinygltf::Primitive& prim, const char* name) {
  std::vector<Vec3f> out;
  const auto it = prim.attributes.find(name);
  if (it == prim.attributes.end()) return out;
  const std::vector<float> f = read.floats(it->second, 3);
  for (std::size_t i = 0; i + 2 < f.size(); i += 3) out.push_back({f[i], f[i + 1], f[i + 2]});
  return out;
}

// Vec3f arrays placed by a mesh's node transform (gltf_read.h mesh_transforms).
void place(const Mat4d& w, std::vector<Vec3f>& points, std::vector<Vec3f>* directions) {
  if (is_identity(w)) return;
  const auto apply = [](std::vector<Vec3f>& v, auto&& fn) {
    std::vector<float> xyz;
    xyz.reserve(v.size() * 3);
    for (const Vec3f& q : v) xyz.insert(xyz.end(), {q.x, q.y, q.z});
    fn(xyz);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  };
  apply(points, [&](std::vector<float>& xyz) { place_points(w, xyz); });
  if (directions) apply(*directions, [&](std::vector<float>& xyz) { place_directions(w, xyz); });
}

PointImpostorScene point_scene(const tinygltf::Model& m, const std::string& path) {
  PointImpostorScene s;
  s.pixel = static_cast<float>(m.extensions.at(kPointExtension).Get("pixelSize").GetNumberAsDouble());
  if (!(s.pixel > 0)) fail(path, "points", std::string(kPointExtension) + ".pixelSize must be positive");
  AccessorReader read{m, path};
  const std::vector<Mat4d> placed = mesh_transforms(m);
  for (std::size_t mi = 0; mi < m.meshes.size(); ++mi)
    for (const tinygltf::Primitive& prim : m.meshes[mi].primitives) {
      if (prim.mode != TINYGLTF_MODE_POINTS || !s.positions.empty()) continue;
      s.positions = read_vec3(read, prim, "POSITION");
      s.normals = read_vec3(read, prim, "NORMAL");
      s.colors = read_colors(read, prim, s.positions.size());
      place(placed[mi], s.positions, &s.normals);
    }
  if (s.positions.empty()) fail(path, "points", "has " + std::string(kPointExtension) + " but no POINTS primitive with points");
  if (!s.normals.empty() && s.normals.size() != s.positions.size()) fail(path, "points", "NORMAL and POSITION counts differ");
  if (s.normals.empty()) s.normals.assign(s.positions.size(), Vec3f{0, 0, 1});
  for (Vec3f q : s.positions) s.bounds.add(q);
  return s;
}

ClusterScene cluster_scene(const tinygltf::Model& m, const std::string& path) {
  ClusterScene s;
  s.cell = static_cast<float>(m.nodes[0].extras.Get(kCellWidthExtra).GetNumberAsDouble());
  AccessorReader read{m, path};
  const std::vector<Mat4d> placed = mesh_transforms(m);
  for (std::size_t mi = 0; mi < m.meshes.size(); ++mi)
    for (const tinygltf::Primitive& prim : m.meshes[mi].primitives) {
      std::vector<Vec3f> pos = read_vec3(read, prim, "POSITION");
      const std::vector<Rgb8> col = read_colors(read, prim, pos.size());
      if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
        std::vector<Vec3f> nrm = read_vec3(read, prim, "NORMAL");
        if (nrm.size() != pos.size()) fail(path, "mesh", "cluster LOD triangles need one NORMAL per vertex");
        place(placed[mi], pos, &nrm);
        const auto base = static_cast<std::uint32_t>(s.mesh.positions.size());
        // The baker writes the triangles unindexed; a Draco-compressed variant comes back indexed.
        if (prim.indices >= 0) {
          for (std::uint32_t i : read.indices(prim.indices)) {
            if (i >= pos.size()) fail(path, "mesh", "index " + std::to_string(i) + " out of range (" + std::to_string(pos.size()) + " vertices)");
            s.mesh.indices.push_back(base + i);
          }
        } else {
          for (std::size_t i = 0; i < pos.size(); ++i) s.mesh.indices.push_back(base + static_cast<std::uint32_t>(i));
        }
        s.mesh.positions.insert(s.mesh.positions.end(), pos.begin(), pos.end());
        s.mesh.normals.insert(s.mesh.normals.end(), nrm.begin(), nrm.end());
        s.mesh.colors.insert(s.mesh.colors.end(), col.begin(), col.end());
      } else if (prim.mode == TINYGLTF_MODE_LINE) {
        place(placed[mi], pos, nullptr);
        const auto th = prim.attributes.find(kThicknessAttribute);
        if (th == prim.attributes.end()) fail(path, "lines", "cluster LOD lines need _THICKNESS");
        const std::vector<float> t = read.floats(th->second, 1);
        if (t.size() != pos.size() || pos.size() % 2) fail(path, "lines", "_THICKNESS needs one value per line vertex");
        s.line_positions.insert(s.line_positions.end(), pos.begin(), pos.end());
        s.line_colors.insert(s.line_colors.end(), col.begin(), col.end());
        for (std::size_t i = 0; i < t.size(); i += 2) s.thickness.push_back(t[i]);
      } else if (prim.mode == TINYGLTF_MODE_POINTS) {
        place(placed[mi], pos, nullptr);
        s.points.insert(s.points.end(), pos.begin(), pos.end());
        s.point_colors.insert(s.point_colors.end(), col.begin(), col.end());
      }
    }
  for (const auto* v : {&s.mesh.positions, &s.line_positions, &s.points})
    for (Vec3f q : *v) s.bounds.add(q);
  s.mesh.bounds = s.bounds;
  if (s.bounds.empty()) fail(path, "mesh", "a cluster LOD without geometry");
  return s;
}

// The impostor level of the file (or of its mesh `only_mesh` alone, >= 0).
ImpostorScene impostor_scene(const tinygltf::Model& m, const std::string& path, int only_mesh = -1);

}  // namespace

// A combined LOD file (`qf-bake --lod-file`): the scene's one root node lists its lower LODs
// under MSFT_lod and their screen coverages in its extras. Empty when the file has none.
std::vector<int> lod_nodes(const tinygltf::Model& m, const std::vector<int>& roots, const std::string& path, std::vector<double>& coverage) {
  if (roots.size() != 1 || roots[0] < 0 || roots[0] >= static_cast<int>(m.nodes.size())) return {};
  const tinygltf::Node& root = m.nodes[static_cast<std::size_t>(roots[0])];
  const auto ext = root.extensions.find(kLodExtension);
  if (ext == root.extensions.end()) return {};
  std::vector<int> nodes{roots[0]};
  for (int id : number_array<int>(ext->second, "ids", path)) nodes.push_back(id);
  coverage = number_array<double>(root.extras, kScreenCoverageExtra, path);
  return nodes;
}

namespace {

// Whether mesh `mesh` has a triangle primitive: a combined LOD file may hold a point impostor,
// which the item view cannot show (the engine view can).
bool has_triangles(const tinygltf::Model& m, int mesh) {
  if (mesh < 0 || mesh >= static_cast<int>(m.meshes.size())) return false;
  for (const tinygltf::Primitive& p : m.meshes[static_cast<std::size_t>(mesh)].primitives)
    if (p.mode == TINYGLTF_MODE_TRIANGLES) return true;  // as expand_triangles reads them
  return false;
}

// The scene of a parsed file, whatever it holds.
BakedScene baked_scene(const tinygltf::Model& m, const std::string& path) {
  BakedScene s;
  const std::vector<int> roots = scene_roots(m);
  std::vector<double> coverage;
  const std::vector<int> lods = lod_nodes(m, roots, path, coverage);
  if (!lods.empty()) {
    // Each LOD alone, finest first; the file itself stands for the finest.
    for (int node : lods) {
      if (node < 0 || node >= static_cast<int>(m.nodes.size())) fail(path, "nodes", "MSFT_lod names node " + std::to_string(node) + ", which does not exist");
      BakedScene level;
      level.engine = engine_scene(m, path, {node});
      const int mesh = m.nodes[static_cast<std::size_t>(node)].mesh;
      if (has_triangles(m, mesh)) level.impostor = impostor_scene(m, path, mesh);
      else level.impostor.bounds = level.engine.bounds;  // drawn by the engine method alone
      s.lods.push_back(std::move(level));
    }
    s.lod_coverage = coverage;
    s.engine = s.lods[0].engine;
    s.impostor = s.lods[0].impostor;
    return s;
  }
  s.engine = engine_scene(m, path, roots);
  if (m.extensions.count(kPointExtension)) {
    s.kind = BakedScene::kPoints;
    s.points = point_scene(m, path);
  } else if (!m.nodes.empty() && m.nodes[0].extras.Has(kCellWidthExtra)) {
    s.kind = BakedScene::kCluster;
    s.cluster = cluster_scene(m, path);
  } else {
    s.impostor = impostor_scene(m, path);
    // The item view ignores node transforms (a baked level has none; a game asset may): the file
    // is framed where an engine shows it.
    s.asset = !m.extensions.count("QF_impostor_level");
    if (!s.engine.bounds.empty()) s.impostor.bounds = s.engine.bounds;
  }
  return s;
}

}  // namespace

BakedScene load_baked(const std::string& path) { return baked_scene(read_gltf(path), path); }  // parsed once

BakedScene load_baked(const std::vector<std::uint8_t>& glb, const std::string& name) { return baked_scene(parse_gltf(name, &glb), name); }

ImpostorScene load_gltf(const std::string& path) { return impostor_scene(read_gltf(path), path); }

namespace {

// The triangles of one material, in file order: the first vertex of each.
struct TriangleGroup {
  int material;
  std::vector<std::uint32_t> first;
};

// Step 1: every triangle primitive of every mesh (or of `only_mesh` alone, >= 0), expanded to
// flat vertex arrays in `s`; the groups list the triangles per primitive, in file order.
std::vector<TriangleGroup> expand_triangles(const tinygltf::Model& m, const std::string& path, int only_mesh, ImpostorScene& s) {
  AccessorReader read{m, path};
  const std::vector<Mat4d> placed = mesh_transforms(m);
  std::vector<TriangleGroup> groups;
  for (std::size_t mi = 0; mi < m.meshes.size(); ++mi) {
    if (only_mesh >= 0 && mi != static_cast<std::size_t>(only_mesh)) continue;
    for (const tinygltf::Primitive& prim : m.meshes[mi].primitives) {
      if (prim.mode != TINYGLTF_MODE_TRIANGLES) continue;
      const auto pos_it = prim.attributes.find("POSITION");
      if (pos_it == prim.attributes.end()) fail(path, "mesh", "a triangle primitive has no POSITION");
      std::vector<float> pos = read.floats(pos_it->second, 3);
      // Where its node places it (a quantized level's dequantization; a baked level has none).
      if (!is_identity(placed[mi])) place_points(placed[mi], pos);
      // The base colour's texture coordinates, through its KHR_texture_transform (gltfpack's dequantization).
      int uv_set = 0;
      const std::array<float, 6> uvt = base_uv_transform(m, prim.material, uv_set);
      const auto uv_it = prim.attributes.find("TEXCOORD_" + std::to_string(uv_set));
      std::vector<float> uv = uv_it == prim.attributes.end() ? std::vector<float>() : read.floats(uv_it->second, 2);
      transform_uv_pairs(uvt, uv);
      std::vector<std::uint32_t> idx;
      if (prim.indices >= 0) {
        idx = read.indices(prim.indices);
      } else {
        for (std::uint32_t i = 0; i < pos.size() / 3; ++i) idx.push_back(i);
      }
      TriangleGroup g{prim.material, {}};
      for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
        g.first.push_back(static_cast<std::uint32_t>(s.positions.size() / 3));
        for (int c = 0; c < 3; ++c) {
          const std::size_t v = idx[t + static_cast<std::size_t>(c)];
          if (v * 3 + 2 >= pos.size()) fail(path, "mesh", "an index is past the end of POSITION");
          s.positions.insert(s.positions.end(), {pos[v * 3], pos[v * 3 + 1], pos[v * 3 + 2]});
          s.uvs.insert(s.uvs.end(), {uv.empty() ? 0.0f : uv[v * 2], uv.empty() ? 0.0f : uv[v * 2 + 1]});
          s.bounds.add({pos[v * 3], pos[v * 3 + 1], pos[v * 3 + 2]});
        }
      }
      groups.push_back(std::move(g));
    }
  }
  return groups;
}

// The scene texture a material draws with: its base colour image, else `white`.
std::uint32_t texture_of(const tinygltf::Model& m, int material, std::uint32_t white) {
  if (material < 0 || material >= static_cast<int>(m.materials.size())) return white;
  const int t = m.materials[static_cast<std::size_t>(material)].pbrMetallicRoughness.baseColorTexture.index;
  if (t < 0 || t >= static_cast<int>(m.textures.size())) return white;
  const int src = gltf::texture_source(m.textures[static_cast<std::size_t>(t)]);
  return src >= 0 && src < static_cast<int>(m.images.size()) ? static_cast<std::uint32_t>(src) : white;
}

// The atlases' alpha back to the basis functions' weights (core/weight_alpha.h): the writer
// stored them with the extension's alphaExponent for engines' alpha test; the blend needs the
// weights. A 256-entry table, applied before any mip level is made.
void decode_weights(double exponent, const std::string& path, ImpostorScene& s) {
  if (!(exponent >= 1) || !std::isfinite(exponent)) fail(path, "extension", "alphaExponent must be a number >= 1");
  std::uint8_t table[256];
  for (int a = 0; a < 256; ++a)
    table[a] = static_cast<std::uint8_t>(std::lround(255.0 * decode_alpha(a / 255.0, exponent)));
  for (std::size_t t = 0; t + 1 < s.textures.size(); ++t)  // the last one is the white texture
    for (std::size_t k = 3; k < s.textures[t].rgba.size(); k += 4) s.textures[t].rgba[k] = table[s.textures[t].rgba[k]];
}

// Step 2 for plain glTF: consecutive triangle pairs are quads; others stand alone; each item with
// its own centroid and area-weighted normal.
void plain_items(const tinygltf::Model& m, const std::vector<TriangleGroup>& groups, std::uint32_t white, ImpostorScene& s) {
  for (const TriangleGroup& g : groups) {
    for (std::size_t t = 0; t < g.first.size();) {
      const bool pair = t + 1 < g.first.size();
      Item it;
      it.first_vertex = g.first[t];
      it.vertex_count = pair ? 6 : 3;
      it.texture = texture_of(m, g.material, white);
      t += pair ? 2 : 1;
      Vec3f sum, area;
      for (std::uint32_t tri = 0; tri < it.vertex_count; tri += 3) {
        Vec3f p[3];
        for (int c = 0; c < 3; ++c) {
          const std::size_t v = (it.first_vertex + tri + static_cast<std::uint32_t>(c)) * 3;
          p[c] = {s.positions[v], s.positions[v + 1], s.positions[v + 2]};
          sum = sum + p[c];
        }
        area = area + cross(p[1] - p[0], p[2] - p[0]);
      }
      it.center = sum * (1.0f / static_cast<float>(it.vertex_count));
      it.normal = normalized(area);
      s.items.push_back(it);
    }
  }
}

// The accessor one of the extension's arrays names; -1 when the key is absent. Files baked by
// quasiflat 0.7 and earlier held the arrays in the JSON itself.
int extension_accessor(const tinygltf::Value& ext, const char* key, const std::string& path) {
  if (!ext.Has(key)) return -1;
  const tinygltf::Value& v = ext.Get(key);
  if (!v.IsInt())
    fail(path, "extension", std::string(kImpostorExtension) + " " + key +
                                " is not an accessor index (a file baked by quasiflat 0.7 or earlier, which held it as a JSON array: bake the asset again)");
  return v.GetNumberAsInt();
}
std::vector<std::uint32_t> extension_integers(const AccessorReader& read, const tinygltf::Value& ext, const char* key, const std::string& path) {
  const int accessor = extension_accessor(ext, key, path);
  return accessor < 0 ? std::vector<std::uint32_t>() : read.indices(accessor);
}

// Step 2 with the extension: quad k is the k-th pair of triangles of the mesh's primitives taken
// in order (the writer emits one primitive per atlas image, 4 vertices and 2 triangles a quad);
// its plane comes from its corners as for plain glTF, the domains and the graph from the extension.
void extension_items(const tinygltf::Model& m, const tinygltf::Value& ext, const std::string& path,
                     const std::vector<TriangleGroup>& groups, std::uint32_t white, ImpostorScene& s) {
  const auto quads = static_cast<std::size_t>(to_integer<std::uint32_t>(ext.Get("quadCount").GetNumberAsDouble(), path, "quadCount"));
  const AccessorReader read{m, path};
  s.offsets = extension_integers(read, ext, "neighborOffsets", path);
  s.neighbors = extension_integers(read, ext, "neighbors", path);
  s.domains = extension_integers(read, ext, "domain", path);
  if (const int errors = extension_accessor(ext, "error", path); errors >= 0) s.errors = read.floats(errors, 1);
  if ((!s.domains.empty() && s.domains.size() != quads) || s.errors.size() != s.domains.size())
    fail(path, "extension", std::string(kImpostorExtension) + " domain and error do not hold quadCount " + std::to_string(quads) + " entries each");
  if (s.offsets.size() != quads + 1 || s.offsets.back() != s.neighbors.size())
    fail(path, "extension", std::string(kImpostorExtension) + " neighbour rows do not match quadCount " + std::to_string(quads));
  for (std::size_t k = 0; k < quads; ++k)
    if (s.offsets[k] > s.offsets[k + 1]) fail(path, "extension", "neighborOffsets decrease at quad " + std::to_string(k));
  for (std::uint32_t nb : s.neighbors)
    if (nb >= quads) fail(path, "extension", "a neighbour index is out of range");
  for (const TriangleGroup& g : groups)
    if (g.first.size() % 2 != 0) fail(path, "extension", "a primitive's triangle count is odd (a quad is two triangles)");
  plain_items(m, groups, white, s);
  if (s.items.size() != quads)
    fail(path, "extension", "the mesh holds " + std::to_string(s.items.size()) + " quads, the extension's quadCount is " + std::to_string(quads));
  for (const Item& it : s.items) {
    const std::size_t v = it.first_vertex * 3;
    // Two triangles over four corners: (0, 1, 2) and (0, 2, 3).
    if (std::memcmp(&s.positions[v], &s.positions[v + 9], 3 * sizeof(float)) != 0 ||
        std::memcmp(&s.positions[v + 6], &s.positions[v + 12], 3 * sizeof(float)) != 0)
      fail(path, "extension", "a quad's two triangles do not share its diagonal");
  }
  s.has_extension = true;
  s.level = ext.Has("level") ? to_integer<int>(ext.Get("level").GetNumberAsDouble(), path, "level") : -1;
  if (ext.Has("alphaRef")) s.alpha_ref = static_cast<float>(ext.Get("alphaRef").GetNumberAsDouble());
  if (ext.Has("alphaExponent")) decode_weights(ext.Get("alphaExponent").GetNumberAsDouble(), path, s);
}

ImpostorScene impostor_scene(const tinygltf::Model& m, const std::string& path, int only_mesh) {
  ImpostorScene s;
  // Textures: one per glTF image, plus a white one at the end for untextured materials.
  for (const tinygltf::Image& img : m.images) s.textures.push_back(to_image(img, path));
  const auto white = static_cast<std::uint32_t>(s.textures.size());
  s.textures.push_back(white_image());
  if (!m.materials.empty()) {
    s.alpha_mode = m.materials[0].alphaMode;
    s.alpha_cutoff = static_cast<float>(m.materials[0].alphaCutoff);
    s.double_sided = m.materials[0].doubleSided;
  }
  // 1. The triangles, 2. the items (the extension's quads, else triangle pairs).
  const std::vector<TriangleGroup> groups = expand_triangles(m, path, only_mesh, s);
  const auto ext_it = m.extensions.find(kImpostorExtension);
  if (ext_it != m.extensions.end()) extension_items(m, ext_it->second, path, groups, white, s);
  else plain_items(m, groups, white, s);
  // 3. One normal per item on all its vertices.
  s.normals.resize(s.positions.size());
  for (const Item& it : s.items)
    for (std::uint32_t v = it.first_vertex; v < it.first_vertex + it.vertex_count; ++v) {
      s.normals[v * 3] = it.normal.x;
      s.normals[v * 3 + 1] = it.normal.y;
      s.normals[v * 3 + 2] = it.normal.z;
    }
  if (s.items.empty()) fail(path, "empty", "the file has no triangles to draw");
  return s;
}

}  // namespace

}  // namespace qf::render
