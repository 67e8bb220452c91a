// Batch bakes for build farms (`qf-bake batch`): a manifest of assets (schemas/batch.schema.json),
// baked in parallel child processes, incrementally (an asset whose input bytes, settings and tool
// version are unchanged is skipped), optionally one shard of the manifest, with a JSON report.
//
// Each asset bakes in a forked child process: a crash or an out-of-memory kill fails that asset
// only, its peak memory is measured exactly (wait4), and the parent never runs OpenMP (a forked
// child of a process that did would hang in libgomp). Children die with the parent
// (PR_SET_PDEATHSIG), and each asset folder is built beside the old one and swapped in whole, under
// a lock (core/output_folder.h, pipeline/asset write_asset), so a killed batch leaves each asset
// folder either as it was or complete, and two batches never write one folder at once; the next
// run rebakes what is missing or stale.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "core/file_io.h"
#include "pipeline/asset.h"

namespace qf {

// An asset's state in a batch run. The report names it (asset_status_name): "pending" (never in a
// finished report), "baked", "up to date", "failed", "skipped" (not started after a failure),
// "would bake" (--dry-run).
enum class AssetStatus { kPending, kBaked, kUpToDate, kFailed, kSkipped, kWouldBake };
inline constexpr std::size_t kAssetStatusCount = 6;
const char* asset_status_name(AssetStatus s);
// The status a report names; kPending for a name that is none.
AssetStatus asset_status_from_name(const std::string& name);

struct BatchAsset {
  std::size_t index = 0;    // position in the manifest's list
  std::string name;         // its folder under the batch output (unique)
  std::string input;        // as the manifest writes it (named in the asset's manifest and report)
  std::string path;         // resolved against the manifest's folder
  nlohmann::json settings;  // the manifest's defaults overlaid by the asset's own: bake option -> value
                            // (part of the asset's key, as written)
  AssetOptions options;     // `settings` read (filled by the caller, with the bake command's readers)
};

struct BatchManifest {
  std::string path;
  std::string sha256;   // of the manifest file: shard reports of one manifest carry the same
  std::string output;   // resolved against the manifest's folder; empty when it names none
  std::vector<BatchAsset> assets;
};

// Reads and checks a batch manifest. Throws InputError("batch.*") naming the file, the JSON
// location (e.g. "assets[3].settings") and what was expected.
BatchManifest read_batch_manifest(const std::string& path);
// The same on the manifest file's bytes already in memory; `path` names it and resolves inputs.
BatchManifest parse_batch_manifest(ByteView bytes, const std::string& path);

struct BatchOptions {
  std::string output;          // root folder; asset A goes to OUTPUT/A
  int jobs = 1;                // assets baked at once
  int threads = 0;             // OpenMP threads per bake; 0 = cores / jobs (at least 1)
  int shard_index = 1, shard_count = 1;  // bake assets with manifest index % count == index - 1
  bool force = false;          // rebake even when up to date
  bool keep_going = false;     // after a failure, still start the remaining assets
  bool dry_run = false;        // say what would be baked, bake nothing
  std::string version;         // the tool's version: part of every asset's key
  bool eval = false;           // measure each level with `qf-render eval` (render_exe)
  int eval_views = 6;
  std::string render_exe;
  bool terminal = false;       // progress as one rewritten line (else one plain line per asset)
  bool quiet = false;          // no progress at all
};

// The manifest indices shard `index` of `count` bakes: every count-th asset, from index - 1.
std::vector<std::size_t> shard_assets(std::size_t assets, int index, int count);

// The asset's key: SHA-256 of the tool version, its input name, its settings, its input bytes and
// (when it has any) the names and bytes of the files it reads (io/model_io.h, input_dependencies).
// Throws InputError(file.unreadable) when the input cannot be read.
std::string asset_key(const BatchAsset& asset, const std::string& version);

// True when FOLDER/manifest.json carries `key` and every file it lists is there with its size.
bool asset_up_to_date(const std::string& folder, const std::string& key);

// Runs the batch; returns its report (schemas/batch-report.schema.json). Progress goes to `log`.
nlohmann::json run_batch(const BatchManifest& manifest, const BatchOptions& options, std::FILE* log);

// Joins shard reports of one manifest into one report. Throws UsageError when they come from
// different manifests or shardings, or name a shard twice.
nlohmann::json merge_batch_reports(const std::vector<nlohmann::json>& reports, const std::vector<std::string>& names);

// The exit code a report stands for: 0 when every asset it should have is baked or up to date
// (and no shard is missing), 1 otherwise.
int batch_exit_code(const nlohmann::json& report);

}  // namespace qf
