// Mesh sampling benchmark (issue 7, like table 1 of the seed paper): per mesh and LDI size, the
// layers per axis, points produced and the time of the GL and CPU backends, each with the faster
// per-axis variant (the default) and with every triangle on every axis. GL times include making
// the EGL context (~80 ms) and compiling the shaders; the best of 3 runs.
// After `--textured`, textured meshes (glTF, OBJ + MTL) get a second table: the same geometry
// sampled (CPU backend, the default) with its materials and with them stripped, at LDI 256 and
// 1000, and the materials' overhead (issue 17's target: at most 30%).
// usage: qf-bench-sample MESH... [--textured TEXTURED_MESH...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "io/model_io.h"
#include "sample/sample.h"

using namespace qf;

namespace {

// One sampling of `mesh`, in seconds; `points` gets the points made.
double sample_seconds(const TriangleMesh& mesh, const SampleOptions& o, const std::string& path, std::size_t& points) {
  const auto t = std::chrono::steady_clock::now();
  points = sample_mesh(mesh, o, path).size();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The same geometry without its look: no materials, UVs or textures (vertex colours kept, as an
// untextured PLY would have them), so the sampler takes its uncoloured path.
TriangleMesh without_materials(TriangleMesh m) {
  m.materials.clear();
  m.triangle_materials.clear();
  m.corner_uvs.clear();
  m.textures.clear();
  return m;
}

// The same materials without their textures: base colour factors only (an untextured asset as
// engines hold it), so the difference to the textured mesh is the texture lookups alone.
TriangleMesh without_textures(TriangleMesh m) {
  for (SurfaceMaterial& material : m.materials) material.texture = -1;
  m.textures.clear();
  return m;
}

void textured_table(const std::vector<std::string>& paths) {
  std::printf("\ntextured vs untextured sampling (CPU backend, per-axis, best of 5 interleaved runs, seconds;\n");
  std::printf("no material: materials, UVs and textures removed; factors: materials kept, textures removed)\n");
  std::printf("%-26s %6s %9s %5s %9s %11s %9s %9s %11s %11s\n", "mesh", "tris", "texels", "LDI", "points", "no material", "factors",
              "textured", "vs no mat.", "vs factors");
  for (const std::string& path : paths) {
    const TriangleMesh textured = read_model(path).mesh;
    const TriangleMesh plain = without_materials(textured), factors = without_textures(textured);
    std::size_t texels = 0;
    for (const TextureImage& t : textured.textures) texels += static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
    const std::string name = path.substr(path.find_last_of('/') + 1);
    for (int ldi : {256, 1000}) {
      SampleOptions o;
      o.ldi_size = ldi;
      std::size_t n_plain = 0, n_factors = 0, n_textured = 0;
      double t_plain = 1e30, t_factors = 1e30, t_textured = 1e30;
      // Interleaved, so that all see the same load on a shared machine; the best of 5 each.
      for (int run = 0; run < 5; ++run) {
        t_plain = std::min(t_plain, sample_seconds(plain, o, path, n_plain));
        t_factors = std::min(t_factors, sample_seconds(factors, o, path, n_factors));
        t_textured = std::min(t_textured, sample_seconds(textured, o, path, n_textured));
      }
      std::printf("%-26s %6zu %9zu %5d %9zu %11.4f %9.4f %9.4f %10.1f%% %10.1f%%\n", name.c_str(), textured.triangles.size(), texels, ldi,
                  n_textured, t_plain, t_factors, t_textured, 100 * (t_textured / t_plain - 1), 100 * (t_textured / t_factors - 1));
      std::fflush(stdout);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes, textured;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--textured") {
      for (++i; i < argc; ++i) textured.push_back(argv[i]);
      break;
    }
    meshes.push_back(argv[i]);
  }
  if (!meshes.empty())
    std::printf("%-26s %6s %5s %8s %-9s %10s %9s %8s\n", "mesh", "tris", "LDI", "backend", "variant", "layers", "points", "seconds");
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const std::string& path = meshes[i];
    const TriangleMesh mesh = read_model(path).mesh;
    const std::string name = path.substr(path.find_last_of('/') + 1);
    for (int ldi : {100, 1000})
      for (const char* backend : {"gl", "cpu"})
        for (bool per_axis : {true, false}) {
          SampleOptions o;
          o.ldi_size = ldi;
          o.backend = backend;
          o.per_axis_triangles = per_axis;
          double best = 1e30;
          SampleStats st;
          std::size_t n = 0;
          for (int run = 0; run < 3; ++run) {
            const auto t = std::chrono::steady_clock::now();
            n = sample_mesh(mesh, o, path, &st).size();
            best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
          }
          char layers[32];
          std::snprintf(layers, sizeof layers, "%d/%d/%d", st.layers[0], st.layers[1], st.layers[2]);
          std::printf("%-26s %6zu %5d %8s %-9s %10s %9zu %8.3f\n", name.c_str(), mesh.triangles.size(), ldi, st.backend.c_str(),
                      per_axis ? "per-axis" : "all", layers, n, best);
          std::fflush(stdout);
        }
  }
  if (!textured.empty()) textured_table(textured);
  return 0;
}
