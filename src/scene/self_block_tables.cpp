// Distance tables of self blocks: for two links moved relative to each other by one or two
// revolute values (kMaxTableValues), a grid over those values holding, per cell C, bounds on
// the links' signed distance d(q) (the smallest over the block's shape pairs) at every q in C:
//
//   lower(C) = min over pairs p of  d_p(c) - reach_p,    upper(C) = min over pairs p of
//   d_p(c) + reach_p,   reach_p = sum_v lever_{p,v} w_v
//
// with c the cell's centre, w_v half the cell's width along keying value v and lever_{p,v}
// how far any point of one shape of p moves relative to the other per unit of v (the pair's
// lever arms, motion_bounds.cpp). Why: along the straight joint-space motion from c to q in C,
// pair p's signed distance changes by at most sum_v lever_{p,v} |q_v - c_v| <= reach_p (only
// the keying values move one link relative to the other; the other values move both rigidly).
// A value of a continuous joint is taken modulo one turn (the same pose). Links moved by three
// values get a table over two: one link is swept through a turn about the joint next to it
// (swept_links.cpp; the link whose sweep grows its hulls least), its shapes replaced by the
// sweeps, which contain it at every value of that joint; such a table's upper bounds are
// +infinity, and a pair whose sweep meets the other shape bounds lower by the balls' gap (no
// penetration depth measured: such a cell decides nothing anyway). Per pair the bounds
// use the pair's own levers: pieces near the joints that move them barely move, so a block of
// links always close at their joint (a decomposed upper arm over its base) is still proven
// apart by the pieces that matter.
//
// Measuring a cell: d_p(c) is a converged signed distance, or a proven bound of
// signed_distance_below (kAboveCutoff: only in lower), or the pair's ball gap when its query
// did neither (only in lower); lower is capped at kCap; the bounding hulls' distance minus the
// block's largest reach bounds every pair from below. Half-widths are enlarged by a millionth,
// so that a point on a cell's boundary (or a rounding error away from it) is inside. Both
// bounds are stored as floats rounded outwards, packed in one atomic word. Cells are measured
// by measure_self_tables (queries only read them: a cell not measured decides nothing), on
// whichever thread, always to the same value (it depends only on the cell), so racing
// measurements store the same word.
//
// Near shapes. A cell whose lower bound is kTableSlack or less decides nothing, and is_valid
// tests the block's pairs at q exactly. Most of a decomposed link's pieces are still far from
// the other link there: the cell keeps (links with at most 64 shapes together) a mask of the
// shapes of the pairs whose own bound d_p(c) - reach_p is kTableSlack or less; every other
// pair is apart by more than that anywhere in the cell, so is_valid tests only the pairs of
// two marked shapes (instead of every piece against the other link's hull first). A pair the
// lower bound's pass left with only a bound (its query stopped above lo) is settled by a
// boolean test at distance kTableSlack + reach_p (within_distance: exact outside a tolerance
// band far below kTableSlack), only in undecided cells. On the UR5 46% of the cells are
// undecided (blocks of links always close at some piece), 14% of their pairs joining two near
// shapes (test SelfTables.MbmRobotsBoundsHoldAgainstBruteForce); measuring
// its tables takes about 40% longer (3.1 -> 4.3 s on two threads).
//
// Why not on demand: measuring a cell costs about one exact test of the block (0.3 to 17 us on
// the MotionBenchMaker robots), and planning visits new cells faster than it revisits them;
// measured lazily, certified RRTConnect on 33 UR5 problems took 3 to 5 times longer than
// without tables.
//
// The tables depend on the model's shapes and kinematics only: one set per model and padding
// revision, shared by all its checkers (a registry of weak references: they live while a
// checker of the model does), with a budget of cells per model. Checkers of other
// allowed-collision matrices or scenes share the link pairs they have in common.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/scene/collision_checker.hpp>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "collision_checker_internals.hpp"

