#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>

#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/objectives.hpp>
#include <hullcheck/ompl/state_validity_checker.hpp>

namespace hullcheck {

namespace ob = ::ompl::base;

ob::OptimizationObjectivePtr make_max_min_clearance_objective(const ob::SpaceInformationPtr& si) {
  return std::make_shared<ob::MaximizeMinClearanceObjective>(si);
}

ClearanceCostObjective::ClearanceCostObjective(const ob::SpaceInformationPtr& si, double scale)
    : ob::StateCostIntegralObjective(si, /*enableMotionCostInterpolation=*/true), scale_(scale) {
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    throw InputError("ClearanceCostObjective: scale must be finite and > 0");
  }
  description_ = "Clearance cost (integral of exp(-clearance/scale))";
}

ob::Cost ClearanceCostObjective::stateCost(const ob::State* s) const {
  const double d = si_->getStateValidityChecker()->clearance(s);
  // Far from everything (or nothing checked): no cost.
  return ob::Cost(std::isfinite(d) ? std::exp(-d / scale_) : 0.0);
}

ClearanceMarginObjective::ClearanceMarginObjective(const ob::SpaceInformationPtr& si, double margin,
                                                   double length_weight)
    : ob::StateCostIntegralObjective(si, /*enableMotionCostInterpolation=*/true),
      margin_(margin),
      length_weight_(length_weight) {
  if (!(margin > 0.0) || !std::isfinite(margin) || !(length_weight >= 0.0) ||
      !std::isfinite(length_weight)) {
    throw InputError(
        "ClearanceMarginObjective: margin must be finite and > 0, length_weight finite and >= 0");
  }
  description_ = "Clearance margin (length and a hinge on clearance below the margin)";
}

double ClearanceMarginObjective::density(double d) const {
  return length_weight_ + std::max(0.0, margin_ - d) / margin_;
}

ob::Cost ClearanceMarginObjective::stateCost(const ob::State* s) const {
  // The density is flat from the margin up: hullcheck's checker need not measure past it.
  const ob::StateValidityChecker* validity = si_->getStateValidityChecker().get();
  const auto* ours = dynamic_cast<const StateValidityChecker*>(validity);
  return ob::Cost(
      density(ours != nullptr ? ours->clearance_below(s, margin_) : validity->clearance(s)));
}

ob::OptimizationObjectivePtr make_length_clearance_objective(const ob::SpaceInformationPtr& si,
                                                             double length_weight,
                                                             double clearance_weight,
                                                             double scale) {
  if (!(length_weight >= 0.0) || !(clearance_weight >= 0.0)) {
    throw InputError("make_length_clearance_objective: weights must be >= 0");
  }
  auto multi = std::make_shared<ob::MultiOptimizationObjective>(si);
  multi->addObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si), length_weight);
  multi->addObjective(std::make_shared<ClearanceCostObjective>(si, scale), clearance_weight);
  return multi;
}

}  // namespace hullcheck
