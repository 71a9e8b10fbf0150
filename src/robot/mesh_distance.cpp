#include "mesh_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace hullcheck::detail {

namespace {
constexpr int kLeafSize = 4;  // triangles per leaf of the box tree
constexpr int kDegenerateRay = std::numeric_limits<int>::min();  // crossings(): retry
}  // namespace

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Barycentric tests on the dot products d1..d6 of the corner-to-p vectors with the edges.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double den = d1 - d3;
    return den > 0.0 ? Eigen::Vector3d(a + (d1 / den) * ab) : a;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double den = d2 - d6;
    return den > 0.0 ? Eigen::Vector3d(a + (d2 / den) * ac) : a;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double den = (d4 - d3) + (d5 - d6);
    return den > 0.0 ? Eigen::Vector3d(b + ((d4 - d3) / den) * (c - b)) : b;
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // Degenerate (zero-area) triangle: the nearest of its three edges.
    Eigen::Vector3d best = a;
    for (const auto& [s, t] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      const Eigen::Vector3d e = t - s;
      const double len2 = e.squaredNorm();
      const double u = len2 > 0.0 ? std::clamp((p - s).dot(e) / len2, 0.0, 1.0) : 0.0;
      const Eigen::Vector3d q = s + u * e;
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    }
    return best;
  }
  return a + (vb / sum) * ab + (vc / sum) * ac;
}

MeshDistance::MeshDistance(const TriangleMesh& mesh) {
  const std::size_t n = mesh.triangles.size();
  a_.resize(n);
  b_.resize(n);
  c_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    a_[i] = mesh.vertices.at(mesh.triangles[i][0]);
    b_[i] = mesh.vertices.at(mesh.triangles[i][1]);
    c_[i] = mesh.vertices.at(mesh.triangles[i][2]);
  }
  if (n > 0) {
    nodes_.reserve(2 * n / kLeafSize + 2);
    build(0, static_cast<int>(n));
  }
}

int MeshDistance::build(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int i = begin; i < end; ++i) {
    const auto k = static_cast<std::size_t>(i);
    lo = lo.cwiseMin(a_[k]).cwiseMin(b_[k]).cwiseMin(c_[k]);
    hi = hi.cwiseMax(a_[k]).cwiseMax(b_[k]).cwiseMax(c_[k]);
  }
  nodes_[static_cast<std::size_t>(id)].lo = lo;
  nodes_[static_cast<std::size_t>(id)].hi = hi;
  nodes_[static_cast<std::size_t>(id)].begin = begin;
  nodes_[static_cast<std::size_t>(id)].end = end;
  if (end - begin <= kLeafSize) return id;
  // Median split of the triangle centroids along the box's longest axis.
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  std::vector<int> order(static_cast<std::size_t>(end - begin));
  std::iota(order.begin(), order.end(), begin);
  const auto centre = [&](int i) {
    const auto k = static_cast<std::size_t>(i);
    return a_[k][axis] + b_[k][axis] + c_[k][axis];
  };
  const auto mid = order.begin() + static_cast<std::ptrdiff_t>(order.size() / 2);
  std::nth_element(order.begin(), mid, order.end(),
                   [&](int x, int y) { return centre(x) < centre(y); });
  std::vector<Eigen::Vector3d> a, b, c;
  for (int i : order) {
    a.push_back(a_[static_cast<std::size_t>(i)]);
    b.push_back(b_[static_cast<std::size_t>(i)]);
    c.push_back(c_[static_cast<std::size_t>(i)]);
  }
  std::copy(a.begin(), a.end(), a_.begin() + begin);
  std::copy(b.begin(), b.end(), b_.begin() + begin);
  std::copy(c.begin(), c.end(), c_.begin() + begin);
  const int split = begin + (end - begin) / 2;
  const int left = build(begin, split);
  const int right = build(split, end);
  nodes_[static_cast<std::size_t>(id)].left = left;
  nodes_[static_cast<std::size_t>(id)].right = right;
  return id;
}

double MeshDistance::box_distance_squared(const Node& n, const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = (n.lo - p).cwiseMax(p - n.hi).cwiseMax(0.0);
  return d.squaredNorm();
}

double MeshDistance::triangle_distance(const Eigen::Vector3d& p, int triangle) const {
  const auto k = static_cast<std::size_t>(triangle);
  return (closest_point_on_triangle(p, a_[k], b_[k], c_[k]) - p).norm();
}

