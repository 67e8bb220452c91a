// Error types and the process exit codes they map to (0 ok, 1 bad input, 2 bad usage, 3 internal,
// 4 an output that cannot be written, 5 an output folder another process is writing).
#pragma once

#include <stdexcept>
#include <string>

namespace qf {

// 4 and 5 are apart from 2 so that a farm can tell a job to retry (5: the folder is busy; 4: the
// disk is full or read-only, an operator's matter) from one whose command line is wrong (2).
enum class ExitCode : int { kOk = 0, kBadInput = 1, kUsage = 2, kInternal = 3, kOutput = 4, kBusy = 5 };

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

// An output that cannot be written although the command line names it well: the disk or quota
// is full, the file system is read-only, permission is refused, an I/O error. The message names
// the file and the system's reason.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output folder that another process (on this machine or, through the shared file system's
// locks, another) is baking into now: nothing was written. Retrying later succeeds.
class BusyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The error for an output path that failed with `err` (an errno): UsageError when the path itself
// is wrong (a missing folder, a file where a folder should be), else OutputError. `what` is the
// message's start, e.g. "cannot create output file 'x'".
[[noreturn]] void throw_output_error(const std::string& what, int err);

// How a failure is reported, the same way by every program (cli/program.h) and in batch reports
// (pipeline/batch): the exit code, a stable code (the InputError's, else "usage", "output" for an
// output that cannot be written, "busy" for an output folder another bake holds, "internal") and
// the message. Call it inside a catch block: it classifies the exception being handled (a bad
// input file is kBadInput; a bad command line or an output path naming a missing folder kUsage; an
// output the system refuses to write, a full disk included, kOutput; a busy folder kBusy; anything
// else, out of memory included, kInternal).
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
