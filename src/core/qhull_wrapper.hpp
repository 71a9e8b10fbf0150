// Thin RAII wrapper over qhull's reentrant C library (not installed).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace hullcheck::detail {

/// Output of one qhull run: the input indices of the hull vertices and the hull's facets as
/// input indices (triangles in 3D, outward; edges in 2D).
struct QhullOutput {
  std::vector<int> vertex_ids;
  std::vector<std::array<int, 3>> facets;  // 3D: triangle; 2D: edge (third entry -1)
};

/// Runs qhull on `count` points of dimension `dim` (2 or 3) stored contiguously in `coords`.
/// Tries "Qt" first, then joggled input ("QJ") on a precision error. Throws std::runtime_error
/// with qhull's message when both fail.
QhullOutput run_qhull(int dim, const std::vector<double>& coords);

}  // namespace hullcheck::detail
