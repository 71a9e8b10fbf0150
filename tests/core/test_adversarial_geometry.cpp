// Adversarial geometry: pairs built to break a GJK/EPA engine (identical and nested shapes,
// points inside hulls, exact face contact, flat/collinear/single-point sets, curved cores at
// the same pose, margins larger than the cores' overlap, mixed and extreme scales), each with
// an answer from an independent oracle:
//  - polytopes (hulls, boxes, and the point/segment cores of spheres/capsules): exhaustive
//    feature search (tests/oracles brute_force_distance) when apart, qhull on the Minkowski
//    difference when overlapping; margins and radii then subtract exactly (the signed distance
//    of a convex set grown by a ball of radius r is the set's minus r);
//  - aligned boxes and cylinders, cylinder against a point: closed forms (their difference is
//    an aligned box or cylinder).
// For every pair and every query (free functions in both orders, signed_distance_below around
// the answer, ProximityPair in a random query order before and after moving B away and back,
// both poses translated together) the test asserts:
//  - no exception and no NaN for valid input;
//  - every answer with status kConverged within the tolerance of the oracle, with witness
//    points consistent with the normal (point_b - point_a == signed_distance * normal);
//  - signed_distance_below's kAboveCutoff only when the oracle is at least the cutoff.
// Answers flagged kIterationCap or kDegenerate are counted and held to a looser bound.
//
// Pair count: 100,000 by default (CI), HULLCHECK_ADVERSARIAL_PAIRS=N for long runs (the README
// gives the command); a failing pair prints its seed, reproduced with HULLCHECK_ADVERSARIAL_SEED.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <hullcheck/core.hpp>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "oracles.hpp"
#include "rng.hpp"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define HULLCHECK_ADVERSARIAL_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define HULLCHECK_ADVERSARIAL_SANITIZED 1
#endif
#endif

namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using hullcheck::Shape;
using hullcheck::Status;
using hullcheck::oracle::Rng;
using Points = std::vector<Vector3d>;

/// The test's tolerance: 10x the library's default relative tolerance (1e-10 x scale), at
/// least 1e-15 m (the library's floor is 1e-16 m), plus rounding of coordinates as large as the
/// translations involved.
double test_tolerance(double scale, double translation) {
  return std::max(1e-9 * scale, 1e-15) + 1e-13 * translation;
}

/// A shape for the library and the same shape for the oracle: a polytope core (local points)
/// and a radius (own radius + margin), or a cylinder for the closed forms.
struct TestShape {
  std::optional<Shape> shape;
  Points core;          // local points of the polytope core (empty for a cylinder)
  double radius = 0.0;  // sphere/capsule radius + margin
  double extent = 0.0;  // largest |local point| of the shape, radius included
};

TestShape hull_shape(const Points& points, double margin) {
  TestShape s;
  s.shape = Shape(hullcheck::ConvexHull(points)).inflated(margin);
  s.core = points;
  s.radius = margin;
  for (const Vector3d& p : points) s.extent = std::max(s.extent, p.norm());
  s.extent += margin;
  return s;
}

Points box_corners(const Vector3d& half) {
  Points corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(),
                         i & 4 ? half.z() : -half.z());
  }
  return corners;
}

TestShape box_shape(const Vector3d& half, double margin) {
  TestShape s;
  s.shape = Shape(hullcheck::Box(2.0 * half)).inflated(margin);
  s.core = box_corners(half);
  s.radius = margin;
  s.extent = half.norm() + margin;
  return s;
}

TestShape sphere_shape(double radius, double margin) {
  TestShape s;
  s.shape = Shape(hullcheck::Sphere(radius)).inflated(margin);
  s.core = {Vector3d::Zero()};
  s.radius = radius + margin;
  s.extent = s.radius;
  return s;
}

