// libFuzzer target: the glTF 2.0 reader (decode_gltf, baker/io/gltf_read.cpp) on the bytes as
// "fuzz.glb" when they start like a binary glTF ('g' of the "glTF" magic), else as "fuzz.gltf";
// then the mesh's invariants, its materials' and texture coordinates' included. The bytes are
// read from memory; the path puts the model in an empty folder of its own ($QF_FUZZ_SCRATCH from
// scripts/fuzz.sh, else one under /dev/shm), so external buffer and image URIs name files that
// are not there (the "missing file" answers), not whatever lies in the working folder.
// Mutations: gltf_mutator.h (structural, one time in four). Built with QF_FUZZ_CANARY (the target
// fuzz_gltf_canary, test-only) it also replays 0.8.0's two stack overflows (gltf_canary.h).
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "fuzz_common.h"
#include "gltf_mutator.h"
#ifdef QF_FUZZ_CANARY
#include "gltf_canary.h"
#endif

namespace {

std::string scratch_dir;
void remove_scratch() {
  std::error_code ec;
  std::filesystem::remove_all(scratch_dir, ec);
}
std::string model_folder() {
  const char* given = std::getenv("QF_FUZZ_SCRATCH");
  if (given && *given) {
    std::filesystem::create_directories(given);
    return given;
  }
  const char* base = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
  scratch_dir = std::string(base) + "/qf-fuzz-gltf-" + std::to_string(::getpid());
  std::filesystem::create_directories(scratch_dir);
  std::atexit(remove_scratch);
  return scratch_dir;
}

void check_materials(const qf::TriangleMesh& m) {
  QF_FUZZ_CHECK(m.triangle_materials.empty() || m.triangle_materials.size() == m.triangles.size());
  for (std::uint32_t i : m.triangle_materials) QF_FUZZ_CHECK(i < m.materials.size());
  QF_FUZZ_CHECK(m.corner_uvs.empty() || m.corner_uvs.size() == m.triangles.size());
  for (const qf::SurfaceMaterial& s : m.materials) {
    QF_FUZZ_CHECK(s.texture < static_cast<int>(m.textures.size()));
    for (float c : s.base_color) QF_FUZZ_CHECK(std::isfinite(c));
  }
  for (const qf::TextureImage& t : m.textures)
    QF_FUZZ_CHECK(t.width > 0 && t.height > 0 && t.rgba.size() == std::size_t(t.width) * std::size_t(t.height) * 4);
}

// Reads the bytes as a .glb or .gltf and checks the mesh; a file with non-finite positions is
// read again dropping them, as --drop-nonfinite does. Returns the reader's error code, "" when it
// read the file. InputError is the expected answer to a bad file; anything else escapes.
std::string read_and_check(const std::uint8_t* data, std::size_t size, const std::string& path) {
  qf::ReadOptions options;
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      const qf::TriangleMesh m = qf::decode_gltf(qf::fuzz::view(data, size), path, options);
      qf::fuzz::check_mesh(m);
      check_materials(m);
      return "";
    } catch (const qf::InputError& e) {
      QF_FUZZ_CHECK(!e.code().empty() && e.file() == path);
      if (e.code() != "gltf.nonfinite") return e.code();
      options.drop_nonfinite = true;
    }
  }
  QF_FUZZ_CHECK(!"a file read with drop_nonfinite still reports a non-finite coordinate");
  return "";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string folder = model_folder(), glb = folder + "/fuzz.glb", gltf = folder + "/fuzz.gltf";
  const std::string code = read_and_check(data, size, size > 0 && data[0] == 'g' ? glb : gltf);
#ifdef QF_FUZZ_CANARY
  qf::fuzz::canary::check(data, size, code);
#else
  (void)code;
#endif
  return 0;
}

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size, unsigned int seed) {
  return qf::fuzz::mutate_gltf(data, size, max_size, seed);
}
