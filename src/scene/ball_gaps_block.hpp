// clearance_lower_bound_batch's SIMD gap kernels (ball_gaps_block.cpp), for a block of
// kPoseBlockLanes configurations, with the layouts of ball_tests_block.hpp: spheres as rows of
// kPoseBlockLanes values (x, y, z, radius per sphere; m, model frame), a box as kBoxValues
// values. Each kernel lowers gap[k] (kPoseBlockLanes values, m) to its own lane-k gap.
#pragma once

#include <cstddef>

namespace hullcheck::detail {

/// gap[k] = min(gap[k], min over spheres i of (distance from centre i to `box`) - radius i):
/// when positive, a lower bound on the distance between the spheres' union and the box.
void lower_sphere_box_gap(const double* spheres, std::size_t n, const double* box, double* gap);
/// gap[k] = min(gap[k], min over spheres i of a, j of b of |c_i - c_j| - r_i - r_j): when
/// positive, a lower bound on the distance between the two unions.
void lower_sphere_pair_gap(const double* a, std::size_t na, const double* b, std::size_t nb,
                           double* gap);

}  // namespace hullcheck::detail
