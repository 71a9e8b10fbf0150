// hullcheck::core: exact proximity queries (collision, distance, penetration) between convex
// shapes. One include for the whole proximity core.
//
// Design: A. Casalino, "How to use the GJK_EPA class" (2019), kept with the test data as
// shared/seed/gjk_epa_design.txt. Comments cite it as "Casalino" with its section, equation,
// figure or algorithm number: Algorithm 1 (GJK's closest region, section 2), Algorithm 2 (the
// boolean GJK, section 2.1), Algorithm 3 (EPA, section 3), the caching pair's state machine
// (section 4, figure 14), X-Y-Z angles (appendix B). ARCHITECTURE.md maps them to files.
#pragma once

#include <hullcheck/core/convex_hull.hpp>
#include <hullcheck/core/errors.hpp>
#include <hullcheck/core/limits.hpp>
#include <hullcheck/core/pose.hpp>
#include <hullcheck/core/primitives.hpp>
#include <hullcheck/core/proximity_pair.hpp>
#include <hullcheck/core/queries.hpp>
#include <hullcheck/core/query_options.hpp>
#include <hullcheck/core/query_result.hpp>
#include <hullcheck/core/shape.hpp>
#include <hullcheck/core/warm_start.hpp>
