// VampPeer for VAMP's Panda and UR5 (see vamp_peer.hpp). Compiled with -mavx2 -mfma -mbmi2.
#include "vamp_peer.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <Eigen/Geometry>
#include <vamp/collision/factory.hh>
#include <vamp/planning/rrtc.hh>
#include <vamp/planning/validate.hh>
#include <vamp/random/halton.hh>
#include <vamp/robots/panda.hh>
#include <vamp/robots/ur5.hh>

namespace hullcheck::bench {
namespace {

namespace ob = ::ompl::base;
constexpr std::size_t kRake = vamp::FloatVectorWidth;
using Environment = vamp::collision::Environment<vamp::FloatVector<kRake>>;

// A configuration from doubles: a zeroed buffer of num_scalars_rounded floats (VAMP reads whole
// vectors of it).
template <class Robot>
typename Robot::Configuration configuration(const double* values) {
  typename Robot::ConfigurationBuffer buffer{};
  for (std::size_t i = 0; i < Robot::dimension; ++i) buffer[i] = static_cast<float>(values[i]);
  return typename Robot::Configuration(buffer.data());
}

template <class Robot>
typename Robot::Configuration configuration(const ob::State* state) {
  return configuration<Robot>(state->as<ob::RealVectorStateSpace::StateType>()->values);
}

template <class Robot>
class Validity : public ob::StateValidityChecker {
 public:
  Validity(const ob::SpaceInformationPtr& si, const Environment& env)
      : ob::StateValidityChecker(si), env_(env) {}
  bool isValid(const ob::State* state) const override {
    const auto q = configuration<Robot>(state);
    return vamp::planning::validate_motion<Robot, kRake, 1>(q, q, env_);
  }

 private:
  const Environment& env_;
};

template <class Robot>
class Motions : public ob::MotionValidator {
 public:
  Motions(const ob::SpaceInformationPtr& si, const Environment& env)
      : ob::MotionValidator(si), env_(env) {}
  bool checkMotion(const ob::State* a, const ob::State* b) const override {
    return vamp::planning::validate_motion<Robot, kRake, Robot::resolution>(
        configuration<Robot>(a), configuration<Robot>(b), env_);
  }
  bool checkMotion(const ob::State* a, const ob::State* b,
                   std::pair<ob::State*, double>& last) const override {
    last.first = nullptr;  // VAMP has no last valid state
    last.second = 0.0;
    return checkMotion(a, b);
  }

 private:
  const Environment& env_;
};

template <class Robot>
class Peer : public VampPeer {
 public:
  Peer(const std::vector<VampObstacle>& obstacles, float range) : range_(range) {
    vamp::collision::Environment<float> env;
    for (const VampObstacle& o : obstacles) {
      const Eigen::Vector3f c(o.center[0], o.center[1], o.center[2]);
      Eigen::Matrix3f r;
      for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = o.rotation[i];
      const Eigen::Quaternionf rotation(r);
      if (o.kind == VampObstacle::kBox || o.as_box) {
        const Eigen::Vector3f half =
            o.kind == VampObstacle::kBox
                ? Eigen::Vector3f(o.half_extents[0], o.half_extents[1], o.half_extents[2])
                : Eigen::Vector3f(o.radius, o.radius, o.half_length);
        env.cuboids.push_back(vamp::collision::factory::cuboid::eigen_rot(c, rotation, half));
      } else if (o.kind == VampObstacle::kCylinder) {
        const Eigen::Vector3f axis = r.col(2) * o.half_length;
        const Eigen::Vector3f a = c - axis, b = c + axis;
        env.capsules.push_back(vamp::collision::factory::capsule::endpoints::eigen(a, b, o.radius));
      } else {
        env.spheres.push_back(vamp::collision::factory::sphere::eigen(c, o.radius));
      }
    }
    env.sort();
    env_ = Environment(env);
  }
  std::vector<std::string> joint_names() const override {
    return {Robot::joint_names.begin(), Robot::joint_names.end()};
  }
  std::vector<double> lower() const override { return bounds(0.0f); }
  std::vector<double> upper() const override { return bounds(1.0f); }
  bool valid(const std::vector<double>& q) const override {
    const auto c = configuration<Robot>(q.data());
    return vamp::planning::validate_motion<Robot, kRake, 1>(c, c, env_);
  }
  void attach(const ob::SpaceInformationPtr& si) const override {
    si->setStateValidityChecker(std::make_shared<Validity<Robot>>(si, env_));
    si->setMotionValidator(std::make_shared<Motions<Robot>>(si, env_));
  }
  double plan(const std::vector<double>& start, const std::vector<double>& goal) const override {
    vamp::planning::RRTCSettings settings;
    settings.range = range_;
    settings.max_iterations = 1000000;
    settings.max_samples = 1000000;
    auto rng = std::make_shared<vamp::rng::Halton<Robot>>();
    rng->reset();
    const auto result = vamp::planning::RRTC<Robot, kRake, Robot::resolution>::solve(
        configuration<Robot>(start.data()), configuration<Robot>(goal.data()), env_, settings, rng);
    // VAMP's own timer, as its papers report: it starts after the trees' buffers are allocated
    // and zeroed (parents and radii of max_samples entries, several ms for 1,000,000).
    const double seconds = 1e-9 * static_cast<double>(result.nanoseconds);
    return result.path.empty() ? -seconds : seconds;
  }

 private:
  // VAMP's joint limits: its configuration scaling maps [0, 1] to them.
  std::vector<double> bounds(float unit) const {
    typename Robot::ConfigurationBuffer buffer{};
    for (std::size_t i = 0; i < Robot::dimension; ++i) buffer[i] = unit;
    auto q = typename Robot::Configuration(buffer.data());
    Robot::scale_configuration(q);
    const auto values = q.to_array();  // (q[{i, 0}] would read row i of a one-row vector)
    return std::vector<double>(values.begin(), values.begin() + Robot::dimension);
  }

  Environment env_;
  float range_;
};

}  // namespace

std::unique_ptr<VampPeer> VampPeer::make(const std::string& robot,
                                         const std::vector<VampObstacle>& obstacles) {
  if (robot == "panda") return std::make_unique<Peer<vamp::robots::Panda>>(obstacles, 1.0f);
  if (robot == "ur5") return std::make_unique<Peer<vamp::robots::UR5>>(obstacles, 1.5f);
  return nullptr;
}

}  // namespace hullcheck::bench
