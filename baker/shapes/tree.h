// A generated sample tree: the classic impostor case, where mesh simplification has nothing to
// collapse (thousands of separate alpha-masked leaf quads).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/types.h"

namespace qf {

struct TreeOptions {
  std::size_t leaves = 3000;
  std::uint64_t seed = 1;  // same seed, same tree, on every platform
};

// A trunk and branches (tapered tubes with a generated bark texture, material 0) and `leaves`
// quads (material 1: a generated leaf texture, alpha MASK at 0.5, double-sided) in a crown of
// radius ~1.3 around the branch tips, 4 units tall, standing on y = 0 (glTF's up).
TriangleMesh generate_tree(const TreeOptions& options = {});

struct BushOptions {
  std::size_t leaves = 1800;
  std::uint64_t seed = 1;
};

// A bush: 9-14 thin stems (the bark material 0) rising from the ground in a fan, and `leaves`
// small leaf quads (material 1, as the tree's) along their upper parts, about 1.2 units tall and
// 1.6 wide, standing on y = 0. Foliage without a trunk: its look is the leaves' coverage.
TriangleMesh generate_bush(const BushOptions& options = {});

struct CardTreeOptions {
  std::size_t cards = 220;
  std::uint64_t seed = 1;
};

// A broadleaf tree as game assets build one (issue 49): a trunk and limbs (bark, material 0) and
// `cards` square cards 0.6-0.9 a side (material 1, alpha MASK at 0.5, double-sided), each a
// texture of 40 scattered leaves whose cut-away texels are transparent black, facing random
// directions in a crown about the limbs' tips; about 4 units tall, standing on y = 0.
TriangleMesh generate_card_tree(const CardTreeOptions& options = {});

// A bare tree: a trunk and six limbs branching four times down to twigs far thinner than a pixel
// at the sizes it is seen far away (~0.004 units in a tree ~4 tall), bark only (material 0, as the
// tree's), opaque. The thin parts an impostor must not lose (issue 48); `seed` sets the branching.
TriangleMesh generate_bare_tree(std::uint64_t seed = 1);

}  // namespace qf
