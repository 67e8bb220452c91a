// The batch report (schemas/batch-report.schema.json): a run's, its totals and summary, the join
// of shard reports, and the exit code a report stands for.
#include <algorithm>
#include <set>

#include "core/error.h"
#include "core/file_io.h"
#include "pipeline/batch_parts.h"

namespace qf {
namespace {

using batch::Json;

constexpr const char* kStatusNames[kAssetStatusCount] = {"pending", "baked", "up to date", "failed", "skipped", "would bake"};

// Counts, primitives, texels, bytes and the summed asset time of report entries (which carry
// "status"). bytes: all the assets wrote; chain_bytes: what the recommended chains ship, of the
// assets that have one.
Json totals_of(const Json& assets) {
  std::array<std::size_t, kAssetStatusCount> counts{};
  std::size_t primitives = 0, texels = 0, bytes = 0, chain_bytes = 0;
  double seconds = 0;
  for (const Json& e : assets) {
    ++counts[static_cast<std::size_t>(asset_status_from_name(e.value("status", std::string())))];
    if (e.contains("primitives")) primitives += e["primitives"].get<std::size_t>();
    if (e.contains("texels")) texels += e["texels"].get<std::size_t>();
    if (e.contains("bytes")) bytes += e["bytes"].get<std::size_t>();
    if (e.contains("chain_bytes")) chain_bytes += e["chain_bytes"].get<std::size_t>();
    if (e.contains("seconds")) seconds += e["seconds"].get<double>();
  }
  Json t{{"assets", assets.size()}, {"primitives", primitives}, {"texels", texels}, {"bytes", bytes},
         {"chain_bytes", chain_bytes}, {"asset_seconds", round_to(seconds, 3)}};
  for (AssetStatus s : {AssetStatus::kBaked, AssetStatus::kUpToDate, AssetStatus::kFailed, AssetStatus::kSkipped, AssetStatus::kWouldBake})
    t[asset_status_name(s)] = counts[static_cast<std::size_t>(s)];
  return t;
}

}  // namespace

const char* asset_status_name(AssetStatus s) { return kStatusNames[static_cast<std::size_t>(s)]; }

AssetStatus asset_status_from_name(const std::string& name) {
  for (std::size_t i = 0; i < kAssetStatusCount; ++i)
    if (name == kStatusNames[i]) return static_cast<AssetStatus>(i);
  return AssetStatus::kPending;
}

namespace batch {

Json batch_report(const BatchManifest& m, const BatchOptions& o, const BatchState& state, int threads, double seconds) {
  Json entries = state.entries;
  for (std::size_t i = 0; i < entries.size(); ++i) entries[i]["status"] = asset_status_name(state.status[i]);
  Json report{{"manifest", m.path},
              {"manifest_sha256", m.sha256},
              {"output", o.output},
              {"tool_version", o.version},
              {"shard", {{"index", o.shard_index}, {"count", o.shard_count}}},
              {"shards", Json::array({o.shard_index})},
              {"jobs", o.jobs},
              {"threads_per_job", threads},
              {"force", o.force},
              {"keep_going", o.keep_going},
              {"assets", entries},
              {"totals", totals_of(entries)},
              {"seconds", round_to(seconds, 3)}};
  return report;
}

void print_summary(std::FILE* log, const Json& report, const BatchOptions& o) {
  if (o.quiet || !log) return;
  const Json& t = report["totals"];
  std::fprintf(log, "qf-bake batch: %zu asset(s)%s: %zu baked, %zu up to date, %zu failed, %zu skipped in %.2f s\n",
               report["assets"].size(),
               o.shard_count > 1 ? (" (shard " + std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count) + ")").c_str() : "",
               t["baked"].get<std::size_t>(), t["up to date"].get<std::size_t>(), t["failed"].get<std::size_t>(),
               t["skipped"].get<std::size_t>(), report["seconds"].get<double>());
  for (const Json& e : report["assets"])
    if (e["status"] == "failed")
      std::fprintf(log, "qf-bake batch: FAILED %s: %s\n", e["name"].get<std::string>().c_str(), e["error"]["message"].get<std::string>().c_str());
  for (const Json& e : report["assets"])
    if (e["status"] == "would bake") std::fprintf(log, "qf-bake batch: would bake %s\n", e["name"].get<std::string>().c_str());
}

}  // namespace batch

Json merge_batch_reports(const std::vector<Json>& reports, const std::vector<std::string>& names) {
  if (reports.empty()) throw UsageError("merge-reports needs at least one report");
  const Json& first = reports[0];
  Json assets = Json::array();
  std::set<long long> shards;
  std::set<std::size_t> indices;
  double seconds = 0;
  for (std::size_t r = 0; r < reports.size(); ++r) {
    const Json& rep = reports[r];
    if (!rep.is_object() || !rep.contains("assets") || !rep.contains("shard") || !rep.contains("shards"))
      throw UsageError(names[r] + ": not a qf-bake batch report");
    if (rep["manifest_sha256"] != first["manifest_sha256"])
      throw UsageError(names[r] + ": a report of another manifest (or another version of it) than " + names[0]);
    if (rep["shard"]["count"] != first["shard"]["count"])
      throw UsageError(names[r] + ": sharded " + rep["shard"]["count"].dump() + " ways, " + names[0] + " " + first["shard"]["count"].dump());
    for (const Json& s : rep["shards"])
      if (!shards.insert(s.get<long long>()).second) throw UsageError(names[r] + ": shard " + s.dump() + " is in two reports");
    for (const Json& e : rep["assets"]) {
      if (!indices.insert(e["index"].get<std::size_t>()).second)
        throw UsageError(names[r] + ": asset " + e["name"].get<std::string>() + " is in two reports");
      assets.push_back(e);
    }
    seconds = std::max(seconds, rep["seconds"].get<double>());
  }
  std::stable_sort(assets.begin(), assets.end(), [](const Json& a, const Json& b) { return a["index"] < b["index"]; });
  Json missing = Json::array();
  const long long count = first["shard"]["count"].get<long long>();
  for (long long s = 1; s <= count; ++s)
    if (!shards.count(s)) missing.push_back(s);
  Json out = first;
  out.erase("shard");
  out["shard"] = {{"index", 0}, {"count", count}};
  out["shards"] = Json(std::vector<long long>(shards.begin(), shards.end()));
  out["missing_shards"] = missing;
  out["assets"] = assets;
  out["totals"] = totals_of(assets);
  out["seconds"] = seconds;  // the slowest shard: the wall time when they ran side by side
  return out;
}

int batch_exit_code(const Json& report) {
  if (report.contains("missing_shards") && !report["missing_shards"].empty()) return 1;
  for (const Json& e : report["assets"]) {
    const AssetStatus s = asset_status_from_name(e.value("status", std::string()));
    if (s != AssetStatus::kBaked && s != AssetStatus::kUpToDate && s != AssetStatus::kWouldBake) return 1;
  }
  return 0;
}

}  // namespace qf