TestShape capsule_shape(double radius, double length, double margin) {
  TestShape s;
  s.shape = Shape(hullcheck::Capsule(radius, length)).inflated(margin);
  s.core = {Vector3d(0, 0, -0.5 * length), Vector3d(0, 0, 0.5 * length)};
  s.radius = radius + margin;
  s.extent = 0.5 * length + s.radius;
  return s;
}

/// A pair with its oracle answer (the exact signed distance).
struct Case {
  const char* family = "";
  TestShape a, b;
  Isometry3d pose_a = Isometry3d::Identity();
  Isometry3d pose_b = Isometry3d::Identity();
  double truth = 0.0;
};

Isometry3d random_pose(Rng& rng, double reach) {
  Isometry3d pose = Isometry3d::Identity();
  pose.linear() = rng.rotation();
  pose.translation() = rng.in_box(reach);
  return pose;
}

/// Exact signed distance of two placed polytope cores grown by radius_a + radius_b.
double polytope_truth(const Case& c) {
  const Points wa = hullcheck::oracle::transformed(c.a.core, c.pose_a);
  const Points wb = hullcheck::oracle::transformed(c.b.core, c.pose_b);
  const hullcheck::oracle::Distance d = hullcheck::oracle::brute_force_distance(wa, wb);
  const double core =
      d.overlapping ? -hullcheck::oracle::minkowski_penetration(wa, wb).depth : d.distance;
  return core - c.a.radius - c.b.radius;
}

/// Signed distance of the origin to the aligned box |x_i| <= half_i placed at `centre`
/// (negative inside: minus the distance to the nearest face).
double box_signed_distance(const Vector3d& centre, const Vector3d& half) {
  const Vector3d q = centre.cwiseAbs() - half;
  const double outside = q.cwiseMax(0.0).norm();
  return outside > 0.0 ? outside : q.maxCoeff();
}

/// Signed distance of the origin to the cylinder of `radius` and `half_length` (axis z) placed
/// at `centre`.
double cylinder_signed_distance(const Vector3d& centre, double radius, double half_length) {
  const double radial = std::hypot(centre.x(), centre.y()) - radius;
  const double axial = std::abs(centre.z()) - half_length;
  if (radial <= 0.0 && axial <= 0.0) return std::max(radial, axial);
  return std::hypot(std::max(radial, 0.0), std::max(axial, 0.0));
}

Points random_hull_points(Rng& rng, double size) {
  return hullcheck::oracle::random_hull_points(rng.bits(), rng.integer(4, 16), size);
}

double random_margin(Rng& rng, double size) {
  return rng.coin(0.5) ? 0.0 : size * rng.uniform(0.0, 0.3);
}

// ------------------------------------------------------------------------------------------
// Families

/// The same hull twice at the same pose (the difference is centrally symmetric: every face
/// has an opposite twin at the same distance).
Case identical(Rng& rng, double size) {
  Case c;
  c.family = "identical";
  c.a = hull_shape(random_hull_points(rng, size), random_margin(rng, size));
  c.b = rng.coin() ? c.a : hull_shape(c.a.core, random_margin(rng, size));
  c.pose_a = c.pose_b = random_pose(rng, size);
  c.truth = polytope_truth(c);
  return c;
}

/// B a shrunk copy of A inside it (or a single point inside it), same pose.
Case nested(Rng& rng, double size) {
  Case c;
  c.family = "nested";
  const Points outer = random_hull_points(rng, size);
  c.a = hull_shape(outer, random_margin(rng, size));
  Points inner;
  if (rng.coin(0.3)) {
    Vector3d p = Vector3d::Zero();
    double total = 0.0;
    for (const Vector3d& v : outer) {
      const double w = rng.uniform();
      p += w * v;
      total += w;
    }
    inner.push_back(p / total);
  } else {
    const double s = rng.uniform(0.05, 0.999);
    for (const Vector3d& v : outer) inner.push_back(s * v);
  }
  c.b = hull_shape(inner, random_margin(rng, size));
  c.pose_a = c.pose_b = random_pose(rng, size);
  if (rng.coin()) std::swap(c.a, c.b);
  c.truth = polytope_truth(c);
  return c;
}

