// CollisionChecker::JointGrid: cells over at most kMaxGridValues configuration values, shared by
// the warm-start grids of self pairs and the distance tables of self blocks.
#include <cmath>
#include <hullcheck/scene/collision_checker.hpp>

namespace hullcheck {

namespace {

// Value x of a continuous joint taken into [lower, lower + one turn).
double wrapped(double x, double lower) {
  return x - 2.0 * M_PI * std::floor((x - lower) / (2.0 * M_PI));
}

}  // namespace

std::size_t CollisionChecker::JointGrid::setup(const RobotModel& model, const int* keys, int count,
                                               int cells_per_value) {
  dims = count;
  std::size_t total = 1;
  for (int d = 0; d < count; ++d) {
    const int v = keys[d];
    double lo = model.lower_limits()[v], hi = model.upper_limits()[v];
    wraps[d] = !std::isfinite(lo) || !std::isfinite(hi);
    if (wraps[d]) {
      lo = -M_PI;
      hi = M_PI;
    }
    variables[d] = v;
    lower[d] = lo;
    cells[d] = hi > lo ? cells_per_value : 1;
    cells_per_unit[d] = hi > lo ? cells_per_value / (hi - lo) : 0.0;
    total *= static_cast<std::size_t>(cells[d]);
  }
  return total;
}

double CollisionChecker::JointGrid::half_width(int d) const {
  return cells_per_unit[d] > 0.0 ? 0.5 / cells_per_unit[d] : 0.0;
}

long CollisionChecker::JointGrid::cell(const double* q, bool clamp) const {
  long cell = 0;
  for (int d = 0; d < dims; ++d) {
    const double x = q[variables[d]];
    const double t = coordinate(d, x);
    int i = 0;
    if (cells_per_unit[d] > 0.0) {
      if (!(t >= 0.0 && t < cells[d])) {
        if (!clamp) return -1;
        i = t <= 0.0 ? 0 : cells[d] - 1;  // NaN: the first cell
      } else {
        i = static_cast<int>(t);
      }
    } else if (!clamp && x != lower[d]) {
      return -1;
    }
    cell = cell * cells[d] + i;
  }
  return cell;
}

double CollisionChecker::JointGrid::coordinate(int d, double x) const {
  if (wraps[d]) x = wrapped(x, lower[d]);
  return (x - lower[d]) * cells_per_unit[d];
}

void CollisionChecker::JointGrid::center(std::size_t cell, Eigen::VectorXd& q) const {
  for (int d = dims - 1; d >= 0; --d) {
    const auto i = static_cast<int>(cell % static_cast<std::size_t>(cells[d]));
    cell /= static_cast<std::size_t>(cells[d]);
    q[variables[d]] = cells_per_unit[d] > 0.0 ? lower[d] + (i + 0.5) / cells_per_unit[d] : lower[d];
  }
}

}  // namespace hullcheck
