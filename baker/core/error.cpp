// Error message formatting, and the one mapping of errors to exit codes.
#include "core/error.h"

#include <cerrno>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>

namespace qf {

static std::string compose(const std::string& code, const std::string& file, const std::string& where,
                           const std::string& detail) {
  std::string msg = file;
  if (!where.empty()) msg += ": " + where;
  msg += ": " + detail + " [" + code + "]";
  return msg;
}

InputError::InputError(std::string code, std::string file, std::string where, std::string detail)
    : std::runtime_error(compose(code, file, where, detail)),
      code_(std::move(code)),
      file_(std::move(file)),
      where_(std::move(where)),
      detail_(std::move(detail)) {}

ErrorOutcome current_error_outcome() {
  try {
    throw;
  } catch (const InputError& e) {
    return {ExitCode::kBadInput, e.code(), e.what()};
  } catch (const UsageError& e) {
    return {ExitCode::kUsage, "usage", e.what()};
  } catch (const OutputError& e) {
    return {ExitCode::kOutput, "output", e.what()};
  } catch (const BusyError& e) {
    return {ExitCode::kBusy, "busy", e.what()};
  } catch (const std::filesystem::filesystem_error& e) {
    // The file-system calls that throw work on outputs (inputs are read through InputFile): a path
    // that names a missing folder or a file where a folder belongs is the command line's mistake,
    // anything else (no space, read-only, no permission, I/O) the output's.
    const int err = e.code().value();
    if (e.code().category() == std::generic_category() || e.code().category() == std::system_category())
      if (err == ENOENT || err == ENOTDIR || err == EISDIR || err == ENAMETOOLONG)
        return {ExitCode::kUsage, "output", std::string("cannot write output: ") + e.what()};
    return {ExitCode::kOutput, "output", std::string("cannot write output: ") + e.what()};
  } catch (const std::bad_alloc&) {
    return {ExitCode::kInternal, "internal", "internal error: out of memory"};
  } catch (const std::exception& e) {
    return {ExitCode::kInternal, "internal", std::string("internal error: ") + e.what()};
  }
}

void throw_output_error(const std::string& what, int err) {
  const std::string message = what + ": " + std::strerror(err);
  if (err == ENOENT || err == ENOTDIR || err == EISDIR || err == ENAMETOOLONG) throw UsageError(message);
  throw OutputError(message);
}

std::string at_byte(unsigned long long offset) { return "byte " + std::to_string(offset); }
std::string at_line(unsigned long long line) { return "line " + std::to_string(line); }

}  // namespace qf
