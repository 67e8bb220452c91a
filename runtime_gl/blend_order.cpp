// Draw lists of the render methods (see blend_order.h).
#include "runtime_gl/blend_order.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"

namespace qf::render {
namespace {

const std::vector<std::pair<std::string, Method>>& table() {
  static const std::vector<std::pair<std::string, Method>> t{
      {"overlap", Method::kOverlap},          {"two-pass", Method::kTwoPass},  {"backface-hard", Method::kBackfaceHard},
      {"backface-soft", Method::kBackfaceSoft}, {"blend-all", Method::kBlendAll}, {"no-blend", Method::kNoBlend},
      {"engine", Method::kEngine}};
  return t;
}

bool faces(const Item& it, Vec3f eye) { return dot(it.normal, eye - it.center) > 0; }
// Double-sided levels draw quads seen from behind too (lit with the flipped normal), so open
// surfaces and thin parts show from every side; single-sided ones cull them as GL would.
bool visible(const ImpostorScene& s, const Item& it, Vec3f eye) { return s.double_sided || faces(it, eye); }

// Item indices sorted by distance from the eye, nearest first; ties by index.
std::vector<std::uint32_t> front_to_back(const ImpostorScene& s, Vec3f eye) {
  std::vector<float> d2(s.items.size());
  for (std::size_t k = 0; k < s.items.size(); ++k) {
    const Vec3f v = s.items[k].center - eye;
    d2[k] = dot(v, v);
  }
  std::vector<std::uint32_t> order(s.items.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return d2[a] < d2[b]; });
  return order;
}

// Paper fig. 10: the front-most visible primitive not yet drawn and its not-yet-drawn neighbours
// are blended, then the primitive's pixels are locked in the depth buffer. Neighbours facing away
// are culled (paper fig. 14c: "P2 is not rendered because it is backfacing"); drawn, they would add
// their colour through the primitive in front of them wherever the surface bends by more than 90°.
// A double-sided level's back-facing quads still come in their own turn, behind the locks of
// everything in front of them: they fill what nothing in front covers (an open surface's inside).
std::vector<DrawOp> overlap(const ImpostorScene& s, Vec3f eye) {
  std::vector<DrawOp> ops;
  std::vector<char> drawn(s.items.size(), 0);
  const bool graph = s.offsets.size() == s.items.size() + 1;
  for (std::uint32_t d : front_to_back(s, eye)) {
    if (!visible(s, s.items[d], eye)) continue;
    if (!drawn[d]) ops.push_back({d, Pass::kColor}), drawn[d] = 1;
    if (graph)
      for (std::uint32_t j = s.offsets[d]; j < s.offsets[d + 1]; ++j) {
        const std::uint32_t e = s.neighbors[j];
        if (!drawn[e] && faces(s.items[e], eye)) ops.push_back({e, Pass::kColor}), drawn[e] = 1;
      }
    ops.push_back({d, Pass::kLock});
  }
  return ops;
}

}  // namespace

const std::vector<std::string>& method_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& e : table()) n.push_back(e.first);
    return n;
  }();
  return names;
}

Method method_from_name(const std::string& name) {
  for (const auto& e : table())
    if (e.first == name) return e.second;
  std::string all;
  for (const auto& n : method_names()) all += (all.empty() ? "" : ", ") + n;
  throw UsageError("unknown render method '" + name + "' (one of: " + all + ")");
}

std::string method_name(Method m) {
  for (const auto& e : table())
    if (e.second == m) return e.first;
  return "?";
}

bool is_additive(Method m) { return m != Method::kNoBlend && m != Method::kEngine; }

std::vector<DrawOp> plan_draws(Method method, const ImpostorScene& s, Vec3f eye) {
  const auto n = static_cast<std::uint32_t>(s.items.size());
  std::vector<DrawOp> ops;
  switch (method) {
    case Method::kOverlap:
      return overlap(s, eye);
    case Method::kTwoPass:
      // Unsorted: the offset depth image decides which fragments blend (thesis 4.4.2).
      for (std::uint32_t k = 0; k < n; ++k)
        if (visible(s, s.items[k], eye)) ops.push_back({k, Pass::kDepthOffset});
      for (std::uint32_t k = 0; k < n; ++k)
        if (visible(s, s.items[k], eye)) ops.push_back({k, Pass::kColor});
      return ops;
    case Method::kBackfaceHard:
    case Method::kBackfaceSoft: {
      // Back to front: a back face wipes (or darkens) what lies behind it (thesis 4.4.3).
      std::vector<std::uint32_t> order = front_to_back(s, eye);
      std::reverse(order.begin(), order.end());
      const Pass dark = method == Method::kBackfaceHard ? Pass::kDarkenHard : Pass::kDarkenSoft;
      for (std::uint32_t k : order) ops.push_back({k, faces(s.items[k], eye) ? Pass::kAddNoDepth : dark});
      return ops;
    }
    case Method::kBlendAll:
      for (std::uint32_t k = 0; k < n; ++k)
        if (visible(s, s.items[k], eye)) ops.push_back({k, Pass::kAddNoDepth});
      return ops;
    case Method::kNoBlend:
      for (std::uint32_t k = 0; k < n; ++k)
        if (visible(s, s.items[k], eye)) ops.push_back({k, Pass::kOpaque});
      return ops;
    case Method::kEngine:  // not a pass list: draw_engine draws the file's materials
      return ops;
  }
  return ops;
}

}  // namespace qf::render
