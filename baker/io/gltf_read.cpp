// glTF 2.0 input (.gltf with external or data-URI buffers and images, .glb): the default scene as
// one world-space triangle mesh with its metallic-roughness materials (model_io.h, decode_gltf). The one
// baker file that parses glTF; tinygltf reads the JSON and the buffers, this file checks every
// accessor against its buffer before reading it, so a malformed file is an InputError naming its
// JSON path and never a read out of bounds.
#include <fcntl.h>
#include <sys/stat.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/input_limits.h"
#include "gltf/compressed_gltf.h"
#include "gltf/image_decode.h"
#include "gltf/png.h"
#include "io/asset_files.h"
#include "io/gltf_json.h"
#include "io/gltf_primitives.h"
#include "io/model_io.h"

namespace qf {
namespace {

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores it
constexpr Mat4 kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// The extensions a file may require: what this reader honours (the compressed ones decoded by
// gltf/compressed_gltf.h and gltf/image_decode.h). Anything else required is refused.
const std::set<std::string>& supported_extensions() {
  static const std::set<std::string> s = [] {
    std::set<std::string> names{"KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_materials_unlit"};
    for (const std::string& e : gltf_input::decoded_extensions()) names.insert(e);
    return names;
  }();
  return s;
}

std::string supported_list() {
  std::string out;
  for (const std::string& e : supported_extensions()) out += (out.empty() ? "" : ", ") + e;
  return out;
}

[[noreturn]] void fail(const std::string& path, const std::string& code, const std::string& where, const std::string& what) {
  throw InputError("gltf." + code, path, where, what);
}

// ---- 1. Parsing ----------------------------------------------------------------------------

// What the file-system callbacks and the image loader share.
struct ParseContext {
  const tinygltf::Model* model = nullptr;
  std::filesystem::path root;  // canonical: every external file must resolve inside it
  std::size_t memory_limit = 0;  // ReadOptions::memory_limit: an external file larger is not read
};

// tinygltf opens external files through these. Each path is walked again inside the root (the
// references were checked before parsing; this is what is opened), opened without blocking (a
// FIFO renamed in since would otherwise hang) and read only if it is a regular file. No "~" or
// "$VAR" expansion (tinygltf's default runs wordexp on the file's text).
std::optional<std::filesystem::path> inside(const std::string& abs, void* user) {
  return io::resolve_inside(static_cast<ParseContext*>(user)->root, "/", abs);
}

bool file_exists(const std::string& abs, void* user) {
  const std::optional<std::filesystem::path> p = inside(abs, user);
  std::error_code ec;
  return p && std::filesystem::is_regular_file(*p, ec);
}

std::string expand_nothing(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& abs, void* user) {
  const std::optional<std::filesystem::path> p = inside(abs, user);
  const int fd = p ? ::open(p->c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOFOLLOW) : -1;
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) ||
      static_cast<std::uint64_t>(st.st_size) > memory_limit(static_cast<ParseContext*>(user)->memory_limit)) {
    if (fd >= 0) ::close(fd);
    if (err) *err += "an external file cannot be read as a regular file inside the asset's folder, within the memory limit\n";
    return false;
  }
  out->resize(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  while (done < out->size()) {
    const ssize_t n = ::read(fd, out->data() + done, out->size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  out->resize(done);
  return true;
}

bool write_nothing(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// The image loader keeps each image's encoded bytes (component 0 marks them); decode_images
// decodes them once the memory they need has been checked. tinygltf 2.7 hands an image's
// bufferView to the loader without checking that it lies within its buffer: checked here.
bool keep_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
  const std::string where = "images[" + std::to_string(index) + "]" + (image->uri.empty() || image->uri.rfind("data:", 0) == 0 ? "" : " (" + image->uri + ")");
  if (image->bufferView >= 0) {
    const tinygltf::Model& m = *static_cast<ParseContext*>(user)->model;
    const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(image->bufferView));
    const std::size_t buffer = m.buffers.at(static_cast<std::size_t>(v.buffer)).data.size();
    if (v.byteOffset > buffer || v.byteLength > buffer - v.byteOffset || size < 0 ||
        static_cast<std::size_t>(size) != v.byteLength) {
      *err += where + ": its bufferView reaches past the end of its buffer";
      return false;
    }
  }
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->component = 0;
  return true;
}

// Refuses, before tinygltf opens anything, a buffer or image URI that leads outside the asset's
// folder or names something other than a regular file: InputError naming the URI as written.
void check_references(const nlohmann::json& j, const std::string& path, const std::filesystem::path& root,
                      const std::filesystem::path& folder) {
  for (const char* array : {"buffers", "images"}) {
    const auto a = j.find(array);
    if (a == j.end() || !a->is_array()) continue;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const nlohmann::json& item = (*a)[i];
      const auto uri = item.is_object() ? item.find("uri") : item.end();
      if (uri == item.end() || !uri->is_string()) continue;
      const std::string written = uri->get<std::string>();
      if (written.rfind("data:", 0) == 0) continue;
      io::confined_file(root, folder, io::percent_decoded(written), written, path, "gltf",
                        std::string(array) + "[" + std::to_string(i) + "].uri");
    }
  }
}

tinygltf::Model parse(ByteView bytes, const std::string& path, const ReadOptions& options) {
  // Before any JSON parser: tinygltf's recursion is as deep as the file nests.
  check_gltf_json_depth(bytes.data(), bytes.size(), path, "gltf");
  check_glb_chunks(bytes.data(), bytes.size(), path, "gltf.parse");
  std::vector<std::uint8_t> rewritten;
  const nlohmann::json j = io::gltf_json(bytes);
  const std::filesystem::path root = io::asset_root(path, options.asset_root);
  const std::filesystem::path folder = io::asset_root(path, "");
  if (j.is_object()) {
    io::check_gltf_json_types(j, path);
    check_references(j, path, root, folder);
    // What tinygltf would refuse of a Draco or meshopt file (gltf/compressed_gltf.h).
    rewritten = gltf_input::prepared_for_tinygltf(bytes, {path, "gltf", options.memory_limit});
    if (!rewritten.empty()) bytes = ByteView(rewritten.data(), rewritten.size());
  }
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  ParseContext context{&m, root, options.memory_limit};
  loader.SetImageLoader(&keep_image, &context);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&file_exists, &expand_nothing, &read_whole_file, &write_nothing, &context});
  std::string err, warn;
  const std::string base = folder.string();
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&m, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()), base)
                         : loader.LoadASCIIFromString(&m, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                                      static_cast<unsigned>(bytes.size()), base);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    std::replace(err.begin(), err.end(), '\n', ';');
    fail(path, "parse", "", err.empty() ? "is not a readable glTF 2.0 file" : err);
  }
  for (const std::string& e : m.extensionsRequired)
    if (!supported_extensions().count(e))
      fail(path, "unsupported_extension", "extensionsRequired",
           "requires the extension " + e + ", which qf-bake does not read (it reads: " + supported_list() + ")");
  // Meshopt views and Draco primitives into plain accessors, their sizes checked first.
  gltf_input::decode_compressed(m, {path, "gltf", options.memory_limit});
  return m;
}