namespace hullcheck {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Cells per keying value, by the number of keying values: half a cell's width is about 6 mrad,
// 49 mrad and 98 mrad of a 2 pi range.
constexpr int kCellsPerValue[] = {1, 1024, 256, 40};  // for 0 .. kMaxGridValues values
// Cells a model's tables may hold together (8 bytes each, allocated when a table is set up).
constexpr std::size_t kCellBudget = std::size_t{1} << 22;
// Blocks without bounding hulls are measured pair by pair: not for blocks with more pairs.
constexpr int kMaxPairsWithoutHulls = 64;
// Lower bounds are measured up to this (m): a table decides a block when its bounds clear
// min_clearance (1e-6 m by default) or the exact tests' slack, so larger values would decide
// little more, while every pair within the cap plus its reach costs an exact query per cell.
constexpr double kCap = 0.002;
// Tables only over at most this many values (three-value grids have too many cells to measure).
constexpr int kMaxTableValues = 2;
// Half-widths are enlarged by this fraction (points on, or rounding errors off, a boundary).
constexpr double kWidthSlack = 1e-6;

float round_down(double x) {
  auto f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

float round_up(double x) {
  auto f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

std::uint64_t pack(double lower, double upper) {
  if (std::isnan(lower)) lower = -kInfinity;
  if (std::isnan(upper)) upper = kInfinity;
  const float lo = round_down(lower), up = round_up(upper);
  std::uint32_t a = 0, b = 0;
  std::memcpy(&a, &lo, sizeof a);
  std::memcpy(&b, &up, sizeof b);
  return (std::uint64_t{a} << 32) | b;
}

void unpack(std::uint64_t word, double* lower, double* upper) {
  const auto a = static_cast<std::uint32_t>(word >> 32);
  const auto b = static_cast<std::uint32_t>(word);
  float lo = 0.0f, up = 0.0f;
  std::memcpy(&lo, &a, sizeof lo);
  std::memcpy(&up, &b, sizeof up);
  *lower = lo;
  *upper = up;
}

}  // namespace

std::shared_ptr<CollisionChecker::ModelSelfTables> CollisionChecker::model_self_tables() const {
  static std::mutex registry_mutex;
  static std::vector<std::weak_ptr<ModelSelfTables>> registry;
  const std::lock_guard<std::mutex> lock(registry_mutex);
  std::shared_ptr<ModelSelfTables> found;
  for (auto it = registry.begin(); it != registry.end();) {
    std::shared_ptr<ModelSelfTables> entry = it->lock();
    if (!entry) {
      it = registry.erase(it);
      continue;
    }
    if (entry->model == model_ && entry->padding_revision == padding_revision_) found = entry;
    ++it;
  }
  if (!found) {
    found = std::make_shared<ModelSelfTables>();
    found->model = model_;
    found->padding_revision = padding_revision_;
    registry.push_back(found);
  }
  return found;
}

const std::vector<CollisionChecker::SelfTable*>* CollisionChecker::self_block_tables() const {
  if (!self_tables_->model->any_measured.load(std::memory_order_acquire)) return nullptr;
  return &set_up_self_tables();
}

const std::vector<CollisionChecker::SelfTable*>& CollisionChecker::set_up_self_tables() const {
  static_assert(sizeof(kCellsPerValue) / sizeof(kCellsPerValue[0]) == kMaxGridValues + 1);
  SelfTables& out = *self_tables_;
  std::call_once(out.built, [&] {
    ModelSelfTables& shared = *out.model;
    out.per_block.assign(self_blocks_.size(), nullptr);
    const MotionLevers& levers = motion_levers();
    const std::lock_guard<std::mutex> lock(shared.mutex);
    // Links swept for this set-up and their coarse sweeps' growth, by (link ball, joint): a
    // link is swept about the same joint for every link beyond it (a forearm against a
    // gripper's links).
    std::map<std::pair<int, int>, std::shared_ptr<const SweptLink>> sweeps;
    std::map<std::pair<int, int>, double> growths;
    const auto sweep = [&](int x, int joint) {
      const auto [it, fresh] = sweeps.try_emplace({x, joint});
      if (fresh) it->second = sweep_link(x, joint);
      return it->second;
    };
    const auto growth = [&](int x, int joint) {
      const auto [it, fresh] = growths.try_emplace({x, joint});
      if (fresh) it->second = sweep_growth(x, joint);
      return it->second;
    };
    for (std::size_t k = 0; k < self_blocks_.size(); ++k) {
      const SelfBlock& block = self_blocks_[k];
      const LinkBall& ball_a = link_balls_[static_cast<std::size_t>(block.link_a)];
      const LinkBall& ball_b = link_balls_[static_cast<std::size_t>(block.link_b)];
      const bool hulls = ball_a.bound >= 0 && ball_b.bound >= 0;
      if (!hulls && block.end - block.begin > kMaxPairsWithoutHulls) continue;
      std::unique_ptr<SelfTable>& table = shared.tables[{ball_a.link, ball_b.link}];
      if (!table) {
        int keys[kMaxGridValues];
        bool revolute = true;
        int key_count = relative_drivers(ball_a.link, ball_b.link, kMaxGridValues, keys, &revolute);
        if (key_count > kMaxTableValues + 1 || !revolute) continue;
        std::shared_ptr<const SweptLink> swept;
        if (key_count > kMaxTableValues) {
          // One value too many: the link whose sweep grows it least is swept, its joint's value
          // dropped from the keys.
          const int joint_a = sweep_joint(block.link_a, block.link_b, key_count);
          const int joint_b = sweep_joint(block.link_b, block.link_a, key_count);
          if (joint_a < 0 || joint_b < 0) continue;
          swept = growth(block.link_a, joint_a) <= growth(block.link_b, joint_b)
                      ? sweep(block.link_a, joint_a)
                      : sweep(block.link_b, joint_b);
          if (!swept) continue;
          key_count = static_cast<int>(std::remove(keys, keys + key_count, swept->driver) - keys);
        }
        auto made = std::make_unique<SelfTable>();
        made->swept = swept;
        made->cell_count = made->setup(*model_, keys, key_count, kCellsPerValue[key_count]);
        if (shared.cells + made->cell_count > kCellBudget) continue;
        // Per pair and for the whole block (the bounding hulls): how far the links move
        // relative to each other between a cell's centre and any point of the cell.
        const auto reach_of = [&](const auto& lever_row) {
          double r = 0.0;
          for (int d = 0; d < key_count; ++d) {
            r += made->half_width(d) * lever_row(made->variables[d]);
          }
          return (1.0 + kWidthSlack) * r;
        };
        made->block_reach = reach_of(levers.self_block_levers.row(static_cast<Eigen::Index>(k)));
        made->pair_reach.resize(static_cast<std::size_t>(block.end - block.begin));
        for (int p = block.begin; p < block.end; ++p) {
          made->pair_reach[static_cast<std::size_t>(p - block.begin)] =
              reach_of(levers.self_pair_levers.row(p));
        }
        made->bounds = std::make_unique<std::atomic<std::uint64_t>[]>(made->cell_count);
        for (std::size_t c = 0; c < made->cell_count; ++c) {
          made->bounds[c].store(SelfTable::kUnmeasured, std::memory_order_relaxed);
        }
        if (link_shape_count(ball_a.link) + link_shape_count(ball_b.link) <= 64) {
          made->near_shapes = std::make_unique<std::atomic<std::uint64_t>[]>(made->cell_count);
          for (std::size_t c = 0; c < made->cell_count; ++c) {
            made->near_shapes[c].store(kAllShapesNear, std::memory_order_relaxed);
          }
        }
        shared.cells += made->cell_count;
        table = std::move(made);
      }
      out.per_block[k] = table.get();
    }
  });
  return out.per_block;
}

void CollisionChecker::measure_self_tables(int threads) const {
  require_current_padding();
  if (threads < 0) {
    throw InputError(
        "CollisionChecker::measure_self_tables: threads must be >= 0 (0: every "
        "hardware thread), got " +
        std::to_string(threads));
  }
  const std::vector<SelfTable*>& tables = set_up_self_tables();
  // Every table's cells, numbered one after the other (table k's from first[k]), taken in
  // chunks by the threads: a cell's value depends only on the cell, so the order is free.
  std::vector<std::size_t> first(tables.size() + 1, 0);
  for (std::size_t k = 0; k < tables.size(); ++k) {
    first[k + 1] = first[k] + (tables[k] == nullptr ? 0 : tables[k]->cell_count);
  }
  const std::size_t total = first.back();
  constexpr std::size_t kChunk = 1024;
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors;
  const auto work = [&](std::exception_ptr* error) {
    try {
      Scratch& s = scratch();
      for (std::size_t begin = next.fetch_add(kChunk); begin < total;
           begin = next.fetch_add(kChunk)) {
        auto k = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), begin) -
                                          first.begin() - 1);
        for (std::size_t i = begin; i < std::min(total, begin + kChunk); ++i) {
          while (i >= first[k + 1]) ++k;
          measure_self_table_cell(static_cast<int>(k), static_cast<long>(i - first[k]), s);
        }
      }
    } catch (...) {
      *error = std::current_exception();
      next.store(total);  // the others stop at their next chunk
    }
  };
  const std::size_t wanted = threads > 0
                                 ? static_cast<std::size_t>(threads)
                                 : std::max<std::size_t>(1, std::thread::hardware_concurrency());
  const std::size_t count = std::min(wanted, total / kChunk + 1);
  errors.resize(count);
  std::vector<std::thread> workers;
  for (std::size_t t = 1; t < count; ++t) workers.emplace_back(work, &errors[t]);
  work(&errors[0]);
  for (std::thread& w : workers) w.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  for (SelfTable* table : tables) {
    if (table != nullptr) std::call_once(table->summary_once, [table] { table->summarize(); });
  }
}

