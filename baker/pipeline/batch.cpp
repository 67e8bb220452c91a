// Batch bakes: the per-asset keys, one asset's bake in its child process, and run_batch's steps
// (the manifest is read in batch_manifest.cpp, the children run by batch_scheduler.cpp, the report
// made in batch_report.cpp).
#include "pipeline/batch.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <system_error>
#include <thread>

#include "core/error.h"
#include "core/file_io.h"
#include "core/hash.h"
#include "gltf/png.h"
#include "io/model_io.h"
#include "pipeline/batch_parts.h"

extern char** environ;

namespace qf {

using batch::Clock;
using batch::Json;
using batch::since;

std::string asset_key(const BatchAsset& a, const std::string& version) {
  const InputFile file(a.path);
  Sha256 h;
  // Json objects iterate their keys in sorted order: the same settings always dump the same.
  h.update_field("quasiflat asset key 1").update_field(version).update_field(a.input).update_field(a.settings.dump());
  h.update(file.bytes());
  // The files the input reads (a glTF's buffers and images, an OBJ's MTL and textures): a changed
  // texture is a changed asset. Added only when there are any, so other inputs keep their keys. A
  // missing one is marked, not an error here: the bake then reports it as the reader words it.
  for (const InputDependency& d : input_dependencies(a.path)) {
    h.update_field("dependency").update_field(d.name);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(d.path, ec)) {
      h.update_field("missing");
      continue;
    }
    const InputFile dep(d.path);
    h.value(static_cast<std::uint64_t>(dep.bytes().size())).update(dep.bytes());
  }
  return h.hex();
}

bool asset_up_to_date(const std::string& folder, const std::string& key) {
  const Json m = read_asset_manifest(folder);
  return m.is_object() && m.contains("batch_key") && m["batch_key"] == key && listed_files_present(folder, m);
}

namespace {

// Runs `argv` and returns its standard output (empty, with `status` non-zero, on failure).
std::string run_capture(const std::vector<std::string>& argv, int& status) {
  status = -1;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return "";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int err = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  std::string out;
  if (err == 0) {
    char buf[65536];
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) != 0;) {
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) break;
      out.append(buf, static_cast<std::size_t>(n));
    }
    int ws = 0;
    while (::waitpid(pid, &ws, 0) < 0 && errno == EINTR) {
    }
    status = WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws);
  }
  ::close(fds[0]);
  return out;
}

// `qf-render eval` of every level against the asset's input.
Json evaluate_levels(const BatchAsset& a, const std::string& folder, const Json& levels, const BatchOptions& o) {
  Json out = Json::array();
  for (const Json& l : levels) {
    int status = 0;
    const std::string text = run_capture({o.render_exe, "eval", a.path, folder + "/" + l["file"].get<std::string>(), "--views",
                                          std::to_string(o.eval_views), "--no-engine"},
                                         status);
    const Json r = Json::parse(text, nullptr, false);
    Json e{{"level", l["level"]}};
    if (status != 0 || !r.is_object() || !r.contains("mean") || !r["mean"].is_object() || r["mean"].empty()) {
      e["error"] = o.render_exe + " eval exited with status " + std::to_string(status);
    } else {
      const Json& m = r["mean"].begin().value();
      e["method"] = r["mean"].begin().key();
      for (const char* k : {"psnr", "iou", "holes", "see_through"}) e[k] = m[k];
    }
    out.push_back(e);
  }
  return out;
}

// True for a name that OUTDIR/NAME would share with the batch's report or its page
// ("batch-report.json", "batch-report-2-of-4.html"): the asset's folder would take the report's place.
bool names_a_batch_file(const std::string& name) {
  const std::string head = "batch-report";
  if (name.compare(0, head.size(), head) != 0) return false;
  std::string rest = name.substr(head.size());
  for (const char* ext : {".json", ".html"})
    if (rest.size() >= 5 && rest.compare(rest.size() - 5, 5, ext) == 0) {
      rest.resize(rest.size() - 5);
      unsigned i = 0, n = 0;
      char extra = 0;
      return rest.empty() || std::sscanf(rest.c_str(), "-%u-of-%u%c", &i, &n, &extra) == 2;
    }
  return false;
}