/// A random polytope-cored shape: hull, box, sphere, capsule, or a degenerate hull (flat
/// polygon, segment, single point, duplicated points).
TestShape random_polytope_shape(Rng& rng, double size) {
  const double margin = random_margin(rng, size);
  switch (rng.integer(0, 7)) {
    case 0:
    case 1:
      return hull_shape(random_hull_points(rng, size), margin);
    case 2:
      return box_shape(
          size * Vector3d(rng.uniform(0.05, 1), rng.uniform(0.05, 1), rng.uniform(0.05, 1)),
          margin);
    case 3:
      return sphere_shape(size * rng.uniform(0.0, 1.0), margin);
    case 4:
      return capsule_shape(size * rng.uniform(0.0, 0.5), size * rng.uniform(0.0, 2.0), margin);
    case 5: {  // flat polygon
      Points points;
      const int n = rng.integer(3, 8);
      for (int i = 0; i < n; ++i) {
        const double phi = 2 * M_PI * (i + rng.uniform(-0.3, 0.3)) / n;
        points.emplace_back(size * std::cos(phi), size * std::sin(phi), 0.0);
      }
      return hull_shape(points, margin);
    }
    case 6: {  // segment, or a single point
      const Vector3d e = size * rng.unit_vector();
      return hull_shape(rng.coin() ? Points{e, -e} : Points{e}, margin);
    }
    default: {  // duplicated points
      Points points = random_hull_points(rng, size);
      const std::size_t n = points.size();
      for (std::size_t i = 0; i < n; ++i) points.push_back(points[i]);
      return hull_shape(points, margin);
    }
  }
}

/// Two random polytope-cored shapes placed near contact (centres within ~2 sizes).
Case random_pair(Rng& rng, double size) {
  Case c;
  c.family = "random";
  c.a = random_polytope_shape(rng, size);
  c.b = random_polytope_shape(rng, size);
  c.pose_a = random_pose(rng, size);
  c.pose_b = c.pose_a * random_pose(rng, 1.5 * size);
  c.truth = polytope_truth(c);
  return c;
}

/// A tiny shape against a large one, near the large one's surface.
Case mixed_scales(Rng& rng, double size) {
  Case c;
  c.family = "mixed-scales";
  const double small = size * std::pow(10.0, -rng.uniform(3.0, 6.0));
  c.a = random_polytope_shape(rng, size);
  c.b = random_polytope_shape(rng, small);
  c.pose_a = random_pose(rng, size);
  const Vector3d direction = rng.unit_vector();
  // Support point of A's core along the direction, then a little outside or inside it.
  const Vector3d local = c.pose_a.linear().transpose() * direction;
  Vector3d far = c.a.core.front();
  for (const Vector3d& p : c.a.core) {
    if (p.dot(local) > far.dot(local)) far = p;
  }
  Isometry3d pose_b = Isometry3d::Identity();
  pose_b.linear() = rng.rotation();
  pose_b.translation() = c.pose_a * far + direction * (c.a.radius + small * rng.uniform(-3, 3));
  c.pose_b = pose_b;
  if (rng.coin()) {
    std::swap(c.a, c.b);
    std::swap(c.pose_a, c.pose_b);
  }
  c.truth = polytope_truth(c);
  return c;
}

