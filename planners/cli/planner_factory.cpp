#include "planner_factory.hpp"

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/fmt/BFMT.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/ABITstar.h>
#include <ompl/geometric/planners/informedtrees/AITstar.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/prm/SPARS.h>
#include <ompl/geometric/planners/prm/SPARStwo.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTsharp.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/SORRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/sst/SST.h>
#include <ompl/geometric/planners/stride/STRIDE.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/ompl/objectives.hpp>
#include <map>

namespace hullcheck::cli {
namespace {

namespace ob = ::ompl::base;
namespace og = ::ompl::geometric;

using Factory = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr&)>;

template <class P>
Factory make() {
  return [](const ob::SpaceInformationPtr& si) { return std::make_shared<P>(si); };
}

// Usual spelling -> constructor.
const std::vector<std::pair<std::string, Factory>>& planners() {
  static const std::vector<std::pair<std::string, Factory>> list = {
      {"RRTConnect", make<og::RRTConnect>()},
      {"RRT", make<og::RRT>()},
      {"RRT*", make<og::RRTstar>()},
      {"InformedRRT*", make<og::InformedRRTstar>()},
      {"SORRT*", make<og::SORRTstar>()},
      {"RRT#", make<og::RRTsharp>()},
      {"LazyRRT", make<og::LazyRRT>()},
      {"TRRT", make<og::TRRT>()},
      {"BiTRRT", make<og::BiTRRT>()},
      {"LBTRRT", make<og::LBTRRT>()},
      {"BIT*", make<og::BITstar>()},
      {"ABIT*", make<og::ABITstar>()},
      {"AIT*", make<og::AITstar>()},
      {"PRM", make<og::PRM>()},
      {"PRM*", make<og::PRMstar>()},
      {"LazyPRM", make<og::LazyPRM>()},
      {"LazyPRM*", make<og::LazyPRMstar>()},
      {"SPARS", make<og::SPARS>()},
      {"SPARS2", make<og::SPARStwo>()},
      {"FMT*", make<og::FMT>()},
      {"BFMT*", make<og::BFMT>()},
      {"KPIECE1", make<og::KPIECE1>()},
      {"BKPIECE1", make<og::BKPIECE1>()},
      {"LBKPIECE1", make<og::LBKPIECE1>()},
      {"EST", make<og::EST>()},
      {"BiEST", make<og::BiEST>()},
      {"SBL", make<og::SBL>()},
      {"STRIDE", make<og::STRIDE>()},
      {"PDST", make<og::PDST>()},
      {"SST", make<og::SST>()},
  };
  return list;
}

// Lower case, "star" -> "*".
std::string canonical(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (std::size_t at; (at = name.find("star")) != std::string::npos;) name.replace(at, 4, "*");
  return name;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<std::string> planner_names() {
  std::vector<std::string> names;
  for (const auto& entry : planners()) names.push_back(entry.first);
  return names;
}

ob::PlannerPtr make_planner(const std::string& name, const ob::SpaceInformationPtr& si) {
  const std::string wanted = canonical(name);
  for (const auto& [known, factory] : planners()) {
    if (canonical(known) == wanted) return factory(si);
  }
  throw InputError("unknown planner '" + name + "' (known: " + joined(planner_names()) + ")");
}

ob::OptimizationObjectivePtr make_objective(const std::string& name,
                                            const ob::SpaceInformationPtr& si) {
  if (name == "length") return std::make_shared<ob::PathLengthOptimizationObjective>(si);
  if (name == "clearance") return make_max_min_clearance_objective(si);
  if (name == "clearance-cost") return std::make_shared<ClearanceCostObjective>(si);
  if (name == "length+clearance") return make_length_clearance_objective(si, 1.0, 1.0);
  throw InputError("unknown objective '" + name +
                   "' (known: length, clearance, clearance-cost, length+clearance)");
}

}  // namespace hullcheck::cli
