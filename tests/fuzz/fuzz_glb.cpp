// libFuzzer target: the runtime's .glb loader, load_baked (runtime_gl/loader.h) as qf-render and
// qf-diff use it, then the scene's invariants (vertex arrays, items within them, neighbours in range).
// The loader reads only from a path (tinygltf's LoadBinaryFromFile, chosen by the ".glb" name), so each
// input is written to a file in a private folder under /dev/shm (memory, not disk) first.
// Mutations: gltf_mutator.h (structural changes to the JSON chunk, its lengths rewritten).
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "fuzz_common.h"
#include "gltf_mutator.h"
#include "runtime_gl/loader.h"

namespace {

// The folder: $QF_FUZZ_SCRATCH (scripts/fuzz.sh makes one and removes it), else a folder of this
// process under /dev/shm, removed at exit.
std::string scratch_dir;
void remove_scratch() {
  std::error_code ec;
  std::filesystem::remove_all(scratch_dir, ec);
}
std::string scratch_file() {
  const char* given = std::getenv("QF_FUZZ_SCRATCH");
  if (given && *given) {
    std::filesystem::create_directories(given);
    return std::string(given) + "/input.glb";
  }
  const char* base = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
  scratch_dir = std::string(base) + "/qf-fuzz-glb-" + std::to_string(::getpid());
  std::filesystem::create_directories(scratch_dir);
  std::atexit(remove_scratch);
  return scratch_dir + "/input.glb";
}

void check_impostor(const qf::render::ImpostorScene& s) {
  const std::size_t vertices = s.positions.size() / 3;
  QF_FUZZ_CHECK(s.positions.size() % 3 == 0);
  QF_FUZZ_CHECK(s.normals.empty() || s.normals.size() == s.positions.size());
  QF_FUZZ_CHECK(s.uvs.empty() || s.uvs.size() == 2 * vertices);
  for (const qf::render::Item& it : s.items) {
    QF_FUZZ_CHECK(std::uint64_t{it.first_vertex} + it.vertex_count <= vertices);
    QF_FUZZ_CHECK(it.texture < s.textures.size() || s.textures.empty());
  }
  for (const qf::render::Image& im : s.textures)
    QF_FUZZ_CHECK(im.width >= 0 && im.height >= 0 &&
                  im.rgba.size() == 4 * static_cast<std::size_t>(im.width) * static_cast<std::size_t>(im.height));
  if (!s.offsets.empty()) {
    QF_FUZZ_CHECK(s.offsets.size() == s.items.size() + 1 && s.offsets.back() == s.neighbors.size());
    for (std::uint32_t n : s.neighbors) QF_FUZZ_CHECK(n < s.items.size());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = scratch_file();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const qf::render::BakedScene s = qf::render::load_baked(path);
    if (s.kind == qf::render::BakedScene::kImpostor) check_impostor(s.impostor);
    if (s.kind == qf::render::BakedScene::kPoints) {
      const auto& p = s.points;
      QF_FUZZ_CHECK(p.normals.empty() || p.normals.size() == p.positions.size());
      QF_FUZZ_CHECK(p.colors.empty() || p.colors.size() == p.positions.size());
    }
    if (s.kind == qf::render::BakedScene::kCluster) {
      const auto& c = s.cluster;
      QF_FUZZ_CHECK(c.line_positions.size() % 2 == 0);
      QF_FUZZ_CHECK(c.line_colors.empty() || c.line_colors.size() == c.line_positions.size());
      QF_FUZZ_CHECK(c.thickness.empty() || 2 * c.thickness.size() == c.line_positions.size());
      QF_FUZZ_CHECK(c.mesh.indices.size() % 3 == 0);
      for (std::uint32_t i : c.mesh.indices) QF_FUZZ_CHECK(i < c.mesh.positions.size());
    }
  } catch (const qf::InputError& e) {
    QF_FUZZ_CHECK(e.file() == path);
  }
  return 0;
}

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size, unsigned int seed) {
  return qf::fuzz::mutate_gltf(data, size, max_size, seed);
}
