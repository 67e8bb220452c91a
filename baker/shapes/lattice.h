// A generated lattice tower: the thin-part impostor case (issue 31), where a mesh simplifier keeps
// every beam or collapses them, and splats one or two samples across a beam make blobs.
#pragma once

#include <cstdint>

#include "core/types.h"

namespace qf {

struct LatticeOptions {
  std::uint64_t seed = 1;  // same seed, same tower, on every platform: storeys, taper, bracing, beam width
};

// A square tower standing on y = 0 (glTF's up), about 4 units tall, its base 1.0-1.6 wide tapering
// to a third to a half of that at the top: four corner posts, a horizontal ring of beams at every
// storey (6-10), each face braced per storey by an X or a single diagonal, beams of square section
// 0.025-0.04 wide; a cross arm near the top. Flat-shaded boxes (no normals: an engine draws each
// face flat) with one opaque painted-steel material, so the look is the shape.
TriangleMesh generate_lattice(const LatticeOptions& options = {});

}  // namespace qf
