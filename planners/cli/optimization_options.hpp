// Command-line options of clearance scopes and of the clearance optimizer, shared by plan and
// benchmark.
#pragma once

#include <CLI/CLI.hpp>
#include <hullcheck/ompl.hpp>
#include <memory>
#include <string>
#include <vector>

#include "clearance_plot.hpp"

namespace hullcheck::cli {

/// --clearance-scope, --optimize, --margin, --length-weight, --optimize-time.
struct OptimizationOptions {
  std::string scope = "auto";  ///< auto | all | obstacles | self
  std::string optimize;        ///< "" or "clearance"
  ClearanceOptimizationOptions settings;

  void add_to(CLI::App& command);
  bool enabled() const { return optimize == "clearance"; }
  /// The PairScope --clearance-scope names for the group `variables` (the other values as in
  /// `fixed`): auto is optimization_scope() at the margin of `settings`; null
  /// for all.
  std::shared_ptr<const PairScope> make_scope(const CollisionChecker& checker,
                                              const std::vector<int>& variables,
                                              const Eigen::VectorXd& fixed) const;
};

/// Clearance over `scope` (null: every checked pair) at each waypoint of `path` and at
/// `per_motion - 1` evenly spaced states inside each motion; positions are joint-space arc
/// length from the start.
std::vector<ClearanceSample> clearance_profile(const PlanningSetup& planning,
                                               const ::ompl::geometric::PathGeometric& path,
                                               const PairScope* scope, int per_motion);

/// Smallest clearance of a profile (+inf when empty).
double profile_minimum(const std::vector<ClearanceSample>& profile);

}  // namespace hullcheck::cli