// ---- 2. What the file will cost --------------------------------------------------------------

std::string image_where(const tinygltf::Image& image, std::size_t index) {
  return "images[" + std::to_string(index) + "]" + (image.uri.empty() || image.uri.rfind("data:", 0) == 0 ? "" : " (" + image.uri + ")");
}

// RGBA8 bytes of every image once decoded, from their headers (PNG, JPEG, KTX2 with its mip
// levels, WebP); an image whose header does not read as one of them is refused here.
double decoded_images_bytes(const tinygltf::Model& m, const std::string& path) {
  double total = 0;
  for (std::size_t i = 0; i < m.images.size(); ++i) {
    const tinygltf::Image& g = m.images[i];
    if (g.component != 0 || g.image.empty()) continue;  // not loaded: MaterialTable says so if used
    const std::optional<ImageHeader> h = image_header(g.image.data(), g.image.size());
    if (!h) fail(path, "image_format", image_where(g, i), "is not a PNG, JPEG, KTX2 or WebP image (or its header does not read)");
    // Twice: the decoded image and the mesh's copy of it.
    total += 2.0 * static_cast<double>(decoded_image_bytes(*h));
  }
  return total;
}

// The image's texels: KTX2 (level 0: the mesh keeps one level) and WebP through the shared
// decoders, which check the header's size against the memory limit first; PNG, JPEG and the rest
// through OpenImageIO.
TextureImage decode_any_image(const tinygltf::Image& g, const std::string& path, std::size_t memory_limit) {
  const ImageDecodeContext c{path, "gltf", memory_limit};
  DecodedImage d;
  if (is_ktx2(g.image.data(), g.image.size())) d = decode_ktx2(g.image.data(), g.image.size(), c, false);
  else if (is_webp(g.image.data(), g.image.size())) d = decode_webp(g.image.data(), g.image.size(), c);
  else return decode_image(g.image.data(), g.image.size(), g.uri);
  return TextureImage{d.width, d.height, std::move(d.rgba)};
}

