#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>

#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/joint_state_space.hpp>
#include <set>
#include <vector>

namespace hullcheck {

namespace ob = ::ompl::base;

namespace {

// Projection on the values of the group's first (up to) three joints in configuration order,
// the proximal ones that move the robot most; planners like KPIECE need one, and OMPL has no
// default for compound spaces.
class ProximalJointsProjection : public ob::ProjectionEvaluator {
 public:
  ProximalJointsProjection(const ob::StateSpace* space, const JointStateSpace& joints)
      : ob::ProjectionEvaluator(space), joints_(joints) {
    // Dimensions of the state (bounded first, then continuous) sorted by configuration index.
    std::vector<int> order(static_cast<std::size_t>(joints.dimension()));
    for (int i = 0; i < joints.dimension(); ++i) order[static_cast<std::size_t>(i)] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return joints.variables()[static_cast<std::size_t>(a)] <
             joints.variables()[static_cast<std::size_t>(b)];
    });
    order.resize(std::min<std::size_t>(3, order.size()));
    dims_ = order;
  }
  unsigned int getDimension() const override { return static_cast<unsigned>(dims_.size()); }
  void defaultCellSizes() override {
    cellSizes_.resize(dims_.size());
    for (std::size_t i = 0; i < dims_.size(); ++i) {
      const Joint& j = joints_.model().joint(
          joints_.model().variable_joint(joints_.variables()[static_cast<std::size_t>(dims_[i])]));
      const double range =
          std::isfinite(j.lower) && std::isfinite(j.upper) ? j.upper - j.lower : 2.0 * M_PI;
      cellSizes_[i] = range > 0.0 ? range / 20.0 : 1.0;
    }
  }
  void project(const ob::State* state, Eigen::Ref<Eigen::VectorXd> projection) const override {
    thread_local Eigen::VectorXd values;
    values.resize(joints_.dimension());
    joints_.to_group_values(state, values);
    for (std::size_t i = 0; i < dims_.size(); ++i) {
      projection[static_cast<Eigen::Index>(i)] = values[dims_[i]];
    }
  }

 private:
  const JointStateSpace& joints_;
  std::vector<int> dims_;
};

}  // namespace

JointStateSpace::JointStateSpace(std::shared_ptr<const RobotModel> model,
                                 std::vector<int> variables, const Eigen::VectorXd& fixed)
    : model_(std::move(model)), fixed_(fixed) {
  if (!model_) throw InputError("JointStateSpace: model is null");
  model_->check_configuration(fixed_);
  if (variables.empty()) throw InputError("JointStateSpace: the group has no active joints");
  std::set<int> seen;
  std::vector<int> continuous;
  for (int v : variables) {
    if (v < 0 || v >= model_->variable_count() || !seen.insert(v).second) {
      throw InputError("JointStateSpace: configuration index " + std::to_string(v) +
                       " is out of range or repeated");
    }
    const Joint& j = model_->joint(model_->variable_joint(v));
    if (j.type == JointType::kContinuous) {
      continuous.push_back(v);
    } else {
      variables_.push_back(v);
    }
  }
  bounded_count_ = static_cast<int>(variables_.size());
  variables_.insert(variables_.end(), continuous.begin(), continuous.end());

  std::shared_ptr<ob::RealVectorStateSpace> real;
  if (bounded_count_ > 0) {
    real = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(bounded_count_));
    ob::RealVectorBounds bounds(static_cast<unsigned>(bounded_count_));
    for (int i = 0; i < bounded_count_; ++i) {
      const Joint& j =
          model_->joint(model_->variable_joint(variables_[static_cast<std::size_t>(i)]));
      bounds.setLow(static_cast<unsigned>(i), j.lower);
      bounds.setHigh(static_cast<unsigned>(i), j.upper);
      real->setDimensionName(static_cast<unsigned>(i), j.name);
    }
    real->setBounds(bounds);
  }
  if (continuous.empty()) {
    space_ = real;
  } else {
    auto compound = std::make_shared<ob::CompoundStateSpace>();
    if (real) compound->addSubspace(real, 1.0);
    for (int v : continuous) {
      auto so2 = std::make_shared<ob::SO2StateSpace>();
      so2->setName(model_->joint(model_->variable_joint(v)).name);
      compound->addSubspace(so2, 1.0);
    }
    compound->lock();
    space_ = compound;
  }
  space_->setName(model_->name());
  space_->registerDefaultProjection(
      std::make_shared<ProximalJointsProjection>(space_.get(), *this));
}

