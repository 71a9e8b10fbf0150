// VampPeer: VAMP (../shared/peers/vamp) behind a plain interface, for bench_vamp. Its one
// translation unit (vamp_peer.cpp) is compiled with AVX2 and FMA, as VAMP requires; nothing of
// Eigen or hullcheck crosses this interface, so the rest of the benchmark keeps the baseline ISA.
#pragma once

#include <ompl/base/SpaceInformation.h>

#include <memory>
#include <string>
#include <vector>

namespace hullcheck::bench {

/// One scene primitive in the model frame, as VAMP's evaluation turns MotionBenchMaker scenes
/// into its own shapes: boxes as oriented cuboids, cylinders as capsules (or, `as_box`, as their
/// bounding cuboid), spheres as spheres.
struct VampObstacle {
  enum Kind { kBox, kCylinder, kSphere };
  Kind kind = kBox;
  float center[3] = {0, 0, 0};
  float rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // row by row, model <- primitive
  float half_extents[3] = {0, 0, 0};                // boxes
  float radius = 0, half_length = 0;                // cylinders (axis z), spheres
  bool as_box = false;
};

class VampPeer {
 public:
  virtual ~VampPeer() = default;
  /// "panda" or "ur5"; nullptr for another robot.
  static std::unique_ptr<VampPeer> make(const std::string& robot,
                                        const std::vector<VampObstacle>& obstacles);
  /// VAMP's joint names, in its configuration order.
  virtual std::vector<std::string> joint_names() const = 0;
  virtual std::vector<double> lower() const = 0;
  virtual std::vector<double> upper() const = 0;
  /// One configuration (VAMP order), checked by VAMP's spheres.
  virtual bool valid(const std::vector<double>& q) const = 0;
  /// VAMP's validity checker and motion validator (1/32 resolution, 8 states per SIMD call) on
  /// `si`, whose space is a RealVectorStateSpace in VAMP's joint order.
  virtual void attach(const ompl::base::SpaceInformationPtr& si) const = 0;
  /// VAMP's own RRTConnect (range: 1.0 Panda, 1.5 UR5; Halton sampler reset): wall seconds, or
  /// a negative value when unsolved.
  virtual double plan(const std::vector<double>& start, const std::vector<double>& goal) const = 0;
};

}  // namespace hullcheck::bench
