// CollisionChecker::check_motion: a proof that a straight joint-space motion is collision-free
// at every configuration, by interval bisection with inflated tests, or its first contact.
//
// The bound. Along q(t) = q0 + t dq, t in [0, 1], a point of robot shape s moves at most
//   rate_s = sum_v |dq_v| lever_{s,v} (+ the prismatic excess)
// per unit of t (motion_bounds.cpp), and the shapes of a self pair move at most the pair's rate
// relative to each other (joints above both links move them together). For an interval with
// centre m and half-width h, every configuration in it places each shape within h rate of where
// it is at q(m), so a signed distance d(m) > h rate + min_clearance (the margin) proves the
// pair keeps clearance > min_clearance over the whole interval. A bounding volume at q(m) (a
// group's or link's ball, a decomposed mesh's hull) contains its members there, so the same
// test on it, with the largest of its members' rates, proves all of them at once.
// Within an interval an item's rate is the smaller of that and a bound from the configuration
// at its middle (rate_of, chain_speed.hpp): the speed its points have at q(m) (the joints'
// motions partly cancel, and the levers hold for every configuration) plus h times a bound on
// how fast that speed can change. Measured (bench_vamp, MBM): on average 0.5 (Panda) and 0.7
// (UR5) of the levers' rate where exact tests are made.
//
// The search. Intervals are examined depth first, left half first, each with the items (blocks
// of pairs or single pairs) that no enclosing interval decided: so when an interval is taken
// from the stack, [0, its start] is proven free. An item is decided when its test passes
// (certified) or when its signed distance at q(m) is at most min_clearance (a contact: then
// only the left half is searched for an earlier one, everything right of m dropped). Items
// within their margin are passed on to the parts of the interval outside the window their
// distance proves around m. An interval stops the search when an item still undecided in it
// moves less than `resolution` within it and its proven clearance at q(m) is within
// resolution / 100 of min_clearance. Above that clearance the windows are at least
// resolution / 100 / rate wide, so the search below the resolution takes a bounded number of
// further intervals; the work is bounded by max_states.
//
// The yes/no mode (!locate_contact, a planner's checkMotion(s1, s2)) examines the end state
// first, then the whole motion as kPoseBlockLanes sampled intervals tiling [0, 1] in one SIMD
// block (sweep_environment, sweep_self: balls, covering spheres and self tables with each
// interval's margins); the search then runs level by level on the runs of intervals left, with
// the environment or self items only when only those are left there.
//
// Contents (in order):
//   check_motion           validates input, runs the search
//   MotionSearch::run      the root items and intervals (after the end state and the sweep, in
//                          the yes/no mode), then the search: depth first, or level order
//   MotionSearch::probe_levels  level order: collision probes a block of states at a time
//   MotionSearch::examine  one interval: forward kinematics and every item's test
//   MotionSearch::test_*   one test per item kind; an item its test cannot decide expands:
//                          a self cluster (two rigid bodies' hulls) into its self blocks, a
//                          self block (its links' hulls) into its pairs or, when more than two
//                          values move its links, into lines (one shape against the other
//                          link's hull) and those into pairs; a shape group (against every
//                          obstacle, kept whole while the interval is coarse) into its
//                          environment blocks, and those into pairs
#include <algorithm>
#include <cmath>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <string>

#include "chain_speed.hpp"
#include "collision_checker_internals.hpp"
#include "sphere_box_rows.hpp"

namespace hullcheck {

namespace {

// See MotionSearch::keep.
constexpr double kSettledFraction = 0.01;
// Cells of a self block's distance table that one walk from an interval's middle visits at
// most. 64 left long coarse intervals unwalked; 256 and 4096 decided the same on the MBM robots
// (the summary levels now answer most long intervals first).
constexpr int kMaxTableCells = 4096;
// Level order: when the first level's examination took at least kProbeAfterQueries exact
// queries, the midpoints of levels 2 .. kProbeLevels are probed (probe_levels) before the
// search goes on. A probe costs about one is_valid per state (less in blocks); the search's
// tests with margins at the following levels cost about as many exact queries per state as the
// first level's and are wasted when a later level finds a contact. Measured (bench_vamp, MBM,
// certified RRTConnect: about 70% of the motions collide): UR5 7.7 -> 7.2 ms median, the Panda
// (fewer queries per state; probing every motion cost it 8%) unchanged.
constexpr int kProbeLevels = 4;
constexpr int kProbeAfterQueries = 8;
// A line (one shape against the other link's hull, test_piece_line) is kept whole while its
// hull distance proves at least this fraction of the interval's half-width; below, its pairs
// are tested. Measured (bench_vamp, UR5, 10 problems per family): 0.05-0.1 best with and
// without the self tables; keeping every line on every block made depth-first motions without
// tables 2.6x as many states (a concave link's hull closer than any of its pieces).
constexpr double kLineWindow = 0.1;

}  // namespace

struct CollisionChecker::MotionSearch {
  // kSelfPieceRow / kSelfPieceColumn: one shape of a self block's link against the other
  // link's bounding hull (index: the shape's first pair in the block; see test_piece_line).
  enum Kind {
    kEnvironmentBlock,
    kSelfBlock,
    kEnvironmentPair,
    kSelfPair,
    kSelfCluster,
    kSelfPieceRow,
    kSelfPieceColumn,
    kEnvironmentGroup
  };
  // kOpen: a bounding hull decided nothing; its block's pieces are tested (hull_outcome).
  enum class Outcome { kCertified, kPending, kContact, kOpen };
  using Item = Scratch::MotionItem;
  using Interval = Scratch::MotionInterval;

  const CollisionChecker& c;
  Scratch& s;
  const MotionCheckOptions& options;
  const MotionLevers& levers;
  const Eigen::Ref<const Eigen::VectorXd>& q0;
  const Eigen::VectorXd& abs_dq;
  const Eigen::VectorXd& dq;
  double extra;  // prismatic excess per unit t: added to every rate (twice for self pairs)
  MotionCheckResult result;

  // The interval being examined.
  double centre = 0.0;
  double half = 0.0;
  double contact_rate = 0.0;  // rate of the item found in contact
  bool at_floor = false;      // an undecided item moves less than `resolution` in it

  double margin(double rate) const { return half * rate + options.min_clearance; }

