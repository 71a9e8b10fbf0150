// OMPL geometric planners by name, and optimization objectives by name.
#pragma once

#include <ompl/base/OptimizationObjective.h>
#include <ompl/base/Planner.h>

#include <string>
#include <vector>

namespace hullcheck::cli {

/// The planner called `name` ("RRTConnect", "RRT*", "BIT*", "PRM*", "LazyPRM", "KPIECE1", ...;
/// "*" and "star" are interchangeable, case is ignored). Throws InputError listing the names.
::ompl::base::PlannerPtr make_planner(const std::string& name,
                                      const ::ompl::base::SpaceInformationPtr& si);
/// The names make_planner accepts, in their usual spelling.
std::vector<std::string> planner_names();

/// Objective by name: "length" (path length), "clearance" (maximise the minimum clearance),
/// "clearance-cost" (integral of exp(-clearance / 5 cm)), "length+clearance" (length plus the
/// clearance cost, equal weights). Throws InputError listing the names.
::ompl::base::OptimizationObjectivePtr make_objective(const std::string& name,
                                                      const ::ompl::base::SpaceInformationPtr& si);

}  // namespace hullcheck::cli
