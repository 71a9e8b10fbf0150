// hullcheck::core: exact proximity queries (collision, distance, penetration) between convex
// shapes. One include for the whole proximity core.
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
