// Batch bakes: the per-asset keys, the scheduler of child processes, the report (the manifest
// itself is read in batch_manifest.cpp).
#include "pipeline/batch.h"

#include <fcntl.h>
#include <omp.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include "core/error.h"
#include "core/file_io.h"
#include "core/hash.h"
#include "gltf/png.h"

extern char** environ;

namespace qf {
namespace {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

std::string asset_key(const BatchAsset& a, const std::string& version) {
  const InputFile file(a.path);
  Sha256 h;
  // Json objects iterate their keys in sorted order: the same settings always dump the same.
  h.update_field("quasiflat asset key 1").update_field(version).update_field(a.input).update_field(a.settings.dump());
  return h.update(file.bytes()).hex();
}

bool asset_up_to_date(const std::string& folder, const std::string& key) {
  const Json m = read_asset_manifest(folder);
  return m.is_object() && m.contains("batch_key") && m["batch_key"] == key && listed_files_present(folder, m);
}

namespace {

// --- one asset, in its child process ------------------------------------------------------------

void write_all(int fd, const std::string& s) {
  std::size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

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

// The child's work: bake, write, and the figures the report needs. Returns the exit code.
int bake_in_child(const BatchAsset& a, const std::string& key, const BatchOptions& o, Json& result) {
  try {
    const std::string folder = o.output + "/" + a.name;
    AssetBake b = bake_asset(a.path, a.options, a.input);
    b.manifest["batch_key"] = key;
    write_asset(folder, b.files, b.manifest, b.report);
    result = {{"points", b.result.points},
              {"cache", b.result.cache},
              {"levels", b.manifest["levels"]},
              {"files", b.files.size() + 2},
              {"warnings", b.result.warnings}};
    if (!b.sampled.backend.empty()) result["sampler"] = b.sampled.backend;
    if (o.eval) result["eval"] = evaluate_levels(a, folder, b.manifest["levels"], o);
    return 0;
  } catch (const std::exception&) {
    const ErrorOutcome e = current_error_outcome();  // as the command line reports it
    result = {{"error", {{"code", e.code}, {"message", e.message}}}};
    return static_cast<int>(e.exit);
  }
}

// --- the scheduler --------------------------------------------------------------------------------

struct Child {
  std::size_t entry = 0;  // in the report's asset list
  pid_t pid = -1;
  int result_fd = -1, log_fd = -1;
  std::string result, log;
  Clock::time_point start;
};

// Forks the child that bakes `a`; its standard error goes to `log_fd`, its result to `result_fd`.
Child start_child(const BatchAsset& a, const std::string& key, const BatchOptions& o, int threads, std::size_t entry) {
  int result[2], log[2];
  if (::pipe2(result, O_CLOEXEC) != 0 || ::pipe2(log, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  const pid_t parent = ::getpid();
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("cannot fork: ") + std::strerror(errno));
  if (pid == 0) {
    // A child outlives no parent: a killed batch takes its bakes with it.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(128 + SIGKILL);
    ::dup2(log[1], 1);
    ::dup2(log[1], 2);
    omp_set_num_threads(threads);
    Json out;
    const int code = bake_in_child(a, key, o, out);
    write_all(result[1], out.dump());
    ::_exit(code);  // no atexit handlers or stdio flushes of the parent's state
  }
  ::close(result[1]);
  ::close(log[1]);
  Child c;
  c.entry = entry;
  c.pid = pid;
  c.result_fd = result[0];
  c.log_fd = log[0];
  c.start = Clock::now();
  return c;
}

// Reads what is there; closes and marks -1 at end of file.
void drain(int& fd, std::string& into) {
  if (fd < 0) return;
  char buf[65536];
  const ssize_t n = ::read(fd, buf, sizeof buf);
  if (n > 0) {
    into.append(buf, static_cast<std::size_t>(n));
  } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
    ::close(fd);
    fd = -1;
  }
}

std::string last_line(const std::string& log) {
  std::string s = log;
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  const std::size_t nl = s.rfind('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

// Fills the asset's report entry from its finished child.
void finish_child(Child& c, Json& entry) {
  int status = 0;
  rusage usage{};
  while (::wait4(c.pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  entry["seconds"] = round_to(since(c.start), 3);
  entry["peak_mb"] = round_to(static_cast<double>(usage.ru_maxrss) / 1024.0, 1);
  const Json result = Json::parse(c.result, nullptr, false);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && result.is_object() && result.contains("levels")) {
    entry["status"] = "baked";
    entry["exit_code"] = 0;
    std::size_t primitives = 0, texels = 0;
    for (const Json& l : result["levels"]) primitives += l["primitives"].get<std::size_t>(), texels += l["texels"].get<std::size_t>();
    entry.update(result);
    entry["primitives"] = primitives;
    entry["texels"] = texels;
    return;
  }
  entry["status"] = "failed";
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    entry["exit_code"] = 128 + sig;
    entry["error"] = {{"code", "crashed"}, {"message", std::string("the bake was killed by signal ") + std::to_string(sig) + " (" +
                                                           strsignal(sig) + ")" + (c.log.empty() ? "" : "; last output: " + last_line(c.log))}};
  } else {
    entry["exit_code"] = WEXITSTATUS(status);
    if (result.is_object() && result.contains("error")) entry["error"] = result["error"];
    else entry["error"] = {{"code", "internal"}, {"message", "the bake ended without a result; last output: " + last_line(c.log)}};
  }
}

// The progress display: one rewritten line on a terminal, else one line per finished asset.
class Progress {
 public:
  Progress(std::FILE* out, const BatchOptions& o, std::size_t total) : out_(out), o_(o), total_(total), start_(Clock::now()) {}
  void finished(const Json& e, std::size_t done) {
    if (o_.quiet || !out_) return;
    const std::string status = e["status"];
    if (o_.terminal) return;  // the status line says it
    if (status == "up to date") return;  // summed up at the end: a rerun of thousands stays readable
    std::fprintf(out_, "qf-bake batch: [%zu/%zu] %s %s", done, total_, status.c_str(), e["name"].get<std::string>().c_str());
    if (status == "baked")
      std::fprintf(out_, " (%.2f s, %zu levels, %zu primitives, peak %.0f MB)", e["seconds"].get<double>(), e["levels"].size(),
                   e["primitives"].get<std::size_t>(), e["peak_mb"].get<double>());
    if (status == "failed") std::fprintf(out_, ": %s", e["error"]["message"].get<std::string>().c_str());
    std::fprintf(out_, "\n");
    std::fflush(out_);
  }
  void line(std::size_t done, const std::map<std::string, std::size_t>& counts, const std::vector<std::string>& running) {
    if (o_.quiet || !out_ || !o_.terminal) return;
    std::string names;
    for (const std::string& n : running) names += (names.empty() ? "" : ", ") + n;
    auto count = [&](const char* k) { return counts.count(k) ? counts.at(k) : std::size_t{0}; };
    std::fprintf(out_, "\r\033[K[%zu/%zu] %zu baked, %zu up to date, %zu failed, %.0f s%s%s", done, total_, count("baked"),
                 count("up to date"), count("failed"), since(start_), names.empty() ? "" : " | baking: ", names.c_str());
    std::fflush(out_);
  }
  void end() {
    if (!o_.quiet && out_ && o_.terminal) std::fprintf(out_, "\r\033[K"), std::fflush(out_);
  }

 private:
  std::FILE* out_;
  const BatchOptions& o_;
  std::size_t total_;
  Clock::time_point start_;
};

Json totals_of(const Json& assets) {
  std::map<std::string, std::size_t> counts;
  std::size_t primitives = 0, texels = 0;
  double seconds = 0;
  for (const Json& e : assets) {
    ++counts[e["status"].get<std::string>()];
    if (e.contains("primitives")) primitives += e["primitives"].get<std::size_t>();
    if (e.contains("texels")) texels += e["texels"].get<std::size_t>();
    if (e.contains("seconds")) seconds += e["seconds"].get<double>();
  }
  Json t{{"assets", assets.size()}, {"primitives", primitives}, {"texels", texels}, {"asset_seconds", round_to(seconds, 3)}};
  for (const char* s : {"baked", "up to date", "failed", "skipped", "would bake"}) t[s] = counts[s];
  return t;
}

}  // namespace

Json run_batch(const BatchManifest& m, const BatchOptions& o, std::FILE* log) {
  const auto start = Clock::now();
  const std::vector<std::size_t> selected = shard_assets(m.assets.size(), o.shard_index, o.shard_count);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = o.threads > 0 ? o.threads : std::max(1, cores / std::max(1, o.jobs));
  Json entries = Json::array();
  std::vector<std::string> keys(selected.size());
  std::deque<std::size_t> queue;  // entries to bake, manifest order
  std::map<std::string, std::size_t> counts;
  Progress progress(log, o, selected.size());
  std::size_t done = 0;
  auto settle = [&](std::size_t i) {
    ++counts[entries[i]["status"].get<std::string>()];
    progress.finished(entries[i], ++done);
  };
  // 1. Keys and the up-to-date check, in this process (cheap: a hash of the input, one small JSON).
  for (std::size_t i = 0; i < selected.size(); ++i) {
    const BatchAsset& a = m.assets[selected[i]];
    const auto t = Clock::now();
    entries.push_back({{"index", a.index}, {"name", a.name}, {"input", a.input}, {"status", "pending"}});
    try {
      keys[i] = asset_key(a, o.version);
    } catch (const InputError& e) {
      entries[i]["status"] = "failed";
      entries[i]["exit_code"] = static_cast<int>(ExitCode::kBadInput);
      entries[i]["error"] = {{"code", e.code()}, {"message", e.what()}};
      settle(i);
      continue;
    }
    entries[i]["key"] = keys[i];
    if (!o.force && asset_up_to_date(o.output + "/" + a.name, keys[i])) {
      entries[i]["status"] = "up to date";
      entries[i]["seconds"] = round_to(since(t), 6);
      settle(i);
    } else if (o.dry_run) {
      entries[i]["status"] = "would bake";
      settle(i);
    } else {
      queue.push_back(i);
    }
  }
  // 2. Bake the rest, `jobs` children at a time.
  if (!queue.empty()) {
    std::filesystem::create_directories(o.output);
    // Loaded once here, not 0.35 s in every child (a failure shows in each asset's error).
    try {
      preload_png_encoder();
    } catch (const std::exception&) {
    }
  }
  std::vector<Child> running;
  bool stopping = false;
  while (!queue.empty() || !running.empty()) {
    while (!stopping && !queue.empty() && static_cast<int>(running.size()) < std::max(1, o.jobs)) {
      const std::size_t i = queue.front();
      queue.pop_front();
      running.push_back(start_child(m.assets[selected[i]], keys[i], o, threads, i));
    }
    if (stopping)
      for (std::size_t i : queue) entries[i]["status"] = "skipped", settle(i);
    if (stopping) queue.clear();
    std::vector<std::string> names;
    std::vector<pollfd> fds;
    for (const Child& c : running) {
      names.push_back(entries[c.entry]["name"]);
      for (int fd : {c.result_fd, c.log_fd})
        if (fd >= 0) fds.push_back({fd, POLLIN, 0});
    }
    progress.line(done, counts, names);
    if (!fds.empty() && ::poll(fds.data(), fds.size(), 250) < 0 && errno != EINTR) throw std::runtime_error("poll failed");
    for (Child& c : running) {
      for (const pollfd& p : fds) {
        if (!(p.revents & (POLLIN | POLLHUP | POLLERR))) continue;
        if (p.fd == c.result_fd) drain(c.result_fd, c.result);
        else if (p.fd == c.log_fd) drain(c.log_fd, c.log);
      }
    }
    for (std::size_t k = 0; k < running.size();) {
      Child& c = running[k];
      if (c.result_fd >= 0 || c.log_fd >= 0) {
        ++k;
        continue;
      }
      finish_child(c, entries[c.entry]);
      if (entries[c.entry]["status"] == "failed" && !o.keep_going) stopping = true;
      settle(c.entry);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
    }
  }
  progress.end();
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
              {"seconds", round_to(since(start), 3)}};
  if (!o.quiet && log) {
    const Json& t = report["totals"];
    std::fprintf(log, "qf-bake batch: %zu asset(s)%s: %zu baked, %zu up to date, %zu failed, %zu skipped in %.2f s\n",
                 selected.size(), o.shard_count > 1 ? (" (shard " + std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count) + ")").c_str() : "",
                 t["baked"].get<std::size_t>(), t["up to date"].get<std::size_t>(), t["failed"].get<std::size_t>(),
                 t["skipped"].get<std::size_t>(), report["seconds"].get<double>());
    for (const Json& e : entries)
      if (e["status"] == "failed") std::fprintf(log, "qf-bake batch: FAILED %s: %s\n", e["name"].get<std::string>().c_str(),
                                                e["error"]["message"].get<std::string>().c_str());
    if (t["would bake"].get<std::size_t>() > 0)
      for (const Json& e : entries)
        if (e["status"] == "would bake") std::fprintf(log, "qf-bake batch: would bake %s\n", e["name"].get<std::string>().c_str());
  }
  return report;
}

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
  for (const Json& e : report["assets"])
    if (e["status"] != "baked" && e["status"] != "up to date" && e["status"] != "would bake") return 1;
  return 0;
}

}  // namespace qf