// Decodes the images keep_image kept (RGBA8).
void decode_images(tinygltf::Model& m, const std::string& path, std::size_t memory_limit) {
  for (std::size_t i = 0; i < m.images.size(); ++i) {
    tinygltf::Image& g = m.images[i];
    if (g.component != 0) continue;
    try {
      TextureImage t = decode_any_image(g, path, memory_limit);
      g.width = t.width, g.height = t.height, g.component = 4, g.bits = 8;
      g.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
      g.image = std::move(t.rgba);
    } catch (const InputError& e) {
      throw InputError(e.code(), path, image_where(g, i), e.detail());
    } catch (const std::exception& e) {
      fail(path, "parse", "", image_where(g, i) + ": " + e.what());
    }
  }
}

// ---- 3. Materials and textures ---------------------------------------------------------------

TextureWrap wrap_of(int mode) {
  if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::kClampToEdge;
  if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::kMirroredRepeat;
  return TextureWrap::kRepeat;
}

// KHR_texture_transform of a texture reference: uv' = T R S uv, and the texCoord set it names.
struct UvTransform {
  double a = 1, b = 0, c = 0, d = 1, ox = 0, oy = 0;  // u' = a u + b v + ox, v' = c u + d v + oy
  int tex_coord = 0;
  Vec2f apply(Vec2f uv) const {
    return {static_cast<float>(a * uv.x + b * uv.y + ox), static_cast<float>(c * uv.x + d * uv.y + oy)};
  }
  bool operator==(const UvTransform& o) const {
    return a == o.a && b == o.b && c == o.c && d == o.d && ox == o.ox && oy == o.oy && tex_coord == o.tex_coord;
  }
};

double number_at(const tinygltf::Value& v, int i, double fallback) {
  if (!v.IsArray() || static_cast<std::size_t>(i) >= v.ArrayLen() || !v.Get(i).IsNumber()) return fallback;
  return v.Get(i).GetNumberAsDouble();
}

// (TextureInfo, NormalTextureInfo, OcclusionTextureInfo: the same fields.)
template <class Info>
UvTransform uv_transform(const Info& info) {
  UvTransform t;
  t.tex_coord = info.texCoord;
  const auto it = info.extensions.find("KHR_texture_transform");
  if (it == info.extensions.end() || !it->second.IsObject()) return t;
  const tinygltf::Value& e = it->second;
  const double r = e.Has("rotation") && e.Get("rotation").IsNumber() ? e.Get("rotation").GetNumberAsDouble() : 0.0;
  const double sx = number_at(e.Get("scale"), 0, 1), sy = number_at(e.Get("scale"), 1, 1);
  t.a = std::cos(r) * sx, t.b = std::sin(r) * sy;
  t.c = -std::sin(r) * sx, t.d = std::cos(r) * sy;
  t.ox = number_at(e.Get("offset"), 0, 0), t.oy = number_at(e.Get("offset"), 1, 0);
  if (e.Has("texCoord") && e.Get("texCoord").IsInt()) t.tex_coord = e.Get("texCoord").GetNumberAsInt();
  return t;
}

// The file's materials as the mesh keeps them; textures are taken on first use. The mesh keeps one
// set of texture coordinates per triangle: a material's textures share the base colour's set and
// transform (or, without a base colour texture, the first channel texture's); a channel texture
// that names other ones is left out, with a warning, and its channel keeps its factor.
class MaterialTable {
 public:
  MaterialTable(const tinygltf::Model& m, const std::string& path, TriangleMesh& mesh, ReadReport* report)
      : m_(m), path_(path), mesh_(mesh), report_(report) {}

