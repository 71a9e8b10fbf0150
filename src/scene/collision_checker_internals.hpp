// CollisionChecker's private types shared by its source files (not installed): per-thread
// scratch storage and the lazily built lever arms.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <hullcheck/scene/collision_checker.hpp>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace hullcheck {

/// A point of the shape, its local frame: the origin of a primitive, the mean of a hull's
/// vertices (collision_checker.cpp).
Eigen::Vector3d point_inside(const Shape& shape);

struct CollisionChecker::Scratch {
  // One shape group's ball against every obstacle box (sphere_box_rows.hpp): the boxes it is
  // clear of (bits), its gaps to them (m).
  std::vector<std::uint64_t> boxes_clear;
  std::vector<double> box_gaps;
  std::vector<Eigen::Isometry3d> link_poses;
  std::vector<Eigen::Isometry3d> shape_poses;
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> lower_bounds;
  std::vector<double> motions;
  Eigen::VectorXd abs_dq;
  Eigen::VectorXd q_end;
  // Shape poses are computed when a pair needs them: posed[i] == stamp when shape_poses[i]
  // belongs to the current query (stamp grows with every place(), so no stale pose is used,
  // whichever checker ran before on this thread).
  std::vector<std::uint64_t> posed;
  std::vector<std::uint64_t> centered;  // centers[i] is current when centered[i] == stamp
  std::uint64_t stamp = 0;
  const std::vector<Eigen::Isometry3d>* link_poses_in = nullptr;  // of the current query
  const double* q = nullptr;  // configuration of the current query, when it has one
  std::vector<Eigen::Vector3d> group_centers;
  std::vector<double> group_radii;
  std::vector<Eigen::Vector3d> link_centers;  // per link_balls_ entry, model frame
  // is_valid: per shape, whether it meets the other link's hull in the self block query
  // stamped there (pieces that do not cannot meet any of that link's pieces): piece_meets_hull.
  std::vector<std::uint64_t> meets_other;
  // is_valid: per self cluster, the placement (stamp) bodies_apart last answered for, and its
  // answer.
  std::vector<std::uint64_t> bodies_tested;
  std::vector<char> bodies_were_apart;
  std::vector<std::pair<double, int>> candidates;  // clearance: queue of (lower bound, code)
  std::vector<std::pair<double, int>> nearest;     // clearance: (ball bound, code)
  std::vector<std::pair<double, int>> expanded;    // clearance: a block's pairs
  // check_motion: the items (blocks or pairs, with their rates) still undecided per interval,
  // one segment per split interval, and the stack of intervals to examine.
  struct MotionItem {
    int kind;     // MotionSearch::Kind
    int index;    // into blocks_, self_blocks_, environment_pairs_ or self_pairs_
    double rate;  // m of relative motion per unit of the motion's parameter t
  };
  struct MotionInterval {
    double begin, end;           // of the motion's parameter t
    int items_begin, items_end;  // into motion_items
  };
  // is_valid_batch: the block's link poses, link ball centres per lane (x, y, z rows of
  // kPoseBlockLanes), and per lane the blocks the balls left undecided (environment blocks as
  // their index, self blocks as -1 - index).
  LinkPoseBlock pose_block;
  std::vector<double> ball_centers;            // link balls as sphere rows (x, y, z, radius)
  std::vector<std::uint8_t> ball_box_clear;    // per link ball and obstacle: lanes clear
  std::vector<std::uint8_t> sphere_box_clear;  // per covering sphere of a shape
  // The motion sweep: a shape group's shapes' balls, each grown by its margin (link frame,
  // x, y, z, radius), at the block's poses (rows of kPoseBlockLanes), and per shape the lanes
  // in which its ball is clear of the current obstacle's box.
  std::vector<double> group_shape_spheres, group_shape_balls;
  std::vector<std::uint8_t> group_shape_clear;
  // check_motion's sweep: per shape group / self block, the lanes it proved (the lanes still
  // open when it was tested; 0 for those not reached).
  std::vector<std::uint8_t> sweep_group_lanes, sweep_block_lanes;
  // check_motion: a shape group's ball's gaps to its obstacles' boxes (test_environment_group).
  std::vector<double> group_gaps;
  std::vector<std::uint8_t> self_balls_apart;  // per self block: lanes with its link balls apart
  // Covering spheres at the block's poses (per cover_ entry, 4 rows of kPoseBlockLanes);
  // shape i's are current when cover_placed[i] == block_stamp.
  std::vector<double> cover_world;
  std::vector<std::uint64_t> cover_placed;
  std::uint64_t block_stamp = 0;
  std::vector<int> undecided[kPoseBlockLanes];
  // clearance_lower_bound_batch: per block of pairs (environment blocks, then self blocks), its
  // links' balls' gap per lane (rows of kPoseBlockLanes), and the blocks in the order refined
  // (smallest gap over the lanes first).
  std::vector<double> block_gaps;
  std::vector<std::pair<double, int>> block_order;
  std::vector<MotionItem> motion_items, motion_items_next;
  // Self-block tables: the configuration and link poses at the centre of a cell being measured.
  Eigen::VectorXd table_q;
  std::vector<Eigen::Isometry3d> table_poses;
  std::vector<Eigen::Vector3d> table_centers;  // per robot shape: its ball's centre there
  // Per pair of the block measured: a lower bound of its distance over the cell, and whether
  // it is only a bound that a query stopped at (not the pair's measured distance).
  std::vector<double> table_pair_lower;
  std::vector<char> table_pair_bound_only;
  std::vector<MotionInterval> motion_intervals, motion_intervals_next;
  Eigen::VectorXd motion_q;  // the configuration being evaluated
  // check_motion's probes: a block of configurations along the motion (kPoseBlockLanes
  // columns) and their verdicts.
  Eigen::MatrixXd motion_probes;
  bool probe_valid[kPoseBlockLanes];
  Eigen::VectorXd motion_dq;    // q1 - q0 (abs_dq holds its magnitudes)
  Eigen::VectorXd motion_back;  // q0 - q1: table walks from an interval's middle backwards
  // Per self block: its hull query's last warm start within the motion numbered `motion`
  // (motion_stamp grows with every check_motion, so every motion starts cold, as on any thread).
  struct MotionWarmStart {
    std::uint64_t motion = 0;
    WarmStart start;
  };
  std::vector<MotionWarmStart> motion_warm;
  std::uint64_t motion_stamp = 0;
};

