// Brute-force triangle geometry for checking the mesh oracle: the distance between two
// triangles from closed-form point-triangle and segment-segment distances (Ericson, Real-Time
// Collision Detection, 5.1.5 and 5.1.9), with no FCL code involved. Header-only, tests only.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

namespace hullcheck::test {

/// A triangle by its corners.
using Triangle3 = std::array<Eigen::Vector3d, 3>;

/// Distance from `p` to the closest point of triangle `t` (Ericson 5.1.5).
inline double point_triangle_distance(const Eigen::Vector3d& p, const Triangle3& t) {
  const Eigen::Vector3d &a = t[0], &b = t[1], &c = t[2];
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

/// Distance between segments p1-q1 and p2-q2 (Ericson 5.1.9).
inline double segment_segment_distance(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                       const Eigen::Vector3d& p2, const Eigen::Vector3d& q2) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= 1e-300 && e <= 1e-300) return r.norm();
  if (a <= 1e-300) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 1e-300) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p1 + s * d1) - (p2 + t * d2)).norm();
}

/// Whether segment p-q crosses triangle `t` (Moller-Trumbore; coplanar contact not detected).
inline bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                     const Triangle3& t) {
  const Eigen::Vector3d e1 = t[1] - t[0], e2 = t[2] - t[0], d = q - p;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-300) return false;
  const Eigen::Vector3d s = p - t[0];
  const double u = s.dot(h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d r = s.cross(e1);
  const double v = d.dot(r) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double w = e2.dot(r) / det;
  return w >= 0.0 && w <= 1.0;
}

/// Distance between two triangles: 0 when an edge of one crosses the other, else the
/// smallest vertex-triangle or edge-edge distance (where the closest pair of two disjoint
/// triangles always lies).
inline double triangle_distance(const Triangle3& x, const Triangle3& y) {
  for (int i = 0; i < 3; ++i) {
    if (segment_crosses_triangle(x[i], x[(i + 1) % 3], y) ||
        segment_crosses_triangle(y[i], y[(i + 1) % 3], x)) {
      return 0.0;
    }
  }
  double best = INFINITY;
  for (int i = 0; i < 3; ++i) {
    best = std::min({best, point_triangle_distance(x[i], y), point_triangle_distance(y[i], x)});
    for (int j = 0; j < 3; ++j) {
      best = std::min(best, segment_segment_distance(x[i], x[(i + 1) % 3], y[j], y[(j + 1) % 3]));
    }
  }
  return best;
}

}  // namespace hullcheck::test
