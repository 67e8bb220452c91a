// Error message formatting.
#include "core/error.h"

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

std::string at_byte(unsigned long long offset) { return "byte " + std::to_string(offset); }
std::string at_line(unsigned long long line) { return "line " + std::to_string(line); }

}  // namespace qf
