// Boolean GJK (Casalino algorithm 2): does the core difference A - B contain the origin, or is it
// farther from it than the shapes' radius? Only search directions are kept, no barycentric
// coordinates, so an iteration costs little more than its support call. Each verdict is proven:
//  - apart: a support point w with d.w < -radius |d| gives a plane separating the origin from
//    the difference by more than radius (Casalino: "collision absent" when <D, P*> < 0);
//  - overlapping: the origin lies inside a tetrahedron of support points (Casalino eq. 26-28).
// When neither is proven (touching contact, margins within reach, iteration cap) the caller
// falls back to the distance GJK, whose tolerance model decides.
#pragma once

#include <Eigen/Core>

namespace hullcheck::detail {

enum class BooleanVerdict { kApart, kOverlapping, kUndecided };

namespace boolean_gjk {

/// A simplex vertex with only the difference point (plain boolean test).
struct PointOnly {
  Eigen::Vector3d w;
  void set(const Eigen::Vector3d& w_in, const Eigen::Vector3d&, const Eigen::Vector3d&) {
    w = w_in;
  }
};

inline Eigen::Vector3d triple(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c) {
  return a.cross(b).cross(c);
}

/// Casalino case a on segment (s[0] newest, s[1]): updates the simplex and the direction.
template <class V>
void line(V* s, int& n, Eigen::Vector3d& d) {
  const Eigen::Vector3d& a = s[0].w;
  const Eigen::Vector3d ab = s[1].w - a;
  if (ab.dot(-a) > 0.0) {
    d = triple(ab, -a, ab);  // orthogonal to ab, towards the origin
    n = 2;
  } else {
    d = -a;
    n = 1;
  }
}

/// Casalino case b on triangle (s[0] newest, s[1], s[2]).
template <class V>
void triangle(V* s, int& n, Eigen::Vector3d& d) {
  const Eigen::Vector3d a = s[0].w;
  const Eigen::Vector3d ao = -a;
  const Eigen::Vector3d ab = s[1].w - a;
  const Eigen::Vector3d ac = s[2].w - a;
  const Eigen::Vector3d abc = ab.cross(ac);
  if (abc.cross(ac).dot(ao) > 0.0) {
    if (ac.dot(ao) > 0.0) {  // edge ac
      s[1] = s[2];
      d = triple(ac, ao, ac);
      n = 2;
      return;
    }
    line(s, n, d);  // edge ab or vertex a
    return;
  }
  if (ab.cross(abc).dot(ao) > 0.0) {
    line(s, n, d);
    return;
  }
  n = 3;
  if (abc.dot(ao) > 0.0) {
    d = abc;
  } else {  // below: flip the winding so that the normal faces the origin
    std::swap(s[1], s[2]);
    d = -abc;
  }
}

/// Casalino case c on tetrahedron (s[0] newest, then a triangle whose winding faces s[0]).
/// Returns true when the origin is enclosed.
template <class V>
bool tetrahedron(V* s, int& n, Eigen::Vector3d& d) {
  const Eigen::Vector3d a = s[0].w;
  const Eigen::Vector3d ao = -a;
  const Eigen::Vector3d ab = s[1].w - a;
  const Eigen::Vector3d ac = s[2].w - a;
  const Eigen::Vector3d ad = s[3].w - a;
  // Faces through a, normals pointing out of the tetrahedron.
  if (ab.cross(ac).dot(ao) > 0.0) {
    n = 3;
    triangle(s, n, d);
    return false;
  }
  if (ac.cross(ad).dot(ao) > 0.0) {
    s[1] = s[2];
    s[2] = s[3];
    n = 3;
    triangle(s, n, d);
    return false;
  }
  if (ad.cross(ab).dot(ao) > 0.0) {
    s[2] = s[1];
    s[1] = s[3];
    n = 3;
    triangle(s, n, d);
    return false;
  }
  return true;
}

}  // namespace boolean_gjk

/// Continues the boolean GJK from a simplex of `n` support points (s[0] newest) and search
/// direction `d`, `iterations` support calls made so far, until at most `max_iterations`.
/// On kOverlapping, `s` holds a tetrahedron of support points enclosing the origin.
template <class MD, class V>
BooleanVerdict gjk_boolean_continue(MD& md, Eigen::Vector3d d, int n, double radius,
                                    int max_iterations, int& iterations, V (&s)[4]) {
  Eigen::Vector3d w, pa, pb;
  iterations = n;
  // Origin on the first point (touching, or a degenerate start): let the distance GJK decide.
  if (!(d.squaredNorm() > 0.0)) return BooleanVerdict::kUndecided;
  while (iterations < max_iterations) {
    ++iterations;
    md.support(d, w, pa, pb);
    const double dw = d.dot(w);
    if (dw < 0.0) {
      if (dw * dw > radius * radius * d.squaredNorm()) return BooleanVerdict::kApart;
      return BooleanVerdict::kUndecided;  // cores apart, but maybe within the radii
    }
    for (int i = n; i > 0; --i) s[i] = s[i - 1];  // newest first
    s[0].set(w, pa, pb);
    ++n;
    switch (n) {
      case 1:
        d = -w;
        break;
      case 2:
        boolean_gjk::line(s, n, d);
        break;
      case 3:
        boolean_gjk::triangle(s, n, d);
        break;
      default:
        if (boolean_gjk::tetrahedron(s, n, d)) return BooleanVerdict::kOverlapping;
        break;
    }
    // Origin on the current segment or triangle (touching, or a degenerate simplex): the
    // direction vanishes; let the distance GJK decide with its tolerance.
    if (!(d.squaredNorm() > 0.0)) return BooleanVerdict::kUndecided;
  }
  return BooleanVerdict::kUndecided;
}

/// Runs the boolean GJK from search direction `d` with at most `max_iterations` support calls.
/// On kOverlapping, `s` holds a tetrahedron of support points enclosing the origin.
template <class MD, class V>
BooleanVerdict gjk_boolean(MD& md, Eigen::Vector3d d, double radius, int max_iterations,
                           int& iterations, V (&s)[4]) {
  if (!(d.squaredNorm() > 0.0)) d = Eigen::Vector3d::UnitX();
  return gjk_boolean_continue(md, d, 0, radius, max_iterations, iterations, s);
}

}  // namespace hullcheck::detail
