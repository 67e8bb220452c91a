// The parts of a batch run (pipeline/batch.h) shared between its files, not part of its interface:
// batch.cpp (keys, the child's bake, run_batch's steps), batch_scheduler.cpp (fork, poll,
// progress) and batch_report.cpp (the report, its totals and summary).
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <cstdio>
#include <deque>
#include <string>
#include <vector>

#include "pipeline/batch.h"

namespace qf::batch {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

inline double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The progress display: one rewritten line on a terminal, else one line per finished asset.
class Progress {
 public:
  Progress(std::FILE* out, const BatchOptions& o, std::size_t total) : out_(out), o_(o), total_(total), start_(Clock::now()) {}
  void finished(const Json& entry, AssetStatus status, std::size_t done);
  void line(std::size_t done, const std::array<std::size_t, kAssetStatusCount>& counts, const std::vector<std::string>& running);
  void end();

 private:
  std::FILE* out_;
  const BatchOptions& o_;
  std::size_t total_;
  Clock::time_point start_;
};

// What a run knows of the assets of its shard, in manifest order: their report entries (without
// "status", added by the report), statuses and keys.
struct BatchState {
  Json entries = Json::array();
  std::vector<AssetStatus> status;
  std::vector<std::string> keys;
  std::array<std::size_t, kAssetStatusCount> counts{};
  std::size_t done = 0;
  // Entry i's status is final: counts it and tells the progress display.
  void settle(std::size_t i, AssetStatus s, Progress& progress);
};

// The child's work: bake, write, and the figures the report needs (or the error, classified as
// the command line classifies it). Returns the child's exit code.
int bake_in_child(const BatchAsset& a, const std::string& key, const BatchOptions& o, Json& result);

// Bakes the entries of `queue` in child processes, `o.jobs` at a time, each with `threads` OpenMP
// threads; after a failure (without keep_going) the rest of the queue is skipped.
void bake_queue(const BatchManifest& m, const std::vector<std::size_t>& selected, std::deque<std::size_t> queue,
                const BatchOptions& o, int threads, BatchState& state, Progress& progress);

// The report of a run (schemas/batch-report.schema.json), and its summary lines on `log`.
Json batch_report(const BatchManifest& m, const BatchOptions& o, const BatchState& state, int threads, double seconds);
void print_summary(std::FILE* log, const Json& report, const BatchOptions& o);

}  // namespace qf::batch
