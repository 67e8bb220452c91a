// How much memory this process may still take: /proc/meminfo, the memory cgroup, QF_MEMORY_LIMIT.
#include "core/memory.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace qf {
namespace {

// The first number in a one-number file (cgroup files); false when absent or "max".
bool read_number(const std::string& path, std::size_t& out) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word) || word.empty() || !std::isdigit(static_cast<unsigned char>(word[0]))) return false;
  out = std::strtoull(word.c_str(), nullptr, 10);
  return true;
}

// `key value` lines (meminfo "MemAvailable: N kB", cgroup memory.stat "inactive_file N").
bool read_keyed(const std::string& path, const std::string& key, std::size_t& out) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string k;
    std::size_t v = 0;
    if (words >> k >> v && (k == key || k == key + ":")) {
      out = v;
      return true;
    }
  }
  return false;
}

// Free room under one cgroup folder's limit; false when it sets none. Dropable page cache
// (inactive files) is counted as free: the kernel reclaims it before it kills.
bool cgroup_room(const std::string& dir, bool v2, std::size_t& room) {
  std::size_t limit = 0, usage = 0, cache = 0;
  if (!read_number(dir + (v2 ? "/memory.max" : "/memory.limit_in_bytes"), limit)) return false;
  if (limit >= (std::size_t{1} << 60)) return false;  // v1 writes "no limit" as ~2^63
  if (!read_number(dir + (v2 ? "/memory.current" : "/memory.usage_in_bytes"), usage)) return false;
  read_keyed(dir + "/memory.stat", v2 ? "inactive_file" : "total_inactive_file", cache);
  const std::size_t used = usage > cache ? usage - cache : 0;
  room = limit > used ? limit - used : 0;
  return true;
}

// The least room of the memory cgroups from this process' own up to the root of the mounted
// hierarchy (a container sees its own cgroup as the root).
bool cgroup_limit(std::size_t& room) {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  bool found = false;
  room = SIZE_MAX;
  while (std::getline(in, line)) {
    // "0::/path" (v2) or "4:memory:/path" (v1).
    const std::size_t a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1);
    const bool v2 = controllers.empty();
    if (!v2 && controllers.find("memory") == std::string::npos) continue;
    const std::string root = v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory";
    std::string path = line.substr(b + 1);
    for (;;) {
      std::size_t r = 0;
      if (cgroup_room(root + path, v2, r)) found = true, room = std::min(room, r);
      if (path.empty() || path == "/") break;
      path = path.substr(0, path.rfind('/'));
    }
  }
  return found;
}

}  // namespace

std::size_t parse_byte_size(const std::string& text) {
  std::size_t pos = 0;
  while (pos < text.size() && std::isdigit(static_cast<unsigned char>(text[pos]))) ++pos;
  std::string unit = text.substr(pos);
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (unit.size() >= 2 && unit.compare(unit.size() - 2, 2, "IB") == 0) unit.resize(unit.size() - 2);
  else if (unit.size() >= 2 && unit.back() == 'B') unit.pop_back();
  static const std::string kUnits = "KMGT";
  const std::size_t u = unit.empty() ? 0 : kUnits.find(unit) + 1;
  if (pos == 0 || pos > 18 || unit.size() > 1 || (!unit.empty() && u == 0))
    throw std::invalid_argument("expected a byte count such as 800M or 2G, got '" + text + "'");
  return std::strtoull(text.substr(0, pos).c_str(), nullptr, 10) << (10 * u);
}

std::string format_bytes(double bytes) {
  char buf[32];
  if (bytes >= 10.0 * (1 << 30)) std::snprintf(buf, sizeof buf, "%.0f GB", bytes / (1 << 30));
  else if (bytes >= 1 << 30) std::snprintf(buf, sizeof buf, "%.1f GB", bytes / (1 << 30));
  else std::snprintf(buf, sizeof buf, "%.0f MB", std::ceil(bytes / (1 << 20)));
  return buf;
}

MemoryBudget available_memory() {
  MemoryBudget m;
  std::size_t kb = 0, room = 0;
  if (read_keyed("/proc/meminfo", "MemAvailable", kb)) m = {kb * 1024, "MemAvailable"};
  if (cgroup_limit(room) && room < m.bytes) m = {room, "cgroup limit"};
  if (const char* cap = std::getenv("QF_MEMORY_LIMIT"); cap && *cap) {
    const std::size_t c = parse_byte_size(cap);
    if (c < m.bytes) m = {c, "QF_MEMORY_LIMIT"};
  }
  return m;
}

}  // namespace qf
