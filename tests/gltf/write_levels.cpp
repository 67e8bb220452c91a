// Writes .glb levels of the sample shapes into a folder, for the Khronos validator test
// (validate_test.sh). usage: qf_write_test_levels OUTDIR
#include <cstdio>
#include <fstream>
#include <string>

#include "amg/basis.h"
#include "analysis/analysis.h"
#include "domains/merge.h"
#include "core/file_io.h"
#include "gltf/glb.h"
#include "pipeline/asset.h"
#include "primitives/texture.h"
#include "sample/sample.h"
#include "shapes/plate.h"
#include "shapes/shapes.h"

using namespace qf;


static ImpostorLevel make_level(const PointSet& p, const AmgHierarchy& h, std::size_t level, bool merge) {
  SparseMatrix psi = basis_at_level(h, level);
  if (merge) psi = merge_domains(psi, p.positions);
  const Domains d = make_domains(psi);
  const std::vector<SupportRect> rects = support_rectangles(p.positions, p.normals, p.radii, psi, d);
  std::vector<Texture> textures;
  for (const SupportRect& r : rects) textures.push_back(resample_texture(p.positions, p.colors, p.normals, p.radii, psi, d, r));
  return make_impostor_level(level, rects, textures, d);
}

static void write_level(const std::string& path, const PointSet& p, const AmgHierarchy& h, std::size_t level, bool merge) {
  write_bytes_atomically(path, encode_glb(make_level(p, h, level, merge)));
}

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: qf_write_test_levels OUTDIR\n"), 2;
  const std::string dir = argv[1];
  for (const char* shape : {"octahedron", "torus", "crease"}) {
    PointSet p = generate_shape(shape, {12000, 1});
    if (std::string(shape) == "crease") p.colors.clear();  // the uncoloured path: a constant base colour
    const AmgHierarchy h = build_hierarchy(analyze_surface(p).stiffness);
    write_level(dir + "/" + shape + "_200.glb", p, h, level_by_primitives(h, 200), false);
    write_level(dir + "/" + shape + "_coarse_merged.glb", p, h, h.level_count() - 2, true);
    if (std::string(shape) == "torus") {  // three levels in one file under MSFT_lod
      const ImpostorLevel a = make_level(p, h, level_by_primitives(h, 300), false);
      const ImpostorLevel b = make_level(p, h, level_by_primitives(h, 100), false);
      const ImpostorLevel c = make_level(p, h, level_by_primitives(h, 30), false);
      const std::vector<std::uint8_t> ga = encode_glb(a), gb = encode_glb(b), gc = encode_glb(c);
      write_bytes_atomically(dir + "/torus_lods.glb", combine_lod_glb({&ga, &gb, &gc}, {0.25, 0.1, 0}, "impostor"));
      // KTX2 textures (KHR_texture_basisu, issue 32): a level, and levels under MSFT_lod.
      GltfOptions k;
      k.textures = GltfOptions::Textures::kKtx2;
      const std::vector<std::uint8_t> ka = encode_glb(a, k), kc = encode_glb(c, k);
      write_bytes_atomically(dir + "/torus_ktx2.glb", ka);
      write_bytes_atomically(dir + "/torus_ktx2_lods.glb", combine_lod_glb({&ka, &kc}, {0.1, 0}, "impostor"));
      // WebP textures (EXT_texture_webp, issue 32): a level, and levels under MSFT_lod.
      GltfOptions w;
      w.textures = GltfOptions::Textures::kWebp;
      const std::vector<std::uint8_t> wa = encode_glb(a, w), wc = encode_glb(c, w);
      write_bytes_atomically(dir + "/torus_webp.glb", wa);
      write_bytes_atomically(dir + "/torus_webp_lods.glb", combine_lod_glb({&wa, &wc}, {0.1, 0}, "impostor"));
    }
  }
  // A point impostor of a sampled mesh (COLOR_0 as 16-bit linear RGBA, mode POINTS).
  SampleOptions so;
  so.backend = "cpu";
  so.ldi_size = 64;
  SampleStats st;
  const PointSet sampled = sample_mesh(generate_mesh("sphere", 6), so, "sphere", &st);
  PointImpostorInfo info;
  info.pixel = st.pixel;
  const std::vector<std::uint8_t> points_glb = encode_point_glb(permuted(sampled, point_permutation(sampled.size(), 1)), info);
  write_bytes_atomically(dir + "/sphere_points.glb", points_glb);
  // A recommended chain's LOD file: a mesh LOD, then the point impostor.
  const std::vector<std::uint8_t> mesh_glb = encode_mesh_glb(generate_mesh("sphere", 6), true);
  write_bytes_atomically(dir + "/sphere_chain_lods.glb", combine_lod_glb({&mesh_glb, &points_glb}, {0.02, 0}, "chain"));
  // A vertex-clustering LOD with triangles, thick lines (_THICKNESS) and colours: a sphere with a
  // thin spike of two long triangles that collapses to an edge.
  TriangleMesh m = generate_mesh("sphere", 8);
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (Vec3f p : {Vec3f{1, 0, 0}, Vec3f{2, 0.01f, 0}, Vec3f{2, -0.01f, 0.01f}, Vec3f{1.02f, 0, 0.01f}}) {
    m.positions.push_back(p);
    m.colors.push_back({200, 30, 30});
  }
  m.triangles.push_back({base, base + 1, base + 2});
  m.triangles.push_back({base, base + 2, base + 3});
  ClusterOptions co;
  co.cell = 0.3f;
  const LodMesh lod = cluster_mesh(m, grade_vertices(m), co);
  write_bytes_atomically(dir + "/sphere_cluster.glb", encode_cluster_glb(lod));
  write_bytes_atomically(dir + "/sphere_cluster_draco.glb", encode_cluster_glb(lod, {}, true));  // KHR_draco_mesh_compression
  // Material channels (issue 31): an asset whose halves differ in metallic, roughness and emission
  // (metallicRoughness and emissive textures), and its level (ORM and emissive atlas textures).
  write_bytes_atomically(dir + "/plate_asset.glb", encode_textured_mesh_glb(generate_material_plate()));
  AssetOptions ao;
  ao.bake.primitives = {8};
  ao.sample.ldi_size = 96;
  ao.cheap_triangles = 0;  // a plate of a few triangles is cheap: baked all the same
  ao.mesh_lods = AssetOptions::MeshLods::kNone;
  const AssetBake plate = bake_asset(dir + "/plate_asset.glb", ao, "plate_asset.glb");
  if (plate.files.empty()) return std::fprintf(stderr, "the plate's bake wrote no level\n"), 1;
  write_bytes_atomically(dir + "/plate_level.glb", plate.files.front().bytes);
  // ... and in KTX2: its ORM (linear) and emissive (sRGB) textures too.
  ao.bake.gltf.textures = GltfOptions::Textures::kKtx2;
  const AssetBake plate_ktx2 = bake_asset(dir + "/plate_asset.glb", ao, "plate_asset.glb");
  if (plate_ktx2.files.empty()) return std::fprintf(stderr, "the plate's KTX2 bake wrote no level\n"), 1;
  write_bytes_atomically(dir + "/plate_level_ktx2.glb", plate_ktx2.files.front().bytes);
  // ... and in WebP: ORM lossless, emission as colour.
  ao.bake.gltf.textures = GltfOptions::Textures::kWebp;
  const AssetBake plate_webp = bake_asset(dir + "/plate_asset.glb", ao, "plate_asset.glb");
  if (plate_webp.files.empty()) return std::fprintf(stderr, "the plate's WebP bake wrote no level\n"), 1;
  write_bytes_atomically(dir + "/plate_level_webp.glb", plate_webp.files.front().bytes);
  return 0;
}
