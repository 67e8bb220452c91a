// A generated power pylon (issue 49): the thin-beam impostor case at its hardest, a tower whose
// every member is ~1/200 of its height or thinner, far below a pixel at the sizes it is seen at.
#pragma once

#include <cstdint>

#include "core/types.h"

namespace qf {

struct PylonOptions {
  std::uint64_t seed = 1;  // same seed, same pylon, on every platform: height, panels, arms
};

// A lattice transmission tower standing on y = 0 (glTF's up), 36-44 units tall (metres), its
// four legs splaying from a waist at 0.62 of the height to a base 0.2-0.24 of the height wide;
// X-braced panels on every face with a ring of horizontals at each panel's top; two or three
// tiers of cross arms (pyramid trusses of four chords laced by zigzag struts) reaching out on
// both sides, an insulator string hanging from each arm's tip, an earth-wire peak on top. Beams
// are square boxes (add_beam): legs 1/200 of the height wide, arm chords 1/260, braces and
// struts 1/320, insulators 1/160. No normals (an engine draws each face flat); materials 0
// "steel" (weathered galvanised grey) and 1 "insulator" (glazed dark green), opaque.
TriangleMesh generate_pylon(const PylonOptions& options = {});

}  // namespace qf
