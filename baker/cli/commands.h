// qf-bake's subcommands. Each returns the process exit code; errors are thrown (cli/program.h maps
// them to messages and exit codes).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "analysis/analysis.h"
#include "clustering/clustering.h"
#include "domains/merge.h"
#include "cli/args.h"
#include "cli/program.h"
#include "io/model_io.h"
#include "pipeline/asset.h"
#include "sample/sample.h"

namespace qf::cli {

// qf-bake's command table (main.cpp makes it a cli::Program).
const std::vector<Command>& commands();

int run_info(const ParsedArgs& args);
int run_convert(const ParsedArgs& args);
int run_generate(const ParsedArgs& args);
int run_billboard(const ParsedArgs& args);
int run_analyze(const ParsedArgs& args);
CommandSpec analyze_spec();

// Shared option: --drop-nonfinite (every command that reads input files).
OptionSpec drop_nonfinite_option();

// Shared by the commands that run the surface analysis: -k, --epsilon, --max-neighbors,
// --classifier, --threads; and reading them into options (UsageError on bad values).
std::vector<OptionSpec> analysis_option_specs();
AnalysisOptions read_analysis_options(const OptionValues& args);

// Mesh sampling options (every command that takes a point set also takes a mesh): --ldi,
// --sampler, --per-axis-triangles; and reading them (UsageError on bad values).
std::vector<OptionSpec> sample_option_specs();
SampleOptions read_sample_options(const OptionValues& args);

// Reads a point set for the analysis; a mesh is sampled into one by depth peeling (its figures in
// `sampled`, when given; sampled->backend stays empty for point-set inputs; the mesh itself in
// `mesh`, when given). Rejects empty sets
// with InputError `command`.empty.
PointSet load_points(const std::string& path, const ParsedArgs& args, const std::string& command, ReadReport& report,
                     SampleStats* sampled = nullptr, TriangleMesh* mesh = nullptr);

// Shared by decompose and bake: --cache/--no-cache, and --merge with its two thresholds.
std::vector<OptionSpec> cache_option_specs();
std::string read_cache_dir(const OptionValues& args);  // "" when the cache is off
std::vector<OptionSpec> merge_option_specs();
// What every command that analyses a point set (or samples a mesh into one) takes: the merge,
// cache, analysis and sampling options, appended in that order (bake, decompose).
void append_point_input_options(std::vector<OptionSpec>& options);
MergeOptions read_merge_options(const OptionValues& args, const DomainOptions& domains);

CommandSpec decompose_spec();
int run_decompose(const ParsedArgs& args);
CommandSpec bake_spec();
int run_bake(const ParsedArgs& args);
// The bake's options (bake_spec) as the pipeline's; UsageError on bad values. Shared with batch.
AssetOptions read_asset_options(const OptionValues& args);
CommandSpec batch_spec();
int run_batch(const ParsedArgs& args);
CommandSpec merge_reports_spec();
int run_merge_reports(const ParsedArgs& args);
CommandSpec tile_spec();
int run_tile(const ParsedArgs& args);
CommandSpec join_spec();
int run_join(const ParsedArgs& args);
CommandSpec cluster_spec();
int run_cluster(const ParsedArgs& args);
CommandSpec simplify_spec();
int run_simplify(const ParsedArgs& args);

}  // namespace qf::cli
