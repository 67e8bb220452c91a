// libFuzzer target: the batch manifest (parse_batch_manifest on the JSON bytes), then the shards it
// would be split into and the settings as the asset keys hash them.
#include <set>

#include "fuzz_common.h"
#include "pipeline/batch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/qf-fuzz/batch/manifest.json";
  try {
    const qf::BatchManifest m = qf::parse_batch_manifest(qf::fuzz::view(data, size), path);
    QF_FUZZ_CHECK(!m.assets.empty() && m.sha256.size() == 64);
    std::set<std::string> names;
    for (const qf::BatchAsset& a : m.assets) {
      QF_FUZZ_CHECK(!a.name.empty() && !a.path.empty() && names.insert(a.name).second);
      (void)a.settings.dump();
    }
    // Shards 1/3..3/3 cover every asset once.
    std::size_t covered = 0;
    for (int i = 1; i <= 3; ++i) covered += qf::shard_assets(m.assets.size(), i, 3).size();
    QF_FUZZ_CHECK(covered == m.assets.size());
  } catch (const qf::InputError& e) {
    QF_FUZZ_CHECK(e.code().rfind("batch.", 0) == 0 && e.file() == path);
  }
  return 0;
}