void CollisionChecker::SelfTable::summarize() {
  // Level 0: the cells' lower bounds (as stored, rounded down); level k from level k - 1, each
  // entry the minimum of the (up to) 2 x 2 entries below it.
  std::vector<float> below(cell_count);
  for (std::size_t c = 0; c < cell_count; ++c) {
    double lo = 0.0, up = 0.0;
    unpack(bounds[c].load(std::memory_order_relaxed), &lo, &up);
    // Exact (stored as a float); never unmeasured here, but such a cell would bound nothing.
    below[c] = std::isnan(lo) ? -std::numeric_limits<float>::infinity() : static_cast<float>(lo);
  }
  std::array<int, kMaxGridValues> size{cells[0], dims > 1 ? cells[1] : 1, 1};
  while (size[0] > 1 || size[1] > 1) {
    const std::array<int, kMaxGridValues> up{(size[0] + 1) / 2, (size[1] + 1) / 2, 1};
    std::vector<float> level(static_cast<std::size_t>(up[0]) * static_cast<std::size_t>(up[1]),
                             std::numeric_limits<float>::infinity());
    for (int i = 0; i < size[0]; ++i) {
      for (int j = 0; j < size[1]; ++j) {
        float& m = level[static_cast<std::size_t>(i / 2) * static_cast<std::size_t>(up[1]) +
                         static_cast<std::size_t>(j / 2)];
        m = std::min(m, below[static_cast<std::size_t>(i) * static_cast<std::size_t>(size[1]) +
                              static_cast<std::size_t>(j)]);
      }
    }
    minima.push_back(level);
    level_size.push_back(up);
    below = std::move(level);
    size = up;
  }
  summarized.store(true, std::memory_order_release);
}