/// Two boxes with the same rotation: exact face contact (offset = sum of half extents along one
/// axis), or any offset; closed form (their difference is an aligned box).
Case aligned_boxes(Rng& rng, double size) {
  Case c;
  c.family = "aligned-boxes";
  const Vector3d ha =
      size * Vector3d(rng.uniform(0.05, 1), rng.uniform(0.05, 1), rng.uniform(0.05, 1));
  const Vector3d hb =
      size * Vector3d(rng.uniform(0.05, 1), rng.uniform(0.05, 1), rng.uniform(0.05, 1));
  const double ma = random_margin(rng, size), mb = random_margin(rng, size);
  c.a = box_shape(ha, ma);
  c.b = box_shape(hb, mb);
  Vector3d offset = rng.in_box(1.0).cwiseProduct(ha + hb);
  if (rng.coin()) {  // cores exactly face to face: dyadic sizes keep the sum exact
    const int axis = rng.integer(0, 2);
    const Vector3d da = ((ha * 64).array().round() / 64).matrix();
    const Vector3d db = ((hb * 64).array().round() / 64).matrix();
    c.a = box_shape(da.cwiseMax(1.0 / 64), ma);
    c.b = box_shape(db.cwiseMax(1.0 / 64), mb);
    offset = Vector3d::Zero();
    offset(axis) =
        (rng.coin() ? 1.0 : -1.0) * ((da.cwiseMax(1.0 / 64))(axis) + (db.cwiseMax(1.0 / 64))(axis));
  }
  const Vector3d half_a = c.a.core.back(), half_b = c.b.core.back();  // corner (+,+,+)
  c.pose_a = Isometry3d::Identity();
  c.pose_a.translation() = rng.in_box(size);
  if (rng.coin()) c.pose_a.linear() = rng.rotation();
  c.pose_b = c.pose_a;
  c.pose_b.translation() += c.pose_a.linear() * offset;
  c.truth = box_signed_distance(offset, half_a + half_b) - ma - mb;
  return c;
}

/// Two cylinders with parallel axes (same rotation), identical ones at the same pose among
/// them, or a cylinder and a sphere: closed form (the difference is a cylinder, grown by the
/// sphere's radius).
Case cylinders(Rng& rng, double size) {
  Case c;
  c.family = "cylinders";
  const double ra = size * rng.uniform(0.05, 1), la = size * rng.uniform(0.05, 2);
  const double ma = random_margin(rng, size);
  c.a.shape = Shape(hullcheck::Cylinder(ra, la)).inflated(ma);
  c.a.extent = std::hypot(ra, 0.5 * la) + ma;
  c.pose_a = random_pose(rng, size);
  const int kind = rng.integer(0, 2);
  Vector3d offset = rng.in_box(size * 1.5);
  if (kind == 0) {  // identical, same pose
    c.b = c.a;
    c.pose_b = c.pose_a;
    c.truth = -std::min(2 * ra, la) - 2 * ma;
    return c;
  }
  if (kind == 1) {  // parallel axes
    const double rb = size * rng.uniform(0.05, 1), lb = size * rng.uniform(0.05, 2);
    const double mb = random_margin(rng, size);
    c.b.shape = Shape(hullcheck::Cylinder(rb, lb)).inflated(mb);
    c.b.extent = std::hypot(rb, 0.5 * lb) + mb;
    c.pose_b = c.pose_a;
    c.pose_b.translation() += c.pose_a.linear() * offset;
    c.truth = cylinder_signed_distance(offset, ra + rb, 0.5 * (la + lb)) - ma - mb;
  } else {  // a sphere anywhere (any rotation)
    const double rb = size * rng.uniform(0.0, 0.5), mb = random_margin(rng, size);
    c.b = sphere_shape(rb, mb);
    c.pose_b = random_pose(rng, size);
    c.pose_b.translation() = c.pose_a * offset;
    c.truth = cylinder_signed_distance(offset, ra, 0.5 * la) - rb - mb - ma;
  }
  if (rng.coin()) {
    std::swap(c.a, c.b);
    std::swap(c.pose_a, c.pose_b);
  }
  return c;
}

using Family = Case (*)(Rng&, double);
constexpr std::array<Family, 6> kFamilies = {identical,    nested,        random_pair,
                                             mixed_scales, aligned_boxes, cylinders};

/// The pair for a seed: a family, then a size from 1e-9 m to 1e5 m (translations stay below
/// 1e6 m, the library's limit).
Case make_case(std::uint64_t seed) {
  Rng rng(seed);
  const Family family =
      kFamilies[static_cast<std::size_t>(rng.integer(0, static_cast<int>(kFamilies.size()) - 1))];
  const double size = rng.coin(0.5) ? rng.uniform(0.05, 2.0) : std::pow(10.0, rng.integer(-9, 5));
  return family(rng, size);
}

