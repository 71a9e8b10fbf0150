#include <ompl/base/DiscreteMotionValidator.h>

#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/planning_setup.hpp>

namespace hullcheck {

namespace ob = ::ompl::base;

ob::ScopedState<> PlanningSetup::state(const Eigen::VectorXd& q) const {
  ob::ScopedState<> s(setup->getStateSpace());
  joints->from_configuration(q, s.get());
  return s;
}

Eigen::VectorXd PlanningSetup::configuration(const ob::State* state) const {
  Eigen::VectorXd q(joints->fixed_configuration().size());
  joints->to_configuration(state, q);
  return q;
}

PlanningSetup make_planning_setup(std::shared_ptr<const CollisionChecker> checker,
                                  const std::vector<int>& variables, const Eigen::VectorXd& fixed,
                                  MotionChecking motions, double discrete_resolution) {
  if (!checker) throw InputError("make_planning_setup: checker is null");
  if (!(discrete_resolution > 0.0 && discrete_resolution <= 1.0)) {
    throw InputError("make_planning_setup: discrete_resolution must be in (0, 1]");
  }
  // The model is owned by the checker; share its lifetime.
  std::shared_ptr<const RobotModel> model(checker, &checker->model());
  PlanningSetup out;
  out.joints = std::make_shared<JointStateSpace>(model, variables, fixed);
  out.setup = std::make_shared<::ompl::geometric::SimpleSetup>(out.joints->space());
  const ob::SpaceInformationPtr& si = out.setup->getSpaceInformation();
  out.validity = std::make_shared<StateValidityChecker>(si, out.joints, checker);
  out.setup->setStateValidityChecker(out.validity);
  if (motions == MotionChecking::kGuaranteed) {
    si->setMotionValidator(std::make_shared<GuaranteedMotionValidator>(si, out.validity));
  } else {
    si->setStateValidityCheckingResolution(discrete_resolution);
    si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
  }
  return out;
}

}  // namespace hullcheck
