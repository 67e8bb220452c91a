// Test-only: the two stack overflows of issue 50 put back into a harness, to measure how fast the
// fuzzer finds them (tests/fuzz/README.md, "Time to find"). Included by fuzz_gltf.cpp only when
// QF_FUZZ_CANARY is defined, i.e. in the target fuzz_gltf_canary, which nothing ships or runs by
// default (EXCLUDE_FROM_ALL; scripts/fuzz.sh never builds it). The reader itself is unchanged: the
// harness replays what 0.8.0 did recursively, once per level, on the same bytes:
// - tinygltf's parser recursed once per JSON level and overflowed at ~14,500 (QF_CANARY_JSON_DEPTH);
// - the glTF reader walked nodes recursively and overflowed at a chain of ~8,100 (QF_CANARY_CHAIN),
//   on files tinygltf accepts (the walk came after the parse).
// Reaching either depth aborts ("canary: ..."), a crash for libFuzzer. 0 turns a check off.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/input_limits.h"

namespace qf::fuzz::canary {

inline std::size_t env_limit(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtoull(v, nullptr, 10) : fallback;
}

[[noreturn]] inline void found(const char* what, std::size_t depth) {
  std::fprintf(stderr, "canary: %s %zu deep\n", what, depth);
  std::abort();
}

// The JSON text of a .gltf, or a .glb's JSON chunk (its declared length, within the bytes).
inline std::string json_text(const std::uint8_t* data, std::size_t size) {
  if (size >= 20 && std::memcmp(data, "glTF", 4) == 0) {
    const std::size_t length = data[12] | data[13] << 8 | data[14] << 16 | std::size_t{data[15]} << 24;
    return std::string(reinterpret_cast<const char*>(data + 20), std::min(length, size - 20));
  }
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Recurses once per JSON level from text[at] (just past an opening bracket) to its closing
// bracket, as a recursive-descent parser does; aborts at `limit` levels. Returns the index past
// the closing bracket (or the end).
__attribute__((noinline)) inline std::size_t nest(const std::string& text, std::size_t at, std::size_t depth, std::size_t limit) {
  if (limit && depth >= limit) found("JSON nested", depth);
  bool in_string = false;
  while (at < text.size()) {
    const char c = text[at++];
    if (in_string) {
      if (c == '\\') ++at;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      at = nest(text, at, depth + 1, limit);
    } else if (c == ']' || c == '}') {
      return at;
    }
  }
  return at;
}

// 0.8.0's recursive node walk from `node` (each node once, as a tree walk), aborting `limit`
// levels down.
__attribute__((noinline)) inline void walk(const nlohmann::json& nodes, std::size_t node, std::size_t depth, std::size_t limit,
                                           std::vector<char>& reached) {
  if (limit && depth >= limit) found("node chain", depth);
  if (node >= nodes.size() || reached[node] || !nodes[node].is_object()) return;
  reached[node] = 1;
  const auto children = nodes[node].find("children");
  if (children == nodes[node].end() || !children->is_array()) return;
  for (const nlohmann::json& c : *children)
    if (c.is_number_unsigned()) walk(nodes, c.get<std::size_t>(), depth + 1, limit, reached);
}

// The roots 0.8.0 walked: the default scene's nodes (scene 0 without "scene"), else every node.
inline std::vector<std::size_t> roots(const nlohmann::json& j) {
  std::vector<std::size_t> out;
  const std::size_t scene = j.contains("scene") && j["scene"].is_number_unsigned() ? j["scene"].get<std::size_t>() : 0;
  if (j.contains("scenes") && j["scenes"].is_array() && scene < j["scenes"].size() && j["scenes"][scene].is_object() &&
      j["scenes"][scene].contains("nodes") && j["scenes"][scene]["nodes"].is_array()) {
    for (const nlohmann::json& r : j["scenes"][scene]["nodes"])
      if (r.is_number_unsigned()) out.push_back(r.get<std::size_t>());
    return out;
  }
  for (std::size_t i = 0; i < j["nodes"].size(); ++i) out.push_back(i);
  return out;
}

// Error codes the reader raises before its node walk (parse, references, extensions): the walk,
// and so 0.8.0's recursion, did not run on such a file.
inline bool refused_before_walk(const std::string& code) {
  static const std::set<std::string> before = {"gltf.json_depth", "gltf.json_type",         "gltf.parse",
                                                "gltf.extension",  "gltf.unsupported_extension", "gltf.draco",
                                                "gltf.meshopt",    "gltf.outside_asset",     "gltf.not_regular_file",
                                                "gltf.no_scene"};
  return before.count(code) > 0;
}

// The two replays on one input; `code` is the reader's error code ("" when it read the file).
inline void check(const std::uint8_t* data, std::size_t size, const std::string& code) {
  static const std::size_t json_limit = env_limit("QF_CANARY_JSON_DEPTH", 14500), chain_limit = env_limit("QF_CANARY_CHAIN", 8100);
  const std::string text = json_text(data, size);
  if (json_limit) nest(text, 0, 0, json_limit);
  if (!chain_limit || refused_before_walk(code) || json_nesting_depth(text.data(), text.size()) > kMaxJsonDepth) return;
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object() || !j.contains("nodes") || !j["nodes"].is_array()) return;
  std::vector<char> reached(j["nodes"].size(), 0);
  for (std::size_t r : roots(j)) walk(j["nodes"], r, 1, chain_limit, reached);
}

}  // namespace qf::fuzz::canary