  // The mesh's material index for glTF material `index` (-1: the glTF default material).
  std::uint32_t material(int index) {
    const auto found = ids_.find(index);
    if (found != ids_.end()) return found->second;
    SurfaceMaterial out;
    if (index >= 0) {
      if (static_cast<std::size_t>(index) >= m_.materials.size())
        fail(path_, "material", "materials[" + std::to_string(index) + "]", "does not exist (" + std::to_string(m_.materials.size()) + " materials)");
      const tinygltf::Material& g = m_.materials[static_cast<std::size_t>(index)];
      out.name = g.name;
      const std::vector<double>& f = g.pbrMetallicRoughness.baseColorFactor;
      for (std::size_t c = 0; c < 4 && c < f.size(); ++c) out.base_color[c] = static_cast<float>(f[c]);
      out.alpha_mode = g.alphaMode == "MASK" ? AlphaMode::kMask : g.alphaMode == "BLEND" ? AlphaMode::kBlend : AlphaMode::kOpaque;
      out.alpha_cutoff = static_cast<float>(g.alphaCutoff);
      out.double_sided = g.doubleSided;
      const std::string at = "materials[" + std::to_string(index) + "]";
      const TextureRef base = texture(index, g.pbrMetallicRoughness.baseColorTexture.index, uv_transform(g.pbrMetallicRoughness.baseColorTexture),
                                      at + ".pbrMetallicRoughness.baseColorTexture");
      out.texture = base.image, out.wrap_s = base.wrap_s, out.wrap_t = base.wrap_t;
      // The other channels (glTF 2.0 3.9.2-3.9.5); factors keep glTF's defaults where absent.
      out.metallic = static_cast<float>(g.pbrMetallicRoughness.metallicFactor);
      out.roughness = static_cast<float>(g.pbrMetallicRoughness.roughnessFactor);
      out.metallic_roughness = texture(index, g.pbrMetallicRoughness.metallicRoughnessTexture.index,
                                       uv_transform(g.pbrMetallicRoughness.metallicRoughnessTexture),
                                       at + ".pbrMetallicRoughness.metallicRoughnessTexture");
      for (std::size_t c = 0; c < 3 && c < g.emissiveFactor.size(); ++c) out.emissive[c] = static_cast<float>(g.emissiveFactor[c]);
      out.emissive_texture = texture(index, g.emissiveTexture.index, uv_transform(g.emissiveTexture), at + ".emissiveTexture");
      out.occlusion = texture(index, g.occlusionTexture.index, uv_transform(g.occlusionTexture), at + ".occlusionTexture");
      out.occlusion_strength = static_cast<float>(g.occlusionTexture.strength);
    }
    const auto id = static_cast<std::uint32_t>(mesh_.materials.size());
    mesh_.materials.push_back(out);
    ids_[index] = id;
    return id;
  }

  // The texture-coordinate set and transform material `index` samples its textures with.
  const UvTransform* transform(int index) const {
    const auto it = transforms_.find(index);
    return it == transforms_.end() ? nullptr : &it->second;
  }

 private:
  // The texture `texture` of material `material` (-1: none), its image taken and its texture
  // coordinates checked against the material's set (see the class comment).
  TextureRef texture(int material, int texture, const UvTransform& uv, const std::string& where) {
    TextureRef out;
    if (texture < 0) return out;
    if (static_cast<std::size_t>(texture) >= m_.textures.size())
      fail(path_, "texture", where, "texture " + std::to_string(texture) + " does not exist");
    const tinygltf::Texture& tex = m_.textures[static_cast<std::size_t>(texture)];
    // A KTX2 or WebP texture names its image in its extension (KHR_texture_basisu, EXT_texture_webp).
    const int source = gltf_input::texture_image(tex);
    if (source < 0 || static_cast<std::size_t>(source) >= m_.images.size())
      fail(path_, "image", "textures[" + std::to_string(texture) + "].source", "names no image of the file");
    const auto known = transforms_.find(material);
    if (known != transforms_.end() && !(known->second == uv)) {
      warn(where + " uses other texture coordinates than the material's base colour: baked with its factor alone");
      return out;
    }
    transforms_[material] = uv;
    if (tex.sampler >= 0 && static_cast<std::size_t>(tex.sampler) < m_.samplers.size()) {
      out.wrap_s = wrap_of(m_.samplers[static_cast<std::size_t>(tex.sampler)].wrapS);
      out.wrap_t = wrap_of(m_.samplers[static_cast<std::size_t>(tex.sampler)].wrapT);
    }
    out.image = image(source);
    return out;
  }

  void warn(const std::string& text) {
    if (report_ && std::find(report_->warnings.begin(), report_->warnings.end(), text) == report_->warnings.end())
      report_->warnings.push_back(text);
  }