MeshDistance::Nearest MeshDistance::nearest(const Eigen::Vector3d& p) const {
  double best = std::numeric_limits<double>::infinity();
  int best_triangle = -1;
  if (nodes_.empty()) return {best, best_triangle};
  // Depth-first, nearer child first, pruned by the best squared distance so far.
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    if (box_distance_squared(n, p) >= best) continue;
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const double d2 = (closest_point_on_triangle(p, a_[k], b_[k], c_[k]) - p).squaredNorm();
        if (d2 < best) {
          best = d2;
          best_triangle = i;
        }
      }
      continue;
    }
    const double dl = box_distance_squared(nodes_[static_cast<std::size_t>(n.left)], p);
    const double dr = box_distance_squared(nodes_[static_cast<std::size_t>(n.right)], p);
    // The tree's depth is about log2(n / kLeafSize) + 1 <= 64 for any count that fits memory.
    if (dl < dr) {
      stack[top++] = n.right;
      stack[top++] = n.left;
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return {std::sqrt(best), best_triangle};
}

double MeshDistance::winding_number(const Eigen::Vector3d& p) const {
  // Solid angle of each triangle seen from p (Van Oosterom and Strackee 1983):
  // tan(omega / 2) = det[a b c] / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|).
  double total = 0.0;
  for (std::size_t i = 0; i < a_.size(); ++i) {
    const Eigen::Vector3d a = a_[i] - p, b = b_[i] - p, c = c_[i] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double det = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(det, den);
  }
  return total / (4.0 * M_PI);
}

int MeshDistance::crossings(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const {
  // Signed: +1 for a triangle the ray crosses from one side, -1 from the other, so that the sum
  // is the winding number of the surface about p (+-1 inside one closed shell, +-2 inside two
  // overlapping ones, 0 outside all).
  if (nodes_.empty()) return 0;
  const Eigen::Vector3d inv = d.cwiseInverse();
  int count = 0;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
    // Slab test of the ray against the node's box.
    const Eigen::Vector3d t0 = (n.lo - p).cwiseProduct(inv);
    const Eigen::Vector3d t1 = (n.hi - p).cwiseProduct(inv);
    const double enter = t0.cwiseMin(t1).maxCoeff();
    const double leave = t0.cwiseMax(t1).minCoeff();
    if (!(leave >= std::max(enter, 0.0))) continue;
    if (n.left >= 0) {
      stack[top++] = n.left;
      stack[top++] = n.right;
      continue;
    }
    for (int i = n.begin; i < n.end; ++i) {
      // Moller-Trumbore, with the degenerate cases reported instead of guessed.
      const auto k = static_cast<std::size_t>(i);
      const Eigen::Vector3d e1 = b_[k] - a_[k], e2 = c_[k] - a_[k];
      const Eigen::Vector3d h = d.cross(e2);
      const double det = e1.dot(h);
      const double scale = e1.norm() * e2.norm();
      if (std::abs(det) <= 1e-12 * scale) {
        // Parallel to the triangle's plane: degenerate when the ray lies in that plane.
        const Eigen::Vector3d normal = e1.cross(e2);
        if (std::abs(normal.dot(p - a_[k])) <= 1e-12 * scale * (p - a_[k]).norm()) {
          return kDegenerateRay;
        }
        continue;
      }
      const Eigen::Vector3d s = p - a_[k];
      const double u = s.dot(h) / det;
      const Eigen::Vector3d q = s.cross(e1);
      const double v = d.dot(q) / det;
      const double t = e2.dot(q) / det;
      constexpr double kEdge = 1e-9;
      if (u < -kEdge || v < -kEdge || u + v > 1.0 + kEdge || t <= 0.0) continue;
      if (u < kEdge || v < kEdge || u + v > 1.0 - kEdge) return kDegenerateRay;  // an edge
      count += det > 0.0 ? 1 : -1;  // the triangle's side the ray enters from
    }
  }
  return count;
}

bool MeshDistance::inside(const Eigen::Vector3d& p) const {
  // Directions with no simple relation to axis-aligned or symmetric geometry.
  static const Eigen::Vector3d kDirections[] = {
      Eigen::Vector3d(0.5773, 0.4207, 0.7001),   Eigen::Vector3d(-0.3307, 0.8843, -0.3296),
      Eigen::Vector3d(0.7912, -0.5213, -0.3199), Eigen::Vector3d(-0.6133, -0.2857, 0.7365),
      Eigen::Vector3d(0.1361, -0.9411, 0.3095),  Eigen::Vector3d(-0.8123, 0.1874, -0.5524),
      Eigen::Vector3d(0.2459, 0.6687, -0.7016),  Eigen::Vector3d(-0.0874, -0.4422, -0.8927)};
  int votes = 0, rays = 0;
  for (const Eigen::Vector3d& d : kDirections) {
    const int c = crossings(p, d);
    if (c == kDegenerateRay) continue;
    votes += c != 0;
    if (++rays == 3) break;
  }
  if (rays < 3) return std::abs(winding_number(p)) >= 0.5;  // every ray grazed an edge
  return votes >= 2;
}

}  // namespace hullcheck::detail
