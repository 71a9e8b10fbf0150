// bench_core: hullcheck vs libccd 2.1, FCL 0.7 and Bullet 3.24 (double) on the same hull pairs.
//
//   bench_core [--quick] [--no-robots] [--pairs=N] [--table=FILE] [google-benchmark flags]
//
// 1. Data: oracle::make_hull_pairs with 8, 32, 128, 512 vertices (~30% overlapping) and, when
//    the shared robots directory exists, hulls of real robot collision meshes at random poses.
//    Every implementation gets the same hull vertices (qhull) and poses.
// 2. Accuracy, once, outside any timed loop: per implementation x query x data set, the largest
//    absolute error against the oracles (brute_force_distance, minkowski_penetration), the
//    number of wrong verdicts outside a band of 1e-9 x scale, and failures.
// 3. Timing with Google Benchmark: each benchmark iteration runs the query over the whole pair
//    list; "t/query" and the tables give the time per query (CPU time / queries).
// 4. Warm start: hullcheck::ProximityPair following B along a path in steps of 1% of the shape
//    size, distance and signed_distance, vs the cold free functions on the same poses.
// 5. Markdown tables on stdout (and in --table=FILE).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <hullcheck/core.hpp>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <oracles.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_data.hpp"
#include "benchmark_flags.hpp"
#include "peers.hpp"

namespace hb = hullcheck::bench;

