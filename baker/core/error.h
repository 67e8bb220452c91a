// Error types and the process exit codes they map to (0 ok, 1 bad input, 2 bad usage, 3 internal).
#pragma once

#include <stdexcept>
#include <string>

namespace qf {

enum class ExitCode : int { kOk = 0, kBadInput = 1, kUsage = 2, kInternal = 3 };

// A problem with an input file. `code` is a stable dotted identifier (e.g. "ply.body.truncated")
// that tests and scripts can match; `where` is "line N" or "byte N" (empty if not applicable);
// what() is the full human-readable message: "FILE: WHERE: DETAIL [code]".
class InputError : public std::runtime_error {
 public:
  InputError(std::string code, std::string file, std::string where, std::string detail);
  const std::string& code() const { return code_; }
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string code_, file_, where_, detail_;
};

// Wrong command line: unknown option, missing argument, unsupported extension.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How a failure is reported, the same way by every program (cli/program.h) and in batch reports
// (pipeline/batch): the exit code, a stable code (the InputError's, else "usage", "output" for an
// output that cannot be written, "internal") and the message. Call it inside a catch block: it
// classifies the exception being handled (a bad input file is kBadInput; a bad command line or an
// unwritable output path kUsage; anything else, out of memory included, kInternal).
struct ErrorOutcome {
  ExitCode exit = ExitCode::kInternal;
  std::string code;
  std::string message;  // InputError: "FILE: WHERE: DETAIL [code]"; internal: "internal error: ..."
};
ErrorOutcome current_error_outcome();

// "byte N" / "line N" helpers for InputError's `where`.
std::string at_byte(unsigned long long offset);
std::string at_line(unsigned long long line);

}  // namespace qf