// A self block's distance table (self_block_tables.cpp): a grid over the values moving its
// links relative to each other, per cell the packed bounds on their signed distance anywhere in
// the cell (kUnmeasured until a query measures it).
// Metres by which a self block's table bounds must prove its links apart (or overlapping) to
// decide it without exact tests: far above the queries' tolerance, so that the exact tests
// would give the same verdict.
constexpr double kTableSlack = 1e-6;

// One link's shapes turned through a whole turn about the axis of the joint next to it on the
// way to another link (swept_links.cpp): each is contained in its SweptShape whatever that
// joint's value, so distances to them bound the link's from below over every value of it.
namespace detail {
struct SweptShape {
  Shape shape;             // link frame: a hull of turned copies, grown by the chord's sag
  Eigen::Vector3d center;  // a ball containing `shape`, link frame
  double radius = 0.0;
};
}  // namespace detail
struct CollisionChecker::SweptLink {
  using SweptShape = detail::SweptShape;
  int link = -1;                      // model link index
  int driver = -1;                    // the configuration value the sweep removes
  std::vector<SweptShape> shapes;     // per collision shape of the link (its index there)
  std::unique_ptr<SweptShape> bound;  // the link's bounding shape swept, when it has one
};

struct CollisionChecker::SelfTable : JointGrid {
  static constexpr std::uint64_t kUnmeasured = ~std::uint64_t{0};
  std::size_t cell_count = 0;
  // Blocks moved by one value more than a table holds: one link swept (its upper bounds are
  // then +infinity: the sweep proves no contact).
  std::shared_ptr<const SweptLink> swept;
  // How far the links move relative to each other between a cell's centre and any point of
  // it, m: per pair of the block (in its order), and at most over the block.
  std::vector<double> pair_reach;
  double block_reach = 0.0;
  std::unique_ptr<std::atomic<std::uint64_t>[]> bounds;  // per cell
  // Per cell, when the two links have at most 64 shapes together (else null): the shapes of
  // the block's pairs whose lower bound over the cell is kTableSlack or less (NearShapeBits).
  // A pair with an unmarked shape is apart by more than kTableSlack everywhere in the cell.
  // Stored before the cell's bounds (release), read after them (acquire).
  std::unique_ptr<std::atomic<std::uint64_t>[]> near_shapes;
  /// Asks for cell(q)'s entries ahead of a lookup: the tables (tens of megabytes on a robot
  /// with decomposed links) are read at random cells, and each lookup would miss the cache.
  void prefetch(const double* q) const {
    const long c = cell(q, false);
    if (c < 0) return;
    __builtin_prefetch(&bounds[static_cast<std::size_t>(c)]);
    if (near_shapes) __builtin_prefetch(&near_shapes[static_cast<std::size_t>(c)]);
  }
  // Once every cell is measured (measure_self_tables): per level k = 1, 2, ... (minima[k - 1]),
  // the smallest lower bound over each aligned square of 2^k cells per keying value, and the
  // level's size per value. Read only when `summarized`.
  std::vector<std::vector<float>> minima;
  std::vector<std::array<int, kMaxGridValues>> level_size;
  std::atomic<bool> summarized{false};
  std::once_flag summary_once;
  /// Builds minima and sets summarized (every cell measured).
  void summarize();
  /// Walks the cells that the motion q0 + t dq crosses for t in [t0, t1], in order, calling
  /// visit(cell) on each; false when visit returns false, the motion leaves the grid (a
  /// bounded value) or crosses more than max_cells cells, or a value without range moves. With
  /// `reached`, a walk as far as it goes: up to where a value leaves the grid, or max_cells
  /// cells; *reached is then where it stopped (t1 when it went through, else the start of the
  /// cell visit refused or did not reach). Defined in self_block_tables.cpp (its only user).
  template <class Visit>
  bool walk(const double* q0, const double* dq, double t0, double t1, int max_cells,
            double* reached, Visit visit) const;
  /// The smallest lower bound over the cells [lo_d, hi_d] (per keying value), at most that of
  /// every one of them: from the coarsest level holding them in two squares per value.
  float box_lower(const int* lo, const int* hi) const;
};