// ------------------------------------------------------------------------------------------
// Checks

/// Failures and counts over a run.
struct Tally {
  long pairs = 0, answers = 0, flagged = 0, failures = 0;
  double worst_flagged = 0.0;  // largest |error| / tolerance among flagged answers
  std::map<std::string, long> by_family, flagged_by_family;
  std::vector<std::string> messages;

  void fail(std::uint64_t seed, const Case& c, const std::string& what) {
    ++failures;
    if (messages.size() < 20) {
      std::ostringstream s;
      s.precision(17);
      s << "seed 0x" << std::hex << seed << std::dec << " (" << c.family << "): " << what
        << " [truth " << c.truth << "]";
      messages.push_back(s.str());
    }
  }
};

bool finite(const Vector3d& v) { return v.allFinite(); }

/// Checks one signed distance answer against the truth. `where` names the query.
void check_signed(const hullcheck::SignedDistanceResult& r, double truth, double tol,
                  const char* where, std::uint64_t seed, const Case& c, Tally& tally) {
  ++tally.answers;
  std::ostringstream s;
  s.precision(17);
  if (!std::isfinite(r.signed_distance) || !finite(r.point_a) || !finite(r.point_b) ||
      !finite(r.normal)) {
    s << where << ": NaN or infinity in the answer";
    tally.fail(seed, c, s.str());
    return;
  }
  const double error = std::abs(r.signed_distance - truth);
  if (r.status != Status::kConverged) {
    ++tally.flagged;
    ++tally.flagged_by_family[c.family];
    tally.worst_flagged = std::max(tally.worst_flagged, error / tol);
    return;
  }
  if (error > tol) {
    s << where << ": signed distance " << r.signed_distance << " converged, error " << error
      << " > tol " << tol;
    tally.fail(seed, c, s.str());
    return;
  }
  const double n = r.normal.norm();
  if (std::abs(n - 1.0) > 1e-6) {
    s << where << ": normal not unit (|n| = " << n << ")";
    tally.fail(seed, c, s.str());
    return;
  }
  const double witness = (r.point_b - r.point_a - r.signed_distance * r.normal).norm();
  if (witness > tol) {
    s << where << ": point_b - point_a differs from signed_distance * normal by " << witness;
    tally.fail(seed, c, s.str());
  }
}

