// The ordering and blending decisions of every render method, as plain CPU functions (no GL):
// which item is drawn in which pass, in what order (method.md 7; paper 4, fig. 10; thesis 4.4).
// draw_gl11 turns each pass into fixed-function state.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime_gl/scene.h"

namespace qf::render {

enum class Method {
  kOverlap,       // overlapping domains: sorted front to back, neighbours blended, lock by depth (default)
  kTwoPass,       // depth pass pushed back by an offset, then additive colour pass (thesis 4.4.2)
  kBackfaceHard,  // back to front; back faces reset the colour where alpha > 0 (thesis 4.4.3)
  kBackfaceSoft,  // back to front; back faces darken the colour by their alpha (thesis 4.4.3)
  kBlendAll,      // every fragment added, no depth test (thesis app. C)
  kNoBlend,       // opaque quads, alpha test at alpha_ref, depth tested (thesis app. C)
  kEngine,        // what a standard glTF PBR engine does (draw_engine.h; no pass list)
};
// "overlap", "two-pass", "backface-hard", "backface-soft", "blend-all", "no-blend", "engine".
const std::vector<std::string>& method_names();
Method method_from_name(const std::string& name);  // throws UsageError for an unknown name
std::string method_name(Method m);

enum class Pass : std::uint8_t {
  kColor,        // colour only, additive (premultiplied texel * lighting), depth tested, no depth writes
  kLock,         // depth only, alpha test alpha > alpha_ref: locks the pixels (paper fig. 10)
  kDepthOffset,  // depth only, pushed back by the depth offset, alpha test alpha > 0 (two-pass)
  kDarkenHard,   // colour and coverage set to 0 where alpha > 0, no depth test (dark back-face)
  kDarkenSoft,   // colour and coverage scaled by 1 - alpha, no depth test (dark back-face, soft)
  kAddNoDepth,   // colour only, additive, no depth test (blend-all; back-face methods' front faces)
  kOpaque,       // straight colour, alpha test > alpha_ref, depth tested and written (no-blend)
};

struct DrawOp {
  std::uint32_t item;
  Pass pass;
};

// Whether the method draws additively onto black and composites the background afterwards by
// coverage (so it is right over any background), rather than drawing over the background directly.
bool is_additive(Method m);

// The draw list of one frame seen from `eye` (empty for kEngine). Sorting is by squared distance
// from the eye to the item's centre, ties by index (stable). An item faces the eye when
// dot(normal, eye - centre) > 0; on single-sided levels every method but the back-face ones culls
// items that do not (as GL back-face culling would); double-sided levels draw them too.
std::vector<DrawOp> plan_draws(Method method, const ImpostorScene& scene, Vec3f eye);

}  // namespace qf::render
