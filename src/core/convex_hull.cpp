#include <Eigen/Geometry>
#include <algorithm>
#include <hullcheck/core/convex_hull.hpp>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/limits.hpp>
#include <string>

#include "detail/hull_data.hpp"
#include "detail/support.hpp"
#include "qhull_wrapper.hpp"

namespace hullcheck {

namespace {

/// Points closer than this (relative to the set's bounding-box diagonal) to a lower-dimensional
/// affine hull are treated as lying on it.
constexpr double kFlatness = 1e-12;

template <class Distance>
int farthest_from(const std::vector<Eigen::Vector3d>& points, const Distance& distance) {
  int best = 0;
  double best_distance = -1.0;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const double d = distance(points[i]);
    if (d > best_distance) {
      best_distance = d;
      best = i;
    }
  }
  return best;
}

struct Hull {
  std::vector<int> ids;                       // input indices of the hull vertices
  std::vector<std::array<int, 2>> edges;      // input indices
  std::vector<std::array<int, 3>> triangles;  // input indices
  int dimension = 0;
};

/// Polygon (dimension 2) from qhull in the plane spanned by u, w through origin o.
Hull planar_hull(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& o,
                 const Eigen::Vector3d& u, const Eigen::Vector3d& w) {
  std::vector<double> coords;
  coords.reserve(2 * points.size());
  for (const auto& p : points) {
    coords.push_back(u.dot(p - o));
    coords.push_back(w.dot(p - o));
  }
  const detail::QhullOutput q = detail::run_qhull(2, coords);
  Hull hull;
  hull.dimension = 2;
  hull.ids = q.vertex_ids;
  for (const auto& f : q.facets) hull.edges.push_back({f[0], f[1]});
  // Order the polygon by angle about its centroid for a triangle fan.
  Eigen::Vector2d centroid(0, 0);
  for (int id : hull.ids) centroid += Eigen::Vector2d(coords[2 * id], coords[2 * id + 1]);
  centroid /= static_cast<double>(hull.ids.size());
  std::vector<int> ordered = hull.ids;
  std::sort(ordered.begin(), ordered.end(), [&](int a, int b) {
    return std::atan2(coords[2 * a + 1] - centroid.y(), coords[2 * a] - centroid.x()) <
           std::atan2(coords[2 * b + 1] - centroid.y(), coords[2 * b] - centroid.x());
  });
  for (std::size_t i = 1; i + 1 < ordered.size(); ++i) {
    hull.triangles.push_back({ordered[0], ordered[i], ordered[i + 1]});
  }
  return hull;
}

Hull compute_hull(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double size = (hi - lo).norm();
  const double flat = kFlatness * size;
  Hull hull;
  if (!(size > 0.0)) {  // all points coincide
    hull.ids = {0};
    return hull;
  }
  // Initial simplex as qhull builds it: farthest point pairs, then from the line, the plane.
  const int i0 = farthest_from(points, [&](const Eigen::Vector3d& p) { return (p - lo).norm(); });
  const Eigen::Vector3d o = points[i0];
  const int i1 = farthest_from(points, [&](const Eigen::Vector3d& p) { return (p - o).norm(); });
  const Eigen::Vector3d u = (points[i1] - o).normalized();
  auto from_line = [&](const Eigen::Vector3d& p) { return (p - o - u * u.dot(p - o)).norm(); };
  const int i2 = farthest_from(points, from_line);
  if (!(from_line(points[i2]) > flat)) {  // collinear: the two extreme points
    const int lo_id = farthest_from(points, [&](const Eigen::Vector3d& p) { return -u.dot(p); });
    const int hi_id = farthest_from(points, [&](const Eigen::Vector3d& p) { return u.dot(p); });
    hull.dimension = 1;
    hull.ids = {lo_id, hi_id};
    hull.edges = {{lo_id, hi_id}};
    return hull;
  }
  const Eigen::Vector3d n = u.cross(points[i2] - o).normalized();
  const int i3 =
      farthest_from(points, [&](const Eigen::Vector3d& p) { return std::abs(n.dot(p - o)); });
  if (!(std::abs(n.dot(points[i3] - o)) > flat)) {  // coplanar: a polygon
    return planar_hull(points, o, u, n.cross(u));
  }
  std::vector<double> coords;
  coords.reserve(3 * points.size());
  for (const auto& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  const detail::QhullOutput q = detail::run_qhull(3, coords);
  hull.dimension = 3;
  hull.ids = q.vertex_ids;
  for (const auto& t : q.facets) {
    hull.triangles.push_back(t);
    hull.edges.push_back({t[0], t[1]});
    hull.edges.push_back({t[1], t[2]});
    hull.edges.push_back({t[2], t[0]});
  }
  return hull;
}

}  // namespace

ConvexHull::ConvexHull(const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) throw InputError("ConvexHull: the point set is empty");
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw InputError("ConvexHull: point " + std::to_string(i) +
                       " has a NaN or infinite coordinate");
    }
    if (!(points[i].cwiseAbs().maxCoeff() <= kMaxLength)) {
      throw InputError("ConvexHull: point " + std::to_string(i) +
                       " has a coordinate of magnitude " +
                       std::to_string(points[i].cwiseAbs().maxCoeff()) + " m, beyond 1e6 m");
    }
  }
  Hull hull;
  try {
    hull = compute_hull(points);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("ConvexHull: cannot hull the point set: ") + e.what());
  }
  auto data = std::make_shared<Data>();
  data->dimension = hull.dimension;
  std::sort(hull.ids.begin(), hull.ids.end());
  hull.ids.erase(std::unique(hull.ids.begin(), hull.ids.end()), hull.ids.end());
  std::vector<int> local(points.size(), -1);  // input index -> vertex index
  for (std::size_t k = 0; k < hull.ids.size(); ++k) {
    local[hull.ids[k]] = static_cast<int>(k);
    const Eigen::Vector3d& p = points[hull.ids[k]];
    data->vertices.push_back(p);
    data->xs.push_back(p.x());
    data->ys.push_back(p.y());
    data->zs.push_back(p.z());
    data->extent = std::max(data->extent, p.norm());
  }
  const int n = static_cast<int>(data->vertices.size());
  while (data->xs.size() % 4 != 0) {  // pad for the vectorised scan (see scan_support_index)
    data->xs.push_back(data->xs[0]);
    data->ys.push_back(data->ys[0]);
    data->zs.push_back(data->zs[0]);
  }
  data->vertex_count = n;
  data->padded_count = static_cast<int>(data->xs.size());
  std::vector<std::vector<std::int32_t>> neighbors(n);
  for (const auto& e : hull.edges) {
    const int a = local[e[0]], b = local[e[1]];
    if (a < 0 || b < 0 || a == b) continue;
    neighbors[a].push_back(b);
    neighbors[b].push_back(a);
  }
  data->neighbour_slots.push_back(0);
  for (int i = 0; i < n; ++i) {
    std::vector<std::int32_t>& list = neighbors[i];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    if (list.size() % 2 != 0) list.push_back(i);  // pad: i's own value never beats it
    data->neighbour_index.insert(data->neighbour_index.end(), list.begin(), list.end());
    for (int axis = 0; axis < 3; ++axis) {
      for (const std::int32_t j : list) data->neighbour_coords.push_back(data->vertices[j][axis]);
    }
    data->neighbour_slots.push_back(static_cast<std::int32_t>(data->neighbour_index.size()));
  }
  for (const auto& t : hull.triangles) {
    data->triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
  }
  // Balls about the bounding-box centre (tighter than the centroid for meshes): the outer one
  // reaches the farthest vertex, the inner one touches the nearest facet plane (none if the
  // centre is not strictly inside).
  Eigen::Vector3d lo = data->vertices[0], hi = data->vertices[0];
  for (const auto& v : data->vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  data->center = centre;
  for (const auto& v : data->vertices) {
    data->outer_radius = std::max(data->outer_radius, (v - centre).norm());
  }
  data->outer_radius *= 1.0 + 1e-12;  // rounding of the norms above
  if (data->dimension == 3) {
    double inner = INFINITY;
    for (const auto& t : data->triangles) {
      const Eigen::Vector3d& p0 = data->vertices[t[0]];
      const Eigen::Vector3d normal =
          (data->vertices[t[1]] - p0).cross(data->vertices[t[2]] - p0).normalized();
      if (normal.allFinite()) inner = std::min(inner, normal.dot(p0 - centre));
    }
    // Valid only with the centre strictly inside (a bounding-box centre need not be).
    if (std::isfinite(inner) && inner > 0.0) data->inner_radius = inner * (1.0 - 1e-9);
  }
  constexpr int kTableSize = 6 * Data::kCells * Data::kCells;
  data->start_table.resize(kTableSize);
  // Each cell's support vertex by climbing from the previous cell's (exact, and cheap for
  // hulls of many vertices); below the threshold the neighbour lists are not used, so scan.
  int previous = 0;
  for (int cell = 0; cell < kTableSize; ++cell) {
    const Eigen::Vector3d d = detail::cube_map_direction(cell);
    previous = n < static_cast<int>(kHillClimbingThreshold)
                   ? detail::scan_support_index(*data, d)
                   : detail::climb_support_index(*data, d, previous);
    data->start_table[cell] = previous;
  }
  data_ = std::move(data);
}

