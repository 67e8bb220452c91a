// The batch and merge-reports commands: a manifest of assets baked for a build farm
// (pipeline/batch), and the shard reports of one manifest joined into one.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <thread>

#include "cli/commands.h"
#include "cli/program.h"
#include "core/error.h"
#include "core/file_io.h"
#include "pipeline/batch.h"
#include "tools/report_html.h"

namespace qf::cli {
namespace {

// Bake options a manifest may not set: the batch decides them for every asset.
bool batch_level_option(const std::string& name) {
  return name == "output" || name == "quiet" || name == "threads" || name == "cache" || name == "no-cache";
}

// A manifest asset's settings (the defaults overlaid by its own) as option values: the bake
// command's table of options (bake_spec) names what may be set, and read_asset_options reads
// them as it reads the command line, each from its JSON value (numbers as numbers, lists as
// lists, switches as booleans; a string is read as the same text on the command line would be).
class ManifestSettings : public OptionValues {
 public:
  // Throws InputError("batch.setting") naming the manifest and the asset for a setting that is
  // no bake option, is the batch's own, or has the wrong kind of value (a switch needs a boolean).
  ManifestSettings(const nlohmann::json& settings, const CommandSpec& spec, const std::string& manifest, const std::string& where)
      : s_(settings) {
    for (const auto& [name, value] : s_.items()) {
      const OptionSpec* option = nullptr;
      for (const OptionSpec& o : spec.options)
        if (o.name == name) option = &o;
      if (!option || batch_level_option(name))
        throw InputError("batch.setting", manifest, where, "'" + name + "' is not a bake option a manifest can set (see qf-bake bake --help; "
                                                           "output, threads, cache and quiet are the batch's own)");
      if (option->metavar.empty() && !value.is_boolean())
        throw InputError("batch.setting", manifest, where, "'" + name + "' is a switch: expected true or false");
      if (!option->metavar.empty() && value.is_boolean())
        throw InputError("batch.setting", manifest, where, "'" + name + "' expects " + option->metavar + ", not a boolean");
    }
  }
  bool has(const std::string& name) const override { return s_.contains(name) && !(s_[name].is_boolean() && !s_[name].get<bool>()); }
  bool flag(const std::string& name) const override { return has(name); }
  std::string get(const std::string& name, const std::string& fallback) const override {
    if (!has(name)) return fallback;
    const nlohmann::json& v = s_[name];
    return v.is_string() ? v.get<std::string>() : v.dump();  // a number where text is expected: named as written
  }
  long long get_int(const std::string& name, long long fallback, long long min, long long max) const override {
    if (!has(name)) return fallback;
    return integer(name, s_[name], min, max);
  }
  double get_double(const std::string& name, double fallback, double min, double max) const override {
    if (!has(name)) return fallback;
    return number(name, s_[name], min, max);
  }
  std::vector<long long> get_int_list(const std::string& name, long long min, long long max) const override {
    std::vector<long long> out;
    if (!has(name)) return out;
    const nlohmann::json& v = s_[name];
    if (v.is_string()) return parse_int_list_option(name, v.get<std::string>(), min, max);
    for (const nlohmann::json& x : v.is_array() ? v : nlohmann::json::array({v})) {
      if (x.is_string()) for (long long n : parse_int_list_option(name, x.get<std::string>(), min, max)) out.push_back(n);
      else out.push_back(integer(name, x, min, max, /*in_list=*/true));
    }
    return out;
  }
  std::vector<double> get_double_list(const std::string& name, double min, double max) const override {
    std::vector<double> out;
    if (!has(name)) return out;
    const nlohmann::json& v = s_[name];
    if (v.is_string()) return parse_double_list_option(name, v.get<std::string>(), min, max);
    for (const nlohmann::json& x : v.is_array() ? v : nlohmann::json::array({v})) {
      if (x.is_string()) for (double n : parse_double_list_option(name, x.get<std::string>(), min, max)) out.push_back(n);
      else out.push_back(number(name, x, min, max, /*in_list=*/true));
    }
    return out;
  }