/// The signed distance with A and B as given, swapped, and both moved by one translation.
void check_free_queries(const Case& c, double tol, std::uint64_t seed, Rng& rng, Tally& tally) {
  const Shape& a = *c.a.shape;
  const Shape& b = *c.b.shape;
  check_signed(hullcheck::signed_distance(a, c.pose_a, b, c.pose_b), c.truth, tol,
               "signed_distance(A,B)", seed, c, tally);
  check_signed(hullcheck::signed_distance(b, c.pose_b, a, c.pose_a), c.truth, tol,
               "signed_distance(B,A)", seed, c, tally);
  Isometry3d moved_a = c.pose_a, moved_b = c.pose_b;
  const double reach = std::min(1e5, 100 * std::max(c.a.extent, c.b.extent));
  const Vector3d shift = rng.in_box(reach);
  moved_a.translation() += shift;
  moved_b.translation() += shift;
  check_signed(hullcheck::signed_distance(a, moved_a, b, moved_b), c.truth,
               tol + 1e-13 * shift.norm(), "signed_distance translated", seed, c, tally);

  const hullcheck::DistanceResult d = hullcheck::distance(a, c.pose_a, b, c.pose_b);
  ++tally.answers;
  if (!std::isfinite(d.distance) || !finite(d.point_a) || !finite(d.point_b)) {
    tally.fail(seed, c, "distance: NaN in the answer");
  } else if (d.status == Status::kConverged &&
             std::abs(d.distance - std::max(c.truth, 0.0)) > tol) {
    tally.fail(seed, c,
               "distance: converged, off by " +
                   std::to_string(std::abs(d.distance - std::max(c.truth, 0.0))));
  }
  const hullcheck::PenetrationResult p = hullcheck::penetration(a, c.pose_a, b, c.pose_b);
  ++tally.answers;
  if (!std::isfinite(p.depth) || !finite(p.point_a) || !finite(p.normal)) {
    tally.fail(seed, c, "penetration: NaN in the answer");
  } else if (p.status == Status::kConverged) {
    if (std::abs(p.depth - std::max(-c.truth, 0.0)) > tol) {
      tally.fail(seed, c, "penetration: converged, depth " + std::to_string(p.depth));
    } else if (p.depth > 0.0 && (p.point_a - p.point_b - p.depth * p.normal).norm() > tol) {
      tally.fail(seed, c, "penetration: witnesses contradict the normal");
    }
  }
  const bool hit = hullcheck::intersect(a, c.pose_a, b, c.pose_b);
  ++tally.answers;
  if (std::abs(c.truth) > tol && hit != (c.truth < 0.0)) {
    tally.fail(seed, c, std::string("intersect: ") + (hit ? "true" : "false"));
  }
  // signed_distance_below with a cutoff on either side of the truth.
  for (const double cutoff : {c.truth - 2 * tol - std::abs(c.truth) * rng.uniform(),
                              c.truth + 2 * tol + std::abs(c.truth) * rng.uniform()}) {
    const hullcheck::SignedDistanceResult r =
        hullcheck::signed_distance_below(a, c.pose_a, b, c.pose_b, cutoff);
    if (r.status == Status::kAboveCutoff) {
      ++tally.answers;
      if (!(r.signed_distance >= cutoff && r.signed_distance <= c.truth + tol)) {
        std::ostringstream s;
        s.precision(17);
        s << "signed_distance_below(" << cutoff << "): kAboveCutoff with bound "
          << r.signed_distance;
        tally.fail(seed, c, s.str());
      }
      if (cutoff > c.truth + tol) tally.fail(seed, c, "kAboveCutoff for a cutoff above truth");
    } else {
      check_signed(r, c.truth, tol, "signed_distance_below", seed, c, tally);
    }
  }
}

/// ProximityPair: a random order of the four queries, then B moved away and back and another
/// random order; every answer against the truth.
void check_pair_object(const Case& c, double tol, std::uint64_t seed, Rng& rng, Tally& tally) {
  hullcheck::ProximityPair pair;
  pair.set_shape_a(*c.a.shape, c.pose_a);
  pair.set_shape_b(*c.b.shape, c.pose_b);
  const auto run_in_random_order = [&](const char* when) {
    std::array<int, 4> order = {0, 1, 2, 3};
    for (int i = 3; i > 0; --i) std::swap(order[i], order[rng.integer(0, i)]);
    for (const int q : order) {
      ++tally.answers;
      const std::string where = std::string("ProximityPair ") + when + " ";
      if (q == 0) {
        const bool hit = pair.in_collision();
        if (std::abs(c.truth) > tol && hit != (c.truth < 0.0)) {
          tally.fail(seed, c, where + "in_collision: " + (hit ? "true" : "false"));
        }
      } else if (q == 1) {
        const hullcheck::DistanceResult& d = pair.distance();
        if (d.status == Status::kConverged &&
            !(std::abs(d.distance - std::max(c.truth, 0.0)) <= tol)) {
          tally.fail(seed, c, where + "distance: " + std::to_string(d.distance));
        }
      } else if (q == 2) {
        const hullcheck::PenetrationResult& p = pair.penetration();
        if (p.status == Status::kConverged &&
            !(std::abs(p.depth - std::max(-c.truth, 0.0)) <= tol)) {
          tally.fail(seed, c, where + "penetration: " + std::to_string(p.depth));
        }
      } else {
        --tally.answers;
        check_signed(pair.signed_distance(), c.truth, tol, (where + "signed_distance").c_str(),
                     seed, c, tally);
      }
    }
  };
  run_in_random_order("first");
  Isometry3d away = c.pose_b;
  away.translation() += rng.unit_vector() * (c.a.extent + c.b.extent) * rng.uniform(0.01, 3.0);
  pair.set_pose_b(away);
  if (rng.coin()) {
    pair.signed_distance();
  } else {
    pair.in_collision();
  }
  pair.set_pose_b(c.pose_b);
  run_in_random_order("after a move and back");
}

