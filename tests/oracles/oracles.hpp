// Independent reference answers for tests and benchmarks. Nothing here uses hullcheck's own
// GJK/EPA or ConvexHull: hulls are built with qhull directly, distances by exhaustive search.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

namespace hullcheck::oracle {

/// Exact distance between the convex hulls of two world-frame point sets, by exhaustive search
/// over feature pairs (vertex/edge/face of each hull, hull faces from qhull). When the hulls
/// overlap, distance is 0 and the points are unspecified (overlapping = true). Touching hulls
/// (distance below 1e-13 x the coordinates' magnitude) count as overlapping. Flat, collinear,
/// single-point and duplicated sets are handled (a set thinner than 1e-12 x its size around a
/// plane or line is treated as lying on it). Throws std::invalid_argument for an empty set.
struct Distance {
  double distance = 0.0;
  Eigen::Vector3d point_a{0, 0, 0}, point_b{0, 0, 0};
  bool overlapping = false;
};
Distance brute_force_distance(const std::vector<Eigen::Vector3d>& world_a,
                              const std::vector<Eigen::Vector3d>& world_b);

/// Penetration depth by hulling the Minkowski difference {a - b} with qhull and taking the facet
/// nearest to the origin. depth = 0 when the origin is outside (not overlapping).
/// normal: unit, translate B by depth*normal to separate (from A towards B).
/// When A - B is flat (e.g. two segments, a point and a polygon), no translation of positive
/// length is needed: depth = 0, and overlapping tells whether they touch (normal then any
/// unit vector orthogonal to the difference). Cost: qhull on |A| x |B| points.
struct Penetration {
  double depth = 0.0;
  Eigen::Vector3d normal{0, 0, 0};
  bool overlapping = false;
};
Penetration minkowski_penetration(const std::vector<Eigen::Vector3d>& world_a,
                                  const std::vector<Eigen::Vector3d>& world_b);

/// Translations along a line for which two hulls overlap with positive depth: B moved by
/// t * direction overlaps A (interiors meet) exactly for lo < t < hi. Empty (lo > hi) when no
/// such t exists, in particular whenever the Minkowski difference A - B is flat (both sets
/// degenerate in compatible ways), since then no translation gives a positive depth.
struct Interval {
  double lo = 1.0, hi = 0.0;
  bool empty() const { return lo > hi; }
};
Interval overlap_interval(const std::vector<Eigen::Vector3d>& world_a,
                          const std::vector<Eigen::Vector3d>& world_b,
                          const Eigen::Vector3d& direction);

/// Points transformed by a pose.
std::vector<Eigen::Vector3d> transformed(const std::vector<Eigen::Vector3d>& local,
                                         const Eigen::Isometry3d& pose);

/// Random test data, deterministic from the seed.
/// `n` points on a randomly scaled ellipsoid (semi-axes in [0.5, 1] x size) in random
/// orientation, centred on the origin: every point is a hull vertex.
std::vector<Eigen::Vector3d> random_hull_points(std::uint64_t seed, int n, double size = 1.0);

/// A pair of point sets with poses, as the benchmarks and randomized tests use them.
struct HullPair {
  std::vector<Eigen::Vector3d> a, b;  // local frames
  Eigen::Isometry3d pose_a = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d pose_b = Eigen::Isometry3d::Identity();
};
/// `count` pairs of hulls with `vertices` vertices each, random poses, about
/// `overlap_fraction` of them overlapping (the rest separated by up to one shape size).
/// Exactly round(overlap_fraction * count) pairs overlap when vertices >= 4 (each placed with
/// overlap_interval, so the labels are the oracle's). Cost: one qhull of the Minkowski
/// difference per pair, O(vertices^2) points: ~3 ms at 64 vertices, ~0.3 s at 512.
std::vector<HullPair> make_hull_pairs(std::uint64_t seed, int count, int vertices,
                                      double overlap_fraction = 0.3, double size = 1.0);

/// Exact distance from `p` to the triangle (a, b, c) (Ericson 5.1.5; degenerate triangles by
/// their edges).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Distance from points to the convex hull of a point set (0 inside), the hull built once with
/// qhull: for a 3D hull, 0 when every facet plane has the point within 1e-12 x (size) inside,
/// else the least distance to a facet triangle; flat and smaller sets by brute_force_distance.
class HullDistance {
 public:
  explicit HullDistance(const std::vector<Eigen::Vector3d>& points);
  double operator()(const Eigen::Vector3d& p) const;

 private:
  std::vector<Eigen::Vector3d> points_;
  int dim_ = 0;
  std::vector<std::array<int, 3>> tris_;
  std::vector<Eigen::Vector3d> plane_n_;
  std::vector<double> plane_h_;
  double eps_ = 0.0;
};

}  // namespace hullcheck::oracle
