// A structure-aware libFuzzer mutator for the glTF targets (fuzz_gltf, fuzz_glb; issue 50): with
// some probability it nests a JSON value hundreds or thousands of levels deeper, doubles an array,
// or grows the node graph (a chain of thousands of nodes, copies of nodes, extra children
// references), in a .gltf's text or a .glb's JSON chunk (its lengths rewritten to match); else it
// hands the bytes to libFuzzer's own mutator. Byte mutations alone do not reach such structures
// (each level or node is one more insertion that earns no new coverage); these mutations do in
// one step, so the JSON-depth and node-graph cases are found within minutes.
// Set QF_FUZZ_MUTATOR=0 to use libFuzzer's mutator alone (the comparison in tests/fuzz/README.md).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/input_limits.h"

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size);

namespace qf::fuzz {

using Rng = std::minstd_rand;

// A count from 1 to 2^max_bits with every power of two equally likely: small steps often, and
// now and then one large enough for the cases (~14,500 levels, ~8,100 nodes) at once.
inline std::size_t spread_count(Rng& rng, int max_bits) {
  const int bits = static_cast<int>(rng() % static_cast<unsigned>(max_bits + 1));
  const std::size_t base = std::size_t{1} << bits;
  return base + rng() % base;
}

// The index just past the JSON value whose opening bracket is at `open` (text[open] is '[' or
// '{'), skipping strings; text.size() when it is not closed.
inline std::size_t value_end(const std::string& text, std::size_t open) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = open; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if ((c == ']' || c == '}') && --depth == 0) {
      return i + 1;
    }
  }
  return text.size();
}

// A random opening bracket of `text` (npos when it has none): a few random probes, then the first
// bracket after the last probe, so that long texts are not scanned whole for each choice.
inline std::size_t random_bracket(const std::string& text, Rng& rng) {
  if (text.empty()) return std::string::npos;
  const std::size_t from = rng() % text.size();
  const std::size_t at = text.find_first_of("[{", from);
  return at != std::string::npos ? at : text.find_first_of("[{");
}

// Wraps the value at a random bracket in `levels` arrays or objects ({"a": ...}), keeping the
// text within `max_size` (fewer levels when it must). False when the text has no bracket.
inline bool nest_deeper(std::string& text, std::size_t max_size, Rng& rng) {
  const std::size_t open = random_bracket(text, rng);
  if (open == std::string::npos) return false;
  const std::size_t close = value_end(text, open);
  const bool objects = rng() % 4 == 0;
  const std::size_t per_level = objects ? 6 : 2;  // {"a": and }, or [ and ]
  std::size_t levels = spread_count(rng, 14);
  if (text.size() >= max_size) return false;
  levels = std::min(levels, (max_size - text.size()) / per_level);
  if (levels == 0) return false;
  std::string head, tail(levels, objects ? '}' : ']');
  head.reserve(levels * (per_level - 1));
  for (std::size_t i = 0; i < levels; ++i) head += objects ? "{\"a\":" : "[";
  text = text.substr(0, open) + head + text.substr(open, close - open) + tail + text.substr(close);
  return true;
}

// Doubles the elements of a random array (or members of an object: duplicate keys, which JSON
// parsers take or refuse differently), within max_size. False when nothing was changed.
inline bool double_contents(std::string& text, std::size_t max_size, Rng& rng) {
  const std::size_t open = random_bracket(text, rng);
  if (open == std::string::npos) return false;
  const std::size_t close = value_end(text, open);
  if (close == text.size() || close - open < 3) return false;  // unclosed or empty
  const std::string inner = text.substr(open + 1, close - open - 2);
  if (text.size() + inner.size() + 1 > max_size) return false;
  text.insert(close - 1, "," + inner);
  return true;
}

// ---- The node graph, on the parsed JSON (a document that does not parse is left alone). ----

// The index of a new node appended to j["nodes"] (made an array when it is not).
inline std::size_t append_node(nlohmann::json& j, nlohmann::json node) {
  if (!j["nodes"].is_array()) j["nodes"] = nlohmann::json::array();
  j["nodes"].push_back(std::move(node));
  return j["nodes"].size() - 1;
}

// Makes `child` a child of node `parent`, or a root of the default scene when parent < 0.
inline void link_child(nlohmann::json& j, long parent, std::size_t child) {
  if (parent >= 0 && static_cast<std::size_t>(parent) < j["nodes"].size() && j["nodes"][parent].is_object()) {
    nlohmann::json& children = j["nodes"][parent]["children"];
    if (!children.is_array()) children = nlohmann::json::array();
    children.push_back(child);
    return;
  }
  if (!j["scenes"].is_array() || j["scenes"].empty()) j["scenes"] = nlohmann::json::array({nlohmann::json::object()});
  if (!j["scenes"][0].is_object()) j["scenes"][0] = nlohmann::json::object();
  nlohmann::json& roots = j["scenes"][0]["nodes"];
  if (!roots.is_array()) roots = nlohmann::json::array();
  roots.push_back(child);
}

// Appends `count` nodes, each the child of the one before (named `twice` times: a tree when 1, a
// graph whose instances double per node when 2), the first hung below a random existing node or
// a scene root, the last with the first mesh when there is one.
inline void grow_chain(nlohmann::json& j, std::size_t count, int twice, Rng& rng) {
  const std::size_t before = j["nodes"].is_array() ? j["nodes"].size() : 0;
  const long parent = before > 0 && rng() % 2 ? static_cast<long>(rng() % before) : -1;
  for (std::size_t k = 0; k < count; ++k) {
    nlohmann::json node = nlohmann::json::object();
    const std::size_t next = before + k + 1;
    if (k + 1 < count) node["children"] = twice == 2 ? nlohmann::json::array({next, next}) : nlohmann::json::array({next});
    else if (j.contains("meshes")) node["mesh"] = 0;
    append_node(j, std::move(node));
  }
  link_child(j, parent, before);
}

