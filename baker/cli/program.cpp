// Command dispatch, help and version for every program (see program.h).
#include "cli/program.h"

#include <algorithm>
#include <iostream>

#include "core/error.h"
#include "core/memory.h"

namespace qf::cli {
namespace {

void print_overview(const Program& p, std::ostream& out) {
  out << p.name << " " << version() << " - " << p.title << "\n\n" << p.usage << "\ncommands:\n";
  for (const Command& c : p.commands) {
    std::string name = "  " + c.spec.name;
    name.resize(std::max(name.size() + 2, p.name_column), ' ');
    out << name << c.spec.summary << "\n";
  }
  out << "\n" << p.exit_codes;
}

bool is_version(const std::string& a) { return a == "--version" || a == "-V"; }

const Command* find_command(const Program& p, const std::string& name) {
  for (const Command& c : p.commands)
    if (c.spec.name == name) return &c;
  return nullptr;
}

int run_command(const Command& c, const std::vector<std::string>& args) {
  if (asks_for_help(args)) return std::cout << help_text(c.spec), 0;
  return c.run(parse_args(c.spec, args));
}

// A program without command words (qf-diff): its one command takes every argument.
int dispatch_single(const Program& p, const std::vector<std::string>& argv) {
  if (!asks_for_help(argv) && argv.size() == 1 && is_version(argv[0])) return std::cout << p.name << " " << version() << "\n", 0;
  return run_command(p.commands.front(), argv);
}

int dispatch(const Program& p, const std::vector<std::string>& argv) {
  if (p.commands.size() == 1 && p.commands.front().spec.name.empty()) return dispatch_single(p, argv);
  if (argv.empty()) return print_overview(p, std::cerr), static_cast<int>(ExitCode::kUsage);
  const std::string& first = argv[0];
  if (first == "--help" || first == "-h" || (first == "help" && argv.size() == 1)) return print_overview(p, std::cout), 0;
  if (first == "help") {
    if (const Command* c = find_command(p, argv[1])) return std::cout << help_text(c->spec), 0;
    throw UsageError("unknown command '" + argv[1] + "' (see " + p.name + " --help)");
  }
  if (is_version(first)) return std::cout << p.name << " " << version() << "\n", 0;
  if (const Command* c = find_command(p, first)) return run_command(*c, std::vector<std::string>(argv.begin() + 1, argv.end()));
  if (p.implicit_for && p.implicit_for(first))
    if (const Command* c = find_command(p, p.implicit_command)) return run_command(*c, argv);
  throw UsageError("unknown command '" + first + "' (see " + p.name + " --help)");
}

}  // namespace

const char* version() { return QF_VERSION; }  // defined by CMake on qf_cli alone

int run_program(const Program& program, int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  // Freed memory stays with the process: the baker's stages and llvmpipe's per-frame scene memory
  // would otherwise hand it back and fault it in again (page-fault storms, gl-notes.md 5.3).
  keep_freed_memory();
  const std::vector<std::string> args(argv + 1, argv + argc);
  return run_with_exit_codes(program.name, [&] { return dispatch(program, args); }, program.bad_input);
}

}  // namespace qf::cli
