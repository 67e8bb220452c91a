// Generated foliage built as game artists build it, from alpha-tested cards (issue 49): a conifer
// of drooping branch cards and a grass clump of bent blades; the broadleaf card tree is in tree.h.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/types.h"

namespace qf {

struct ConiferOptions {
  std::size_t cards = 140;  // branch cards, spread over the tiers about 8 to a tier
  std::uint64_t seed = 1;   // same seed, same tree, on every platform
};

// A conifer 5-6 units tall standing on y = 0 (glTF's up): a tapered trunk (bark, material 0) and
// `cards` branch cards (material 1 "needles": a 128 x 128 texture of a twig, side twigs and dark
// green needles, cut-away texels transparent black, alpha MASK at 0.5, double-sided) in tiers
// round the trunk, each card bent along its length so that its tip droops, the tiers shorter
// towards the top: a cone about 3.4 units across at its base; two crossed cards make the leader.
// Throws UsageError for cards outside 1..100000.
TriangleMesh generate_conifer(const ConiferOptions& options = {});

struct GrassOptions {
  std::size_t blades = 300;
  std::uint64_t seed = 1;
};

// A grass clump standing on y = 0: `blades` bent blades, each a strip of 4 quads 0.3-0.8 tall and
// 0.012-0.02 wide rising from a disc of radius 0.12, leaning and curving outwards, its texture one
// of 8 columns of a 128 x 128 atlas (a blade tapering to a point, from dark green to straw
// yellow; cut-away texels transparent black), one material (alpha MASK at 0.5, double-sided).
// Throws UsageError for blades outside 1..100000.
TriangleMesh generate_grass(const GrassOptions& options = {});

}  // namespace qf
