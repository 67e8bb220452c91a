// Support rectangles: weighted PCA plane, in-plane PCA axes, extent with splat radii, error.
#include "primitives/support.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace qf {
namespace {

Eigen::Vector3d v3(Vec3f p) { return {p.x, p.y, p.z}; }
Vec3f to_vec(const Eigen::Vector3d& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

// Any unit vector perpendicular to n.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = std::fabs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(a).normalized();
}

SupportRect rectangle_of(std::size_t d, const std::vector<Vec3f>& pos, const std::vector<Vec3f>& normals,
                         const std::vector<float>& radii, const SparseMatrix& psi, const Domains& dom,
                         const SupportOptions& o, const Eigen::Vector3d& model_center) {
  SupportRect r;
  r.domain = static_cast<std::uint32_t>(d);
  r.points = static_cast<std::uint32_t>(dom.size(d));
  const std::uint32_t* first = dom.points.data() + dom.offsets[d];
  const std::uint32_t* last = dom.points.data() + dom.offsets[d + 1];
  // 1. Weights, weighted centroid and covariance (relative to the first point, for precision).
  const Eigen::Vector3d origin = v3(pos[*first]);
  double w_sum = 0, r_sum = 0;
  Eigen::Vector3d s = Eigen::Vector3d::Zero(), n_sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d ss = Eigen::Matrix3d::Zero();
  for (const std::uint32_t* p = first; p != last; ++p) {
    const double w = o.weighted ? psi.coeff(*p, static_cast<Eigen::Index>(d)) : 1.0;
    const Eigen::Vector3d x = v3(pos[*p]) - origin;
    w_sum += w, s += w * x, ss += w * x * x.transpose();
    if (!normals.empty()) n_sum += w * v3(normals[*p]);
    r_sum += radii[*p];
  }
  const Eigen::Vector3d mean = s / w_sum;
  const Eigen::Matrix3d cov = ss / w_sum - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  const Eigen::Vector3d center = origin + mean;
  // 2. Orientation: with the points' normals, or away from the model's centre. A degenerate
  //    spread (one point, a line) takes the mean normal itself as the plane normal.
  const Eigen::Vector3d toward = !normals.empty() && n_sum.norm() > 0 ? n_sum.normalized() : (center - model_center);
  const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
  if (ev(1) <= 1e-12 * std::max(ev(2), 1e-300) && toward.norm() > 0) n = toward.normalized();
  if (n.dot(toward) < 0) n = -n;
  // 3. In-plane axes: PCA of the projected points (the projected covariance is P cov P).
  const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - n * n.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> in_plane(proj * cov * proj);
  Eigen::Vector3d u = in_plane.eigenvectors().col(2);
  u = (u - u.dot(n) * n);
  u = u.norm() > 1e-12 ? u.normalized() : perpendicular(n);
  const Eigen::Vector3d v = n.cross(u);
  // 4. Extent: every point's splat fits, plus the margin; and the distance to the plane.
  double lo_u = INFINITY, hi_u = -INFINITY, lo_v = INFINITY, hi_v = -INFINITY, dist = 0;
  for (const std::uint32_t* p = first; p != last; ++p) {
    const Eigen::Vector3d x = v3(pos[*p]) - center;
    double rad = radii[*p];
    if (o.projected_radii && !normals.empty()) rad *= std::fabs(v3(normals[*p]).dot(n));
    const double a = x.dot(u), b = x.dot(v);
    lo_u = std::min(lo_u, a - rad), hi_u = std::max(hi_u, a + rad);
    lo_v = std::min(lo_v, b - rad), hi_v = std::max(hi_v, b + rad);
    dist += std::fabs(x.dot(n));
  }
  r.mean_radius = static_cast<float>(r_sum / r.points);
  const double margin = double(o.margin) * r.mean_radius;
  lo_u -= margin, hi_u += margin, lo_v -= margin, hi_v += margin;
  r.center = to_vec(center + 0.5 * (lo_u + hi_u) * u + 0.5 * (lo_v + hi_v) * v);
  r.normal = to_vec(n), r.axis_u = to_vec(u), r.axis_v = to_vec(v);
  r.half_u = static_cast<float>(0.5 * (hi_u - lo_u)), r.half_v = static_cast<float>(0.5 * (hi_v - lo_v));
  r.error = dist / r.points;
  r.relative_error = r.mean_radius > 0 ? r.error / r.mean_radius : 0.0;
  return r;
}

}  // namespace

std::vector<SupportRect> support_rectangles(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& normals,
                                            const std::vector<float>& radii, const SparseMatrix& psi,
                                            const Domains& domains, const SupportOptions& options) {
  Bounds box;
  for (const Vec3f& p : positions) box.add(p);
  const Eigen::Vector3d model_center = v3(box.center());
  std::vector<std::size_t> nonempty;
  for (std::size_t d = 0; d < domains.count(); ++d)
    if (domains.size(d) > 0) nonempty.push_back(d);
  std::vector<SupportRect> out(nonempty.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(nonempty.size()); ++k)
    out[static_cast<std::size_t>(k)] = rectangle_of(nonempty[static_cast<std::size_t>(k)], positions, normals, radii, psi,
                                                    domains, options, model_center);
  return out;
}

}  // namespace qf
