// Orbit cameras and their matrices (see camera.h).
#include "runtime_gl/camera.h"

#include <algorithm>
#include <cmath>

namespace qf::render {

namespace {
constexpr float kPi = 3.14159265358979f;
float radians(float d) { return d * kPi / 180.0f; }
}  // namespace

Sphere bounding_sphere(const Bounds& b) {
  if (b.empty()) return {};
  const float r = 0.5f * b.diagonal();
  return {b.center(), r > 0 ? r : 1.0f};
}

Mat4 Camera::view() const {
  const Vec3f f = normalized(target - eye), s = normalized(cross(f, up), {1, 0, 0}), u = cross(s, f);
  return {s.x, u.x, -f.x, 0, s.y, u.y, -f.y, 0, s.z, u.z, -f.z, 0, -dot(s, eye), -dot(u, eye), dot(f, eye), 1};
}

Mat4 Camera::projection() const {
  const float t = 1.0f / std::tan(radians(fovy_degrees) * 0.5f);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float n = near_plane, f = far_plane;
  return {t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (f + n) / (n - f), -1, 0, 0, 2 * f * n / (n - f), 0};
}

Vec3f orbit_direction(float azimuth_degrees, float elevation_degrees) {
  const float a = radians(azimuth_degrees), e = radians(elevation_degrees);
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

Vec3f sphere_direction(int i, int n) {
  const double golden = 3.14159265358979 * (3.0 - std::sqrt(5.0));
  const double y = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(std::max(0.0, 1.0 - y * y)), phi = golden * i;
  return {static_cast<float>(r * std::sin(phi)), static_cast<float>(y), static_cast<float>(r * std::cos(phi))};
}

Vec3f octahedral_direction(int column, int row, int frames) {
  const float u = -1.0f + 2.0f * static_cast<float>(column) / static_cast<float>(frames - 1);
  const float v = -1.0f + 2.0f * static_cast<float>(row) / static_cast<float>(frames - 1);
  float x = u, z = v;
  const float y = 1.0f - std::fabs(u) - std::fabs(v);
  if (y < 0) x = (1.0f - std::fabs(v)) * (u < 0 ? -1.0f : 1.0f), z = (1.0f - std::fabs(u)) * (v < 0 ? -1.0f : 1.0f);
  return normalized(Vec3f{x, y, z}, {0, 1, 0});
}

double Camera::focal_pixels() const { return height / (2 * std::tan(double(radians(fovy_degrees)) * 0.5)); }

Camera orbit_camera(const Sphere& s, Vec3f direction, float distance, int width, int height, float fovy_degrees) {
  Camera c;
  c.width = width;
  c.height = height;
  c.fovy_degrees = fovy_degrees;
  if (distance <= 0) {
    // The sphere fits the narrower field of view: sin(half angle) = r / d.
    const float half_y = radians(fovy_degrees) * 0.5f;
    const float half_x = std::atan(std::tan(half_y) * static_cast<float>(width) / static_cast<float>(height));
    distance = s.radius / std::sin(std::min(half_x, half_y));
  }
  c.target = s.center;
  c.eye = s.center + direction * distance;
  // Y is up unless we look along it.
  c.up = std::fabs(direction.y) > 0.99f ? Vec3f{0, 0, -1} : Vec3f{0, 1, 0};
  c.near_plane = std::max(distance - 1.5f * s.radius, distance * 1e-3f);
  c.far_plane = distance + 1.5f * s.radius;
  return c;
}

}  // namespace qf::render