const std::vector<Eigen::Vector3d>& ConvexHull::vertices() const { return data_->vertices; }
std::size_t ConvexHull::vertex_count() const { return data_->vertices.size(); }
int ConvexHull::dimension() const { return data_->dimension; }
const std::vector<std::array<int, 3>>& ConvexHull::triangles() const { return data_->triangles; }
double ConvexHull::extent() const { return data_->extent; }
const Eigen::Vector3d& ConvexHull::bounding_ball_center() const { return data_->center; }
double ConvexHull::bounding_ball_radius() const { return data_->outer_radius; }

std::vector<int> ConvexHull::neighbors(int i) const {
  if (i < 0 || i >= static_cast<int>(vertex_count())) {
    throw InputError("ConvexHull::neighbors: vertex index " + std::to_string(i) + " out of range");
  }
  std::vector<int> list;
  for (std::int32_t slot = data_->neighbour_slots[i]; slot < data_->neighbour_slots[i + 1];
       ++slot) {
    const int j = data_->neighbour_index[slot];
    if (j != i) list.push_back(j);  // not the padding
  }
  return list;
}

int ConvexHull::support_index(const Eigen::Vector3d& direction) const {
  int index = -1;
  const detail::HullCore core{data_.get()};
  core.support(direction, index);
  return index;
}

Eigen::Vector3d ConvexHull::support(const Eigen::Vector3d& direction) const {
  return data_->vertices[support_index(direction)];
}

double convex_hull_volume(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 4) return 0.0;
  std::vector<double> coords;
  coords.reserve(3 * points.size());
  for (const Eigen::Vector3d& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  detail::QhullOutput out;
  try {
    out = detail::run_qhull(3, coords);
  } catch (const std::exception&) {
    return 0.0;  // flat or degenerate: no volume
  }
  double volume = 0.0;
  const Eigen::Vector3d& o = points[0];
  for (const auto& f : out.facets) {
    if (f[2] < 0) return 0.0;
    const Eigen::Vector3d& a = points[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d& b = points[static_cast<std::size_t>(f[1])];
    const Eigen::Vector3d& c = points[static_cast<std::size_t>(f[2])];
    volume += (a - o).dot((b - o).cross(c - o));
  }
  return std::abs(volume) / 6.0;
}

}  // namespace hullcheck
