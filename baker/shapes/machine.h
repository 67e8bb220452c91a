// A generated multi-part machine (issue 49): an assembly as a CAD export gives it, one node per
// body, most of whose triangles lie inside a housing where no view can see them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"

namespace qf {

struct MachineOptions {
  std::uint64_t seed = 1;  // same seed, same machine: window, gears, motor, pipe run, bolts
};

// One body of the assembly: its own mesh and material (an opaque base colour, as CAD tools export).
struct MachinePart {
  std::string name;   // the node's name: "housing", "gear_large", ...
  bool inner = false;  // wholly inside the housing's cavity: seen only through its openings
  TriangleMesh mesh;   // closed prisms, no normals (flat-shaded faces), one material
};

struct Machine {
  std::vector<MachinePart> parts;
  Bounds cavity;  // the housing's inside: every inner part lies within it
};

// A gearbox about 1.9 x 1.2 x 1.2 units standing on y = 0 (glTF's up): a base plate, a closed
// box housing with walls 0.04 thick, opened by a window in its front (z+) and a port in its right
// end (x+) where the output shaft leaves; inside, a motor block, two shafts with a meshing pair of
// gears (18-40 teeth) and bearing blocks; outside, bolts along the cover, a coupling on the
// output shaft and a pipe run over the top and down the back. Each part one material.
Machine generate_machine(const MachineOptions& options = {});

// The assembly as one .glb: a root node "machine" whose children are the parts' nodes, each with
// its own mesh and material, named after the part (what a CAD export's scene holds).
std::vector<std::uint8_t> encode_machine_glb(const Machine& machine);

}  // namespace qf