  MotionCheckResult run();
  /// Appends the root items: per shape group against every obstacle (`environment`), the self
  /// blocks and clusters (`self`); with `lanes` (a run of the sweep's), only those the sweep did
  /// not prove in every one of them (s.sweep_group_lanes, s.sweep_block_lanes).
  void add_items(bool environment, bool self, std::uint8_t lanes = 0);
  MotionCheckResult run_depth_first();  // locate_contact
  MotionCheckResult run_level_order();  // !locate_contact
  /// The first of the midpoints of levels [first, last] (level k: 2^(k-1) of them), in level
  /// order, where the robot collides (is_valid_batch's verdicts, a block at a time); -1 when
  /// none does.
  double probe_levels(int first, int last);
  MotionCheckResult stop(MotionVerdict verdict, double last_free, double contact) {
    result.verdict = verdict;
    result.last_free = last_free;
    result.contact = contact;
    return result;
  }
  /// Tests the items [begin, end) at the interval's centre m, appending the undecided ones
  /// (then, after a contact, the contact's and all untested ones) to *out.
  Outcome examine(double m, const std::vector<Item>& in, int begin, int end);
  Outcome test(const Item& item);
  Outcome test_environment_block(const Item& item);
  /// A shape group against every obstacle (its environment blocks) while the interval is too
  /// coarse to tell them apart: certified, kept whole (probed for contact), or opened into its
  /// blocks. One item per group instead of one per group and obstacle at the coarse levels,
  /// where most are kept (the UR5: 126 blocks tested per motion at the first level). Measured
  /// (bench_vamp, 30 Panda / 10 UR5 problems per family, three alternations, process user
  /// time): Panda 3.48 -> 3.32 s, UR5 9.20 -> 8.97 s, the same states and exact queries.
  Outcome test_environment_group(const Item& item);
  Outcome test_self_block(const Item& item);
  /// The pairs of a self block whose link hulls come within min_clearance: per shape of the
  /// link with fewer, that shape against the other link's hull, each an item (test_piece_line).
  Outcome test_block_lines(const SelfBlock& block, double rate);
  /// The pairs of a self block whose shapes are both among `near` (its table's near shapes
  /// over the interval, self_block_segment_near), each an item; the others are certified.
  Outcome test_near_pairs(const SelfBlock& block, std::uint64_t near);
  /// One shape of a self block's link against the other link's hull (which holds all of its
  /// shapes): certified, kept whole, or opened into its pairs when within min_clearance.
  Outcome test_piece_line(const Item& item);
  /// The self blocks of a cluster: its bodies' hulls first, then each block as an item.
  Outcome test_self_cluster(const Item& item);
  double self_block_rate(int block) const {
    return levers.self_block_levers.row(block).dot(abs_dq) + 2.0 * extra;
  }
  double self_pair_rate(int pair) const {
    return levers.self_pair_levers.row(pair).dot(abs_dq) + 2.0 * extra;
  }
  /// The number of robot shapes of model link `link`.
  int link_shapes(int link) const { return c.link_shape_count(link); }
  /// Tests item_at(0 .. count), each an item of its own; after a contact the remaining ones are
  /// appended untested. kCertified otherwise: the undecided ones were kept.
  template <class ItemAt>
  Outcome test_each(int count, ItemAt item_at) {
    for (int i = 0; i < count; ++i) {
      if (test(item_at(i)) == Outcome::kContact) {
        for (int k = i + 1; k < count; ++k) out->push_back(item_at(k));
        return Outcome::kContact;
      }
    }
    return Outcome::kCertified;
  }
  /// Forward kinematics and the shapes placed at q(t).
  void place_at(double t) {
    ++result.states;
    s.motion_q = q0 + t * dq;
    c.model_->compute_link_poses_unchecked(s.motion_q.data(), s.link_poses.data());
    c.place(s.link_poses, s);
    s.q = s.motion_q.data();  // self pairs' warm-start grids, self blocks' tables
  }
  /// A block on an interval too coarse to decide it: kept whole, tested for contact only.
  Outcome probe_block(const Item& item, double gap, double rate);
  /// What a block's bounding-hull query `r` (cutoff: the block's margin) decides: kCertified,
  /// kPending (kept whole), or kOpen (test the pieces). `lower` is another lower bound on the
  /// block's signed distance at q(m) (its table's; -inf when none). With `min_window`, kept
  /// whole only while the hull's distance proves at least that fraction of the half-width.
  Outcome hull_outcome(const Item& item, double rate, const SignedDistanceResult& r, double lower,
                       double min_window = 0.0);
  /// True when a bounding volume of size `radius` may move by more than its own size within
  /// the interval (its margin exceeds the radius), above the resolution: its pairs cannot be
  /// told apart yet.
  bool coarse(double inflated, double radius, double rate) const {
    return inflated > radius && half * rate > options.resolution;
  }
  Outcome test_pair(std::size_t pair, const Item& item);
  /// The item's rate within the interval (how far its shapes, or their bounding volumes, move
  /// per unit t, relative to each other for self items): the smaller of its levers' rate
  /// (item.rate) and the bound from their speeds at q(m) and how fast those can change
  /// (chain_speed.hpp). Measured (bench_vamp, Panda): ~0.5 of the levers' rate on average.
  double rate_of(const Item& item);
  /// rate_of for pair `pair` (index as pair_distance_below's) of levers' rate `lever_rate`; *a
  /// and *b receive its shapes' speed bounds relative to their links' common ancestor (the
  /// world for an environment pair, whose *b is zero), not usable when the levers' rate holds
  /// for want of them (a prismatic joint moves).
  double pair_rate(std::size_t pair, double lever_rate, ChainSpeed* a, ChainSpeed* b);
  /// The speed bound at q(m) of the points within `radius` of `ball_centre` on model link `link`,
  /// relative to the frame its chain's first `from` joints move, `arms` their lever arms per
  /// joint (chain_speed.hpp).
  ChainSpeed link_speed(int link, std::size_t from, const double* arms,
                        const Eigen::Vector3d& ball_centre, double radius);
  /// Robot shape `shape`'s (its ball's).
  ChainSpeed shape_speed(int shape, std::size_t from);
  /// The distance between a point of each of the pair's shapes at q(m): >= the signed distance.
  double pair_upper_bound(std::size_t pair) const;
  /// A pair within its margin (at `rate`), apart at q(m) along the unit `normal` (from its robot
  /// shape, or its first shape, towards the other): certified, or kept, by how fast its shapes
  /// can approach along that direction (directional_rate, and their speed bounds `a`, `b` from
  /// pair_rate when usable); kPending when nothing is gained.
  Outcome test_direction(std::size_t pair, const Item& item, const Eigen::Vector3d& normal,
                         double lower, double rate, const ChainSpeed& a, const ChainSpeed& b);
  /// A bound on how fast, per unit t within the interval, the gap between shapes a and b (b < 0:
  /// an obstacle) along the unit direction n can shrink, n being fixed in the frame of their
  /// links' deepest common ancestor (the world for an obstacle). See the file comment.
  double directional_rate(int a, int b, const Eigen::Vector3d& n) const;
  /// How many joints the chains of model links a and b share from the root: those move the
  /// two together, rigidly.
  std::size_t common_joints(int link_a, int link_b) const {
    const std::vector<int>& chain_a = levers.link_chains[static_cast<std::size_t>(link_a)];
    const std::vector<int>& chain_b = levers.link_chains[static_cast<std::size_t>(link_b)];
    std::size_t common = 0;
    while (common < chain_a.size() && common < chain_b.size() &&
           chain_a[common] == chain_b[common]) {
      ++common;
    }
    return common;
  }
  /// Self block `slot`'s warm start for its hull query, from its previous query in this motion
  /// (cold on its first use in this motion). Measured: it saves a tenth on the UR5's motions;
  /// warm starting pairs the same way cost the Panda's a quarter more (starts from a distant
  /// interval's answer are worse than the ball centres' or the grid's).
  WarmStart& warm_start(std::size_t slot);
  /// The pairs [begin, end) of a block (pair indices as pair_distance_below's), each tested as
  /// an item of its own; after a contact the remaining ones are appended untested.
  Outcome test_block_pairs(int kind, int begin, int end);
  /// The outcome of an exact query with cutoff margin(rate).
  Outcome exact_outcome(const SignedDistanceResult& r, double rate);
  std::vector<Item>* out = nullptr;  // where examine() writes the items left undecided

