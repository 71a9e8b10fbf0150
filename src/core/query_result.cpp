#include <hullcheck/core/query_result.hpp>

namespace hullcheck {

const char* to_string(Status status) {
  switch (status) {
    case Status::kConverged:
      return "converged";
    case Status::kIterationCap:
      return "iteration cap";
    case Status::kDegenerate:
      return "degenerate";
    case Status::kAboveCutoff:
      return "above cutoff";
  }
  return "unknown";
}

}  // namespace hullcheck
