// is_valid_batch's SIMD ball tests (ball_tests_block.cpp), for a block of kPoseBlockLanes
// configurations. Spheres: rows of kPoseBlockLanes values, x, y, z and radius per sphere (m,
// model frame). Boxes: kBoxValues each, the world-to-box rotation row by row, the centre, the
// half extents. Lane k's bit (1 << k) of a mask is set when the test proves it clear by more
// than `slack` (m).
#pragma once

#include <cstddef>
#include <cstdint>

namespace hullcheck::detail {

inline constexpr std::size_t kBoxValues = 15;
/// Covering-sphere pairs of a self block (two links) compared for a whole block at most: the
/// batch queries bound larger blocks by their links' balls instead.
inline constexpr std::size_t kMaxSpherePairs = 256;

/// Places `n` spheres given in one link's frame (x, y, z, radius each, m) at that link's poses:
/// `pose` is the link's 12 rows of kPoseBlockLanes values (LinkPoseBlock::entry(link, 0)),
/// `out` receives n spheres as rows x, y, z, radius (model frame). Rounding: a few ulps of the
/// centres' coordinates, far below the tests' slack.
void place_spheres(const double* pose, const double* spheres, std::size_t n, double* out);
/// out[i * m + j]: the lanes where sphere i is clear of box j.
void spheres_clear_of_boxes(const double* spheres, std::size_t n, const double* boxes,
                            std::size_t m, double slack, std::uint8_t* out);
/// The lanes where some sphere reaches into `box` by more than `slack`.
std::uint8_t spheres_in_box(const double* spheres, std::size_t n, const double* box, double slack);
/// out[k]: the lanes where spheres pairs[2k] and pairs[2k + 1] of `spheres` are apart, for the
/// `count` pairs.
void sphere_pairs_apart(const double* spheres, const int* pairs, std::size_t count, double slack,
                        std::uint8_t* out);
/// The lanes where every sphere of `a` is clear of every sphere of `b`.
std::uint8_t spheres_apart(const double* a, std::size_t na, const double* b, std::size_t nb,
                           double slack);

}  // namespace hullcheck::detail