  int image(int source) {
    const auto found = images_.find(source);
    if (found != images_.end()) return found->second;
    const tinygltf::Image& g = m_.images[static_cast<std::size_t>(source)];
    if (g.image.empty() || g.width <= 0 || g.height <= 0 || g.component != 4)
      fail(path_, "image", "images[" + std::to_string(source) + "]" + (g.uri.empty() ? "" : " (" + g.uri + ")"),
           "could not be read: the image file is missing or unreadable");
    TextureImage t;
    t.width = g.width;
    t.height = g.height;
    t.rgba = g.image;
    const int id = static_cast<int>(mesh_.textures.size());
    mesh_.textures.push_back(std::move(t));
    images_[source] = id;
    return id;
  }

  const tinygltf::Model& m_;
  const std::string& path_;
  TriangleMesh& mesh_;
  ReadReport* report_;
  std::map<int, std::uint32_t> ids_;
  std::map<int, int> images_;
  std::map<int, UvTransform> transforms_;
};

// ---- 5. The scene ----------------------------------------------------------------------------

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k) r[c * 4 + row] += a[k * 4 + row] * b[c * 4 + k];
  return r;
}

Mat4 local_matrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    Mat4 m;
    std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
    return m;
  }
  // T * R * S, R from the unit quaternion (x, y, z, w).
  const double tx = n.translation.size() == 3 ? n.translation[0] : 0, ty = n.translation.size() == 3 ? n.translation[1] : 0,
               tz = n.translation.size() == 3 ? n.translation[2] : 0;
  double x = 0, y = 0, z = 0, w = 1;
  if (n.rotation.size() == 4) x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
  const double sx = n.scale.size() == 3 ? n.scale[0] : 1, sy = n.scale.size() == 3 ? n.scale[1] : 1, sz = n.scale.size() == 3 ? n.scale[2] : 1;
  return Mat4{(1 - 2 * (y * y + z * z)) * sx, (2 * (x * y + z * w)) * sx, (2 * (x * z - y * w)) * sx, 0,
              (2 * (x * y - z * w)) * sy, (1 - 2 * (x * x + z * z)) * sy, (2 * (y * z + x * w)) * sy, 0,
              (2 * (x * z + y * w)) * sz, (2 * (y * z - x * w)) * sz, (1 - 2 * (x * x + y * y)) * sz, 0,
              tx, ty, tz, 1};
}

double determinant3(const Mat4& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
}

struct SceneReader {
  const tinygltf::Model& m;
  const std::string& path;
  const ReadOptions& options;
  ReadReport* report;
  TriangleMesh mesh;
  MaterialTable materials;
  bool any_normals = false, any_colors = false, any_uvs = false;
  std::vector<std::pair<std::size_t, std::size_t>> flat_ranges;  // vertices of primitives without NORMAL
  std::size_t skipped = 0;

  SceneReader(const tinygltf::Model& model, const std::string& p, const ReadOptions& o, ReadReport* r)
      : m(model), path(p), options(o), report(r), materials(model, p, mesh, r) {}

  void warn(const std::string& text) {
    if (report && std::find(report->warnings.begin(), report->warnings.end(), text) == report->warnings.end())
      report->warnings.push_back(text);
  }

  // A node with a mesh, placed: what add_mesh instantiates.
  struct Instance {
    int node, mesh;
    Mat4 world;
  };

