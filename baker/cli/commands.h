// qf-bake's subcommands. Each returns the process exit code; errors are thrown (see main.cpp).
#pragma once

#include <string>
#include <vector>

#include "cli/args.h"

namespace qf::cli {

struct Command {
  CommandSpec spec;
  int (*run)(const ParsedArgs&);
};

const std::vector<Command>& commands();

int run_info(const ParsedArgs& args);
int run_convert(const ParsedArgs& args);
int run_generate(const ParsedArgs& args);
int run_analyze(const ParsedArgs& args);
CommandSpec analyze_spec();

// Shared option: --drop-nonfinite (every command that reads input files).
OptionSpec drop_nonfinite_option();

}  // namespace qf::cli