 private:
  // A JSON number in range is read as it is; anything else gets the command line's message for
  // the same value written out (the text readers reject it as they would on the command line).
  static long long integer(const std::string& name, const nlohmann::json& v, long long min, long long max, bool in_list = false) {
    if (v.is_string()) return parse_int_option(name, v.get<std::string>(), min, max);
    if (v.is_number_integer() && !(v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(max)) &&
        v.get<long long>() >= min && v.get<long long>() <= max)
      return v.get<long long>();
    if (in_list) parse_int_list_option(name, v.dump(), min, max);  // throws, with the list's message
    return parse_int_option(name, v.dump(), min, max);              // throws
  }
  static double number(const std::string& name, const nlohmann::json& v, double min, double max, bool in_list = false) {
    if (v.is_string()) return parse_double_option(name, v.get<std::string>(), min, max);
    if (v.is_number() && v.get<double>() >= min && v.get<double>() <= max) return v.get<double>();
    if (in_list) parse_double_list_option(name, v.dump(), min, max);  // throws, with the list's message
    return parse_double_option(name, v.dump(), min, max);              // throws
  }
  const nlohmann::json& s_;
};

// Reads every asset's settings into its bake options with the bake command's own readers.
// Errors name the manifest entry.
void read_settings(BatchManifest& m, const std::string& cache_dir) {
  const CommandSpec spec = bake_spec();
  for (BatchAsset& a : m.assets) {
    const std::string where = "assets[" + std::to_string(a.index) + "] (" + a.name + ")";
    try {
      a.options = read_asset_options(ManifestSettings(a.settings, spec, m.path, where));
    } catch (const UsageError& e) {
      throw InputError("batch.setting", m.path, where, e.what());
    }
    a.options.bake.cache_dir = cache_dir;
  }
}

std::string report_path(const ParsedArgs& args, const BatchOptions& o) {
  if (args.has("report")) return args.get("report");
  if (o.shard_count == 1) return o.output + "/batch-report.json";
  return o.output + "/batch-report-" + std::to_string(o.shard_index) + "-of-" + std::to_string(o.shard_count) + ".json";
}

void write_report(const std::string& path, const nlohmann::json& report) {
  write_file_atomically(path, [&](std::ostream& out) { out << report.dump(2) << "\n"; });
}

// The report's page (render::batch_page) beside it: its name with .html for .json. Returns its path.
std::string write_page(const std::string& report_path, const nlohmann::json& report) {
  const std::filesystem::path page = std::filesystem::path(report_path).replace_extension(".html");
  const std::string html = render::batch_page(report, page.parent_path().empty() ? "." : page.parent_path().string());
  write_file_atomically(page.string(), [&](std::ostream& out) { out << html; });
  return page.string();
}

}  // namespace

CommandSpec batch_spec() {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  CommandSpec spec{
      "batch", "MANIFEST [options]",
      "bake every asset of a manifest: in parallel, incrementally, optionally one shard of it",
      "MANIFEST is JSON (schemas/batch.schema.json): {\"output\": DIR, \"defaults\": {OPTION: VALUE},\n"
      "\"assets\": [PATH | {\"input\": PATH, \"name\": NAME, \"settings\": {OPTION: VALUE}}]}. Paths are relative\n"
      "to the manifest; OPTION is any `qf-bake bake` option (e.g. \"primitives\": [300, 30], \"merge\": true);\n"
      "an asset's settings override the defaults. Asset NAME (default: the input's stem) is baked into\n"
      "OUTDIR/NAME exactly as `qf-bake bake` would, plus a \"batch_key\" in its manifest.json.\n"
      "An asset whose input bytes, settings and qf-bake version match that key is not rebaked.\n"
      "Each asset bakes in its own process: a bad or crashing asset fails alone, with its file and\n"
      "reason in the report. A killed batch leaves no half-written file; rerunning it finishes the job.\n"
      "The report (JSON, schemas/batch-report.schema.json) gives per asset its status, time, peak\n"
      "memory, primitives and texels; beside it, the same name with .html is its page for a browser:\n"
      "one sortable row per asset with its thumbnail, figures and failure message, linking the asset's\n"
      "report.html (each asset writes one unless its settings say \"no-report-html\": true).\n"
      "Exit status: 0 when every asset is baked or up to date, 1 when\n"
      "any failed (or was skipped after a failure) or the manifest is bad, 2 for a bad command line.",
      {{"output", 'o', "OUTDIR", "the manifest's \"output\"", "root folder of the baked assets"},
       {"jobs", 'j', "N", std::to_string(cores) + " (cores)", "assets baked at once"},
       {"threads", 0, "N", "cores / jobs", "threads of each asset's bake (outputs do not depend on it)"},
       {"shard", 0, "I/N", "1/1", "bake shard I of N: the assets at positions I, I+N, I+2N, ... of the manifest (1-based);\n"
                                  "run I = 1..N on N machines (see docs/farm.md: a Slurm array job), then merge-reports"},
       {"force", 0, "", "", "rebake every asset, up to date or not"},
       {"keep-going", 'k', "", "", "after a failed asset, still bake the rest (default: stop starting new ones, like make)"},
       {"dry-run", 'n', "", "", "list what would be baked; bake nothing"},
       {"report", 0, "FILE", "OUTDIR/batch-report.json (shards: batch-report-I-of-N.json)", "where the batch report goes"},
       {"eval", 0, "", "", "measure each baked level against its input with `qf-render eval` (PSNR, IoU, holes) into the report"},
       {"eval-views", 0, "N", "6", "--eval: viewpoints per level"},
       {"quiet", 'q', "", "", "no progress and no summary (the report is still written)"}},
      1, 1};
  for (const OptionSpec& o : cache_option_specs()) spec.options.push_back(o);
  return spec;
}

int run_batch(const ParsedArgs& args) {
  BatchManifest m = read_batch_manifest(args.positional[0]);
  BatchOptions o;
  o.output = args.get("output", m.output);
  if (o.output.empty()) throw UsageError("batch: the manifest names no \"output\" folder; give -o OUTDIR");
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.jobs = static_cast<int>(args.get_int("jobs", cores, 1, 256));
  o.threads = static_cast<int>(args.get_int("threads", 0, 1, 1024));
  if (args.has("shard")) {
    const std::string s = args.get("shard");
    int i = 0, n = 0;
    char extra = 0;
    if (std::sscanf(s.c_str(), "%d/%d%c", &i, &n, &extra) != 2 || n < 1 || i < 1 || i > n)
      throw UsageError("--shard expects I/N with 1 <= I <= N, got '" + s + "'");
    o.shard_index = i, o.shard_count = n;
  }
  o.force = args.flag("force");
  o.keep_going = args.flag("keep-going");
  o.dry_run = args.flag("dry-run");
  o.version = version();
  o.eval = args.flag("eval");
  o.eval_views = static_cast<int>(args.get_int("eval-views", o.eval_views, 1, 1000));
  o.render_exe = std::filesystem::path(std::filesystem::read_symlink("/proc/self/exe")).parent_path().string() + "/qf-render";
  if (o.eval && ::access(o.render_exe.c_str(), X_OK) != 0)
    throw UsageError("--eval needs qf-render beside qf-bake (" + o.render_exe + " not found)");
  o.quiet = args.flag("quiet");
  o.terminal = ::isatty(2) != 0;
  read_settings(m, read_cache_dir(args));
  const nlohmann::json report = run_batch(m, o, stderr);
  if (!o.dry_run) {
    const std::string path = report_path(args, o);
    write_report(path, report);
    const std::string page = write_page(path, report);
    if (!o.quiet) std::fprintf(stderr, "qf-bake batch: report: %s, page: %s\n", path.c_str(), page.c_str());
  }
  return batch_exit_code(report);
}

CommandSpec merge_reports_spec() {
  return {"merge-reports", "REPORT.json... -o OUT.json",
          "join the reports of the shards of one batch (qf-bake batch --shard I/N) into one",
          "Checks that the reports come from the same manifest and sharding, with no shard or asset twice;\n"
          "the joined report lists every asset in manifest order, the totals, and the shards missing;\n"
          "its page for a browser goes beside it (OUT.html, as qf-bake batch writes one).\n"
          "Exit status: 0 when every asset is baked or up to date and no shard is missing, else 1.",
          {{"output", 'o', "OUT.json", "", "the joined report; required"}, {"quiet", 'q', "", "", "print no summary"}},
          1, std::numeric_limits<std::size_t>::max()};
}

int run_merge_reports(const ParsedArgs& args) {
  args.require("output");
  std::vector<nlohmann::json> reports;
  for (const std::string& path : args.positional) {
    const InputFile f(path);
    const ByteView b = f.bytes();
    try {
      reports.push_back(nlohmann::json::parse(b.data(), b.data() + b.size()));
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError("batch.report", path, at_byte(e.byte), std::string("not valid JSON: ") + e.what());
    }
  }
  const nlohmann::json merged = merge_batch_reports(reports, args.positional);
  write_report(args.get("output"), merged);
  write_page(args.get("output"), merged);
  if (!args.flag("quiet")) {
    const nlohmann::json& t = merged["totals"];
    std::fprintf(stderr, "qf-bake merge-reports: %zu report(s), %zu assets: %zu baked, %zu up to date, %zu failed, %zu skipped%s\n",
                 reports.size(), t["assets"].get<std::size_t>(), t["baked"].get<std::size_t>(), t["up to date"].get<std::size_t>(),
                 t["failed"].get<std::size_t>(), t["skipped"].get<std::size_t>(),
                 merged["missing_shards"].empty() ? "" : ("; missing shards: " + merged["missing_shards"].dump()).c_str());
  }
  return batch_exit_code(merged);
}

}  // namespace qf::cli