  // The scene's mesh instances in depth-first order (a node's mesh, then its children's subtrees
  // in order), walked with a stack of our own: a file's depth must not decide the call stack's
  // (a chain of ~8,100 nodes overflowed the recursive walk). glTF requires the nodes to form a
  // forest (glTF 2.0, 3.5.3): a node among its own ancestors is a cycle; a node reached twice
  // (a child of two nodes, listed twice, or a root that is also a child) is refused too, as it
  // would multiply the instances below it (nodes each naming the next twice: 2^40 from 2 KB).
  std::vector<Instance> instances(const std::vector<int>& roots) {
    std::vector<Instance> out;
    std::vector<char> reached(m.nodes.size(), 0), on_path(m.nodes.size(), 0);
    struct Step {
      int node;
      Mat4 parent;
      int parent_node;  // -1 for a root
      bool leave;       // the walk leaves `node`: no longer an ancestor
    };
    std::vector<Step> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, kIdentity, -1, false});
    while (!stack.empty()) {
      const Step s = stack.back();
      stack.pop_back();
      if (s.leave) {
        on_path[static_cast<std::size_t>(s.node)] = 0;
        continue;
      }
      const std::string where = s.parent_node < 0 ? std::string("scenes") : "nodes[" + std::to_string(s.parent_node) + "].children";
      if (s.node < 0 || static_cast<std::size_t>(s.node) >= m.nodes.size())
        fail(path, "node", where, "node " + std::to_string(s.node) + " does not exist (" + std::to_string(m.nodes.size()) + " nodes)");
      const std::size_t i = static_cast<std::size_t>(s.node);
      const std::string here = "nodes[" + std::to_string(s.node) + "]";
      if (on_path[i]) fail(path, "node_cycle", here, "is its own ancestor (the node tree has a cycle)");
      if (reached[i])
        fail(path, "node_tree", here, "is reached twice (from " + where + "): a child of two nodes, or listed twice; glTF nodes form a tree");
      reached[i] = on_path[i] = 1;
      const tinygltf::Node& n = m.nodes[i];
      const Mat4 world = multiply(s.parent, local_matrix(n));
      if (n.mesh >= 0) {
        if (static_cast<std::size_t>(n.mesh) >= m.meshes.size()) fail(path, "mesh", here + ".mesh", "names a mesh that does not exist");
        // A skinned mesh's node transform is ignored (glTF 3.7.3.3); with the joints at rest the
        // vertices are where the mesh stores them.
        if (n.skin >= 0) warn("skins are not animated: " + here + " is baked in its bind pose");
        out.push_back({s.node, n.mesh, n.skin >= 0 ? kIdentity : world});
      }
      stack.push_back({s.node, kIdentity, -1, true});
      for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) stack.push_back({*c, world, s.node, false});
    }
    return out;
  }

  // Bytes the instances will take as the mesh and its reading's temporaries, from the accessors'
  // declared counts, before any is read (a count of 2^62 is a figure here, not an allocation).
  double instances_bytes(const std::vector<Instance>& list) const {
    // Per vertex: the primitive's floats (position, normal, colour, uv: 48 bytes), the mesh's
    // position, normal and colour (27) and the remap (4); per index: the index and its corner (8),
    // a third of a triangle's index, material and corner uvs (40 / 3) and the vertex a flat-shaded
    // triangle gets for each corner (27).
    constexpr double kVertexBytes = 80, kIndexBytes = 48;
    const auto count = [&](int accessor) {
      return accessor >= 0 && static_cast<std::size_t>(accessor) < m.accessors.size()
                 ? static_cast<double>(m.accessors[static_cast<std::size_t>(accessor)].count) : 0.0;
    };
    double total = 0, draco = 0;  // Draco: the largest stream's decoding, one primitive at a time
    for (const Instance& in : list)
      for (const tinygltf::Primitive& p : m.meshes[static_cast<std::size_t>(in.mesh)].primitives) {
        const auto pos = p.attributes.find("POSITION");
        const double vertices = pos == p.attributes.end() ? 0.0 : count(pos->second);
        total += vertices * kVertexBytes + (p.indices >= 0 ? count(p.indices) : vertices) * kIndexBytes;
        draco = std::max(draco, io::draco_decoding_bytes(m, p));
      }
    return total + draco;
  }

  void add_mesh(int index, const Mat4& world) {
    const tinygltf::Mesh& g = m.meshes[static_cast<std::size_t>(index)];
    const bool mirror = determinant3(world) < 0;
    for (std::size_t k = 0; k < g.primitives.size(); ++k) {
      const tinygltf::Primitive& p = g.primitives[k];
      const std::string where = "meshes[" + std::to_string(index) + "].primitives[" + std::to_string(k) + "]";
      const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        ++skipped;
        continue;
      }
      if (!p.targets.empty()) warn("morph targets are not applied: meshes[" + std::to_string(index) + "] is baked without them");
      const std::uint32_t material = materials.material(p.material);
      const UvTransform* uvt = materials.transform(p.material);
      const io::PrimitiveData d = io::read_primitive(m, p, uvt ? uvt->tex_coord : 0, path, where);
      add_primitive(d, world, mirror, material, uvt, where);
    }
  }

  void add_primitive(const io::PrimitiveData& d, const Mat4& world, bool mirror, std::uint32_t material, const UvTransform* uvt,
                     const std::string& where) {
    const std::size_t n = d.positions.size() / 3, first = mesh.positions.size();
    // Normals go by the inverse transpose: the cofactor matrix (row r, column c: the cofactor of
    // M[r][c]; w is column-major, M[r][c] = w[4c + r]) over the determinant, whose size does not
    // matter as they are normalized but whose sign does (a mirroring node). The adjugate (the
    // transpose of this) turned each rotated part's normals by the inverse rotation:
    // 2CylinderEngine drawn from our reading scored 15.9 dB against the file.
    const double* w = world.data();
    const double s = determinant3(world) < 0 ? -1 : 1;
    const double i00 = s * (w[5] * w[10] - w[9] * w[6]), i01 = s * (w[9] * w[2] - w[1] * w[10]), i02 = s * (w[1] * w[6] - w[5] * w[2]);
    const double i10 = s * (w[8] * w[6] - w[4] * w[10]), i11 = s * (w[0] * w[10] - w[8] * w[2]), i12 = s * (w[4] * w[2] - w[0] * w[6]);
    const double i20 = s * (w[4] * w[9] - w[8] * w[5]), i21 = s * (w[8] * w[1] - w[0] * w[9]), i22 = s * (w[0] * w[5] - w[4] * w[1]);
    std::vector<std::uint32_t> remap(n, UINT32_MAX);
    for (std::size_t i = 0; i < n; ++i) {
      const double x = d.positions[3 * i], y = d.positions[3 * i + 1], z = d.positions[3 * i + 2];
      const Vec3f p{static_cast<float>(w[0] * x + w[4] * y + w[8] * z + w[12]), static_cast<float>(w[1] * x + w[5] * y + w[9] * z + w[13]),
                    static_cast<float>(w[2] * x + w[6] * y + w[10] * z + w[14])};
      if (!is_finite(p)) {
        if (!options.drop_nonfinite)
          fail(path, "nonfinite", where + ".attributes.POSITION", "vertex " + std::to_string(i) + " has a non-finite coordinate (see --drop-nonfinite)");
        if (report) ++report->dropped_nonfinite;
        continue;
      }
      remap[i] = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.push_back(p);
      if (!d.normals.empty()) {
        const double a = d.normals[3 * i], b = d.normals[3 * i + 1], c = d.normals[3 * i + 2];
        mesh.normals.push_back(normalized({static_cast<float>(i00 * a + i01 * b + i02 * c), static_cast<float>(i10 * a + i11 * b + i12 * c),
                                           static_cast<float>(i20 * a + i21 * b + i22 * c)}));
      }
      if (!d.colors.empty()) {
        const float* c = &d.colors[4 * i];
        mesh.colors.push_back({linear_to_srgb8(c[0]), linear_to_srgb8(c[1]), linear_to_srgb8(c[2])});
      }
    }
    const std::size_t added = mesh.positions.size() - first;
    fill_missing(first, added, !d.normals.empty(), !d.colors.empty());
    for (std::size_t t = 0; t + 2 < d.corners.size(); t += 3) {
      Triangle tri{remap[d.corners[t]], remap[d.corners[t + 1]], remap[d.corners[t + 2]]};
      if (tri[0] == UINT32_MAX || tri[1] == UINT32_MAX || tri[2] == UINT32_MAX) {
        if (report) ++report->dropped_triangles;
        continue;
      }
      std::array<Vec2f, 3> uv{};
      for (int k = 0; k < 3; ++k)
        if (!d.uvs.empty()) {
          const std::size_t v = d.corners[t + static_cast<std::size_t>(k)];
          const Vec2f raw{d.uvs[2 * v], d.uvs[2 * v + 1]};
          uv[static_cast<std::size_t>(k)] = uvt ? uvt->apply(raw) : raw;
        }
      if (mirror) std::swap(tri[1], tri[2]), std::swap(uv[1], uv[2]);
      mesh.triangles.push_back(tri);
      mesh.triangle_materials.push_back(material);
      mesh.corner_uvs.push_back(uv);
    }
    if (!d.uvs.empty()) any_uvs = true;
  }

  // Keeps normals and colours one per vertex when only some primitives have them: colours default
  // to white (glTF's factor 1), and vertices without normals are remembered to get flat ones.
  void fill_missing(std::size_t first, std::size_t added, bool has_normals, bool has_colors) {
    if (has_normals && !any_normals) {
      any_normals = true;
      mesh.normals.insert(mesh.normals.begin(), first, Vec3f{});
    } else if (!has_normals && any_normals) {
      mesh.normals.resize(first + added);
    }
    if (!has_normals && added) flat_ranges.push_back({first, first + added});
    if (has_colors && !any_colors) {
      any_colors = true;
      mesh.colors.insert(mesh.colors.begin(), first, Rgb8{255, 255, 255});
    } else if (!has_colors && any_colors) {
      mesh.colors.resize(first + added, Rgb8{255, 255, 255});
    }
  }

  // glTF draws primitives without NORMAL flat (3.7.2.1). Where other primitives have normals, the
  // flat ones' triangles get vertices of their own carrying the face normal.
  void make_flat_normals() {
    if (!any_normals) {
      mesh.normals.clear();
      return;
    }
    std::vector<char> flat(mesh.positions.size(), 0);
    for (const auto& [a, b] : flat_ranges)
      for (std::size_t i = a; i < b; ++i) flat[i] = 1;
    for (Triangle& t : mesh.triangles) {
      if (!flat[t[0]]) continue;
      const Vec3f normal = normalized(cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]));
      for (std::uint32_t& v : t) {
        mesh.positions.push_back(mesh.positions[v]);
        mesh.normals.push_back(normal);
        if (!mesh.colors.empty()) mesh.colors.push_back(mesh.colors[v]);
        v = static_cast<std::uint32_t>(mesh.positions.size() - 1);
      }
    }
    // The shared copies of the flat vertices are no longer used; leaving them costs nothing in
    // sampling (only triangles are drawn).
  }
};

