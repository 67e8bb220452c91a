// A sample asset with material channels (issue 31, item 3): a flat 2 x 1 plate in z = 0, facing
// +z, double-sided, whose left half (x < 1) and right half are two glTF materials. `qf-bake generate plate`
// writes it; the tests bake it (nothing read from outside the repository).
#pragma once

#include "core/types.h"

namespace qf {

// `varying`: the left half a rough dielectric (roughness factor 0.9, metallic 0, no emission), the
// right half polished metal through its metallic-roughness texture (G 51 = roughness 0.2, B 255 =
// metallic 1, factors 1) and emitting (1, 0.5, 0): factor x a white emissive texture. Otherwise
// both halves have roughness 0.5 and metallic 0 (the right half through a texture of G 255, B 255
// under factors 0.5 and 0) and no emission: constant channels, which a level keeps as factors.
// `occluded`: the right half also has an occlusion texture of R 128 (occlusion 0.5).
TriangleMesh generate_material_plate(bool varying = true, bool occluded = false);

}  // namespace qf
