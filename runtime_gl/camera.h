// Cameras for runtime_gl: an orbit around a bounding sphere (azimuth/elevation/distance, or view i
// of N spread evenly over the sphere), and its OpenGL matrices. Pure CPU, no GL.
#pragma once

#include <array>

#include "core/types.h"

namespace qf::render {

using Mat4 = std::array<float, 16>;  // column-major, as glLoadMatrixf takes it

struct Sphere {
  Vec3f center;
  float radius = 1;
};
// The sphere around a box: its centre, half its diagonal (a point box gets radius 1).
Sphere bounding_sphere(const Bounds& b);

struct Camera {
  Vec3f eye, target, up{0, 1, 0};
  float fovy_degrees = 30;
  float near_plane = 0.1f, far_plane = 100;
  int width = 512, height = 512;
  Mat4 view() const;        // world -> eye (gluLookAt)
  Mat4 projection() const;  // gluPerspective
  // Z0 = height / (2 tan(fovy / 2)): pixels per world unit at distance 1, so a length L at distance
  // d spans L Z0 / d pixels and one pixel there is R = d / Z0 long (paper 5; Low & Tan 4).
  double focal_pixels() const;
};

// Unit direction from the target to the eye: azimuth about +Y from +Z, elevation above the XZ plane
// (degrees; Y is up, as in glTF).
Vec3f orbit_direction(float azimuth_degrees, float elevation_degrees);
// Direction i of n spread evenly over the sphere (a Fibonacci lattice; deterministic).
Vec3f sphere_direction(int i, int n);
// The direction of frame (column, row) of an octahedral impostor's `frames` x `frames` grid (the
// view-dependent peer of issue 49: scripts/octahedral_peer.py reads the same layout): grid point
// (u, v) = -1 + 2 (column, row) / (frames - 1) on the octahedral map of the whole sphere, Y up:
// (u, 1 - |u| - |v|, v) on the upper half; below the equator (|u| + |v| > 1) the corners fold
// over, x = (1 - |v|) sign(u), z = (1 - |u|) sign(v). Unit length; frames >= 2.
Vec3f octahedral_direction(int column, int row, int frames);

// Looks at the sphere from `direction` (unit, target to eye). distance <= 0 frames the sphere: it
// just fits the smaller of the two fields of view. Near/far hug the sphere.
Camera orbit_camera(const Sphere& s, Vec3f direction, float distance, int width, int height, float fovy_degrees = 30);

}  // namespace qf::render
