// The out-of-core bake's parts (pipeline/out_of_core.h): scratch files that go away, links that
// interpolate, textures streamed from the scratch file that equal the in-memory ones when the
// subsample is every point (whatever the batches), and a bake past --max-memory that runs out of
// core, deterministically at any thread count.
#include <gtest/gtest.h>
#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "amg/basis.h"
#include "pipeline/bake.h"
#include "pipeline/out_of_core.h"
#include "core/scratch.h"
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

// The pid of a process that has exited and been reaped: no process has it (for a while).
pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

// A kill -9 leaves a scratch file behind (no handler runs); the next scratch file made in that
// folder removes it, and leaves a live process' file alone.
TEST(OutOfCore, ScratchFilesOfDeadProcessesAreRemovedByTheNextRun) {
  const std::string dir = temp_folder("stale-scratch");
  const std::string dead = dir + "/qf-spill-" + std::to_string(dead_pid()) + "-AbC123.scratch";
  const std::string live = dir + "/qf-spill-" + std::to_string(::getppid()) + "-XyZ789.scratch";
  const std::string other = dir + "/notes-1-AbC123.scratch";
  for (const std::string& f : {dead, live, other}) std::ofstream(f) << "x";
  {
    ScratchFile f("test", dir);
    EXPECT_FALSE(std::filesystem::exists(dead));
    EXPECT_TRUE(std::filesystem::exists(live));
    EXPECT_TRUE(std::filesystem::exists(other));
    // A file of this process stays while it lives: the next one made here sees it live.
    ScratchFile g("test", dir);
    EXPECT_TRUE(std::filesystem::exists(f.path()));
  }
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
  StreamedPoints s = spill_points(blocks_of(input), {input.size(), input.size(), dir});
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
  StreamedPoints s = spill_points(blocks_of(input), {2000, input.size(), dir});
  EXPECT_EQ(s.subsample.size(), 2000u);
  EXPECT_DOUBLE_EQ(s.stride, 4.0);
  EXPECT_EQ(link_points(s), 0u);
  // Every tile's reach is about the subsample's spacing, far below the sphere's size.
  for (const StreamedPoints::Tile& t : s.tiles) {
    EXPECT_GT(t.reach, 0.0f);
    EXPECT_LT(t.reach, 0.1f * s.bounds.diagonal());
  }
  std::filesystem::remove_all(dir);
}

// The points read back from the scratch file's tiles, in file order.
std::vector<Vec3f> tile_positions(const StreamedPoints& s) {
  std::vector<Vec3f> out;
  for (const StreamedPoints::Tile& t : s.tiles) {
    std::vector<Vec3f> p(t.count);
    s.file->read(p.data(), p.size() * sizeof(Vec3f), t.offset);
    out.insert(out.end(), p.begin(), p.end());
  }
  return out;
}

// Blocks of `size` points (copies), as a reader hands them over.
PointBlocks blocks_of_size(const PointSet& points, std::size_t size) {
  return [&points, size](const std::function<void(PointSet&)>& each) {
    for (std::size_t first = 0; first < points.size(); first += size) {
      std::vector<std::uint32_t> part;
      for (std::size_t i = first; i < std::min(points.size(), first + size); ++i) part.push_back(static_cast<std::uint32_t>(i));
      PointSet b = permuted(points, part);
      each(b);
    }
  };
}

TEST(OutOfCore, SpillSortedOnDiskIsTheMortonOrderWhateverTheRunsAndBlocks) {
  // A shuffled set with coincident points (ties by arrival) and more points than a tile.
  PointSet input = generate_shape("sphere", {100000, 4});
  for (std::size_t i = 0; i < 5000; ++i) input.positions[i + 50000] = input.positions[i];
  const std::vector<Vec3f> expected = permuted(input, morton_order(input.positions)).positions;
  const std::string dir = temp_folder("sort");
  const StreamedPoints one = spill_points(blocks_of(input), {3000, input.size(), dir});
  EXPECT_TRUE(tile_positions(one) == expected);
  EXPECT_GT(one.tiles.size(), 1u);
  // Blocks of 777 points sorted in runs of about 10k, 7 points: the same tiles and subsample.
  for (std::size_t run : {std::size_t{10000}, std::size_t{7}}) {
    SCOPED_TRACE("runs of " + std::to_string(run));
    const StreamedPoints many = spill_points(blocks_of_size(input, 777), {3000, run, dir});
    EXPECT_TRUE(tile_positions(many) == expected);
    EXPECT_TRUE(many.subsample.positions == one.subsample.positions);
    EXPECT_TRUE(many.subsample.normals == one.subsample.normals);
    EXPECT_GT(many.scratch_peak, std::uint64_t{2} * input.size() * sizeof(Vec3f));
  }
  std::filesystem::remove_all(dir);
}

TEST(OutOfCore, OutliersAreJudgedOnTheSubsampleAndTheLinks) {
  // A sphere with 200 strays far out: the subsample's strays go, and every stray full point is
  // linked to nothing; factor 0 keeps them all.
  PointSet input = generate_shape("sphere", {40000, 6});
  for (std::size_t i = 0; i < 200; ++i) {
    const float a = 0.7f * float(i);
    input.positions[i * 199] = Vec3f{3.0f * std::cos(a), 3.0f * std::sin(a), 0.01f * float(i)};
  }
  const std::string dir = temp_folder("outliers");
  StreamedPoints s = spill_points(blocks_of(input), {10000, input.size(), dir});
  const std::size_t sub = s.subsample.size();
  const std::size_t gone = drop_subsample_outliers(s, 10.0f);
  EXPECT_GT(gone, 0u);
  EXPECT_LE(gone, 200u);
  EXPECT_EQ(s.subsample.size(), sub - gone);
  EXPECT_TRUE(std::isfinite(s.outlier_limit));
  EXPECT_EQ(link_points(s), 200u);
  StreamedPoints kept = spill_points(blocks_of(input), {10000, input.size(), dir});
  EXPECT_EQ(drop_subsample_outliers(kept, 0.0f), 0u);
  EXPECT_EQ(link_points(kept), 0u);
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
  // From a stream, as a reader hands the blocks over: the same bake (no outliers to drop).
  o.outlier_factor = 10;
  const BakeResult c = bake(blocks_of_size(input, 4321), a.memory, o, "torus");
  EXPECT_EQ(c.points, 40000u);
  EXPECT_EQ(c.dropped_outliers, 0u);
  ASSERT_EQ(c.levels.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_TRUE(c.levels[k].glb == a.levels[k].glb) << "level " << k << " differs from a stream";
  EXPECT_TRUE(std::filesystem::is_empty(o.scratch_dir)) << "the scratch file is left behind";
  std::filesystem::remove_all(o.scratch_dir);
}

}  // namespace
}  // namespace qf