// The bits of a self block's near-shape masks: bit i for link a's i-th shape, bit shapes_a + j
// for link b's j-th (at most 64 together).
struct CollisionChecker::NearShapeBits {
  int first_a = 0, first_b = 0, shapes_a = 0;  // the links' first robot shapes, a's count
  /// The bits of pair p's two shapes.
  std::uint64_t of(const SelfPair& p) const {
    return (std::uint64_t{1} << (p.a - first_a)) | (std::uint64_t{1} << (shapes_a + p.b - first_b));
  }
  /// True when both of p's shapes are in `mask`.
  bool both(std::uint64_t mask, const SelfPair& p) const {
    const std::uint64_t bits = of(p);
    return (mask & bits) == bits;
  }
};

// The tables of one model at one padding revision, keyed by link pair, shared by its
// checkers through a registry (self_block_tables.cpp).
struct CollisionChecker::ModelSelfTables {
  std::shared_ptr<const RobotModel> model;
  int padding_revision = 0;
  std::atomic<bool> any_measured{false};  // some cell of `tables` is measured
  std::mutex mutex;                       // guards tables and cells
  std::map<std::pair<int, int>, std::unique_ptr<SelfTable>> tables;
  std::size_t cells = 0;
  // Self pairs' warm-start grids by (link a, shape a, link b, shape b): they depend on the
  // model's shapes and kinematics only, so the checkers of one model (every scene of a
  // benchmark) share them. Guarded by `mutex` while built; read-only after.
  std::map<std::array<int, 4>, std::unique_ptr<WarmStartGrid>> warm_grids;
  // Rigid bodies' hulls by their root link (CollisionChecker::body_hull). Guarded by `mutex`.
  std::map<int, std::shared_ptr<const Shape>> body_hulls;
  // Per joint and robot shape, the lever arm (CollisionChecker::joint_arms), once built.
  bool joint_arms_built = false;
  Eigen::MatrixXd joint_arms;
  // The robot shapes' covering and inner spheres (build_covering_spheres), once built.
  bool spheres_built = false;
  std::vector<Eigen::Vector4d> cover, inner;
  std::vector<int> cover_begin;
};