float CollisionChecker::SelfTable::box_lower(const int* lo, const int* hi) const {
  const int lo1 = dims > 1 ? lo[1] : 0, hi1 = dims > 1 ? hi[1] : 0;
  // The first level whose squares hold the range in at most two per value (the top level is
  // one square).
  std::size_t k = 0;
  while (k < minima.size() && ((hi[0] >> k) - (lo[0] >> k) > 1 || (hi1 >> k) - (lo1 >> k) > 1)) {
    ++k;
  }
  float m = std::numeric_limits<float>::infinity();
  if (k == 0) {
    for (int i = lo[0]; i <= hi[0]; ++i) {
      for (int j = lo1; j <= hi1; ++j) {
        double l = 0.0, u = 0.0;
        unpack(
            bounds[static_cast<std::size_t>(i) * static_cast<std::size_t>(dims > 1 ? cells[1] : 1) +
                   static_cast<std::size_t>(j)]
                .load(std::memory_order_relaxed),
            &l, &u);
        m = std::min(
            m, std::isnan(l) ? -std::numeric_limits<float>::infinity() : static_cast<float>(l));
      }
    }
    return m;
  }
  const std::vector<float>& level = minima[k - 1];
  const int width = level_size[k - 1][1];
  for (int i = lo[0] >> k; i <= (hi[0] >> k); ++i) {
    for (int j = lo1 >> k; j <= (hi1 >> k); ++j) {
      m = std::min(m, level[static_cast<std::size_t>(i) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>(j)]);
    }
  }
  return m;
}

