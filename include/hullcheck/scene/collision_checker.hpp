// CollisionChecker: a robot configuration against the robot itself and a static scene.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <hullcheck/core/query_result.hpp>
#include <hullcheck/core/warm_start.hpp>
#include <hullcheck/robot/allowed_collision_matrix.hpp>
#include <hullcheck/robot/robot_model.hpp>
#include <hullcheck/scene/motion_check.hpp>
#include <hullcheck/scene/pair_scope.hpp>
#include <hullcheck/scene/planning_scene.hpp>
#include <limits>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>

namespace hullcheck {

/// Which checked pairs a clearance query takes its minimum over. A planner wanting distance to
/// the world asks kObstacles: with kAll, a fixed pair of the robot's own links that stay close
/// (a wrist over its forearm, say) can hide the obstacle clearance along a whole path.
enum class ClearanceScope {
  kAll,        ///< Enabled self pairs and robot-obstacle pairs.
  kObstacles,  ///< Robot-obstacle pairs only.
  kSelf,       ///< Enabled self pairs only.
};

/// The closest (or deepest) checked pair at a configuration: a robot shape against another
/// robot shape (self) or against an obstacle.
struct ClearanceResult {
  /// Signed distance, m: > 0 apart, < 0 overlapping (minus the penetration depth, by EPA);
  /// +inf when nothing is checked.
  double distance = std::numeric_limits<double>::infinity();
  bool self = false;        ///< true: robot vs robot; false: robot vs obstacle.
  int link_a = -1;          ///< Robot link of A.
  int shape_a = -1;         ///< Index into that link's shapes.
  int link_b = -1;          ///< Robot link of B when `self`, else -1.
  int shape_b = -1;         ///< Shape index of link_b when `self`.
  int obstacle = -1;        ///< Index into the scene's obstacles when not `self`.
  std::string_view name_a;  ///< Link name of A; link or obstacle name of B. Valid while the
  std::string_view name_b;  ///< checker lives.
  Eigen::Vector3d point_a{0, 0, 0};  ///< Witness points, model frame, m.
  Eigen::Vector3d point_b{0, 0, 0};
  Eigen::Vector3d normal{0, 0, 0};  ///< Unit, from A to B; point_b - point_a = distance*normal.
  Status status = Status::kConverged;
  int exact_queries = 0;  ///< Shape pairs that needed GJK (the rest were culled).
  int iterations = 0;     ///< GJK and EPA iterations of those queries, all together.
};

/// Checks configurations of one robot against its enabled self pairs (allowed-collision matrix)
/// and the obstacles of one static scene (minus the scene's allowed link/object pairs), with
/// the robot's padding.
///
/// Broad phase: robot shapes' bounding balls against each other and against each obstacle's
/// oriented bounding box, links' and shape groups' balls first; for a link decomposed into
/// convex pieces (RobotLoadOptions::mesh_geometry), its mesh's hull before its pieces (it
/// contains them: a clear hull clears them all, and its distance bounds theirs); exact GJK/EPA
/// (core queries, their tolerances) for the survivors. Pieces of one link are never paired.
/// The padding is the model's at construction: after RobotModel::set_link_padding or
/// set_default_padding, queries throw std::logic_error (build a new checker).
/// All query methods are const and thread-safe: scratch storage is per thread, allocated on a
/// thread's first call and reused, so queries do not allocate after that.
class CollisionChecker {
 public:
  /// Throws InputError when the matrix is not sized for the model. The scene's allowed pairs
  /// (link/link, link/object) are applied; entries naming neither a link nor an object of this
  /// scene change nothing (MoveIt keeps such names in its matrices too). With no scene (an
  /// empty one) the checker is the robot's self-collision checker. Builds the warm-start
  /// grids of self pairs moved by at most two configuration values (32 x 32 exact queries for
  /// two values, 128 for one; about 4 ms for the Panda).
  CollisionChecker(std::shared_ptr<const RobotModel> model, AllowedCollisionMatrix matrix,
                   PlanningScene scene = {});

  const RobotModel& model() const { return *model_; }
  /// The model, shared: a caller can keep it as long as it needs (the Python binding does).
  const std::shared_ptr<const RobotModel>& shared_model() const { return model_; }
  const PlanningScene& scene() const { return scene_; }
  const AllowedCollisionMatrix& matrix() const { return matrix_; }