// The tables of one checker's self blocks, from the model's shared set.
struct CollisionChecker::SelfTables {
  std::shared_ptr<ModelSelfTables> model;  // found at construction
  std::once_flag built;
  std::vector<SelfTable*> per_block;  // per self block: its table, or nullptr
};

// Lever arms (m per unit of a configuration value; 1 for prismatic values, which move points by
// |dq|), built by build_motion_levers under `built`.
struct CollisionChecker::MotionLevers {
  std::once_flag built;
  // motion_bound: per value, the largest lever arm over the shapes it moves.
  Eigen::VectorXd lever;
  // safe_advance: per robot shape / per self pair, the motion per unit of each value.
  Eigen::MatrixXd shape_levers;      // shapes x values
  Eigen::MatrixXd self_pair_levers;  // self pairs x values
  // check_motion: per shape group / self block, the largest of its members' levers per value
  // (their dot product with |dq| bounds every member's).
  Eigen::MatrixXd group_levers;  // groups x values
  // Per self block: its links are moved relative to each other by more than two values (its
  // table, if any, sweeps a link; check_motion splits it into lines, see test_block_lines).
  std::vector<char> many_drivers;
  Eigen::MatrixXd cluster_levers;     // self clusters x values: the largest of their blocks'
  Eigen::MatrixXd self_block_levers;  // self blocks x values
  // check_motion's directional rates: per model link, the movable joints above it from the
  // root down, and per joint and shape the lever per unit of the joint's own value.
  std::vector<std::vector<int>> link_chains;
  const Eigen::MatrixXd* joint_arms = nullptr;  // joints x shapes: the model's shared ones
  // check_motion's speed bounds (chain_speed.hpp) for bounding volumes: per joint, the largest
  // lever of the shapes of a shape group / of a link ball's link (joints x groups, joints x
  // link balls), and per group the model link carrying all its shapes (-1: several links).
  Eigen::MatrixXd group_arms, link_ball_arms;
  std::vector<int> group_link;
};

// Bounds on the signed distance of A and B from their supporting planes normal to the unit
// vector n (from A towards B): every point of A is at most n.a_max along n, every point of
// B at least n.b_min, so distance >= n.(b_min - a_max) (and depth <= -that when overlapping:
// the difference A - B reaches no further than that along -n). The two support points are
// points of the shapes, so their distance bounds the signed distance from above.
inline void slab_bounds(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                        const Eigen::Isometry3d& pose_b, const Eigen::Vector3d& n, double* lower,
                        double* upper) {
  const Eigen::Vector3d a_max = pose_a * a.support(pose_a.linear().transpose() * n);
  const Eigen::Vector3d b_min = pose_b * b.support(-(pose_b.linear().transpose() * n));
  *lower = n.dot(b_min - a_max);
  *upper = (b_min - a_max).norm();
}

}  // namespace hullcheck
