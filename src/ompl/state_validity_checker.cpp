#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/state_validity_checker.hpp>

namespace hullcheck {

StateValidityChecker::StateValidityChecker(const ::ompl::base::SpaceInformationPtr& si,
                                           std::shared_ptr<const JointStateSpace> space,
                                           std::shared_ptr<const CollisionChecker> checker)
    : ::ompl::base::StateValidityChecker(si),
      space_(std::move(space)),
      checker_(std::move(checker)) {
  if (!space_ || !checker_) throw InputError("StateValidityChecker: null space or checker");
  if (&space_->model() != &checker_->model()) {
    throw InputError("StateValidityChecker: the space and the checker use different robot models");
  }
  specs_.clearanceComputationType = ::ompl::base::StateValidityCheckerSpecs::EXACT;
  specs_.hasValidDirectionComputation = false;
}

Eigen::VectorXd& StateValidityChecker::configuration(const ::ompl::base::State* state) const {
  thread_local Eigen::VectorXd q;
  if (q.size() != space_->fixed_configuration().size()) {
    q.resize(space_->fixed_configuration().size());
  }
  space_->to_configuration(state, q);
  checks_.fetch_add(1, std::memory_order_relaxed);
  return q;
}

namespace {

// This thread's last isValid(state) answer: the checker, the configuration and the verdict.
struct LastAnswer {
  const void* checker = nullptr;
  Eigen::VectorXd q;
  bool valid = false;
};
thread_local LastAnswer last_answer;

}  // namespace

bool StateValidityChecker::isValid(const ::ompl::base::State* state) const {
  const Eigen::VectorXd& q = configuration(state);
  const bool valid = checker_->is_valid(q);
  last_answer.checker = this;
  last_answer.q = q;  // sized once per thread (no allocation after)
  last_answer.valid = valid;
  return valid;
}

bool StateValidityChecker::last_valid_is(const Eigen::VectorXd& q) const {
  return last_answer.checker == this && last_answer.valid && last_answer.q.size() == q.size() &&
         last_answer.q == q;
}

void StateValidityChecker::set_clearance_scope(std::shared_ptr<const PairScope> scope) {
  if (scope) {
    // Rejects a scope of another checker now rather than at the first query.
    checker_->clearance(space_->fixed_configuration(), *scope);
  }
  scope_ = std::move(scope);
}

ClearanceResult StateValidityChecker::scoped_clearance(const Eigen::VectorXd& q,
                                                       double below) const {
  return scope_ ? checker_->clearance(q, *scope_, below)
                : checker_->clearance(q, ClearanceScope::kAll, below);
}

bool StateValidityChecker::isValid(const ::ompl::base::State* state, double& dist) const {
  const Eigen::VectorXd& q = configuration(state);
  dist = scoped_clearance(q).distance;
  if (!scope_) return dist > 0.0;
  return dist > 0.0 && checker_->is_valid(q);
}

double StateValidityChecker::clearance(const ::ompl::base::State* state) const {
  return scoped_clearance(configuration(state)).distance;
}

double StateValidityChecker::clearance_below(const ::ompl::base::State* state, double below) const {
  return scoped_clearance(configuration(state), below).distance;
}

ClearanceResult StateValidityChecker::closest(const ::ompl::base::State* state) const {
  return scoped_clearance(configuration(state));
}

}  // namespace hullcheck