  /// True when no checked pair overlaps at configuration q (checked: count and finiteness).
  /// Stops at the first overlap found. Self pairs whose distance table is measured
  /// (measure_self_tables) are decided from it where it proves them apart or overlapping.
  bool is_valid(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// Minimum signed distance over all checked pairs at q, with the pair and witnesses. Self
  /// pairs moved by at most two configuration values (wrist links, fingers) start GJK from
  /// their warm-start grid's cell for q: about half the iterations on random Panda states, the
  /// same answers to the query tolerance, and the same answer for the same q on every thread.
  /// `scope` restricts the minimum to robot-obstacle or to self pairs; with none of its pairs
  /// checked, the result's distance is +inf.
  /// `below`, m (not NaN): a cap for callers that only need clearances below it (a margin):
  /// pairs whose bounds prove them at or above it are skipped, and when no pair is closer than
  /// `below` the result has no pair (link_a -1) and distance +inf. Below the cap the answer is
  /// the same as without one. Throws InputError for a NaN cap.
  ClearanceResult clearance(const Eigen::Ref<const Eigen::VectorXd>& q,
                            ClearanceScope scope = ClearanceScope::kAll,
                            double below = std::numeric_limits<double>::infinity()) const;
  /// clearance over the pairs of `scope` (see PairScope); +inf when it holds no checked pair.
  ClearanceResult clearance(const Eigen::Ref<const Eigen::VectorXd>& q, const PairScope& scope,
                            double below = std::numeric_limits<double>::infinity()) const;
  /// A PairScope of this checker: robot-obstacle pairs when `obstacles`, and the checked self
  /// link pairs listed (model link indices, either order). Throws InputError naming a listed
  /// pair that is not a checked link pair (checked_link_pairs()).
  PairScope pair_scope(bool obstacles,
                       const std::vector<std::pair<int, int>>& self_link_pairs) const;
  /// The PairScope holding the pairs of `scope`.
  PairScope pair_scope(ClearanceScope scope) const;
  /// is_valid for many configurations: the columns of `configurations` (variable_count() rows),
  /// verdicts written to valid[0 .. cols()). Identical to is_valid column by column (tested on
  /// every MotionBenchMaker family, near-contact states included). Blocks of kPoseBlockLanes
  /// columns: forward kinematics vectorised across the block (RobotModel::
  /// compute_link_poses_block), then link balls against obstacle boxes and against each other
  /// for the whole block; a column whose balls leave some pair undecided (by more than 1e-9 m
  /// of rounding slack) gets is_valid's exact tests for those pairs only, at poses from the
  /// scalar forward kinematics. Throws InputError naming the first bad column. Thread-safe; no
  /// allocation after a thread's first call.
  void is_valid_batch(const Eigen::Ref<const Eigen::MatrixXd>& configurations, bool* valid) const;
  /// Lower bounds on clearance() (every checked pair, m) for many configurations: the columns
  /// of `configurations`, bounds written to lower[0 .. cols()), with
  ///   min(clearance, e) <= lower <= clearance,  e = max(exact_below, 0),
  /// clearance being the exact minimum over the checked pairs at the column (clearance()'s, to
  /// its queries' tolerance): where lower is below e it is that minimum. Blocks of
  /// kPoseBlockLanes columns: vectorised forward kinematics, then per block of pairs a bound
  /// from its links' balls, refined in increasing order of that bound by covering spheres (each
  /// shape's contain it) against the obstacle's box (which contains the obstacle) or the other
  /// link's spheres, and by a self block's table when measured (measure_self_tables), all lanes
  /// at once, less 1e-9 m for the block poses' rounding. A column where some block's bound is
  /// not positive or is below e gets min(bound, clearance) from clearance()'s search capped at
  /// its bound (see `below`). Far from contact the bound is as loose as the spheres
  /// (millimetres to centimetres); raise `exact_below` for exact values wherever the clearance
  /// is below it. For roadmaps and datasets: a column whose bound exceeds r is certainly r
  /// clear. Throws InputError naming the first bad column, or for a NaN exact_below.
  /// Thread-safe; no allocation after a thread's first call.
  void clearance_lower_bound_batch(const Eigen::Ref<const Eigen::MatrixXd>& configurations,
                                   double exact_below, double* lower) const;
  /// The same for link poses from RobotModel::compute_link_poses. clearance_at has no
  /// configuration to look the grids up with: its queries start cold (same answers, slower).
  bool is_valid_at(const std::vector<Eigen::Isometry3d>& link_poses) const;
  ClearanceResult clearance_at(const std::vector<Eigen::Isometry3d>& link_poses,
                               ClearanceScope scope = ClearanceScope::kAll) const;
  ClearanceResult clearance_at(const std::vector<Eigen::Isometry3d>& link_poses,
                               const PairScope& scope) const;

  /// The robot's checked link pairs (model link indices, a < b): links with geometry that the
  /// matrix (with the scene's allowed pairs) does not allow to touch.
  std::vector<std::pair<int, int>> checked_link_pairs() const;
  /// Every checked link pair overlapping at the link poses (as in checked_link_pairs()),
  /// appended to `out`; obstacles are not considered. Same broad phase and exact tests as
  /// is_valid_at, which stops at the first overlap instead. Allocates only when `out` grows.
  void colliding_link_pairs_at(const std::vector<Eigen::Isometry3d>& link_poses,
                               std::vector<std::pair<int, int>>& out) const;

  /// Measures every cell of the self blocks' distance tables now: bounds on the signed distance
  /// of link pairs moved relative to each other by one or two revolute values, over a fine grid
  /// of those values (exact queries at each cell's centre); for pairs moved by three, lower
  /// bounds over two of them, one link swept through a whole turn about the joint next to it
  /// (the hull of 16 turned copies grown by the chord's sag). Afterwards is_valid,
  /// is_valid_batch and check_motion decide such pairs from the tables wherever the bounds
  /// prove them apart (or overlapping) by more than 1e-6 m, with the same verdicts as without
  /// (the exact tests run where the bounds decide nothing, only on the pairs of the cell's
  /// near shapes: those that may come within 1e-6 m of the other link there). The tables
  /// depend only on the model and its padding: every checker of the same model object shares
  /// them, so this runs once per model while one of them lives (later calls return at once).
  /// Measured (this project's benchmarks, one thread, 2026-12-07): 0.14 s for the
  /// MotionBenchMaker Panda, 8.4-9.2 s for its UR5 with decomposed meshes (4.7 s on two).
  /// Without it no table is used. The cells are measured on
  /// `threads` threads (this one and threads - 1 started for the call and joined before it
  /// returns; 0: one per hardware thread); the tables are the same whatever the count. Throws
  /// InputError for threads < 0. Thread-safe; it may run while other threads query.
  void measure_self_tables(int threads = 0) const;

  /// Upper bound, m, on how far any point of any checked robot shape moves relative to any
  /// other checked shape or obstacle along the straight joint-space motion from q0 to q1 (each
  /// value interpolated linearly): a motion whose bound is below the clearance at q0 cannot
  /// collide. From the kinematic chain: per joint, |dq| times a bound, over every configuration,
  /// on the largest distance from its axis to any point of the shapes it moves (prismatic:
  /// |dq|); doubled when self pairs are checked (both links may move).
  double motion_bound(const Eigen::Ref<const Eigen::VectorXd>& q0,
                      const Eigen::Ref<const Eigen::VectorXd>& q1) const;

  /// One step of conservative advancement along the straight joint-space motion q + s*dq:
  /// the largest s in [0, 1] this call can certify, i.e. every configuration q + t*dq with
  /// 0 <= t <= s is collision-free (1: the whole motion), or -1 when some checked pair at q is
  /// within `min_clearance` (m) of touching (or overlapping). Per pair: s_p = distance_p / motion_p
  /// with motion_p a bound on how far the pair's shapes move relative to each other per unit s
  /// (joints above both links of a self pair move them together and do not count). Exact
  /// distances are computed only for pairs whose bounding-volume gap could limit s. Prismatic
  /// values beyond their limits (not clamped) add to the motion bounds. Thread-safe; the
  /// per-thread scratch grows on first use only.
  double safe_advance(const Eigen::Ref<const Eigen::VectorXd>& q,
                      const Eigen::Ref<const Eigen::VectorXd>& dq, double min_clearance) const;

  /// Proves the straight joint-space motion q0 -> q1 (each value interpolated linearly; pass
  /// q1 with continuous joints' values already unwrapped for the short way round) free at
  /// every configuration, or finds its first contact. Interval bisection: over an interval of
  /// the motion with centre m and half-width h, a pair whose shapes move at most `rate` relative
  /// to each other per unit of t (the lever arms of safe_advance) and whose signed distance at
  /// q(m) exceeds h * rate + min_clearance keeps its clearance over the whole interval; pairs
  /// (and first their groups' balls, links' balls and mesh hulls, rigid bodies' hulls, with the
  /// largest rate of their members) that cannot be decided so are passed to the interval's halves,
  /// left half first, so that the certified part [0, last_free] grows from q0. Tests are ball gaps
  /// and signed_distance_below with the margin as cutoff (exact distances only where a pair is
  /// within its margin). Thread-safe; per-thread scratch grows on first use only. Throws
  /// InputError on a bad configuration or options.
  MotionCheckResult check_motion(const Eigen::Ref<const Eigen::VectorXd>& q0,
                                 const Eigen::Ref<const Eigen::VectorXd>& q1,
                                 const MotionCheckOptions& options = {}) const;

 private:
  friend struct SelfTableTestAccess;    // tests/scene/test_self_tables.cpp: the tables' bounds
  friend struct MotionLeverTestAccess;  // tests/scene/test_motion_levers.cpp: the lever arms
  friend struct RigidBodyTestAccess;    // tests/scene/test_rigid_body_clusters.cpp: body hulls
  struct RobotShape {
    int link;
    int shape;
    Eigen::Vector3d center;  // bounding ball centre in the link frame
    double radius;
    std::string_view link_name;
    bool at_link_frame;      // the shape's origin is the identity: its pose is the link's pose
    Eigen::Vector3d inside;  // a point of the shape, link frame (distance upper bounds)
  };
  struct ShapeGroup {  // consecutive robot shapes, shapes_[begin, end), culled together
    int begin, end;
    // The pieces of one decomposed mesh: shapes_[bound] is a piece whose element_hull (the
    // mesh's hull, at the pieces' common pose) contains them all; -1 otherwise.
    int bound = -1;
    // All of one link's shapes: their enclosing ball, fixed in that link's frame; -1 otherwise.
    int link = -1;
    Eigen::Vector3d local_center = Eigen::Vector3d::Zero();
    double radius = 0.0;
  };
  struct ObstacleBox {           // oriented bounding box of an obstacle (margin included)
    Eigen::Matrix3d rotation_t;  // world -> box frame rotation
    Eigen::Vector3d center;      // world
    Eigen::Vector3d half_extents;
  };
  struct SelfPair {
    int a, b;  // indices into shapes_
  };
  struct SelfBlock {     // the self pairs of one link pair, self_pairs_[begin, end)
    int link_a, link_b;  // indices into link_balls_
    int begin, end;
  };
  struct LinkBall {          // a ball enclosing every shape ball of one link
    int link;                // index into the model's links
    Eigen::Vector3d center;  // link frame
    double radius;
    // A shape containing all of the link's shapes: shapes_[bound]'s element hull when the link
    // is one decomposed mesh, shapes_[bound] itself when it is one shape; -1 otherwise.
    int bound = -1;
  };
  // A rigid body (links joined by fixed joints) and a convex hull containing every robot shape
  // of its links, padding included (rigid_body_clusters.cpp).
  struct RigidBodyHull {
    int root = -1;  // the body's topmost link (a model link index): the hull's frame
    std::shared_ptr<const Shape> hull;
    Eigen::Vector3d center = Eigen::Vector3d::Zero();  // a ball containing the hull, root frame
    double radius = 0.0;
  };
  // The self blocks joining the same two rigid bodies, when there are two or more: check_motion
  // tests the bodies' hulls first, one query for all of them (a gripper's links against the
  // forearm, say).
  struct SelfCluster {
    int body_a, body_b;  // indices into bodies_
    int begin, end;      // cluster_blocks_[begin, end): its self blocks
  };
  /// Robot shape `shape`'s padded shape (the model's).
  const Shape& shape_of(int shape) const;
  /// The shape containing robot shape `shape`'s group or link (see `bound` above).
  const Shape& bounding_shape(int shape) const;
  struct EnvironmentPair {
    int shape;     // index into shapes_
    int obstacle;  // index into scene_.obstacles
  };
  struct EnvironmentBlock {  // the pairs of one shape group with one obstacle
    int group;               // index into groups_
    int obstacle;
    int begin, end;  // environment_pairs_[begin, end)
  };
  // Warm starts of a self pair whose relative pose depends on at most two configuration
  // values (wrist links, say): a grid over those values, each cell holding the final GJK
  // simplex (hull vertex pairs) and direction (minus the normal from A to B, A's frame) at the
  // cell's centre, computed at construction. A query at q starts GJK from its cell's entry,
  // re-evaluated at the actual poses: a starting point only (answers to the same tolerance),
  // and the same one for the same q on any thread. clearance's slab bound for the pair is
  // taken along the cell's direction (near the best separating direction, so near the answer).
  // clearance and safe_advance use them; is_valid does not (its boolean GJK exits after a few
  // iterations on these pairs, and starting it from the grid's direction measured slower).
  // Cells over at most kMaxGridValues configuration values (joint_grid.cpp): each value's range
  // between its limits (one turn for a continuous joint) cut into equal cells.
  static constexpr int kMaxGridValues = 3;
  struct JointGrid {
    int dims = -1;  // number of keying values; -1: no grid
    int variables[kMaxGridValues] = {0, 0, 0};
    double lower[kMaxGridValues] = {0, 0, 0};
    double cells_per_unit[kMaxGridValues] = {0, 0, 0};  // cells per radian (or metre)
    int cells[kMaxGridValues] = {1, 1, 1};
    bool wraps[kMaxGridValues] = {false, false, false};  // continuous: the grid covers one turn
    /// Over the values keys[0 .. count), `cells_per_value` cells each; returns the cell count.
    std::size_t setup(const RobotModel& model, const int* keys, int count, int cells_per_value);
    /// Half a cell's width along value d (0 for a value without range).
    double half_width(int d) const;
    /// The cell holding configuration q: clamped into the grid, or -1 outside it unless clamp.
    long cell(const double* q, bool clamp) const;
    /// Value x of keying value d in cell units from the grid's lower end (a continuous joint's
    /// value taken modulo one turn first); 0 for a value without range.
    double coordinate(int d, double x) const;
    /// Writes the centre of `cell` into q's keying values.
    void center(std::size_t cell, Eigen::VectorXd& q) const;
  };
  struct WarmStartGrid : JointGrid {
    std::vector<WarmStart> starts;
    const WarmStart& at(const double* q) const {
      return starts[static_cast<std::size_t>(cell(q, true))];
    }
  };
  /// Fills warm_grids_ from the model's shared set, building the grids it lacks.
  void build_warm_start_grids();

  // Robot shapes per group of the obstacle broad phase: a group's bounding ball is tested
  // against an obstacle first, its shapes only when it is not clear (consecutive links follow
  // the kinematic chain, so a group is a few neighbouring links, or one decomposed link).
  static constexpr int kGroupSize = 4;

  // Construction (collision_checker.cpp), in order.
  std::vector<std::vector<bool>> apply_scene_allowed_pairs();
  void index_shapes();
  void build_self_pairs();
  void build_groups();
  void build_environment_pairs(const std::vector<std::vector<bool>>& link_object_allowed);
  void build_self_clusters();
  /// The topmost link joined to `link` by fixed joints only (`link` itself when its parent
  /// joint moves or it is a root).
  int rigid_root(int link) const;
  /// The body of links whose rigid root is `root`, with its hull from the model's shared set
  /// (built there when absent).
  RigidBodyHull body_hull(int root) const;
  void enclosing_ball(int begin, int end, Eigen::Vector3d* center, double* radius) const;
  struct MotionLevers;
  // Motion bounds' data (motion_bounds.cpp): above[l][j] is true when joint j is on the path
  // from the root to link l; the lever arms, built once by the first call of motion_levers().
  std::vector<std::vector<bool>> joints_above_links() const;
  const MotionLevers& motion_levers() const;
  void build_motion_levers(MotionLevers& out) const;
  /// Per joint and robot shape, how far the shape's points move per unit of the joint's own
  /// value (motion_bounds.cpp); from the model's shared set, built there when absent.
  const Eigen::MatrixXd& joint_arms() const;
  /// The configuration values driving the movable joints above exactly one of the two links
  /// (those moving one relative to the other), written to keys[0..]; returns their count, or
  /// at_most + 1 as soon as there are more than at_most. *revolute, when given, tells whether
  /// every movable joint found is revolute or continuous.
  int relative_drivers(int link_a, int link_b, int at_most, int* keys,
                       bool* revolute = nullptr) const;

  struct Scratch;
  Scratch& scratch() const;
  // is_valid's broad phase and exact tests (collision_verdict.cpp): does any pair of the block
  // overlap at the placed shapes?
  bool environment_block_overlaps(const EnvironmentBlock& block, Scratch& s) const;
  /// The same after the block's group ball was found to reach the obstacle's box.
  bool environment_block_shapes_overlap(const EnvironmentBlock& block, Scratch& s) const;
  bool self_block_overlaps(const SelfBlock& block, Scratch& s) const;
  /// is_valid at the shapes placed in s (with s.q, when set, for the self blocks' tables).
  bool placed_is_valid(Scratch& s) const;
  // The same, out of line, for check_motion (motion_certificate.cpp).
  bool environment_block_collides(int block, Scratch& s) const;
  /// The covering spheres of robot shapes [begin, end) at the block's poses, placed on first
  /// use in the block: rows of kPoseBlockLanes (x, y, z, radius per sphere), consecutive.
  const double* place_cover(int begin, int end, Scratch& s) const;
  /// The block's lanes in which robot shape `shape` is proven clear of obstacle `obstacle`'s
  /// box by more than `slack` (m): by the shape's ball, and where that leaves lanes of `needed`,
  /// by its covering spheres (placed then).
  std::uint8_t shape_clear_of_box(int shape, std::size_t obstacle, double slack,
                                  std::uint8_t needed, Scratch& s) const;
  /// The block's lanes in which all of robot shape `shape`'s covering spheres (placed then) are
  /// clear of obstacle `obstacle`'s box by more than `slack` (m); uses s.sphere_box_clear.
  std::uint8_t cover_clear_of_box(int shape, std::size_t obstacle, double slack, Scratch& s) const;
  /// Throws InputError unless `configurations` has variable_count() rows and every column is a
  /// configuration of the model (naming `who` and the column); std::logic_error after a padding
  /// change.
  void check_columns(const Eigen::Ref<const Eigen::MatrixXd>& configurations,
                     const char* who) const;
  /// The robot shapes [first_shape, end_shape) of link ball `link_ball`'s link and their
  /// covering spheres' count.
  struct LinkCover {
    int first_shape = 0, end_shape = 0;
    std::size_t spheres = 0;
  };
  LinkCover link_cover(int link_ball) const;
  /// The covering spheres of robot shapes [first_shape, end_shape), counted.
  std::size_t cover_spheres(int first_shape, int end_shape) const;
  /// Forward kinematics of columns [first, first + count) into s.pose_block (SIMD), the link
  /// balls placed into s.ball_centers (rows of kPoseBlockLanes), covering spheres made ready
  /// for place_cover.
  void place_block(const Eigen::Ref<const Eigen::MatrixXd>& configurations, Eigen::Index first,
                   int count, Scratch& s) const;
  /// clearance_lower_bound_batch: raises gap[0 .. count) (a lower bound on block b's pairs'
  /// signed distance per lane; environment blocks first, then self blocks) with the pairs'
  /// covering spheres and, for a self block where they leave it below max(e, 0+), its table.
  void refine_block_gap(const Eigen::Ref<const Eigen::MatrixXd>& configurations, Eigen::Index first,
                        int count, std::size_t b, double e, double* gap, Scratch& s) const;
  /// check_motion's environment over the motion q0 + t dq (t in [0, 1]) at once
  /// (motion_sweep.cpp): returns the lanes k whose interval [k, k + 1] / kPoseBlockLanes the
  /// shapes' volumes at its middle prove clear of every obstacle by more than min_clearance;
  /// *colliding receives lanes proven in collision at their middle (inner balls in a box
  /// obstacle, within the blocks tested before every lane had failed): the first shape proving
  /// any ends the sweep (0 returned). `extra`: the prismatic excess per unit t. Fills
  /// s.motion_probes and the block scratch (place_block).
  std::uint8_t sweep_environment(const Eigen::Ref<const Eigen::VectorXd>& q0,
                                 const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_dq,
                                 double extra, double min_clearance, std::uint8_t* colliding,
                                 Scratch& s) const;
  /// sweep_environment's shape balls: `group`'s shapes' balls, each grown by h times its rate
  /// (plus `extra`) and min_clearance, at the block's poses into s.group_shape_balls.
  void place_group_shape_balls(const ShapeGroup& group, double h, const Eigen::VectorXd& abs_dq,
                               double extra, double min_clearance, Scratch& s) const;
  /// The same for the self blocks, at the block sweep_environment placed.
  std::uint8_t sweep_self(const Eigen::Ref<const Eigen::VectorXd>& q0, const Eigen::VectorXd& dq,
                          const Eigen::VectorXd& abs_dq, double extra, double min_clearance,
                          Scratch& s) const;
  /// is_valid_batch for one block of up to kPoseBlockLanes columns starting at `first`.
  void is_valid_block(const Eigen::Ref<const Eigen::MatrixXd>& configurations, Eigen::Index first,
                      int count, bool* valid, Scratch& s) const;
  bool self_block_collides(int block, Scratch& s) const;
  /// True when self cluster `cluster`'s two rigid bodies' hulls are apart at the placed poses
  /// (then none of its blocks' pairs meets); computed once per placement.
  bool bodies_apart(int cluster, Scratch& s) const;
  /// Whether is_valid tests self cluster `cluster`'s body hulls before its blocks: when they
  /// replace more than kGroupSize block queries. Measured (bench_python_reference, MBM
  /// bookshelf_small scene 1): the UR5's gripper (12 blocks) 6-12% faster per state, the
  /// Panda's hand and fingers (4) 4-8% slower.
  /// The number of robot shapes of model link `link`.
  int link_shape_count(int link) const {
    const auto l = static_cast<std::size_t>(link);
    return shape_begin_[l + 1] - shape_begin_[l];
  }
  bool many_blocks(int cluster) const {
    const SelfCluster& c = self_clusters_[static_cast<std::size_t>(cluster)];
    return c.end - c.begin > kGroupSize;
  }
  // Whether robot shape `shape` meets `other` (the hull of link ball `other_ball`, the other
  // link of its self block) at its pose; tested once per block query, whose stamp is `mark`
  // (s.meets_other).
  bool piece_meets_hull(int shape, int other_ball, const Shape& other,
                        const Eigen::Isometry3d& other_pose, std::uint64_t mark, Scratch& s) const;
  void place(const std::vector<Eigen::Isometry3d>& link_poses, Scratch& s) const;
  const Eigen::Isometry3d& shape_pose(int shape, Scratch& s) const;
  /// Centre (model frame) of robot shape `shape`'s ball at the current query's poses.
  const Eigen::Vector3d& center(int shape, Scratch& s) const;
  /// clearance() at the shapes placed by place() (clearance_search.cpp).
  /// With `self_mask` (per self block, 1: seeded), only those self blocks are searched.
  /// With `below`, pairs bounded at or above it are skipped (clearance's cap).
  ClearanceResult nearest_pair(Scratch& s, ClearanceScope scope, const char* self_mask = nullptr,
                               double below = std::numeric_limits<double>::infinity()) const;
  /// Throws InputError when clearance's cap is NaN.
  static void check_below(double below);
  /// The self mask of `scope`; throws InputError when the scope is not this checker's.
  const char* self_mask(const PairScope& scope) const;
  struct NearestSearch;
  struct MotionSearch;  // check_motion's bisection (motion_certificate.cpp)
  /// signed_distance_below(cutoff) of checked pair i (environment pairs first, then self pairs)
  /// at the shape poses of the current query.
  SignedDistanceResult pair_distance_below(std::size_t i, double cutoff, Scratch& s) const;
  /// A lower bound on checked pair i's signed distance (numbered as pair_distance_below's) from
  /// its shapes' balls (and the obstacle's box) at the current query's poses.
  double pair_ball_gap(std::size_t i, Scratch& s) const;
  double box_gap(const ObstacleBox& box, const Eigen::Vector3d& c, double radius,
                 Eigen::Vector3d* direction = nullptr) const;
  /// Extra motion bound (m) over the straight motion q0 -> q1 from prismatic values beyond the
  /// limits the lever arms assume.
  double prismatic_excess_motion(const Eigen::Ref<const Eigen::VectorXd>& q0,
                                 const Eigen::Ref<const Eigen::VectorXd>& q1) const;

  std::shared_ptr<const RobotModel> model_;
  AllowedCollisionMatrix matrix_;
  PlanningScene scene_;
  std::vector<RobotShape> shapes_;
  std::vector<ObstacleBox> boxes_;
  std::vector<Eigen::Vector3d> obstacle_points_;  // a point of each obstacle, world
  std::vector<SelfPair> self_pairs_;              // grouped by link pair
  std::vector<SelfBlock> self_blocks_;
  std::vector<LinkBall> link_balls_;    // links with geometry
  std::vector<int> link_ball_of_link_;  // per model link: its index in link_balls_, or -1
  // Covering spheres (x, y, z in the link's frame, radius) of robot shape i:
  // cover_[cover_begin_[i] .. cover_begin_[i + 1]) (covering_spheres.cpp).
  std::vector<Eigen::Vector4d> cover_;
  std::vector<Eigen::Vector4d> inner_;  // per robot shape: a ball inside it (link frame)
  std::vector<char> exact_box_;         // per obstacle: boxes_ is the obstacle itself
  std::vector<double> box_values_;      // boxes_ packed for the SIMD tests (ball_tests_block.hpp)
  std::vector<double> box_rows_;        // boxes_ as rows, one column per box (sphere_box_rows.hpp)
  std::vector<int> cover_begin_;
  void build_covering_spheres();
  std::vector<int> shape_begin_;  // per link (and one past): its first index in shapes_
  std::vector<EnvironmentPair> environment_pairs_;  // grouped by block
  std::vector<ShapeGroup> groups_;
  // Per shape group g: the link balls of its links, group_balls_[group_ball_begin_[g] ..
  // group_ball_begin_[g + 1]) (is_valid_batch's environment blocks).
  std::vector<int> group_ball_begin_, group_balls_;
  std::vector<int> self_block_balls_;  // per self block: link_a, link_b (the SIMD ball tests)
  std::vector<EnvironmentBlock> blocks_;
  // Per shape group g: its environment blocks, blocks_[group_block_begin_[g] ..
  // group_block_begin_[g + 1]) (check_motion's per-group items).
  std::vector<int> group_block_begin_;
  bool has_self_pairs_ = false;
  std::vector<RigidBodyHull> bodies_;  // the rigid bodies of self_clusters_
  std::vector<SelfCluster> self_clusters_;
  std::vector<int> cluster_blocks_;    // self block indices, by cluster
  std::vector<int> cluster_of_block_;  // per self block: its cluster, or -1
  std::vector<int> link_depth_;        // per link: joints between it and the root
  int padding_revision_ = 0;           // the model's when the bounding volumes were computed
  /// Throws std::logic_error when the model's padding changed since construction.
  void require_current_padding() const;
  // The lever arms of motion_bound and safe_advance, built on first use (their size grows with
  // shapes x configuration values, too large for long chains that never need them); shared by
  // copies (they depend only on what copies share).
  std::shared_ptr<MotionLevers> motion_levers_;
  // Distance tables of self blocks (self_block_tables.cpp): for a block whose links are moved
  // relative to each other by one or two revolute values (three: one link swept about a joint,
  // swept_links.cpp), a grid over those values holding, per cell, bounds on the links' signed
  // distance everywhere in the cell, measured by
  // measure_self_tables. They depend only on the model (and its padding): shared by every
  // checker of the same model (found at construction); copies share them.
  struct SelfTable;
  struct NearShapeBits;
  /// The layout of self block `block`'s near-shape masks (SelfTable::near_shapes).
  NearShapeBits near_shape_bits(const SelfBlock& block) const;
  struct SelfTables;
  struct SweptLink;
  /// The joint next to `link_ball`'s link on the way to `other_ball`'s (swept_links.cpp): -1
  /// unless exactly `drivers` values, each moving one revolute joint there, move the two
  /// relative to each other.
  int sweep_joint(int link_ball, int other_ball, int drivers) const;
  /// `joint`'s axis line (a point and unit direction) in `link_ball`'s link frame.
  void sweep_axis(int link_ball, int joint, Eigen::Vector3d* origin, Eigen::Vector3d* axis) const;
  /// m^3: how much a coarse sweep of `link_ball`'s link about `joint` adds to its shapes' hulls.
  double sweep_growth(int link_ball, int joint) const;
  /// `link_ball`'s link swept through a turn about `joint` (sweep_joint's); null when a hull
  /// cannot be built.
  std::unique_ptr<SweptLink> sweep_link(int link_ball, int joint) const;
  struct ModelSelfTables;
  std::shared_ptr<SelfTables> self_tables_;
  /// The tables of the model (and padding revision) from a registry, made when absent.
  std::shared_ptr<ModelSelfTables> model_self_tables() const;
  /// Per self block, its table or nullptr, set up on first use (the lever arms are built then).
  const std::vector<SelfTable*>& set_up_self_tables() const;
  /// set_up_self_tables() once any cell of the model's tables is measured; before, nullptr
  /// (queries read no table, and nothing is built or allocated for them).
  const std::vector<SelfTable*>* self_block_tables() const;
  /// Bounds, m, on self block `block`'s signed distance at configuration q (all values):
  /// *lower <= distance <= *upper, those of the cell holding q. False, leaving the bounds
  /// untouched, when the block has no table, q lies outside its grid, or the cell is not
  /// measured.
  /// With `near_shapes`: also the cell's shapes that may be within kTableSlack of the other
  /// link (SelfTable::near_shapes), or kAllShapesNear when the table keeps none.
  bool self_block_bounds(int block, const double* q, double* lower, double* upper,
                         std::uint64_t* near_shapes = nullptr) const;
  static constexpr std::uint64_t kAllShapesNear = ~std::uint64_t{0};
  /// A lower bound, m, on self block `block`'s signed distance over the straight motion
  /// q0 + t dq, t in [t0, t1]: the smallest lower bound of the cells it crosses. False (the
  /// bound not written) when the block has no table, the motion leaves the grid, crosses more
  /// than `max_cells` cells or one not measured, or the bound falls to `needed` or below.
  /// With `reached`: the walk goes as far as it can (up to max_cells cells, or the grid's edge)
  /// and *reached is where it stopped: every cell of [t0, *reached) is measured with a lower
  /// bound above `needed` (t1 when it returns true; t0 when the first cell fails).
  bool self_block_segment_lower(int block, const double* q0, const double* dq, double t0, double t1,
                                int max_cells, double needed, double* lower,
                                double* reached = nullptr) const;
  /// The near shapes (self_block_bounds) of every cell the straight motion q0 + t dq crosses
  /// for t in [t0, t1], or-ed: a pair of the block with a shape not among them is apart by more
  /// than kTableSlack over that whole motion. False (nothing written) when the block's table
  /// keeps no near shapes, the motion leaves the grid, crosses more than max_cells cells or one
  /// not measured.
  bool self_block_segment_near(int block, const double* q0, const double* dq, double t0, double t1,
                               int max_cells, std::uint64_t* near_shapes) const;
  /// True when every cell of the box in self block `block`'s grid spanned by the straight
  /// motion q0 + t dq, t in [t0, t1], has a lower bound above `needed` (m), from the table's
  /// summary levels (built by measure_self_tables): the box holds every cell the motion
  /// crosses. False when the table is not summarized, the motion leaves the grid or crosses a
  /// continuous value's seam, or some cell of the box is not above `needed`.
  bool self_block_box_lower(int block, const double* q0, const double* dq, double t0, double t1,
                            double needed) const;
  /// Measures cell `cell` of self block `block`'s table (exact queries at its centre, with s's
  /// table scratch; the query placed in s is left as it is) unless it is measured; queries of
  /// the model's checkers read the tables from then on.
  void measure_self_table_cell(int block, long cell, Scratch& s) const;
  // Per self pair, its warm-start grid (owned by the model's shared set), or nullptr.
  std::vector<const WarmStartGrid*> warm_grids_;
};

}  // namespace hullcheck
