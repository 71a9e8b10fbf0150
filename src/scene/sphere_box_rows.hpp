// One sphere against many oriented boxes, vectorised across the boxes (sphere_box_rows.cpp):
// is_valid's and check_motion's environment culling, where one shape group's ball meets every
// obstacle's box. The boxes come as rows: kBoxValues rows (ball_tests_block.hpp's order: the
// world-to-box rotation row by row, the centre, the half extents; m, model frame) of `padded`
// values each, one column per box, padded with zero boxes whose results are not to be read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hullcheck::detail {

/// Columns of the rows for `count` boxes: a multiple of 8 (every SIMD width's lane count).
std::size_t box_rows_padded(std::size_t count);
/// The rows of `count` boxes given as kBoxValues values each (ball_tests_block.hpp).
std::vector<double> pack_box_rows(const double* boxes, std::size_t count);
/// Sets bit j % 64 of bits[j / 64] for each box j of the `padded` columns that the sphere
/// (centre c: x, y, z; radius, m) is clear of by more than `slack` (its centre farther than
/// radius + slack from the box), clears the others. bits: padded / 64 words, rounded up.
void sphere_clear_of_box_rows(const double* rows, std::size_t padded, const double* c,
                              double radius, double slack, std::uint64_t* bits);
/// gaps[j], for each of the `padded` boxes: CollisionChecker::box_gap's lower bound on the
/// signed distance between anything in the sphere and anything in box j (centre outside: its
/// distance to the box minus the radius; inside: minus the radius and the centre's depth).
void sphere_box_row_gaps(const double* rows, std::size_t padded, const double* c, double radius,
                         double* gaps);

}  // namespace hullcheck::detail