bool CollisionChecker::self_block_box_lower(int block, const double* q0, const double* dq,
                                            double t0, double t1, double needed) const {
  const std::vector<SelfTable*>* tables = self_block_tables();
  const SelfTable* table = tables == nullptr ? nullptr : (*tables)[static_cast<std::size_t>(block)];
  if (table == nullptr || !table->summarized.load(std::memory_order_acquire)) return false;
  int lo[kMaxGridValues] = {0, 0, 0}, hi[kMaxGridValues] = {0, 0, 0};
  for (int d = 0; d < table->dims; ++d) {
    const int v = table->variables[d];
    if (table->cells_per_unit[d] == 0.0) {  // a value without range: it must stay at it
      if (dq[v] != 0.0 || q0[v] != table->lower[d]) return false;
      continue;
    }
    // The motion's range in cell units, without crossing a continuous value's seam or a
    // bounded value's grid ends (the cell walk handles those).
    const double u0 = table->coordinate(d, q0[v] + t0 * dq[v]);
    const double u1 = u0 + dq[v] * table->cells_per_unit[d] * (t1 - t0);
    const double a = std::min(u0, u1), b = std::max(u0, u1);
    if (!(a >= 0.0 && b <= table->cells[d])) return false;
    lo[d] = std::min(static_cast<int>(a), table->cells[d] - 1);
    hi[d] = std::min(static_cast<int>(b), table->cells[d] - 1);
  }
  return table->box_lower(lo, hi) > needed;
}

bool CollisionChecker::self_block_bounds(int block, const double* q, double* lower, double* upper,
                                         std::uint64_t* near_shapes) const {
  const std::vector<SelfTable*>* tables = self_block_tables();
  const SelfTable* table = tables == nullptr ? nullptr : (*tables)[static_cast<std::size_t>(block)];
  if (table == nullptr) return false;
  const long cell = table->cell(q, false);
  if (cell < 0) return false;
  const auto c = static_cast<std::size_t>(cell);
  const std::uint64_t word = table->bounds[c].load(std::memory_order_acquire);
  if (word == SelfTable::kUnmeasured) return false;
  unpack(word, lower, upper);
  if (near_shapes != nullptr) {
    *near_shapes = table->near_shapes == nullptr
                       ? kAllShapesNear
                       : table->near_shapes[c].load(std::memory_order_relaxed);
  }
  return true;
}