// Step 1 of run_batch: every selected asset's key, and whether it is up to date (cheap, in this
// process: a hash of the input, one small JSON). Returns the entries left to bake.
std::deque<std::size_t> check_assets(const BatchManifest& m, const std::vector<std::size_t>& selected, const BatchOptions& o,
                                     batch::BatchState& state, batch::Progress& progress) {
  std::deque<std::size_t> queue;  // manifest order
  for (std::size_t i = 0; i < selected.size(); ++i) {
    const BatchAsset& a = m.assets[selected[i]];
    const auto t = Clock::now();
    state.entries.push_back({{"index", a.index}, {"name", a.name}, {"input", a.input}});
    // Whatever is wrong with one asset (unreadable, a folder, an input the bake cannot read, a name
    // the batch's own files take) fails that asset, in the report; the batch goes on.
    try {
      if (names_a_batch_file(a.name))
        throw InputError("batch.name", m.path, "assets[" + std::to_string(a.index) + "]",
                         "'" + a.name + "' is the name of the batch's own report; give the asset another \"name\"");
      state.keys[i] = asset_key(a, o.version);
    } catch (const std::exception&) {
      const ErrorOutcome e = current_error_outcome();
      state.entries[i]["exit_code"] = static_cast<int>(e.exit);
      state.entries[i]["error"] = {{"code", e.code}, {"message", e.message}};
      state.settle(i, AssetStatus::kFailed, progress);
      continue;
    }
    state.entries[i]["key"] = state.keys[i];
    if (!o.force && asset_up_to_date(o.output + "/" + a.name, state.keys[i])) {
      // A bake killed after its swap leaves a complete folder, and beside it its lock file and the
      // old content it was removing: taking the lock a moment removes them (a folder another run
      // is writing now is left to it).
      try {
        const OutputFolder tidy(o.output + "/" + a.name);
      } catch (const std::exception&) {
      }
      state.entries[i]["seconds"] = round_to(since(t), 6);
      // Its bytes as a baked asset's, so that the totals weigh the whole output folder.
      const OutputBytes bytes = output_bytes(read_asset_manifest(o.output + "/" + a.name));
      state.entries[i]["bytes"] = bytes.written;
      if (bytes.chain) state.entries[i]["chain_bytes"] = *bytes.chain;
      state.settle(i, AssetStatus::kUpToDate, progress);
    } else if (o.dry_run) {
      state.settle(i, AssetStatus::kWouldBake, progress);
    } else {
      queue.push_back(i);
    }
  }
  return queue;
}

}  // namespace

namespace batch {

int bake_in_child(const BatchAsset& a, const std::string& key, const BatchOptions& o, Json& result) {
  try {
    const std::string folder = o.output + "/" + a.name;
    OutputFolder out(folder);  // before the bake: another batch baking this asset now is refused at once
    AssetBake b = bake_asset(a.path, a.options, a.input);
    b.manifest["batch_key"] = key;
    write_asset(out, b.files, b.manifest, b.report, b.page);
    const OutputBytes bytes = output_bytes(read_asset_manifest(folder));  // as written, with its "files"
    result = {{"points", b.result.points},
              {"cache", b.result.cache},
              {"levels", b.manifest["levels"]},
              {"files", b.files.size() + 2},
              {"warnings", b.result.warnings},
              {"bytes", bytes.written}};
    if (bytes.chain) result["chain_bytes"] = *bytes.chain;
    if (!b.sampled.backend.empty()) result["sampler"] = b.sampled.backend;
    if (o.eval) result["eval"] = evaluate_levels(a, folder, b.manifest["levels"], o);
    return 0;
  } catch (const std::exception&) {
    const ErrorOutcome e = current_error_outcome();  // as the command line reports it
    result = {{"error", {{"code", e.code}, {"message", e.message}}}};
    return static_cast<int>(e.exit);
  }
}

}  // namespace batch

Json run_batch(const BatchManifest& m, const BatchOptions& o, std::FILE* log) {
  const auto start = Clock::now();
  const std::vector<std::size_t> selected = shard_assets(m.assets.size(), o.shard_index, o.shard_count);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = o.threads > 0 ? o.threads : std::max(1, cores / std::max(1, o.jobs));
  batch::BatchState state;
  state.status.assign(selected.size(), AssetStatus::kPending);
  state.keys.resize(selected.size());
  batch::Progress progress(log, o, selected.size());
  // 1. Keys and the up-to-date check.
  std::deque<std::size_t> queue = check_assets(m, selected, o, state, progress);
  // 2. Bake the rest, `jobs` children at a time.
  if (!queue.empty()) {
    std::filesystem::create_directories(o.output);
    // Loaded once here, not 0.35 s in every child (a failure shows in each asset's error).
    try {
      preload_png_encoder();
    } catch (const std::exception&) {
    }
  }
  batch::bake_queue(m, selected, std::move(queue), o, threads, state, progress);
  // 3. The report.
  const Json report = batch::batch_report(m, o, state, threads, since(start));
  batch::print_summary(log, report, o);
  return report;
}

}  // namespace qf