  // The interval's items left undecided are all proven over [m - window_left, m + window_right]
  // (the smallest of their own windows, from a lower bound on their distance at q(m), or from
  // a self block's table cells).
  double window_left = 0.0, window_right = 0.0;

  /// Passes `item` on to the interval's parts; `lower` bounds its signed distance at q(m), and
  /// the item's clearance shrinks at most at `window_rate` (>= its rate by default) within the
  /// interval.
  void keep(const Item& item, double lower) { keep(item, lower, item.rate); }
  void keep(const Item& item, double lower, double window_rate) {
    out->push_back(item);
    const double reach = lower - options.min_clearance;  // proven clearance left, m
    // Below the resolution an item stops the search only when its proven clearance at q(m) is
    // within a hundredth of the resolution: a pair further away is proven over windows of at
    // least that size around each middle, so a few more intervals decide it (a waypoint a few
    // micrometres from contact is reached, not called "maybe").
    at_floor = at_floor || (half * item.rate <= options.resolution &&
                            !(reach > kSettledFraction * options.resolution));
    const double w = !(reach > 0.0)      ? 0.0
                     : window_rate > 0.0 ? reach / window_rate
                                         : std::numeric_limits<double>::infinity();
    window_left = std::min(window_left, w);
    window_right = std::min(window_right, w);
  }
  /// Passes `item` on, proven over [m - left, m + right].
  void keep_window(const Item& item, double left, double right) {
    out->push_back(item);
    window_left = std::min(window_left, left);
    window_right = std::min(window_right, right);
  }
};

void validate(const MotionCheckOptions& options, const std::string& who) {
  if (!(options.min_clearance >= 0.0) || !std::isfinite(options.min_clearance) ||
      !(options.resolution > 0.0) || !std::isfinite(options.resolution) || options.max_states < 1) {
    throw InputError(who +
                     ": min_clearance must be finite and >= 0, resolution finite and > 0, "
                     "max_states >= 1");
  }
}

MotionCheckResult CollisionChecker::check_motion(const Eigen::Ref<const Eigen::VectorXd>& q0,
                                                 const Eigen::Ref<const Eigen::VectorXd>& q1,
                                                 const MotionCheckOptions& options) const {
  model_->check_configuration(q0);
  model_->check_configuration(q1);
  validate(options, "CollisionChecker::check_motion");
  require_current_padding();
  Scratch& s = scratch();
  // Per-thread scratch: allocates on first use only.
  if (s.motion_dq.size() != q0.size()) s.motion_dq.resize(q0.size());
  if (s.abs_dq.size() != q0.size()) s.abs_dq.resize(q0.size());
  ++s.motion_stamp;  // the warm starts of earlier motions are not used
  // Warm starts per self block, then per self cluster.
  const std::size_t warm_slots = self_blocks_.size() + self_clusters_.size();
  if (s.motion_warm.size() < warm_slots) s.motion_warm.resize(warm_slots);
  if (s.motion_back.size() != q0.size()) s.motion_back.resize(q0.size());
  s.motion_dq = q1 - q0;
  s.motion_back = -s.motion_dq;
  s.abs_dq = s.motion_dq.cwiseAbs();
  const double extra = prismatic_excess_motion(q0, q1);
  MotionSearch search{*this, s, options, motion_levers(), q0, s.abs_dq, s.motion_dq, extra, {}};
  return search.run();
}

MotionCheckResult CollisionChecker::MotionSearch::run() {
  // The root interval [0, 1] holds every block (none: nothing to check).
  s.motion_items.clear();
  s.motion_intervals.clear();
  if (!options.locate_contact && options.end_first) {
    // The motion's end first, as OMPL's discrete validator does: a planner's new state collides
    // more often than any other of the motion, and is_valid's verdict (a collision there is a
    // contact: signed distance <= 0 <= min_clearance) is cheaper than the first level's tests
    // with margins. Measured (bench_vamp, 30 Panda / 10 UR5 problems per family, two paired
    // runs): Panda 1.109 / 1.117 -> 0.985 / 1.077 ms, UR5 3.76 / 3.73 -> 3.45 / 3.70 ms.
    place_at(1.0);
    if (!c.placed_is_valid(s)) return stop(MotionVerdict::kContact, 0.0, 1.0);
  }
  // Yes/no mode: the environment and the self blocks over the whole motion at once, a block of
  // sampled intervals (motion_sweep.cpp); the search then takes the runs of intervals left
  // (their first level), with only the items that some of their intervals left undecided.
  // Measured (bench_vamp, 30 Panda / 10 UR5 problems per family, three alternations, process
  // user time, the same motions and verdicts): Panda 3.25 -> 2.80 s, UR5 8.21 -> 7.98 s.
  if (!options.locate_contact && result.states + kPoseBlockLanes <= options.max_states) {
    const double width = 1.0 / kPoseBlockLanes;  // lane k: [k, k + 1] * width
    std::uint8_t colliding = 0;
    const std::uint8_t environment_clear =
        c.sweep_environment(q0, dq, abs_dq, extra, options.min_clearance, &colliding, s);
    result.states += kPoseBlockLanes;
    for (int k = 0; k < kPoseBlockLanes; ++k) {
      if (colliding & (1u << k)) return stop(MotionVerdict::kContact, 0.0, (k + 0.5) * width);
    }
    const std::uint8_t self_clear = c.sweep_self(q0, dq, abs_dq, extra, options.min_clearance, s);
    const std::uint8_t clear = environment_clear & self_clear;
    for (int k = 0; k < kPoseBlockLanes;) {
      if ((clear & (1u << k)) != 0) {
        ++k;
        continue;
      }
      int end = k;  // the run of lanes [k, end) not proven
      std::uint8_t run_lanes = 0;
      while (end < kPoseBlockLanes && (clear & (1u << end)) == 0) {
        run_lanes |= static_cast<std::uint8_t>(1u << end++);
      }
      const auto items_begin = static_cast<int>(s.motion_items.size());
      add_items((environment_clear & run_lanes) != run_lanes, (self_clear & run_lanes) != run_lanes,
                run_lanes);
      s.motion_intervals.push_back(
          {k * width, end * width, items_begin, static_cast<int>(s.motion_items.size())});
      k = end;
    }
    return run_level_order();
  }
  add_items(true, true);
  if (!s.motion_items.empty()) {
    s.motion_intervals.push_back({0.0, 1.0, 0, static_cast<int>(s.motion_items.size())});
  }
  return options.locate_contact ? run_depth_first() : run_level_order();
}

void CollisionChecker::MotionSearch::add_items(bool environment, bool self, std::uint8_t lanes) {
  // A group or block the sweep proved over each of the run's lanes is proven over the run.
  const auto proven = [&](const std::vector<std::uint8_t>& by_sweep, std::size_t k) {
    return lanes != 0 && (by_sweep[k] & lanes) == lanes;
  };
  // Per shape group, its blocks against every obstacle as one item (test_environment_group).
  for (std::size_t g = 0; g < c.groups_.size() && environment; ++g) {
    if (c.group_block_begin_[g] == c.group_block_begin_[g + 1]) continue;  // no obstacle checked
    if (proven(s.sweep_group_lanes, g)) continue;
    s.motion_items.push_back(
        {kEnvironmentGroup, static_cast<int>(g),
         levers.group_levers.row(static_cast<Eigen::Index>(g)).dot(abs_dq) + extra});
  }
  if (!self) return;
  for (std::size_t k = 0; k < c.self_blocks_.size(); ++k) {
    if (c.cluster_of_block_[k] >= 0 || proven(s.sweep_block_lanes, k)) continue;
    s.motion_items.push_back(
        {kSelfBlock, static_cast<int>(k), self_block_rate(static_cast<int>(k))});
  }
  // A cluster's blocks one by one when any has a table (cheaper than the hulls' query).
  const std::vector<SelfTable*>* tables = c.self_block_tables();
  for (std::size_t k = 0; k < c.self_clusters_.size(); ++k) {
    const SelfCluster& cluster = c.self_clusters_[k];
    const auto first = c.cluster_blocks_.begin() + cluster.begin;
    const bool tabled =
        tables != nullptr && std::any_of(first, first + (cluster.end - cluster.begin), [&](int b) {
          return (*tables)[static_cast<std::size_t>(b)] != nullptr;
        });
    if (std::all_of(first, first + (cluster.end - cluster.begin), [&](int b) {
          return proven(s.sweep_block_lanes, static_cast<std::size_t>(b));
        })) {
      continue;
    }
    if (!tabled) {
      s.motion_items.push_back(
          {kSelfCluster, static_cast<int>(k),
           levers.cluster_levers.row(static_cast<Eigen::Index>(k)).dot(abs_dq) + 2.0 * extra});
      continue;
    }
    for (int i = cluster.begin; i < cluster.end; ++i) {
      const int block = c.cluster_blocks_[static_cast<std::size_t>(i)];
      if (proven(s.sweep_block_lanes, static_cast<std::size_t>(block))) continue;
      s.motion_items.push_back({kSelfBlock, block, self_block_rate(block)});
    }
  }
}

MotionCheckResult CollisionChecker::MotionSearch::run_depth_first() {
  // Depth first, left half first: when an interval is taken, [0, its start] is proven free.
  double proven_until = 0.0;  // [0, proven_until] is free
  double contact = -1.0;      // the earliest contact found, if any
  out = &s.motion_items;
  while (!s.motion_intervals.empty()) {
    const Interval interval = s.motion_intervals.back();
    s.motion_intervals.pop_back();
    // Segments past this interval's belong to finished intervals.
    s.motion_items.resize(static_cast<std::size_t>(interval.items_end));
    if (result.states >= options.max_states) {
      return stop(MotionVerdict::kStateBudget, interval.begin, interval.begin);
    }
    const double m = 0.5 * (interval.begin + interval.end);
    half = 0.5 * (interval.end - interval.begin);
    const auto kept = static_cast<int>(s.motion_items.size());
    const Outcome outcome = examine(m, s.motion_items, interval.items_begin, interval.items_end);
    const auto kept_end = static_cast<int>(s.motion_items.size());
    if (outcome == Outcome::kContact) {
      contact = m;
      if (half * contact_rate <= options.resolution) {
        return stop(MotionVerdict::kContact, interval.begin, m);
      }
      s.motion_intervals.clear();  // nothing right of the contact matters
      s.motion_intervals.push_back({interval.begin, m, kept, kept_end});
      continue;
    }
    if (at_floor) {
      return stop(contact >= 0.0 ? MotionVerdict::kContact : MotionVerdict::kNearContact,
                  interval.begin, m);
    }
    if (kept_end == kept) {  // every item decided over the whole interval
      proven_until = interval.end;
      continue;
    }
    // The parts outside [m - left, m + right], the right one first on the stack: the left one
    // is examined first.
    const double left = std::min(window_left, half), right = std::min(window_right, half);
    if (left >= half) proven_until = std::min(m + right, interval.end);
    if (m + right < interval.end) {
      s.motion_intervals.push_back({m + right, interval.end, kept, kept_end});
    }
    if (m - left > interval.begin) {
      s.motion_intervals.push_back({interval.begin, m - left, kept, kept_end});
    }
  }
  if (contact >= 0.0) {  // the search left of the contact ended proving everything before it
    return stop(MotionVerdict::kContact, std::min(proven_until, contact), contact);
  }
  return stop(MotionVerdict::kFree, 1.0, 1.0);
}

MotionCheckResult CollisionChecker::MotionSearch::run_level_order() {
  // Level by level (after the end state, run()), each from left to right (the order of OMPL's
  // discrete validator): a contact anywhere is found at the coarsest level that holds it. The items
  // of the next level go to a second buffer; the two swap after each level.
  int level = 1;
  s.motion_items_next.clear();
  s.motion_intervals_next.clear();
  out = &s.motion_items_next;
  while (!s.motion_intervals.empty()) {
    for (const Interval& interval : s.motion_intervals) {
      if (result.states >= options.max_states) return stop(MotionVerdict::kStateBudget, 0.0, 0.0);
      const double m = 0.5 * (interval.begin + interval.end);
      half = 0.5 * (interval.end - interval.begin);
      const auto kept = static_cast<int>(out->size());
      const Outcome outcome = examine(m, s.motion_items, interval.items_begin, interval.items_end);
      const auto kept_end = static_cast<int>(out->size());
      if (outcome == Outcome::kContact) return stop(MotionVerdict::kContact, 0.0, m);
      if (at_floor) return stop(MotionVerdict::kNearContact, 0.0, m);
      if (kept_end == kept) continue;
      // [m - left, m + right] is proven.
      const double left = std::min(window_left, half), right = std::min(window_right, half);
      if (m - left > interval.begin) {
        s.motion_intervals_next.push_back({interval.begin, m - left, kept, kept_end});
      }
      if (m + right < interval.end) {
        s.motion_intervals_next.push_back({m + right, interval.end, kept, kept_end});
      }
    }
    s.motion_items.swap(s.motion_items_next);
    s.motion_intervals.swap(s.motion_intervals_next);
    s.motion_items_next.clear();
    s.motion_intervals_next.clear();
    if (level++ == 1 && !s.motion_intervals.empty() && result.exact_queries >= kProbeAfterQueries) {
      if (const double t = probe_levels(2, kProbeLevels); t >= 0.0) {
        return stop(MotionVerdict::kContact, 0.0, t);
      }
    }
  }
  return stop(MotionVerdict::kFree, 1.0, 1.0);
}

double CollisionChecker::MotionSearch::probe_levels(int first, int last) {
  // Most motions a planner asks about collide (about 70% of RRTConnect's on the MotionBench-
  // Maker robots), and the search's tests with margins at coarse levels are then wasted: a
  // colliding state found by is_valid's cheaper verdicts, a block of states at a time, ends
  // the check first. A collision there is a contact (signed distance <= 0 <= min_clearance).
  const int n = c.model_->variable_count();
  if (s.motion_probes.rows() != n) s.motion_probes.resize(n, kPoseBlockLanes);
  int filled = 0;
  double ts[kPoseBlockLanes];
  const auto run_block = [&]() {
    c.is_valid_block(s.motion_probes, 0, filled, s.probe_valid, s);
    result.states += filled;
    for (int k = 0; k < filled; ++k) {
      if (!s.probe_valid[k]) return ts[k];
    }
    filled = 0;
    return -1.0;
  };
  for (int level = first; level <= last; ++level) {
    const int count = 1 << (level - 1);
    for (int i = 0; i < count; ++i) {
      if (result.states + filled >= options.max_states) return -1.0;
      const double t = (2 * i + 1) / static_cast<double>(2 * count);
      ts[filled] = t;
      s.motion_probes.col(filled) = q0 + t * dq;
      if (++filled == kPoseBlockLanes) {
        if (const double hit = run_block(); hit >= 0.0) return hit;
      }
    }
  }
  return filled > 0 ? run_block() : -1.0;
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::examine(
    double m, const std::vector<Item>& in, int begin, int end) {
  at_floor = false;
  window_left = window_right = std::numeric_limits<double>::infinity();
  centre = m;
  place_at(m);
  for (int k = begin; k < end; ++k) {
    const Item item = in[static_cast<std::size_t>(k)];  // a copy: `in` may be *out, growing
    if (test(item) == Outcome::kContact) {
      for (int r = k + 1; r < end; ++r) out->push_back(in[static_cast<std::size_t>(r)]);
      return Outcome::kContact;
    }
  }
  return Outcome::kPending;  // the kept items, if any, are undecided
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test(const Item& item) {
  switch (item.kind) {
    case kEnvironmentBlock:
      return test_environment_block(item);
    case kSelfBlock:
      return test_self_block(item);
    case kEnvironmentPair:
      return test_pair(static_cast<std::size_t>(item.index), item);
    case kSelfCluster:
      return test_self_cluster(item);
    case kSelfPieceRow:
    case kSelfPieceColumn:
      return test_piece_line(item);
    case kEnvironmentGroup:
      return test_environment_group(item);
    default:
      return test_pair(c.environment_pairs_.size() + static_cast<std::size_t>(item.index), item);
  }
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_environment_block(
    const Item& item) {
  const EnvironmentBlock& block = c.blocks_[static_cast<std::size_t>(item.index)];
  const auto g = static_cast<std::size_t>(block.group);
  const ObstacleBox& box = c.boxes_[static_cast<std::size_t>(block.obstacle)];
  const double gap = c.box_gap(box, s.group_centers[g], s.group_radii[g]);
  if (gap > margin(item.rate)) return Outcome::kCertified;
  const double rate = rate_of(item);
  const double inflated = margin(rate);
  if (gap > inflated) return Outcome::kCertified;
  if (coarse(inflated, s.group_radii[g], rate)) return probe_block(item, gap, rate);
  const int bound = c.groups_[g].bound;
  if (bound >= 0 && block.end - block.begin > 1) {
    // A decomposed mesh: its hull (containing every piece) first.
    const Obstacle& o = c.scene_.obstacles[static_cast<std::size_t>(block.obstacle)];
    ++result.exact_queries;
    const SignedDistanceResult r = signed_distance_below(
        c.bounding_shape(bound), c.shape_pose(bound, s), o.shape, o.pose, inflated);
    if (const Outcome h = hull_outcome(item, rate, r, -std::numeric_limits<double>::infinity());
        h != Outcome::kOpen) {
      return h;
    }
  }
  return test_block_pairs(kEnvironmentPair, block.begin, block.end);
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_environment_group(
    const Item& item) {
  const auto g = static_cast<std::size_t>(item.index);
  const int first = c.group_block_begin_[g], last = c.group_block_begin_[g + 1];
  const double radius = s.group_radii[g];
  // The group ball's gaps to every obstacle's box at once (SIMD across the boxes), then the
  // smallest of its blocks' (the others are certified); the gaps kept for the contact test
  // below.
  detail::sphere_box_row_gaps(c.box_rows_.data(), detail::box_rows_padded(c.boxes_.size()),
                              s.group_centers[g].data(), radius, s.box_gaps.data());
  double lower = std::numeric_limits<double>::infinity();
  s.group_gaps.resize(static_cast<std::size_t>(last - first));
  for (int b = first; b < last; ++b) {
    const auto o = static_cast<std::size_t>(c.blocks_[static_cast<std::size_t>(b)].obstacle);
    s.group_gaps[static_cast<std::size_t>(b - first)] = s.box_gaps[o];
    lower = std::min(lower, s.box_gaps[o]);
  }
  if (lower > margin(item.rate)) return Outcome::kCertified;
  const double rate = rate_of(item);
  const double inflated = margin(rate);
  if (lower > inflated) return Outcome::kCertified;
  if (!coarse(inflated, radius, rate)) {
    // Fine enough to tell the obstacles apart: each block an item of its own (the ones the
    // group's ball certifies again at once).
    return test_each(last - first, [&](int i) {
      return Item{kEnvironmentBlock, first + i, item.rate};
    });
  }
  // Kept whole, tested for contact only: a box the group's ball reaches (a ball clear of an
  // obstacle's box holds no shape touching it).
  for (int b = first; b < last; ++b) {
    if (s.group_gaps[static_cast<std::size_t>(b - first)] <= 0.0 &&
        c.environment_block_collides(b, s)) {
      out->push_back(item);
      contact_rate = item.rate;
      return Outcome::kContact;
    }
  }
  keep(item, lower, rate);
  return Outcome::kPending;
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_self_block(
    const Item& item) {
  const SelfBlock& block = c.self_blocks_[static_cast<std::size_t>(item.index)];
  const LinkBall& ball_a = c.link_balls_[static_cast<std::size_t>(block.link_a)];
  const LinkBall& ball_b = c.link_balls_[static_cast<std::size_t>(block.link_b)];
  const double gap = (s.link_centers[static_cast<std::size_t>(block.link_a)] -
                      s.link_centers[static_cast<std::size_t>(block.link_b)])
                         .norm() -
                     ball_a.radius - ball_b.radius;
  if (gap > margin(item.rate)) return Outcome::kCertified;
  const double rate = rate_of(item);
  const double inflated = margin(rate);
  if (gap > inflated) return Outcome::kCertified;
  // The block's distance table: walked from q(m) both ways as far as its cells' lower bounds
  // stay above min_clearance. Both ends reached prove the block over the whole interval; half
  // the interval or more, over that window (kept with no exact test here). The cell of q(m)
  // bounds it there.
  double lower = -std::numeric_limits<double>::infinity(), upper = 0.0;
  // First the table's summary: the box of cells the interval spans, all apart.
  if (c.self_block_box_lower(item.index, q0.data(), dq.data(), centre - half, centre + half,
                             options.min_clearance)) {
    return Outcome::kCertified;
  }
  double right = 0.0, left = 0.0, unused = 0.0;
  const bool all_right =
      c.self_block_segment_lower(item.index, s.motion_q.data(), dq.data(), 0.0, half,
                                 kMaxTableCells, options.min_clearance, &unused, &right);
  if (right > 0.0 &&
      c.self_block_segment_lower(item.index, s.motion_q.data(), s.motion_back.data(), 0.0, half,
                                 kMaxTableCells, options.min_clearance, &unused, &left) &&
      all_right) {
    return Outcome::kCertified;
  }
  if (left + right >= half) {
    keep_window(item, left, right);
    return Outcome::kPending;
  }
  if (c.self_block_bounds(item.index, s.q, &lower, &upper)) {
    if (lower > inflated) return Outcome::kCertified;
    if (upper <= options.min_clearance) {
      out->push_back(item);
      contact_rate = item.rate;
      return Outcome::kContact;
    }
  }
  if (coarse(inflated, std::max(ball_a.radius, ball_b.radius), rate)) {
    return probe_block(item, std::max(gap, lower), rate);
  }
  // The table's near shapes over the interval: a pair with a shape not among them is apart by
  // more than kTableSlack (>= min_clearance) over all of it, certified; the others are items.
  std::uint64_t near = 0;
  if (options.min_clearance <= kTableSlack &&
      c.self_block_segment_near(item.index, q0.data(), dq.data(), centre - half, centre + half,
                                kMaxTableCells, &near)) {
    return test_near_pairs(block, near);
  }
  if (ball_a.bound >= 0 && ball_b.bound >= 0 && block.end - block.begin > 1) {
    // Links that are one shape or one decomposed mesh: their hulls first.
    ++result.exact_queries;
    const SignedDistanceResult r =
        signed_distance_below(c.bounding_shape(ball_a.bound), c.shape_pose(ball_a.bound, s),
                              c.bounding_shape(ball_b.bound), c.shape_pose(ball_b.bound, s),
                              inflated, warm_start(static_cast<std::size_t>(item.index)));
    if (const Outcome h = hull_outcome(item, rate, r, lower); h != Outcome::kOpen) return h;
  }
  // Lines only where more than two values move the block's links relative to each other (a
  // forearm against the wrist's last link: a table, if any, sweeps a link). Elsewhere the pairs
  // left are those near each other, which lines only split more finely (measured: UR5 without
  // tables 16.4 -> 17.2 ms with lines there too, 15.8 without).
  if (!levers.many_drivers[static_cast<std::size_t>(item.index)]) {
    return test_block_pairs(kSelfPair, block.begin, block.end);
  }
  return test_block_lines(block, item.rate);
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_near_pairs(
    const SelfBlock& block, std::uint64_t near) {
  const NearShapeBits bits = c.near_shape_bits(block);
  const auto is_near = [&](int p) {
    return bits.both(near, c.self_pairs_[static_cast<std::size_t>(p)]);
  };
  for (int p = block.begin; p < block.end; ++p) {
    if (!is_near(p) || test(Item{kSelfPair, p, self_pair_rate(p)}) != Outcome::kContact) {
      continue;
    }
    for (int k = p + 1; k < block.end; ++k) {
      if (is_near(k)) out->push_back(Item{kSelfPair, k, self_pair_rate(k)});
    }
    return Outcome::kContact;
  }
  return Outcome::kCertified;
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_block_lines(
    const SelfBlock& block, double rate) {
  const LinkBall& ball_a = c.link_balls_[static_cast<std::size_t>(block.link_a)];
  const LinkBall& ball_b = c.link_balls_[static_cast<std::size_t>(block.link_b)];
  const int n_a = link_shapes(ball_a.link), n_b = link_shapes(ball_b.link);
  // One shape against a hull that is only that shape's is the pair itself.
  if (n_a < 2 || n_b < 2 || ball_a.bound < 0 || ball_b.bound < 0) {
    return test_block_pairs(kSelfPair, block.begin, block.end);
  }
  // Lines over the link with fewer shapes: rows (a fixed) are consecutive pairs, columns (b
  // fixed) every n_b-th.
  const bool rows = n_a <= n_b;
  return test_each(rows ? n_a : n_b, [&](int i) {
    return Item{rows ? kSelfPieceRow : kSelfPieceColumn, block.begin + (rows ? i * n_b : i), rate};
  });
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_piece_line(
    const Item& item) {
  // The line's shape (the row's a, the column's b), the other link and its pairs.
  const SelfPair& first = c.self_pairs_[static_cast<std::size_t>(item.index)];
  const bool row = item.kind == kSelfPieceRow;
  const int shape = row ? first.a : first.b;
  const int other_link = c.shapes_[static_cast<std::size_t>(row ? first.b : first.a)].link;
  const LinkBall& other = c.link_balls_[static_cast<std::size_t>(
      c.link_ball_of_link_[static_cast<std::size_t>(other_link)])];
  // A row's pairs are consecutive, a column's n_b apart.
  const int stride = row ? 1 : link_shapes(c.shapes_[static_cast<std::size_t>(first.b)].link);
  const RobotShape& rs = c.shapes_[static_cast<std::size_t>(shape)];
  const double gap =
      (c.center(shape, s) - s.link_centers[static_cast<std::size_t>(
                                c.link_ball_of_link_[static_cast<std::size_t>(other_link)])])
          .norm() -
      rs.radius - other.radius;
  if (gap > margin(item.rate)) return Outcome::kCertified;
  const double rate = rate_of(item);
  const double inflated = margin(rate);
  if (gap > inflated) return Outcome::kCertified;
  ++result.exact_queries;
  const SignedDistanceResult r =
      signed_distance_below(c.shape_of(shape), c.shape_pose(shape, s),
                            c.bounding_shape(other.bound), c.shape_pose(other.bound, s), inflated);
  // Kept whole only while the hull's distance proves a window of at least kLineWindow of the
  // interval: a hull closer than the line's pairs (a concave link) would split the motion
  // where its pairs, on their own, would not.
  if (const Outcome h =
          hull_outcome(item, rate, r, -std::numeric_limits<double>::infinity(), kLineWindow);
      h != Outcome::kOpen) {
    return h;
  }
  return test_each(link_shapes(other_link), [&](int k) {
    const int p = item.index + k * stride;
    return Item{kSelfPair, p, self_pair_rate(p)};
  });
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_self_cluster(
    const Item& item) {
  const SelfCluster& cluster = c.self_clusters_[static_cast<std::size_t>(item.index)];
  const RigidBodyHull& a = c.bodies_[static_cast<std::size_t>(cluster.body_a)];
  const RigidBodyHull& b = c.bodies_[static_cast<std::size_t>(cluster.body_b)];
  const Eigen::Isometry3d& pose_a = (*s.link_poses_in)[static_cast<std::size_t>(a.root)];
  const Eigen::Isometry3d& pose_b = (*s.link_poses_in)[static_cast<std::size_t>(b.root)];
  const double inflated = margin(item.rate);
  const double gap = (pose_a * a.center - pose_b * b.center).norm() - a.radius - b.radius;
  if (gap > inflated) return Outcome::kCertified;
  if (coarse(inflated, std::max(a.radius, b.radius), item.rate)) {
    // Kept whole, tested for contact only: a contact in any of its blocks drops everything
    // right of m (and the cluster is searched left of it).
    for (int i = cluster.begin; i < cluster.end; ++i) {
      if (c.self_block_collides(c.cluster_blocks_[static_cast<std::size_t>(i)], s)) {
        out->push_back(item);
        contact_rate = item.rate;
        return Outcome::kContact;
      }
    }
    keep(item, gap);
    return Outcome::kPending;
  }
  // The bodies' hulls: apart by the margin (certified), or by less (kept whole, over the
  // window their distance proves), or closer than min_clearance: then each block is an item
  // of its own.
  ++result.exact_queries;
  const SignedDistanceResult r = signed_distance_below(
      *a.hull, pose_a, *b.hull, pose_b, inflated,
      warm_start(c.self_blocks_.size() + static_cast<std::size_t>(item.index)));
  if (const Outcome h = hull_outcome(item, item.rate, r, -std::numeric_limits<double>::infinity());
      h != Outcome::kOpen) {
    return h;
  }
  return test_each(cluster.end - cluster.begin, [&](int i) {
    const int block = c.cluster_blocks_[static_cast<std::size_t>(cluster.begin + i)];
    return Item{kSelfBlock, block, self_block_rate(block)};
  });
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::hull_outcome(
    const Item& item, double rate, const SignedDistanceResult& r, double lower, double min_window) {
  const double inflated = margin(rate);
  if (r.status == Status::kAboveCutoff && r.signed_distance >= inflated) {
    return Outcome::kCertified;
  }
  // Hulls apart (converged, above min_clearance): none of their pieces touch at q(m), and the
  // hull distance proves the whole block over a window, so the block stays one item (one query
  // per interval instead of one per piece pair). Above the resolution only: there the pieces,
  // possibly further apart than their hulls, decide.
  if (r.status == Status::kConverged && r.signed_distance > options.min_clearance &&
      r.signed_distance - options.min_clearance >= min_window * half * rate &&
      half * rate > options.resolution) {
    keep(item, std::max(r.signed_distance, lower), rate);
    return Outcome::kPending;
  }
  return Outcome::kOpen;
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::probe_block(
    const Item& item, double gap, double rate) {
  // Too coarse an interval to prove much of this block: only whether it collides at q(m)
  // (is_valid's tests), which drops everything right of m when it does.
  const bool collides = item.kind == kEnvironmentBlock ? c.environment_block_collides(item.index, s)
                                                       : c.self_block_collides(item.index, s);
  if (collides) {
    out->push_back(item);
    contact_rate = item.rate;
    return Outcome::kContact;
  }
  keep(item, gap, rate);
  return Outcome::kPending;
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_block_pairs(int kind,
                                                                                         int begin,
                                                                                         int end) {
  // The block itself is decided once its pairs are tested: its undecided pairs were kept as
  // items of their own.
  return test_each(end - begin, [&](int k) {
    const int i = begin + k;
    if (kind == kEnvironmentPair) {
      const int shape = c.environment_pairs_[static_cast<std::size_t>(i)].shape;
      return Item{kind, i, levers.shape_levers.row(shape).dot(abs_dq) + extra};
    }
    return Item{kind, i, self_pair_rate(i)};
  });
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_pair(
    std::size_t pair, const Item& item) {
  const double gap = c.pair_ball_gap(pair, s);
  if (gap > margin(item.rate)) return Outcome::kCertified;
  ChainSpeed speed_a, speed_b;
  const double rate = pair_rate(pair, item.rate, &speed_a, &speed_b);
  const double inflated = margin(rate);
  if (gap > inflated) return Outcome::kCertified;
  // Where even an upper bound on the distance (from a point of one shape to a point of the
  // other) is within the margin, no test can certify the pair over this interval, above the
  // resolution: only a contact at q(m) is looked for (a query as cheap as a boolean one on
  // shapes apart), and not even that when the balls are apart.
  const bool hopeless = pair_upper_bound(pair) <= inflated && half * rate > options.resolution;
  if (hopeless && gap > options.min_clearance) {
    keep(item, gap, rate);
    return Outcome::kPending;
  }
  ++result.exact_queries;
  const SignedDistanceResult r =
      c.pair_distance_below(pair, hopeless ? options.min_clearance : inflated, s);
  const Outcome outcome =
      hopeless
          ? (r.signed_distance <= options.min_clearance ? Outcome::kContact : Outcome::kPending)
          : exact_outcome(r, rate);
  if (outcome == Outcome::kPending && !hopeless && r.status == Status::kConverged &&
      r.signed_distance > options.min_clearance) {
    return test_direction(pair, item, r.normal, std::max(gap, r.signed_distance), rate, speed_a,
                          speed_b);
  }
  if (outcome == Outcome::kPending) {
    // A converged distance or a proven bound (kAboveCutoff); otherwise only the balls' gap.
    const bool proven = r.status == Status::kConverged || r.status == Status::kAboveCutoff;
    keep(item, proven ? std::max(gap, r.signed_distance) : gap, rate);
  } else if (outcome == Outcome::kContact) {
    contact_rate = item.rate;
    out->push_back(item);  // searched for earlier in the left half
  }
  return outcome;
}

double CollisionChecker::MotionSearch::rate_of(const Item& item) {
  if (extra != 0.0) return item.rate;  // a prismatic joint moves: the levers' rate
  const auto ball_speed = [&](int ball, std::size_t from) {
    const auto b = static_cast<std::size_t>(ball);
    return link_speed(c.link_balls_[b].link, from, levers.link_ball_arms.col(ball).data(),
                      s.link_centers[b], c.link_balls_[b].radius);
  };
  const auto link_of_ball = [&](int ball) {
    return c.link_balls_[static_cast<std::size_t>(ball)].link;
  };
  const auto sum = [](const ChainSpeed& a, const ChainSpeed& b) {
    return ChainSpeed{a.speed + b.speed, a.accel + b.accel, a.usable && b.usable};
  };
  ChainSpeed bound;
  switch (item.kind) {
    case kEnvironmentGroup:
    case kEnvironmentBlock: {
      const auto g = static_cast<std::size_t>(
          item.kind == kEnvironmentGroup ? item.index
                                         : c.blocks_[static_cast<std::size_t>(item.index)].group);
      if (levers.group_link[g] < 0) return item.rate;
      bound = link_speed(levers.group_link[g], 0,
                         levers.group_arms.col(static_cast<Eigen::Index>(g)).data(),
                         s.group_centers[g], s.group_radii[g]);
      break;
    }
    case kEnvironmentPair:
    case kSelfPair: {
      ChainSpeed a, b;
      return pair_rate(item.kind == kEnvironmentPair
                           ? static_cast<std::size_t>(item.index)
                           : c.environment_pairs_.size() + static_cast<std::size_t>(item.index),
                       item.rate, &a, &b);
    }
    case kSelfBlock: {
      const SelfBlock& block = c.self_blocks_[static_cast<std::size_t>(item.index)];
      const std::size_t common =
          common_joints(link_of_ball(block.link_a), link_of_ball(block.link_b));
      bound = sum(ball_speed(block.link_a, common), ball_speed(block.link_b, common));
      break;
    }
    case kSelfPieceRow:
    case kSelfPieceColumn: {
      // The line's shape and the other link's ball (see test_piece_line).
      const SelfPair& first = c.self_pairs_[static_cast<std::size_t>(item.index)];
      const bool row = item.kind == kSelfPieceRow;
      const int shape = row ? first.a : first.b;
      const int other_link = c.shapes_[static_cast<std::size_t>(row ? first.b : first.a)].link;
      const int other = c.link_ball_of_link_[static_cast<std::size_t>(other_link)];
      const std::size_t common =
          common_joints(c.shapes_[static_cast<std::size_t>(shape)].link, other_link);
      bound = sum(shape_speed(shape, common), ball_speed(other, common));
      break;
    }
    default:  // a self cluster: its bodies are several links each
      return item.rate;
  }
  if (!bound.usable) return item.rate;
  return std::min(item.rate, bound.speed + 0.5 * half * bound.accel);
}

double CollisionChecker::MotionSearch::pair_rate(std::size_t pair, double lever_rate, ChainSpeed* a,
                                                 ChainSpeed* b) {
  *b = ChainSpeed{};   // an obstacle stays
  if (extra != 0.0) {  // a prismatic joint moves: the levers' rate
    a->usable = false;
    return lever_rate;
  }
  const std::size_t n_env = c.environment_pairs_.size();
  if (pair < n_env) {
    *a = shape_speed(c.environment_pairs_[pair].shape, 0);
  } else {
    const SelfPair& p = c.self_pairs_[pair - n_env];
    const std::size_t common = common_joints(c.shapes_[static_cast<std::size_t>(p.a)].link,
                                             c.shapes_[static_cast<std::size_t>(p.b)].link);
    *a = shape_speed(p.a, common);
    *b = shape_speed(p.b, common);
  }
  if (!a->usable || !b->usable) return lever_rate;
  return std::min(lever_rate, a->speed + b->speed + 0.5 * half * (a->accel + b->accel));
}

ChainSpeed CollisionChecker::MotionSearch::link_speed(int link, std::size_t from,
                                                      const double* arms,
                                                      const Eigen::Vector3d& ball_centre,
                                                      double radius) {
  return chain_speed(*c.model_, *s.link_poses_in,
                     levers.link_chains[static_cast<std::size_t>(link)], from, dq, arms,
                     ball_centre, radius);
}

ChainSpeed CollisionChecker::MotionSearch::shape_speed(int shape, std::size_t from) {
  const RobotShape& rs = c.shapes_[static_cast<std::size_t>(shape)];
  return link_speed(rs.link, from, levers.joint_arms->col(shape).data(), c.center(shape, s),
                    rs.radius);
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::test_direction(
    std::size_t pair, const Item& item, const Eigen::Vector3d& normal, double lower,
    double pair_rate, const ChainSpeed& speed_a, const ChainSpeed& speed_b) {
  const std::size_t n_env = c.environment_pairs_.size();
  int a = 0, b = -1;
  double slab = 0.0, upper = 0.0;
  if (pair < n_env) {
    const EnvironmentPair& p = c.environment_pairs_[pair];
    const Obstacle& o = c.scene_.obstacles[static_cast<std::size_t>(p.obstacle)];
    a = p.shape;
    slab_bounds(c.shape_of(a), c.shape_pose(a, s), o.shape, o.pose, normal, &slab, &upper);
  } else {
    const SelfPair& p = c.self_pairs_[pair - n_env];
    a = p.a;
    b = p.b;
    slab_bounds(c.shape_of(a), c.shape_pose(a, s), c.shape_of(b), c.shape_pose(b, s), normal, &slab,
                &upper);
  }
  // The gap along the normal shrinks no faster than the shapes move, nor than their points'
  // components along it change: at q(m) by at most the two shapes' along(normal), the normal
  // being fixed in their common ancestor's frame (chain_speed.hpp), and within the interval by
  // at most h accel / 2 more on average over any part [m, m + tau] or [m - tau, m] of it.
  double rate = std::min(directional_rate(a, b, normal), pair_rate);
  if (speed_a.usable && speed_b.usable) {
    rate = std::min(rate, relative_along(speed_a, speed_b, normal) +
                              0.5 * half * (speed_a.accel + speed_b.accel));
  }
  if (slab - half * rate > options.min_clearance) return Outcome::kCertified;
  // Proven over the window either bound gives (the directional one holds within this interval).
  const double reach = lower - options.min_clearance;
  if (slab > options.min_clearance && rate * reach < pair_rate * (slab - options.min_clearance)) {
    keep(item, slab, rate);
  } else {
    keep(item, lower, pair_rate);
  }
  return Outcome::kPending;
}

double CollisionChecker::MotionSearch::directional_rate(int a, int b,
                                                        const Eigen::Vector3d& n) const {
  // Relative to the common ancestor's frame, a point x of a shape moves at
  //   v = sum_j qdot_j u_j x (x - o_j)   (revolute joints j between the ancestor and its link)
  // and n . (u_j x (x - o_j)) = (x - o_j) . (n x u_j), at most the lever arm times |n x u_j|.
  // Within the interval u_j turns (relative to that frame) by at most h times the summed
  // speeds of the revolute joints above j: |n x u_j(t)| <= |n x u_j(m)| + that angle (and <= 1).
  // A prismatic joint moves its points by qdot_j u_j: |n . u_j| bounded the same way.
  const std::vector<Eigen::Isometry3d>& poses = *s.link_poses_in;
  const auto chain_of = [&](int shape) -> const std::vector<int>& {
    return levers
        .link_chains[static_cast<std::size_t>(c.shapes_[static_cast<std::size_t>(shape)].link)];
  };
  const std::vector<int>& chain_a = chain_of(a);
  const std::vector<int>* chain_b = b >= 0 ? &chain_of(b) : nullptr;
  const std::size_t common = b >= 0 ? common_joints(c.shapes_[static_cast<std::size_t>(a)].link,
                                                    c.shapes_[static_cast<std::size_t>(b)].link)
                                    : 0;
  double rate = 0.0;
  const auto add = [&](const std::vector<int>& chain, int shape) {
    double turning = 0.0;  // summed speeds of the revolute joints passed, per unit t
    for (std::size_t i = common; i < chain.size(); ++i) {
      const Joint& joint = c.model_->joint(chain[i]);
      const double speed = std::abs(joint.driver_multiplier() * dq[joint.driver()]);
      const Eigen::Vector3d u =
          poses[static_cast<std::size_t>(joint.child_link)].linear() * joint.axis;
      const double tilt = half * turning;
      if (joint.type == JointType::kPrismatic) {
        rate += speed * std::min(1.0, std::abs(n.dot(u)) + tilt);
      } else {
        rate +=
            speed * (*levers.joint_arms)(chain[i], shape) * std::min(1.0, n.cross(u).norm() + tilt);
        turning += speed;
      }
    }
  };
  add(chain_a, a);
  if (chain_b != nullptr) add(*chain_b, b);
  return rate + (chain_b != nullptr ? 2.0 : 1.0) * extra;
}

WarmStart& CollisionChecker::MotionSearch::warm_start(std::size_t slot) {
  Scratch::MotionWarmStart& w = s.motion_warm[slot];
  if (w.motion != s.motion_stamp) {  // from another motion (or checker): start cold
    w.motion = s.motion_stamp;
    w.start = WarmStart{};
  }
  return w.start;
}

double CollisionChecker::MotionSearch::pair_upper_bound(std::size_t pair) const {
  const std::vector<Eigen::Isometry3d>& poses = *s.link_poses_in;
  const auto point = [&](int shape) {
    const RobotShape& rs = c.shapes_[static_cast<std::size_t>(shape)];
    return Eigen::Vector3d(poses[static_cast<std::size_t>(rs.link)] * rs.inside);
  };
  const std::size_t n_env = c.environment_pairs_.size();
  if (pair < n_env) {
    const EnvironmentPair& p = c.environment_pairs_[pair];
    return (point(p.shape) - c.obstacle_points_[static_cast<std::size_t>(p.obstacle)]).norm();
  }
  const SelfPair& p = c.self_pairs_[pair - n_env];
  return (point(p.a) - point(p.b)).norm();
}

CollisionChecker::MotionSearch::Outcome CollisionChecker::MotionSearch::exact_outcome(
    const SignedDistanceResult& r, double rate) {
  // A proven lower bound at or above the margin certifies; so does a converged distance (exact
  // to 1e-10 x the shapes' size, far below min_clearance's default). An answer that did not
  // converge certifies nothing: the pair is split further (or reported near contact).
  const double inflated = margin(rate);
  if (r.status == Status::kAboveCutoff) {
    return r.signed_distance >= inflated ? Outcome::kCertified : Outcome::kPending;
  }
  if (r.status == Status::kConverged && r.signed_distance > inflated) return Outcome::kCertified;
  return r.signed_distance <= options.min_clearance ? Outcome::kContact : Outcome::kPending;
}

}  // namespace hullcheck