void JointStateSpace::to_group_values(const ob::State* state,
                                      Eigen::Ref<Eigen::VectorXd> values) const {
  if (static_cast<int>(values.size()) != dimension()) {
    throw InputError("JointStateSpace::to_group_values: expected " + std::to_string(dimension()) +
                     " values");
  }
  if (bounded_count_ == dimension()) {
    const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    for (int i = 0; i < bounded_count_; ++i) values[i] = v[i];
    return;
  }
  const auto* compound = state->as<ob::CompoundStateSpace::StateType>();
  unsigned sub = 0;
  if (bounded_count_ > 0) {
    const double* v = compound->as<ob::RealVectorStateSpace::StateType>(sub++)->values;
    for (int i = 0; i < bounded_count_; ++i) values[i] = v[i];
  }
  for (int i = bounded_count_; i < dimension(); ++i) {
    values[i] = compound->as<ob::SO2StateSpace::StateType>(sub++)->value;
  }
}

void JointStateSpace::to_configuration(const ob::State* state,
                                       Eigen::Ref<Eigen::VectorXd> q) const {
  if (q.size() != fixed_.size()) {
    throw InputError("JointStateSpace::to_configuration: q has " + std::to_string(q.size()) +
                     " entries, robot '" + model_->name() + "' has " +
                     std::to_string(fixed_.size()));
  }
  q = fixed_;
  if (bounded_count_ == dimension()) {
    const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    for (int i = 0; i < bounded_count_; ++i) q[variables_[static_cast<std::size_t>(i)]] = v[i];
    return;
  }
  const auto* compound = state->as<ob::CompoundStateSpace::StateType>();
  unsigned sub = 0;
  if (bounded_count_ > 0) {
    const double* v = compound->as<ob::RealVectorStateSpace::StateType>(sub++)->values;
    for (int i = 0; i < bounded_count_; ++i) q[variables_[static_cast<std::size_t>(i)]] = v[i];
  }
  for (int i = bounded_count_; i < dimension(); ++i) {
    q[variables_[static_cast<std::size_t>(i)]] =
        compound->as<ob::SO2StateSpace::StateType>(sub++)->value;
  }
}

void JointStateSpace::from_configuration(const Eigen::Ref<const Eigen::VectorXd>& q,
                                         ob::State* state) const {
  model_->check_configuration(q);
  // The group's values get motion-checked: each within its joint's range. Held values stay as
  // given (data sets hold fingers beyond their limits).
  for (int v : variables_) model_->check_joint_range(v, q[v]);
  const auto wrap = [](double a) {
    const double w = std::remainder(a, 2.0 * M_PI);  // [-pi, pi]
    return w >= M_PI ? w - 2.0 * M_PI : w;
  };
  if (bounded_count_ == dimension()) {
    double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    for (int i = 0; i < bounded_count_; ++i) v[i] = q[variables_[static_cast<std::size_t>(i)]];
    return;
  }
  auto* compound = state->as<ob::CompoundStateSpace::StateType>();
  unsigned sub = 0;
  if (bounded_count_ > 0) {
    double* v = compound->as<ob::RealVectorStateSpace::StateType>(sub++)->values;
    for (int i = 0; i < bounded_count_; ++i) v[i] = q[variables_[static_cast<std::size_t>(i)]];
  }
  for (int i = bounded_count_; i < dimension(); ++i) {
    compound->as<ob::SO2StateSpace::StateType>(sub++)->value =
        wrap(q[variables_[static_cast<std::size_t>(i)]]);
  }
}

}  // namespace hullcheck
