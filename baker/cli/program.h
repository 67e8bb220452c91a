// The one command-line frame of qf-bake, qf-render and qf-diff: a program is a table of commands
// (each an option spec and a function), and run_program does the rest the same way for all three:
// the overview, `--help` / `help COMMAND`, `--version`, the implicit command, and the mapping of
// every error to its message and exit code (core/error.h error_outcome).
#pragma once

#include <string>
#include <vector>

#include "cli/args.h"

namespace qf::cli {

struct Command {
  CommandSpec spec;
  int (*run)(const ParsedArgs&);  // returns the exit code; errors are thrown
};

struct Program {
  std::string name;     // "qf-bake"
  std::string title;    // the overview's first line, after "NAME VERSION - "
  std::string usage;    // the overview's usage lines ("usage: ...\n       ...\n")
  std::string exit_codes;  // the overview's last paragraph ("exit codes: ...\n")
  std::vector<Command> commands;  // one command with an empty name: the program takes no command word
  std::size_t name_column = 17;   // where the overview's summaries start
  // The command run when the first argument names none (e.g. `qf-bake IN -o OUT` = `qf-bake bake
  // IN -o OUT`), when `implicit_for` accepts that argument (null: never).
  std::string implicit_command;
  bool (*implicit_for)(const std::string& first_argument) = nullptr;
  // The exit code of an unreadable or malformed input (qf-diff gives 2: its 1 means "different").
  int bad_input = static_cast<int>(ExitCode::kBadInput);
};

// The project's version, as every program prints it (CMake's project version).
const char* version();

// Runs the program on main's arguments and returns its exit code: 0 ok, 1 bad input (or
// `bad_input`), 2 bad usage or an unwritable output, 3 internal error; the message goes to stderr
// as "NAME: ...". No arguments prints the overview to stderr and exits 2.
int run_program(const Program& program, int argc, char** argv);

}  // namespace qf::cli