// One node-graph change at random: a chain (tree or doubling), copies of existing nodes, or a
// children reference from one node to another (a cycle, a node reached twice, or a new edge).
inline void mutate_nodes(nlohmann::json& j, Rng& rng) {
  const std::size_t n = j["nodes"].is_array() ? j["nodes"].size() : 0;
  switch (n == 0 ? 0 : rng() % 4) {
    case 0: grow_chain(j, spread_count(rng, 13), 1, rng); break;
    case 1: grow_chain(j, spread_count(rng, 6), 2, rng); break;
    case 2:
      for (std::size_t k = spread_count(rng, 8); k > 0; --k) append_node(j, j["nodes"][rng() % n]);
      break;
    default: link_child(j, static_cast<long>(rng() % n), rng() % (n + 1)); break;
  }
}

// The node-graph mutation on a JSON text: parses it (only when it nests no deeper than the
// readers accept, so that the parse stays cheap), mutates, prints it compact. False when the text
// is not a JSON object or the result would exceed max_size.
inline bool mutate_node_graph(std::string& text, std::size_t max_size, Rng& rng) {
  if (json_nesting_depth(text.data(), text.size()) > kMaxJsonDepth) return false;
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) return false;
  mutate_nodes(j, rng);
  std::string out = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);  // bytes that are not UTF-8
  if (out.size() > max_size) return false;
  text.swap(out);
  return true;
}

// ---- .glb framing ----------------------------------------------------------------------------

inline std::uint32_t read_le32(const std::uint8_t* p) { return p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t{p[3]} << 24; }
inline void put_le32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

// A .glb split into its JSON chunk's text and what follows the chunk (the BIN chunk, or junk).
struct GlbParts {
  std::string json;
  std::vector<std::uint8_t> rest;
};

// The parts of a .glb whose JSON chunk header reads (glTF 2.0, 4.4.3: 12-byte header, then the
// JSON chunk's length and type); false for anything else (a .gltf, or a header cut short).
inline bool split_glb(const std::uint8_t* data, std::size_t size, GlbParts& parts) {
  if (size < 20 || std::memcmp(data, "glTF", 4) != 0 || std::memcmp(data + 16, "JSON", 4) != 0) return false;
  const std::size_t length = std::min<std::size_t>(read_le32(data + 12), size - 20);
  parts.json.assign(reinterpret_cast<const char*>(data + 20), length);
  parts.rest.assign(data + 20 + length, data + size);
  return true;
}

// The .glb of `parts` with correct lengths (the JSON padded with spaces to 4 bytes, as the format
// asks): header, version 2, total length, JSON chunk, then the rest as it was.
inline std::vector<std::uint8_t> join_glb(const GlbParts& parts) {
  std::string json = parts.json;
  while (json.size() % 4) json += ' ';
  std::vector<std::uint8_t> out{'g', 'l', 'T', 'F'};
  put_le32(out, 2);
  put_le32(out, static_cast<std::uint32_t>(20 + json.size() + parts.rest.size()));
  put_le32(out, static_cast<std::uint32_t>(json.size()));
  out.insert(out.end(), {'J', 'S', 'O', 'N'});
  out.insert(out.end(), json.begin(), json.end());
  out.insert(out.end(), parts.rest.begin(), parts.rest.end());
  return out;
}

// ---- The mutator -----------------------------------------------------------------------------

// One structural mutation of a JSON text (nest, double, node graph), within max_size bytes.
inline bool mutate_json_text(std::string& text, std::size_t max_size, Rng& rng) {
  switch (rng() % 3) {
    case 0: return nest_deeper(text, max_size, rng);
    case 1: return double_contents(text, max_size, rng);
    default: return mutate_node_graph(text, max_size, rng);
  }
}

// Whether the structural mutations are on: QF_FUZZ_MUTATOR=0 turns them off.
inline bool structural_mutations_on() {
  static const bool on = [] {
    const char* v = std::getenv("QF_FUZZ_MUTATOR");
    return !(v && std::strcmp(v, "0") == 0);
  }();
  return on;
}

// LLVMFuzzerCustomMutator's body: a structural mutation one time in four (the text of a .gltf, or
// the JSON chunk of a .glb rewritten with its lengths), libFuzzer's mutator otherwise or when the
// structural one cannot apply. Returns the new size (<= max_size).
inline std::size_t mutate_gltf(std::uint8_t* data, std::size_t size, std::size_t max_size, unsigned seed) {
  Rng rng(seed);
  if (!structural_mutations_on() || rng() % 4 != 0) return LLVMFuzzerMutate(data, size, max_size);
  GlbParts glb;
  const bool binary = split_glb(data, size, glb);
  std::string text = binary ? glb.json : std::string(reinterpret_cast<const char*>(data), size);
  const std::size_t framing = binary ? size - glb.json.size() + 3 : 0;  // header, rest, padding
  if (max_size <= framing || !mutate_json_text(text, max_size - framing, rng)) return LLVMFuzzerMutate(data, size, max_size);
  if (binary) {
    glb.json.swap(text);
    const std::vector<std::uint8_t> out = join_glb(glb);
    if (out.size() > max_size) return LLVMFuzzerMutate(data, size, max_size);
    std::memcpy(data, out.data(), out.size());
    return out.size();
  }
  std::memcpy(data, text.data(), text.size());
  return text.size();
}

}  // namespace qf::fuzz
