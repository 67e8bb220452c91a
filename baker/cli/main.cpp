// qf-bake entry point: subcommand dispatch and the mapping of errors to exit codes
// (0 ok, 1 bad input, 2 bad usage, 3 internal error).
#include <algorithm>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/memory.h"

#ifndef QF_VERSION
#define QF_VERSION "0.0.0"
#endif

namespace {

void print_overview(std::ostream& out) {
  out << "qf-bake " QF_VERSION " - extreme simplification of point sets and meshes into textured quads\n\n"
         "usage: qf-bake IN -o OUTDIR [options]   bake (the main job; see qf-bake bake --help)\n"
         "       qf-bake COMMAND [arguments] [options]\n"
         "       qf-bake COMMAND --help      options of one command, with their defaults\n"
         "       qf-bake --version\n\ncommands:\n";
  for (const qf::cli::Command& c : qf::cli::commands()) {
    std::string name = "  " + c.spec.name;
    name.resize(std::max<std::size_t>(name.size() + 2, 17), ' ');
    out << name << c.spec.summary << "\n";
  }
  out << "\nexit codes: 0 ok, 1 bad input (the message names the file, the line or byte, and what was\n"
         "expected), 2 bad usage, 3 internal error.\n";
}

int dispatch(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h" || argv[0] == "help") {
    if (argv.size() >= 2 && argv[0] == "help") {
      for (const auto& c : qf::cli::commands())
        if (c.spec.name == argv[1]) return std::cout << qf::cli::help_text(c.spec), 0;
      throw qf::UsageError("unknown command '" + argv[1] + "'");
    }
    print_overview(argv.empty() ? std::cerr : std::cout);
    return argv.empty() ? 2 : 0;
  }
  if (argv[0] == "--version" || argv[0] == "-V") {
    std::cout << "qf-bake " QF_VERSION "\n";
    return 0;
  }
  for (const auto& c : qf::cli::commands()) {
    if (c.spec.name != argv[0]) continue;
    const std::vector<std::string> rest(argv.begin() + 1, argv.end());
    if (qf::cli::asks_for_help(rest)) return std::cout << qf::cli::help_text(c.spec), 0;
    return c.run(qf::cli::parse_args(c.spec, rest));
  }
  // The main job: `qf-bake IN -o OUTDIR` is `qf-bake bake IN -o OUTDIR`.
  if (argv[0].find('.') != std::string::npos && argv[0][0] != '-') {
    std::vector<std::string> with_command{"bake"};
    with_command.insert(with_command.end(), argv.begin(), argv.end());
    return dispatch(with_command);
  }
  throw qf::UsageError("unknown command '" + argv[0] + "' (see qf-bake --help)");
}

}  // namespace

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  qf::keep_freed_memory();
  const std::vector<std::string> args(argv + 1, argv + argc);
  return qf::cli::run_with_exit_codes("qf-bake", [&] { return dispatch(args); });
}
