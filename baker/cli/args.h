// Command-line parsing for every program (qf-bake, qf-render, qf-diff; cli/program.h runs them):
// options declared once, with their defaults and help text, so --help always lists every option
// and its default; typed readers that name the option in their errors.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"

namespace qf::cli {

struct OptionSpec {
  std::string name;          // long name without dashes, e.g. "output"
  char short_name = 0;       // e.g. 'o', or 0
  std::string metavar;       // empty for a flag (takes no value)
  std::string default_text;  // shown in --help; empty = no default (required or off)
  std::string help;
};

struct CommandSpec {
  std::string name;
  std::string usage;    // after "qf-bake NAME ", e.g. "IN OUT [options]"
  std::string summary;  // one line
  std::string details;  // paragraph(s) after the usage line
  std::vector<OptionSpec> options;
  std::size_t min_positional = 0, max_positional = 0;
  std::string program = "qf-bake";  // the executable, for the usage line
};

// Option values by long name: a command line's (ParsedArgs) or a batch manifest's settings
// (cli/batch.cpp). The readers of a command's options take either, so that a manifest setting
// means exactly what the same option means on the command line, read from its JSON value.
class OptionValues {
 public:
  virtual ~OptionValues() = default;
  virtual bool has(const std::string& name) const = 0;
  virtual bool flag(const std::string& name) const = 0;
  virtual std::string get(const std::string& name, const std::string& fallback = "") const = 0;
  // Number options; throw UsageError naming the option when the value is not a number in range.
  virtual long long get_int(const std::string& name, long long fallback, long long min, long long max) const = 0;
  virtual double get_double(const std::string& name, double fallback, double min, double max) const = 0;
  // Lists ("a,b,,c" -> a, b, c on the command line; a JSON list in a manifest); empty when the
  // option is absent. Each number in [min, max], else UsageError naming the option and the item.
  virtual std::vector<long long> get_int_list(const std::string& name, long long min, long long max) const = 0;
  virtual std::vector<double> get_double_list(const std::string& name, double min, double max) const = 0;
  // One of `choices`, else UsageError "--NAME expects A, B or C, got 'X'".
  std::string get_choice(const std::string& name, const std::vector<std::string>& choices, const std::string& fallback) const;
};

// The text readers of ParsedArgs, for values given as text anywhere (e.g. a manifest's string):
// the whole text must be the number (no sign '+', no trailing characters).
long long parse_int_option(const std::string& name, const std::string& text, long long min, long long max);
double parse_double_option(const std::string& name, const std::string& text, double min, double max);
std::vector<long long> parse_int_list_option(const std::string& name, const std::string& text, long long min, long long max);
std::vector<double> parse_double_list_option(const std::string& name, const std::string& text, double min, double max);

class ParsedArgs : public OptionValues {
 public:
  std::vector<std::string> positional;
  bool has(const std::string& name) const override { return values_.count(name) != 0; }
  bool flag(const std::string& name) const override { return has(name); }
  std::string get(const std::string& name, const std::string& fallback = "") const override;
  long long get_int(const std::string& name, long long fallback, long long min, long long max) const override;
  double get_double(const std::string& name, double fallback, double min, double max) const override;
  std::vector<long long> get_int_list(const std::string& name, long long min, long long max) const override;
  std::vector<double> get_double_list(const std::string& name, double min, double max) const override;
  // A required option's value; UsageError "COMMAND needs -o OUTDIR (see PROGRAM COMMAND --help)"
  // when it was not given.
  std::string require(const std::string& name) const;

 private:
  friend ParsedArgs parse_args(const CommandSpec&, const std::vector<std::string>&);
  std::map<std::string, std::string> values_;
  CommandSpec spec_;  // what was parsed against, for messages
};

// Parses arguments (after the subcommand name). "--name value", "--name=value", "-o value" and
// "--" (end of options) are understood. Throws UsageError on unknown options, missing values or
// a wrong number of positional arguments. "--help" is handled by the caller before parsing.
ParsedArgs parse_args(const CommandSpec& spec, const std::vector<std::string>& args);

// Options many commands share, declared once: -o with its metavar and help, and -q.
OptionSpec output_option(const std::string& metavar, const std::string& help);
OptionSpec quiet_option();

// The --help text of a command.
std::string help_text(const CommandSpec& spec);

// Whether `args` (after the command name) ask for help: "--help" or "-h" before any "--".
bool asks_for_help(const std::vector<std::string>& args);

// Runs an executable's body and maps its errors to the exit codes (core/error.h
// current_error_outcome: 1 bad input, 2 bad usage or an unwritable output, 3 internal error),
// printing "PROGRAM: ..." to stderr.
// `bad_input` is the code for an unreadable or malformed input (qf-diff gives 2: its 1 means
// "different").
int run_with_exit_codes(const std::string& program, const std::function<int()>& body,
                        int bad_input = static_cast<int>(ExitCode::kBadInput));

}  // namespace qf::cli