long pair_count() {
  if (const char* env = std::getenv("HULLCHECK_ADVERSARIAL_PAIRS")) return std::atol(env);
#ifdef HULLCHECK_ADVERSARIAL_SANITIZED
  return 10000;  // sanitizer builds: the Release stage runs the full CI count
#else
  return 100000;
#endif
}

void run_pair(std::uint64_t seed, Tally& tally) {
  const Case c = make_case(seed);
  Rng rng(seed ^ 0x9e3779b97f4a7c15ULL);
  const double scale = std::max(c.a.extent, c.b.extent);
  const double translation = std::max(c.pose_a.translation().norm(), c.pose_b.translation().norm());
  const double tol = test_tolerance(scale, translation);
  ++tally.pairs;
  ++tally.by_family[c.family];
  try {
    check_free_queries(c, tol, seed, rng, tally);
    check_pair_object(c, tol, seed, rng, tally);
  } catch (const std::exception& e) {
    tally.fail(seed, c, std::string("exception for valid input: ") + e.what());
  }
}

TEST(Adversarial, GeometryAgainstOracles) {
  Tally tally;
  if (const char* env = std::getenv("HULLCHECK_ADVERSARIAL_SEED")) {
    run_pair(std::strtoull(env, nullptr, 0), tally);
  } else {
    const long count = pair_count();
    for (long i = 0; i < count; ++i) {
      run_pair(0xad5e000000000000ULL + static_cast<std::uint64_t>(i), tally);
    }
  }
  std::cout << "adversarial pairs: " << tally.pairs << ", answers checked: " << tally.answers
            << ", flagged (not converged): " << tally.flagged << " (worst error / tolerance "
            << tally.worst_flagged
            << "), wrong converged answers, NaN or exceptions: " << tally.failures << "\n";
  for (const auto& [family, n] : tally.by_family) {
    std::cout << "  " << family << ": " << n << " pairs, " << tally.flagged_by_family[family]
              << " flagged answers\n";
  }
  for (const std::string& m : tally.messages) ADD_FAILURE() << m;
  EXPECT_EQ(tally.failures, 0);
  // Flagged answers are the best bound EPA reached within its cap: on curved cores whose
  // nearest boundary is a whole circle (identical cylinders at one pose) no polytope of a few
  // hundred vertices closes the gap. Measured within 6.2e-4 x scale over 1,000,000 pairs; held to
  // 1e-3 x scale.
  EXPECT_LE(tally.worst_flagged, 1e6);
}

// Pairs of this generator that failed before the fixes of the adversarial run, one per
// class: warm start after a move and back read as apart (0x13), NaN after a move and back
// (0x20, and 0x22 on aligned boxes), kAboveCutoff below the answer (0x0e), witnesses of the
// opposite face (0x62: point_b - point_a off by twice the depth). Replayed on their own so that
// a change of the generator cannot silently drop them.
TEST(Adversarial, PairsThatFailedBeforeTheFixes) {
  Tally tally;
  for (const std::uint64_t seed :
       {0xad5e000000000013ULL, 0xad5e000000000020ULL, 0xad5e000000000022ULL, 0xad5e00000000000eULL,
        0xad5e000000000062ULL}) {
    run_pair(seed, tally);
  }
  for (const std::string& m : tally.messages) ADD_FAILURE() << m;
  EXPECT_EQ(tally.failures, 0);
}

}  // namespace