template <class Visit>
bool CollisionChecker::SelfTable::walk(const double* q0, const double* dq, double t0, double t1,
                                       int max_cells, double* reached, Visit visit) const {
  if (reached != nullptr) *reached = t0;
  // Cell coordinates u_d(t) = (x_d(t) - lower_d) * cells_per_unit_d along the motion, walked
  // from t0 to t1 one cell boundary at a time (the dimension whose next boundary comes first).
  // The walk's position: its cell's indices and the t of the next boundary per dimension.
  struct Cursor {
    int index[kMaxGridValues] = {0, 0, 0};
    double next[kMaxGridValues] = {0.0, 0.0, 0.0};
  };
  Cursor at;
  double step[kMaxGridValues];  // t between boundaries
  int dir[kMaxGridValues];
  double crossings = 1.0;
  for (int d = 0; d < dims; ++d) {
    const int v = variables[d];
    at.next[d] = std::numeric_limits<double>::infinity();
    step[d] = 0.0;
    dir[d] = 0;
    if (cells_per_unit[d] == 0.0) {  // a value without range: it must stay at it
      if (dq[v] != 0.0 || q0[v] != lower[d]) return false;
      continue;
    }
    // The motion's ends in cell units (a continuous value's start taken into the grid's turn);
    // a bounded value's must both lie in the grid.
    const double u = coordinate(d, q0[v] + t0 * dq[v]);
    const double du = dq[v] * cells_per_unit[d];  // per unit t
    if (!wraps[d] && !(u >= 0.0 && u <= cells[d])) return false;
    const double u1 = coordinate(d, q0[v] + t1 * dq[v]);
    if (!wraps[d] && !(u1 >= 0.0 && u1 <= cells[d])) {
      if (reached == nullptr) return false;
      // A walk as far as it goes: up to where the value leaves the grid.
      t1 = std::min(t1, t0 + ((du > 0.0 ? cells[d] : 0.0) - u) / du);
    }
    at.index[d] = std::min(static_cast<int>(u), cells[d] - 1);
    // The cells crossed are at most one plus the boundaries crossed in each dimension: too
    // many, and nothing is visited (a walk as far as it goes stops at max_cells).
    crossings += std::abs(du) * (t1 - t0) + 1.0;
    if (crossings > max_cells && reached == nullptr) return false;
    if (du > 0.0) {
      dir[d] = 1;
      step[d] = 1.0 / du;
      at.next[d] = t0 + (at.index[d] + 1 - u) * step[d];
    } else if (du < 0.0) {
      dir[d] = -1;
      step[d] = -1.0 / du;
      at.next[d] = t0 + (u - at.index[d]) * step[d];
    }
  }
  const auto cell_of = [&](const Cursor& c) {
    long cell = 0;
    for (int d = 0; d < dims; ++d) cell = cell * cells[d] + c.index[d];
    return static_cast<std::size_t>(cell);
  };
  // Into the next cell; false (c unchanged) when the walk ends in this one. *entered: where.
  const auto advance = [&](Cursor& c, double* entered) {
    int d_next = -1;
    for (int d = 0; d < dims; ++d) {
      if (dir[d] != 0 && (d_next < 0 || c.next[d] < c.next[d_next])) d_next = d;
    }
    if (d_next < 0 || c.next[d_next] >= t1) return false;
    *entered = c.next[d_next];
    int& i = c.index[d_next];
    i += dir[d_next];
    if (wraps[d_next]) {
      i = (i + cells[d_next]) % cells[d_next];
    } else {
      i = std::clamp(i, 0, cells[d_next] - 1);  // only at the grid's edge, by rounding
    }
    c.next[d_next] += step[d_next];
    return true;
  };
  // A second cursor kAhead cells ahead asks for its cells' bounds before they are visited (the
  // cells of a walk lie far apart in memory; each visit would wait for its cache miss).
  // Measured (bench_vamp, UR5: 237k walks, 28 cells each): 81 -> 62-65 cycles per cell.
  constexpr int kAhead = 8;
  Cursor ahead = at;
  double unused = 0.0;
  bool ahead_open = true;
  for (int k = 0; k < kAhead && ahead_open; ++k) {
    ahead_open = advance(ahead, &unused);
    if (ahead_open) __builtin_prefetch(&bounds[cell_of(ahead)]);
  }
  double entered = t0;  // where the walk entered the current cell
  for (int visited = 0; visited < max_cells; ++visited) {
    if (!visit(cell_of(at))) {
      if (reached != nullptr) *reached = entered;
      return false;
    }
    if (!advance(at, &entered)) {
      if (reached != nullptr) *reached = t1;
      return true;
    }
    if (ahead_open && (ahead_open = advance(ahead, &unused))) {
      __builtin_prefetch(&bounds[cell_of(ahead)]);
    }
  }
  if (reached != nullptr) *reached = entered;
  return false;
}

CollisionChecker::NearShapeBits CollisionChecker::near_shape_bits(const SelfBlock& block) const {
  const int link_a = link_balls_[static_cast<std::size_t>(block.link_a)].link;
  const int link_b = link_balls_[static_cast<std::size_t>(block.link_b)].link;
  return {shape_begin_[static_cast<std::size_t>(link_a)],
          shape_begin_[static_cast<std::size_t>(link_b)], link_shape_count(link_a)};
}

bool CollisionChecker::self_block_segment_lower(int block, const double* q0, const double* dq,
                                                double t0, double t1, int max_cells, double needed,
                                                double* lower, double* reached) const {
  const std::vector<SelfTable*>* tables = self_block_tables();
  const SelfTable* table = tables == nullptr ? nullptr : (*tables)[static_cast<std::size_t>(block)];
  if (table == nullptr) {
    if (reached != nullptr) *reached = t0;
    return false;
  }
  double best = std::numeric_limits<double>::infinity();
  const bool through = table->walk(q0, dq, t0, t1, max_cells, reached, [&](std::size_t cell) {
    const std::uint64_t word = table->bounds[cell].load(std::memory_order_relaxed);
    if (word == SelfTable::kUnmeasured) return false;
    double lo = 0.0, up = 0.0;
    unpack(word, &lo, &up);
    if (!(lo > needed)) return false;
    best = std::min(best, lo);
    return true;
  });
  if (through) *lower = best;
  return through;
}