std::vector<int> scene_roots(const tinygltf::Model& m, const std::string& path, ReadReport* report) {
  if (!m.scenes.empty()) {
    const int s = m.defaultScene >= 0 && static_cast<std::size_t>(m.defaultScene) < m.scenes.size() ? m.defaultScene : 0;
    return m.scenes[static_cast<std::size_t>(s)].nodes;
  }
  // No scene: take the nodes that are no node's child, as viewers do.
  std::vector<char> child(m.nodes.size(), 0);
  for (const tinygltf::Node& n : m.nodes)
    for (int c : n.children)
      if (c >= 0 && static_cast<std::size_t>(c) < child.size()) child[static_cast<std::size_t>(c)] = 1;
  std::vector<int> roots;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (!child[i]) roots.push_back(static_cast<int>(i));
  if (report) report->warnings.push_back("the file has no scene: baked its " + std::to_string(roots.size()) + " root nodes");
  if (roots.empty()) fail(path, "no_scene", "scenes", "the file has no scene and no nodes, so nothing to bake");
  return roots;
}

}  // namespace

TriangleMesh decode_gltf(ByteView bytes, const std::string& path, const ReadOptions& options, ReadReport* report) {
  // 1. JSON (its depth first), buffers and the images' encoded bytes, required extensions.
  tinygltf::Model m = parse(bytes, path, options);
  // 2. The default scene's instances, and what they and the decoded images will take, checked
  //    against the memory limit before anything is decoded or instantiated.
  SceneReader scene(m, path, options, report);
  const std::vector<SceneReader::Instance> instances = scene.instances(scene_roots(m, path, report));
  check_memory_need(static_cast<std::uint64_t>(std::min(scene.instances_bytes(instances) + decoded_images_bytes(m, path), 1e19)),
                    options.memory_limit, path, "gltf.memory", "",
                    "reading its " + std::to_string(instances.size()) + " mesh instances and " + std::to_string(m.images.size()) +
                        " images");
  decode_images(m, path, options.memory_limit);
  for (const SceneReader::Instance& in : instances) scene.add_mesh(in.mesh, in.world);
  // 3. Flat normals where a primitive has none, and one surface description for the whole mesh.
  scene.make_flat_normals();
  if (!scene.any_uvs) scene.mesh.corner_uvs.clear();
  if (report) {
    report->format = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0 ? "glb" : "gltf";
    report->skipped_primitives = scene.skipped;
  }
  if (scene.mesh.triangles.empty())
    fail(path, "no_triangles", "scenes",
         "the scene has no triangles to bake" +
             (scene.skipped ? " (" + std::to_string(scene.skipped) + " point or line primitives skipped)" : std::string()));
  return std::move(scene.mesh);
}

TriangleMesh read_gltf(const std::string& path, const ReadOptions& options, ReadReport* report) {
  const InputFile file(path);
  return decode_gltf(file.bytes(), path, options, report);
}

}  // namespace qf