namespace {

constexpr double kBand = 1e-9;  // verdict band, relative to the query's scale
constexpr std::uint64_t kSeed = 20240611;

struct Options {
  bool quick = false;
  bool robots = true;
  int pairs = 0;  // 0: per-set default
  std::string table_file;
  std::string shared_dir;
};

// ---------------------------------------------------------------------------------------------
// Accuracy scoring

struct Score {
  int cases = 0;
  double max_error = 0.0;  // |distance|depth|signed distance - oracle|
  double aux_error = 0.0;  // distance: witness points; penetration: normal (see notes)
  int wrong = 0;           // wrong verdicts outside the band
  int failed = 0;          // no answer: failure status, exception, NaN
  int flagged = 0;         // answered but flagged (hullcheck: status not kConverged)
  std::size_t worst = 0;   // case index of max_error
  std::string exception;   // what() of an exception thrown by the implementation
};

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

void note_error(Score& s, double err, std::size_t i) {
  if (!(err <= s.max_error)) {  // also catches NaN
    s.max_error = std::isnan(err) ? std::numeric_limits<double>::infinity() : err;
    s.worst = i;
  }
}

Score score(hb::Impl& impl, hb::Query q, const std::vector<hb::Case>& cases,
            const std::vector<hb::Truth>& truth) {
  Score s;
  try {
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const hb::Truth& t = truth[i];
      const double band = kBand * t.scale;
      const bool truly_apart = !t.overlapping && t.distance > band;
      const bool truly_overlapping = t.overlapping && t.depth > band;
      ++s.cases;
      switch (q) {
        case hb::Query::kIntersect: {
          const bool hit = impl.intersect(i);
          if ((hit && truly_apart) || (!hit && truly_overlapping)) ++s.wrong;
          break;
        }
        case hb::Query::kDistance: {
          const hb::DistanceOut d = impl.distance(i);
          if (!d.ok || !std::isfinite(d.distance) || !finite(d.point_a) || !finite(d.point_b)) {
            ++s.failed;
            break;
          }
          if (d.flagged) ++s.flagged;
          if ((!d.separated && truly_apart) || (d.separated && truly_overlapping)) ++s.wrong;
          const double value = d.separated ? d.distance : 0.0;
          note_error(s, std::abs(value - t.distance), i);
          if (d.separated && !t.overlapping) {
            const double gap = std::abs((d.point_b - d.point_a).norm() - t.distance);
            const double on_a = hb::point_hull_distance(d.point_a, *cases[i].a, cases[i].pose_a);
            const double on_b = hb::point_hull_distance(d.point_b, *cases[i].b, cases[i].pose_b);
            s.aux_error = std::max({s.aux_error, gap, on_a, on_b});
          }
          break;
        }
        case hb::Query::kPenetration: {
          const hb::PenetrationOut p = impl.penetration(i);
          if (!p.ok || !std::isfinite(p.depth) || !finite(p.normal)) {
            ++s.failed;
            break;
          }
          if (p.flagged) ++s.flagged;
          if ((p.overlapping && truly_apart) || (!p.overlapping && truly_overlapping)) ++s.wrong;
          const double value = p.overlapping ? p.depth : 0.0;
          note_error(s, std::abs(value - t.depth), i);
          if (p.overlapping && t.overlapping) {
            const double n = p.normal.norm();
            const double along =
                n > 0 ? hb::depth_along(t, p.normal / n) : std::numeric_limits<double>::infinity();
            s.aux_error = std::max(s.aux_error, std::abs(along - t.depth));
          }
          break;
        }
        case hb::Query::kSignedDistance: {
          const hb::SignedOut sd = impl.signed_distance(i);
          if (!sd.ok || !std::isfinite(sd.value)) {
            ++s.failed;
            break;
          }
          if (sd.flagged) ++s.flagged;
          const bool hit = sd.value <= 0;
          if ((hit && truly_apart) || (!hit && truly_overlapping)) ++s.wrong;
          note_error(s, std::abs(sd.value - (t.overlapping ? -t.depth : t.distance)), i);
          break;
        }
      }
    }
  } catch (const std::exception& e) {
    s.exception = e.what();
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Benchmarks and their results

struct Entry {
  std::string set, query, impl, api;
  std::size_t queries = 0;  // queries per benchmark iteration
  Score score;
  bool scored = false;
  double ns = std::numeric_limits<double>::quiet_NaN();  // CPU ns per query (fastest repetition)
  double median_ns = std::numeric_limits<double>::quiet_NaN();  // from a "median" aggregate
  // Warm start only.
  double mean_iterations = std::numeric_limits<double>::quiet_NaN();
  double max_warm_cold_diff = std::numeric_limits<double>::quiet_NaN();
  double overlapping_fraction = std::numeric_limits<double>::quiet_NaN();
  double mean_iterations_apart = std::numeric_limits<double>::quiet_NaN();  // apart poses only
};

std::deque<Entry> g_entries;              // stable addresses
std::map<std::string, Entry*> g_by_name;  // benchmark name -> entry

std::string bench_name(const std::string& query, const std::string& set, const std::string& impl) {
  std::string name = query + "/" + set + "/" + impl;
  std::replace(name.begin(), name.end(), ' ', '_');
  return name;
}

void set_counters(benchmark::State& state, std::size_t queries) {
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(queries));
  state.counters["t/query"] = benchmark::Counter(
      static_cast<double>(queries),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void register_query(Entry& entry, hb::Impl* impl, hb::Query q) {
  const std::string name = bench_name(entry.query, entry.set, entry.impl);
  g_by_name[name] = &entry;
  const std::size_t n = entry.queries;
  benchmark::RegisterBenchmark(name.c_str(), [impl, q, n](benchmark::State& state) {
    switch (q) {
      case hb::Query::kIntersect:
        for (auto _ : state) {
          for (std::size_t i = 0; i < n; ++i) benchmark::DoNotOptimize(impl->intersect(i));
        }
        break;
      case hb::Query::kDistance:
        for (auto _ : state) {
          for (std::size_t i = 0; i < n; ++i) benchmark::DoNotOptimize(impl->distance(i));
        }
        break;
      case hb::Query::kPenetration:
        for (auto _ : state) {
          for (std::size_t i = 0; i < n; ++i) benchmark::DoNotOptimize(impl->penetration(i));
        }
        break;
      case hb::Query::kSignedDistance:
        for (auto _ : state) {
          for (std::size_t i = 0; i < n; ++i) benchmark::DoNotOptimize(impl->signed_distance(i));
        }
        break;
    }
    set_counters(state, n);
  });
}

// ---------------------------------------------------------------------------------------------
// Warm start: ProximityPair vs cold free functions along paths of small pose steps.

struct Path {
  hullcheck::Shape a, b;
  Eigen::Isometry3d pose_a;
  std::vector<Eigen::Isometry3d> poses_b;
};

std::vector<Path> make_paths(const hb::DataSet& set, int count, int steps) {
  std::vector<Path> paths;
  for (int k = 0; k < count && k < static_cast<int>(set.cases.size()); ++k) {
    const hb::Case& c = set.cases[static_cast<std::size_t>(k)];
    Path p{
        hullcheck::ConvexHull(c.a->vertices), hullcheck::ConvexHull(c.b->vertices), c.pose_a, {}};
    // B approaches A along the line between their centroids: each step translates it by 1% of
    // the shape size and turns it by 0.01 rad about a fixed axis. The start is placed with the
    // oracle's overlap interval so that about the last third of the path overlaps (the turning
    // makes that approximate).
    const double size = std::max(c.a->extent, c.b->extent);
    const Eigen::Vector3d from = c.pose_b * c.b->centroid;
    const Eigen::Vector3d to = c.pose_a * c.a->centroid;
    Eigen::Vector3d dir = to - from;
    dir = dir.norm() > 1e-12 ? dir.normalized() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
    Eigen::Isometry3d pose = c.pose_b;
    const hullcheck::oracle::Interval overlap = hullcheck::oracle::overlap_interval(
        hullcheck::oracle::transformed(c.a->vertices, c.pose_a),
        hullcheck::oracle::transformed(c.b->vertices, c.pose_b), dir);
    if (!overlap.empty()) {
      pose.translation() += (overlap.lo - (2.0 / 3.0) * steps * 0.01 * size) * dir;
    }
    for (int s = 0; s < steps; ++s) {
      p.poses_b.push_back(pose);
      const Eigen::Vector3d centre = pose * c.b->centroid;
      Eigen::Isometry3d next = Eigen::Isometry3d::Identity();
      next.linear() = Eigen::AngleAxisd(0.01, axis).toRotationMatrix() * pose.linear();
      // Keep the centroid moving on the straight line.
      next.translation() = centre + 0.01 * size * dir - next.linear() * c.b->centroid;
      pose = next;
    }
    paths.push_back(std::move(p));
  }
  return paths;
}

enum class WarmQuery { kDistance, kSignedDistance };

double query_value(hullcheck::ProximityPair& pair, WarmQuery q) {
  return q == WarmQuery::kDistance ? pair.distance().distance
                                   : pair.signed_distance().signed_distance;
}

void measure_warm(Entry& warm, Entry& cold, const std::vector<Path>& paths, WarmQuery q) {
  double warm_iterations = 0, cold_iterations = 0, diff = 0;
  double warm_apart = 0, cold_apart = 0;
  std::size_t queries = 0, overlapping = 0;
  for (const Path& p : paths) {
    hullcheck::ProximityPair pair;
    pair.set_shape_a(p.a, p.pose_a);
    pair.set_shape_b(p.b, p.poses_b.front());
    for (const Eigen::Isometry3d& pose : p.poses_b) {
      pair.set_pose_b(pose);
      const double w = query_value(pair, q);
      warm_iterations += pair.last_iterations();
      double c = 0;
      int iterations = 0;
      if (q == WarmQuery::kDistance) {
        const hullcheck::DistanceResult r = hullcheck::distance(p.a, p.pose_a, p.b, pose);
        c = r.distance;
        iterations = r.iterations;
      } else {
        const hullcheck::SignedDistanceResult r =
            hullcheck::signed_distance(p.a, p.pose_a, p.b, pose);
        c = r.signed_distance;
        iterations = r.iterations;
      }
      cold_iterations += iterations;
      diff = std::max(diff, std::abs(w - c));
      if (c <= 0) {
        ++overlapping;
      } else {
        warm_apart += pair.last_iterations();
        cold_apart += iterations;
      }
      ++queries;
    }
  }
  warm.mean_iterations = warm_iterations / static_cast<double>(queries);
  cold.mean_iterations = cold_iterations / static_cast<double>(queries);
  warm.max_warm_cold_diff = cold.max_warm_cold_diff = diff;
  warm.overlapping_fraction = cold.overlapping_fraction =
      static_cast<double>(overlapping) / static_cast<double>(queries);
  const double apart = static_cast<double>(queries - overlapping);
  warm.mean_iterations_apart = apart > 0 ? warm_apart / apart : std::nan("");
  cold.mean_iterations_apart = apart > 0 ? cold_apart / apart : std::nan("");
  warm.queries = cold.queries = queries;
  warm.scored = cold.scored = true;
}

void register_warm(Entry& warm, Entry& cold, const std::vector<Path>* paths, WarmQuery q) {
  const std::size_t n = warm.queries;
  const std::string warm_name = bench_name(warm.query, warm.set, warm.impl);
  g_by_name[warm_name] = &warm;
  benchmark::RegisterBenchmark(warm_name.c_str(), [paths, q, n](benchmark::State& state) {
    std::vector<hullcheck::ProximityPair> pairs(paths->size());
    for (std::size_t k = 0; k < paths->size(); ++k) {
      pairs[k].set_shape_a((*paths)[k].a, (*paths)[k].pose_a);
      pairs[k].set_shape_b((*paths)[k].b, (*paths)[k].poses_b.front());
    }
    for (auto _ : state) {
      for (std::size_t k = 0; k < paths->size(); ++k) {
        for (const Eigen::Isometry3d& pose : (*paths)[k].poses_b) {
          pairs[k].set_pose_b(pose);
          benchmark::DoNotOptimize(query_value(pairs[k], q));
        }
      }
    }
    set_counters(state, n);
  });
  const std::string cold_name = bench_name(cold.query, cold.set, cold.impl);
  g_by_name[cold_name] = &cold;
  benchmark::RegisterBenchmark(cold_name.c_str(), [paths, q, n](benchmark::State& state) {
    for (auto _ : state) {
      for (const Path& p : *paths) {
        for (const Eigen::Isometry3d& pose : p.poses_b) {
          if (q == WarmQuery::kDistance) {
            benchmark::DoNotOptimize(hullcheck::distance(p.a, p.pose_a, p.b, pose));
          } else {
            benchmark::DoNotOptimize(hullcheck::signed_distance(p.a, p.pose_a, p.b, pose));
          }
        }
      }
    }
    set_counters(state, n);
  });
}

// ---------------------------------------------------------------------------------------------
// Reporter: the console output as usual, plus the CPU time per query for the tables.

class CollectingReporter : public benchmark::ConsoleReporter {
 public:
  // A reporter passed to RunSpecifiedBenchmarks does not get the library's colour
  // auto-detection: colour only on a terminal.
  CollectingReporter() : ConsoleReporter(isatty(fileno(stdout)) != 0 ? OO_Defaults : OO_Tabular) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    // Iteration runs give the fastest repetition; with --benchmark_display_aggregates_only only
    // aggregates arrive here, and the median is used instead (see finish()).
    for (const Run& run : runs) {
      if (run.error_occurred || run.iterations == 0) continue;
      auto it = g_by_name.find(run.run_name.function_name);
      if (it == g_by_name.end()) continue;
      Entry& e = *it->second;
      const double ns = run.cpu_accumulated_time * 1e9 /
                        (static_cast<double>(run.iterations) * static_cast<double>(e.queries));
      if (run.run_type == Run::RT_Iteration) {
        if (!(ns >= e.ns)) e.ns = ns;  // keep the fastest repetition
      } else if (run.aggregate_name == "median") {
        e.median_ns = ns;
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  static void finish() {
    for (Entry& e : g_entries) {
      if (std::isnan(e.ns)) e.ns = e.median_ns;
    }
  }
};

// ---------------------------------------------------------------------------------------------
// Tables

std::string fmt(double v, int precision = 3, bool sci = false) {
  if (std::isnan(v)) return "—";
  if (std::isinf(v)) return "inf";
  std::ostringstream s;
  if (sci) {
    s << std::scientific << std::setprecision(1) << v;
  } else {
    s << std::fixed << std::setprecision(precision) << v;
  }
  return s.str();
}

std::string fmt_ns(double ns) {
  if (std::isnan(ns)) return "—";
  std::ostringstream s;
  s << std::fixed << std::setprecision(ns < 100 ? 1 : 0) << ns;
  return s.str();
}

std::string fmt_err(double e) { return e == 0.0 ? "0" : fmt(e, 0, true); }

const Entry* find_entry(const std::string& query, const std::string& set, const std::string& impl) {
  for (const Entry& e : g_entries) {
    if (e.query == query && e.set == set && e.impl == impl) return &e;
  }
  return nullptr;
}

std::string aux_label(const std::string& query) {
  if (query == "distance") return "witness err";
  if (query == "penetration") return "normal err";
  return "";
}

void print_tables(std::ostream& out, const std::vector<hb::DataSet>& sets,
                  const std::vector<double>& max_scales, const std::vector<std::string>& impl_names,
                  const Options& options) {
  const char* queries[] = {"intersect", "distance", "penetration", "signed_distance"};
  out << "\n## hullcheck vs peers" << (options.quick ? " (quick mode: few pairs, short runs)" : "")
      << "\n\n";
  out << "Time: CPU ns per query (mean over the pair list). Errors: largest |value - oracle| over "
         "the pairs (distance: brute_force_distance; depth: minkowski_penetration). witness err: "
         "largest distance of a reported closest point from its hull, or of |p_b - p_a| from the "
         "true distance. normal err: depth along the reported normal (max a.n - min b.n) minus "
         "the true depth. wrong: verdicts contradicting the oracle by more than 1e-9 x scale. "
         "fail/flag: no answer (failure status, exception, NaN) / answered but flagged as not "
         "converged (hullcheck's status). "
         "vs hullcheck: this implementation's time / hullcheck's time (> 1: hullcheck faster).\n";
  for (const hb::DataSet& set : sets) {
    out << "\n### " << set.name << ": " << set.description << "\n\n";
    out << "| query | implementation | ns/query | vs hullcheck | max error | witness/normal err "
           "| wrong | fail/flag |\n";
    out << "|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const char* q : queries) {
      const Entry* hc = find_entry(q, set.name, "hullcheck");
      for (const std::string& impl : impl_names) {
        const Entry* e = find_entry(q, set.name, impl);
        if (e == nullptr) continue;
        const Score& s = e->score;
        const double ratio = hc != nullptr ? e->ns / hc->ns : std::nan("");
        out << "| " << q << " | " << impl << " | " << fmt_ns(e->ns) << " | "
            << (impl == "hullcheck" ? std::string("1") : fmt(ratio, 2)) << " | "
            << (std::string(q) == "intersect" ? "—" : fmt_err(s.max_error)) << " | "
            << (aux_label(q).empty() ? "—" : fmt_err(s.aux_error)) << " | " << s.wrong << "/"
            << s.cases << " | " << s.failed << "/" << s.flagged
            << (s.exception.empty() ? "" : " (threw: " + s.exception + ")") << " |\n";
      }
    }
  }

  out << "\n### Summary: fastest peer vs hullcheck\n\n"
      << "ratio = peer time / hullcheck time (> 1: hullcheck faster). \"Exact\" peer: no wrong "
         "verdict, no failure, and max error and witness/normal error <= 1e-9 x the largest "
         "scale of the set (hullcheck's own accuracy promise).\n\n";
  out << "| query | set | hullcheck ns | hullcheck max err | fastest peer | ns | max err | ratio "
         "| fastest exact peer | ns | ratio |\n";
  out << "|---|---|---:|---:|---|---:|---:|---:|---|---:|---:|\n";
  for (const char* q : queries) {
    for (std::size_t k = 0; k < sets.size(); ++k) {
      const hb::DataSet& set = sets[k];
      const Entry* hc = find_entry(q, set.name, "hullcheck");
      if (hc == nullptr) continue;
      const Entry* best = nullptr;
      const Entry* best_exact = nullptr;
      for (const std::string& impl : impl_names) {
        if (impl == "hullcheck") continue;
        const Entry* e = find_entry(q, set.name, impl);
        if (e == nullptr || std::isnan(e->ns)) continue;
        if (best == nullptr || e->ns < best->ns) best = e;
        const Score& sc = e->score;
        const double limit = 1e-9 * max_scales[k];
        const bool exact = sc.exception.empty() && sc.wrong == 0 && sc.failed == 0 &&
                           sc.max_error <= limit && sc.aux_error <= limit;
        if (exact && (best_exact == nullptr || e->ns < best_exact->ns)) best_exact = e;
      }
      const bool is_intersect = std::string(q) == "intersect";
      out << "| " << q << " | " << set.name << " | " << fmt_ns(hc->ns) << " | "
          << (is_intersect ? "—" : fmt_err(hc->score.max_error)) << " | "
          << (best ? best->impl : "—") << " | " << (best ? fmt_ns(best->ns) : "—") << " | "
          << (best && !is_intersect ? fmt_err(best->score.max_error) : "—") << " | "
          << (best ? fmt(best->ns / hc->ns, 2) : "—") << " | "
          << (best_exact ? best_exact->impl : "none") << " | "
          << (best_exact ? fmt_ns(best_exact->ns) : "—") << " | "
          << (best_exact ? fmt(best_exact->ns / hc->ns, 2) : "—") << " |\n";
    }
  }

  out << "\n### Warm start: ProximityPair (set_pose_b, B moving 1% of the shape size and 0.01 rad "
         "per step) vs the cold free function on the same poses\n\n";
  out << "Iterations: GJK iterations (plus EPA iterations for overlapping signed_distance), "
         "from last_iterations() and the results' iterations; \"apart\": mean over the poses "
         "where the shapes are apart.\n\n";
  out << "| query | set | queries | overlapping | cold ns | warm ns | cold/warm | cold mean iters "
         "| warm mean iters | apart: cold iters | apart: warm iters | max abs(warm - cold) |\n";
  out << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const char* q : {"distance", "signed_distance"}) {
    for (const hb::DataSet& set : sets) {
      const Entry* warm = find_entry(std::string("warm_") + q, set.name, "ProximityPair");
      const Entry* cold = find_entry(std::string("warm_") + q, set.name, "cold");
      if (warm == nullptr || cold == nullptr) continue;
      out << "| " << q << " | " << set.name << " | " << warm->queries << " | "
          << fmt(100.0 * warm->overlapping_fraction, 0) << "% | " << fmt_ns(cold->ns) << " | "
          << fmt_ns(warm->ns) << " | " << fmt(cold->ns / warm->ns, 2) << " | "
          << fmt(cold->mean_iterations, 2) << " | " << fmt(warm->mean_iterations, 2) << " | "
          << fmt(cold->mean_iterations_apart, 2) << " | " << fmt(warm->mean_iterations_apart, 2)
          << " | " << fmt_err(warm->max_warm_cold_diff) << " |\n";
    }
  }
}

void print_apis(std::ostream& out, const std::vector<std::unique_ptr<hb::Impl>>& impls) {
  out << "\n### What each implementation runs\n\n| implementation | query | API |\n|---|---|---|\n";
  for (const auto& impl : impls) {
    for (hb::Query q : {hb::Query::kIntersect, hb::Query::kDistance, hb::Query::kPenetration,
                        hb::Query::kSignedDistance}) {
      out << "| " << impl->name() << " | " << hb::to_string(q) << " | "
          << (impl->supports(q) ? impl->api(q) : "— (" + impl->api(q) + ")") << " |\n";
    }
  }
}

// Worst cases of hullcheck, to make problems reproducible.
void print_hullcheck_worst(std::ostream& out, const std::vector<hb::DataSet>& sets,
                           const std::vector<std::vector<hb::Truth>>& truths) {
  bool header = false;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    for (const Entry& e : g_entries) {
      if (e.impl != "hullcheck" || e.set != sets[s].name || !e.scored) continue;
      const Score& sc = e.score;
      const hb::Truth& t = truths[s][sc.worst];
      const double tol = 1e-9 * t.scale;
      if (sc.max_error <= tol && sc.wrong == 0 && sc.failed == 0 && sc.exception.empty()) continue;
      if (!header) {
        out << "\n### hullcheck cases beyond 1e-9 x scale\n\n";
        header = true;
      }
      out << "- " << e.query << " / " << e.set << ": max error " << fmt_err(sc.max_error)
          << " at pair " << sc.worst << " (oracle: "
          << (t.overlapping ? "overlapping, depth " + fmt(t.depth, 12)
                            : "apart, distance " + fmt(t.distance, 12))
          << ", scale " << fmt(t.scale, 4) << "), wrong " << sc.wrong << ", fail " << sc.failed
          << (sc.exception.empty() ? "" : ", threw: " + sc.exception) << "\n";
    }
  }
}

Options parse_options(int& argc, char** argv) {
  Options o;
  o.shared_dir = hb::shared_dir();
  hb::take_program_flags(argc, argv,
                         "bench_core [--quick] [--no-robots] [--pairs=N] [--table=FILE] "
                         "[benchmark flags]\n  HULLCHECK_SHARED_DIR: directory with robots/",
                         [&o](const std::string& arg) {
                           if (arg == "--quick") {
                             o.quick = true;
                           } else if (arg == "--no-robots") {
                             o.robots = false;
                           } else if (arg.rfind("--pairs=", 0) == 0) {
                             o.pairs = std::atoi(arg.c_str() + 8);
                           } else if (arg.rfind("--table=", 0) == 0) {
                             o.table_file = arg.substr(8);
                           } else {
                             return false;
                           }
                           return true;
                         });
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  Options options = parse_options(argc, argv);
  // Defaults unless the caller chose: quick mode runs each benchmark for ~2 ms; a full run
  // repeats each 3 times (0.2 s each) and reports the fastest repetition, which is robust to
  // other load on the machine.
  if (!hullcheck::bench::initialize_benchmark(argc, argv, options.quick, 0.002, 3)) return 1;

  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  auto t0 = std::chrono::steady_clock::now();

  // 1. Data.
  struct SetSpec {
    int vertices, full, quick;
  };
  const SetSpec specs[] = {{8, 256, 32}, {32, 256, 32}, {128, 256, 16}, {512, 128, 8}};
  std::vector<hb::DataSet> sets;
  for (const SetSpec& spec : specs) {
    const int count = options.pairs > 0 ? options.pairs : (options.quick ? spec.quick : spec.full);
    sets.push_back(hb::make_random_set(kSeed + static_cast<std::uint64_t>(spec.vertices), count,
                                       spec.vertices));
  }
  if (options.robots) {
    const int count = options.pairs > 0 ? options.pairs : (options.quick ? 16 : 128);
    hb::DataSet robots = hb::make_robot_set(options.shared_dir, kSeed + 1, count);
    if (robots.cases.empty()) {
      std::cerr << "bench_core: no robot meshes under " << options.shared_dir
                << "/robots: skipping the robot set\n";
    } else {
      sets.push_back(std::move(robots));
    }
  }
  std::cerr << "bench_core: data built in " << fmt(seconds_since(t0), 1) << " s\n";

  // 2. Oracle answers and accuracy of every implementation.
  t0 = std::chrono::steady_clock::now();
  std::vector<std::vector<hb::Truth>> truths;
  for (const hb::DataSet& set : sets) truths.push_back(hb::compute_truth(set.cases, threads));
  std::cerr << "bench_core: oracle answers in " << fmt(seconds_since(t0), 1) << " s\n";

  std::vector<std::string> impl_names;
  {
    auto hc = hb::make_hullcheck_impl();
    impl_names.push_back(hc->name());
    for (const auto& p : hb::make_peer_impls()) impl_names.push_back(p->name());
  }
  std::vector<std::vector<std::unique_ptr<hb::Impl>>> impls(sets.size());  // [set][impl]
  const hb::Query all_queries[] = {hb::Query::kIntersect, hb::Query::kDistance,
                                   hb::Query::kPenetration, hb::Query::kSignedDistance};
  t0 = std::chrono::steady_clock::now();
  for (std::size_t s = 0; s < sets.size(); ++s) {
    impls[s].push_back(hb::make_hullcheck_impl());
    for (auto& p : hb::make_peer_impls()) impls[s].push_back(std::move(p));
    for (auto& impl : impls[s]) {
      std::string prepare_error;
      try {
        impl->prepare(sets[s].cases);
      } catch (const std::exception& e) {
        prepare_error = e.what();
      }
      for (hb::Query q : all_queries) {
        if (!impl->supports(q)) continue;
        Entry& e = g_entries.emplace_back();
        e.set = sets[s].name;
        e.query = hb::to_string(q);
        e.impl = impl->name();
        e.api = impl->api(q);
        e.queries = sets[s].cases.size();
        if (prepare_error.empty()) {
          e.score = score(*impl, q, sets[s].cases, truths[s]);
        } else {
          e.score.exception = "prepare: " + prepare_error;
        }
        e.scored = true;
        // Only time what ran without exceptions.
        if (e.score.exception.empty()) register_query(e, impl.get(), q);
      }
    }
  }
  std::cerr << "bench_core: accuracy scored in " << fmt(seconds_since(t0), 1) << " s\n";

  // 4. Warm start paths (measured once here, timed below).
  std::vector<std::vector<Path>> paths(sets.size());
  for (std::size_t s = 0; s < sets.size(); ++s) {
    paths[s] = make_paths(sets[s], options.quick ? 2 : 8, options.quick ? 50 : 200);
    for (WarmQuery q : {WarmQuery::kDistance, WarmQuery::kSignedDistance}) {
      const std::string name =
          std::string("warm_") + (q == WarmQuery::kDistance ? "distance" : "signed_distance");
      Entry& warm = g_entries.emplace_back();
      warm.set = sets[s].name;
      warm.query = name;
      warm.impl = "ProximityPair";
      Entry& cold = g_entries.emplace_back();
      cold.set = sets[s].name;
      cold.query = name;
      cold.impl = "cold";
      try {
        measure_warm(warm, cold, paths[s], q);
        register_warm(warm, cold, &paths[s], q);
      } catch (const std::exception& ex) {
        std::cerr << "bench_core: warm start " << name << " / " << sets[s].name
                  << " threw: " << ex.what() << "\n";
      }
    }
  }

  // 3. Timing (all registered benchmarks).
  CollectingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  CollectingReporter::finish();
  benchmark::Shutdown();

  // 5. Tables.
  std::ostringstream tables;
  std::vector<double> max_scales;
  for (const auto& truth : truths) {
    double m = 0;
    for (const hb::Truth& t : truth) m = std::max(m, t.scale);
    max_scales.push_back(m);
  }
  print_tables(tables, sets, max_scales, impl_names, options);
  print_hullcheck_worst(tables, sets, truths);
  print_apis(tables, impls.front());
  std::cout << tables.str() << std::flush;
  if (!options.table_file.empty()) {
    std::ofstream file(options.table_file);
    file << tables.str();
  }

  // Smoke-run verdict: hullcheck must answer without exceptions.
  int status = 0;
  for (const Entry& e : g_entries) {
    if (e.impl == "hullcheck" && !e.score.exception.empty()) status = 1;
  }
  return status;
}