bool CollisionChecker::self_block_segment_near(int block, const double* q0, const double* dq,
                                               double t0, double t1, int max_cells,
                                               std::uint64_t* near_shapes) const {
  const std::vector<SelfTable*>* tables = self_block_tables();
  const SelfTable* table = tables == nullptr ? nullptr : (*tables)[static_cast<std::size_t>(block)];
  if (table == nullptr || table->near_shapes == nullptr) return false;
  std::uint64_t near = 0;
  const bool through = table->walk(q0, dq, t0, t1, max_cells, nullptr, [&](std::size_t cell) {
    if (table->bounds[cell].load(std::memory_order_acquire) == SelfTable::kUnmeasured) {
      return false;
    }
    near |= table->near_shapes[cell].load(std::memory_order_relaxed);
    return true;
  });
  if (through) *near_shapes = near;
  return through;
}

void CollisionChecker::measure_self_table_cell(int block, long cell, Scratch& s) const {
  const SelfTable& table = *set_up_self_tables()[static_cast<std::size_t>(block)];
  std::atomic<std::uint64_t>& slot = table.bounds[static_cast<std::size_t>(cell)];
  if (slot.load(std::memory_order_relaxed) != SelfTable::kUnmeasured) return;
  // Per-thread scratch: sized on first use only.
  if (s.table_q.size() != model_->variable_count()) s.table_q = model_->default_configuration();
  if (s.table_poses.size() != model_->links().size()) s.table_poses.resize(model_->links().size());
  if (s.table_centers.size() < shapes_.size()) s.table_centers.resize(shapes_.size());
  table.center(static_cast<std::size_t>(cell), s.table_q);
  model_->compute_link_poses_unchecked(s.table_q.data(), s.table_poses.data());
  const std::vector<Eigen::Isometry3d>& poses = s.table_poses;
  const SelfBlock& b = self_blocks_[static_cast<std::size_t>(block)];
  const auto pose_of = [&](int shape) {
    const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
    const Eigen::Isometry3d& link_pose = poses[static_cast<std::size_t>(rs.link)];
    return rs.at_link_frame
               ? link_pose
               : Eigen::Isometry3d(
                     link_pose *
                     model_->link(rs.link).shapes[static_cast<std::size_t>(rs.shape)].origin);
  };
  // A swept link's shapes are their sweeps, at the link's pose (swept_links.cpp).
  const SweptLink* swept = table.swept.get();
  const auto sweep_of = [&](int shape) -> const detail::SweptShape* {
    const RobotShape& rs = shapes_[static_cast<std::size_t>(shape)];
    return swept == nullptr || rs.link != swept->link
               ? nullptr
               : &swept->shapes[static_cast<std::size_t>(rs.shape)];
  };
  const auto placed = [&](int shape, const Shape& unswept) {
    const detail::SweptShape* w = sweep_of(shape);
    return w == nullptr ? std::pair<const Shape*, Eigen::Isometry3d>(&unswept, pose_of(shape))
                        : std::pair<const Shape*, Eigen::Isometry3d>(
                              &w->shape, poses[static_cast<std::size_t>(swept->link)]);
  };
  double lo = kCap, up = kInfinity;
  double floor = -kInfinity;  // from the bounding hulls: no pair is nearer
  std::uint64_t near = 0;     // the near shapes (SelfTable::near_shapes)
  const int bound_a = link_balls_[static_cast<std::size_t>(b.link_a)].bound;
  const int bound_b = link_balls_[static_cast<std::size_t>(b.link_b)].bound;
  if (bound_a >= 0 && bound_b >= 0 && b.end - b.begin > 1) {
    const double reach = table.block_reach;
    const auto bound_placed = [&](int bound) {
      return sweep_of(bound) == nullptr
                 ? placed(bound, bounding_shape(bound))
                 : std::pair<const Shape*, Eigen::Isometry3d>(
                       &swept->bound->shape, poses[static_cast<std::size_t>(swept->link)]);
    };
    const auto [hull_a, pose_a] = bound_placed(bound_a);
    const auto [hull_b, pose_b] = bound_placed(bound_b);
    const SignedDistanceResult r =
        signed_distance_below(*hull_a, pose_a, *hull_b, pose_b, kCap + reach);
    if (r.status == Status::kAboveCutoff || r.status == Status::kConverged) {
      floor = r.signed_distance - reach;
    }
  }
  if (!(floor >= kCap)) {
    // The ball centres of the two links' shapes, once (a decomposed link's pieces are in many
    // pairs).
    const int la = link_balls_[static_cast<std::size_t>(b.link_a)].link;
    const int lb = link_balls_[static_cast<std::size_t>(b.link_b)].link;
    for (const int l : {la, lb}) {
      for (int sh = shape_begin_[static_cast<std::size_t>(l)];
           sh < shape_begin_[static_cast<std::size_t>(l) + 1]; ++sh) {
        const detail::SweptShape* w = sweep_of(sh);
        s.table_centers[static_cast<std::size_t>(sh)] =
            poses[static_cast<std::size_t>(l)] *
            (w == nullptr ? shapes_[static_cast<std::size_t>(sh)].center : w->center);
      }
    }
    const auto radius = [&](int shape) {
      const detail::SweptShape* w = sweep_of(shape);
      return w == nullptr ? shapes_[static_cast<std::size_t>(shape)].radius : w->radius;
    };
    const auto pairs = static_cast<std::size_t>(b.end - b.begin);
    if (s.table_pair_lower.size() < pairs) {
      s.table_pair_lower.resize(pairs);
      s.table_pair_bound_only.resize(pairs);
    }
    for (int p = b.begin; p < b.end; ++p) {
      const SelfPair& pair = self_pairs_[static_cast<std::size_t>(p)];
      const auto i = static_cast<std::size_t>(p - b.begin);
      const double reach = table.pair_reach[i];
      const double gap = (s.table_centers[static_cast<std::size_t>(pair.a)] -
                          s.table_centers[static_cast<std::size_t>(pair.b)])
                             .norm() -
                         radius(pair.a) - radius(pair.b);
      // The pair's lower bound over the cell, measured (bound only = false) or where a test
      // stopped once it was above lo.
      const auto bound = [&](double pair_lower, bool bound_only) {
        s.table_pair_lower[i] = pair_lower;
        s.table_pair_bound_only[i] = bound_only;
        if (!bound_only) lo = std::min(lo, pair_lower);
      };
      if (gap - reach >= lo) {
        bound(gap - reach, true);
        continue;
      }
      const auto [shape_a, pose_a] = placed(pair.a, shape_of(pair.a));
      const auto [shape_b, pose_b] = placed(pair.b, shape_of(pair.b));
      if (swept != nullptr && gap <= 0.0 && intersect(*shape_a, pose_a, *shape_b, pose_b)) {
        bound(gap - reach, false);
        continue;
      }
      const SignedDistanceResult r =
          signed_distance_below(*shape_a, pose_a, *shape_b, pose_b, lo + reach);
      if (r.status == Status::kAboveCutoff) {  // at least lo everywhere in the cell
        bound(std::max(gap, r.signed_distance) - reach, true);
      } else if (r.status == Status::kConverged) {
        bound(r.signed_distance - reach, false);
        // A sweep bounds from below only.
        if (swept == nullptr) up = std::min(up, r.signed_distance + reach);
      } else {
        bound(gap - reach, false);  // nothing proven by the query: the balls' gap bounds it
      }
    }
    // A cell the bounds leave undecided: its near shapes, those of the pairs not proven
    // farther than kTableSlack (a bound only is settled by the boolean test, no distance
    // converged; its verdict is exact outside a tolerance far below kTableSlack).
    if (table.near_shapes != nullptr && !(std::max(lo, floor) > kTableSlack)) {
      const NearShapeBits bits = near_shape_bits(b);
      for (int p = b.begin; p < b.end; ++p) {
        const SelfPair& pair = self_pairs_[static_cast<std::size_t>(p)];
        const auto i = static_cast<std::size_t>(p - b.begin);
        if (s.table_pair_lower[i] > kTableSlack) continue;
        if (s.table_pair_bound_only[i]) {
          const auto [shape_a, pose_a] = placed(pair.a, shape_of(pair.a));
          const auto [shape_b, pose_b] = placed(pair.b, shape_of(pair.b));
          if (!within_distance(*shape_a, pose_a, *shape_b, pose_b,
                               kTableSlack + table.pair_reach[i])) {
            continue;
          }
        }
        near |= bits.of(pair);
      }
    }
  }
  if (table.near_shapes != nullptr) {
    table.near_shapes[static_cast<std::size_t>(cell)].store(near, std::memory_order_relaxed);
  }
  // Release: a query reading the bounds (acquire) sees the near shapes.
  slot.store(pack(std::max(lo, floor), up), std::memory_order_release);
  // Queries read the tables from now on (a release: the tables' set-up is visible to them).
  self_tables_->model->any_measured.store(true, std::memory_order_release);
}

}  // namespace hullcheck
