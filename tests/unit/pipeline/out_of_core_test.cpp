// The out-of-core bake's parts (pipeline/out_of_core.h): scratch files that go away, links that
// interpolate, textures streamed from the scratch file that equal the in-memory ones when the
// subsample is every point (whatever the batches), and a bake past --max-memory that runs out of
// core, deterministically at any thread count.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "amg/basis.h"
#include "pipeline/bake.h"
#include "pipeline/out_of_core.h"
#include "shapes/shapes.h"

namespace qf {
namespace {

std::string temp_folder(const std::string& name) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("qf_ooc_" + name + "_" + std::to_string(::getpid()))).string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(OutOfCore, ScratchFileRoundTripsAndIsRemoved) {
  const std::string dir = temp_folder("scratch");
  std::string path;
  {
    ScratchFile f("test", dir);
    path = f.path();
    EXPECT_TRUE(std::filesystem::exists(path));
    EXPECT_NE(path.find("qf-test-"), std::string::npos) << path;
    const int a[3] = {1, 2, 3}, b[2] = {7, 8};
    EXPECT_EQ(f.append(a, sizeof a), 0u);
    EXPECT_EQ(f.append(b, sizeof b), sizeof a);
    EXPECT_EQ(f.size(), sizeof a + sizeof b);
    int back[2] = {0, 0};
    f.read(back, sizeof back, sizeof a);
    EXPECT_EQ(back[0], 7);
    EXPECT_EQ(back[1], 8);
    EXPECT_THROW(f.read(back, sizeof back, f.size()), std::runtime_error);
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_THROW(ScratchFile("test", dir + "/missing"), std::runtime_error);
  std::filesystem::remove_all(dir);
}

// A level of a torus decomposed in memory, and its textures as the in-memory bake makes them.
struct Level {
  PointSet sorted;
  SparseMatrix psi;
  Domains d;
  std::vector<SupportRect> rects;
  std::vector<Texture> textures;
};

Level in_memory_level(const PointSet& input, std::size_t quads) {
  Level l;
  l.sorted = permuted(input, morton_order(input.positions));
  std::string state;
  const AmgHierarchy h = cached_hierarchy(l.sorted, {}, {}, "", state);
  l.psi = basis_at_level(h, level_by_primitives(h, quads));
  l.d = make_domains(l.psi);
  l.rects = support_rectangles(l.sorted.positions, l.sorted.normals, l.sorted.radii, l.psi, l.d);
  const SparseMatrix alpha = domain_partition(l.psi, l.d);
  for (const SupportRect& r : l.rects)
    l.textures.push_back(resample_texture(l.sorted.positions, l.sorted.colors, l.sorted.normals, l.sorted.radii, alpha, l.d, r));
  return l;
}

int largest_difference(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  if (a.size() != b.size()) return 256;
  int most = 0;
  for (std::size_t i = 0; i < a.size(); ++i) most = std::max(most, std::abs(int(a[i]) - int(b[i])));
  return most;
}

TEST(OutOfCore, EveryPointAsSubsampleGivesTheInMemoryTextures) {
  const PointSet input = generate_shape("torus", {6000, 3});
  const Level l = in_memory_level(input, 30);
  const std::string dir = temp_folder("textures");
  StreamedPoints s = spill_points(input, morton_order(input.positions), input.size(), dir);
  ASSERT_EQ(s.subsample.size(), input.size());
  EXPECT_TRUE(s.subsample.positions == l.sorted.positions);
  EXPECT_GT(s.tiles.size(), 0u);
  link_points(s);
  for (std::size_t batch : {std::size_t{1} << 30, std::size_t{1}}) {  // one batch, and one quad a batch
    SCOPED_TRACE("batch " + std::to_string(batch));
    std::size_t batches = 0;
    std::vector<SupportRect> rects = l.rects;
    const std::vector<Texture> t = streamed_textures(s, s.subsample.normals, l.psi, l.d, rects, {}, {}, {}, batch, &batches);
    // The rectangles remade from every point are the in-memory ones.
    for (std::size_t q = 0; q < rects.size(); ++q) {
      EXPECT_EQ(rects[q].domain, l.rects[q].domain);
      EXPECT_EQ(rects[q].points, l.rects[q].points);
      EXPECT_NEAR(rects[q].half_u, l.rects[q].half_u, 1e-5f);
      EXPECT_NEAR(rects[q].half_v, l.rects[q].half_v, 1e-5f);
      EXPECT_NEAR(length(rects[q].center - l.rects[q].center), 0.0f, 1e-5f);
    }
    EXPECT_EQ(batches, batch > 6000 ? 1u : l.rects.size());
    ASSERT_EQ(t.size(), l.textures.size());
    for (std::size_t q = 0; q < t.size(); ++q) {
      ASSERT_EQ(t[q].width, l.textures[q].width);
      ASSERT_EQ(t[q].height, l.textures[q].height);
      // The alpha renormalisation may sum in another order: a byte at most.
      EXPECT_LE(largest_difference(t[q].rgba, l.textures[q].rgba), 1) << "quad " << q;
      EXPECT_LE(largest_difference(t[q].normals, l.textures[q].normals), 1) << "quad " << q;
    }
  }
  const std::string path = s.file->path();
  s = StreamedPoints();
  EXPECT_FALSE(std::filesystem::exists(path));
  std::filesystem::remove_all(dir);
}

TEST(OutOfCore, SubsampleIsEvenAndLinksInterpolate) {
  const PointSet input = generate_shape("sphere", {8000, 2});
  const std::string dir = temp_folder("links");
  StreamedPoints s = spill_points(input, morton_order(input.positions), 2000, dir);
  EXPECT_EQ(s.subsample.size(), 2000u);
  EXPECT_DOUBLE_EQ(s.stride, 4.0);
  link_points(s);
  // Every tile's reach is about the subsample's spacing, far below the sphere's size.
  for (const StreamedPoints::Tile& t : s.tiles) {
    EXPECT_GT(t.reach, 0.0f);
    EXPECT_LT(t.reach, 0.1f * s.bounds.diagonal());
  }
  std::filesystem::remove_all(dir);
}

TEST(OutOfCore, BakePastTheLimitRunsOutOfCoreAndIsDeterministic) {
  // 40000 points need ~418 MB estimated; 400 MB leaves the subsample ~13k points.
  const PointSet input = generate_shape("torus", {40000, 5});
  BakeOptions o;
  o.primitives = {100, 30};
  o.amg.target_sizes = {100, 30};
  o.max_memory = std::size_t{400} << 20;
  o.scratch_dir = temp_folder("bake");
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const BakeResult a = bake(input, o, "torus");
  omp_set_num_threads(std::max(2, threads));
  const BakeResult b = bake(input, o, "torus");
  BakeOptions whole = o;
  whole.max_memory = std::size_t{1} << 40;
  const BakeResult m = bake(input, whole, "torus");
  omp_set_num_threads(threads);
  EXPECT_FALSE(m.memory.out_of_core);
  ASSERT_EQ(m.levels.size(), 2u);
  EXPECT_TRUE(a.memory.out_of_core);
  EXPECT_GT(a.memory.subsample, 10000u);
  EXPECT_LT(a.memory.subsample, 20000u);
  EXPECT_GT(a.scratch_bytes, 40000u * 31);
  EXPECT_EQ(a.points, 40000u);
  ASSERT_EQ(a.levels.size(), 2u);
  ASSERT_EQ(b.levels.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    // Both aimed at the counts: within 5% of each other.
    EXPECT_NEAR(double(a.levels[k].primitives), double(m.levels[k].primitives), 0.05 * double(m.levels[k].primitives));
    EXPECT_TRUE(a.levels[k].glb == b.levels[k].glb) << "level " << k << " differs between 1 and 2 threads";
  }
  EXPECT_TRUE(std::filesystem::is_empty(o.scratch_dir)) << "the scratch file is left behind";
  std::filesystem::remove_all(o.scratch_dir);
}

}  // namespace
}  // namespace qf
