// The crossed billboard (issue 31's peer): what engines ship for far foliage. Three vertical
// cards through the asset's centre, 60 degrees apart, and one horizontal card, each showing an
// orthographic view of the whole asset (surface_paint.h) with its coverage as alpha, alpha-tested
// and double-sided. The fidelity league measures the impostor levels against it at equal bytes.
#pragma once

#include <cstddef>

#include "core/types.h"

namespace qf {

struct BillboardOptions {
  int side = 128;        // texels along each card's longer side
  float alpha_cutoff = 0.5f;
};

// The four cards as a mesh with one MASK material and texture each (draw with
// encode_textured_mesh_glb). The vertical cards span the asset's extent across them and its
// height (y, glTF's up); the horizontal one its footprint at the centre's height. Normals: none
// (an engine lights each card by its face, flipped behind): the cards carry colour and coverage.
TriangleMesh crossed_billboard(const TriangleMesh& mesh, const BillboardOptions& options = {});

}  // namespace qf
