// hullcheck: exact proximity queries (collision, distance, penetration) between convex shapes.
// One include for the whole proximity core.
#pragma once

#include <hullcheck/convex_hull.hpp>
#include <hullcheck/errors.hpp>
#include <hullcheck/limits.hpp>
#include <hullcheck/pose.hpp>
#include <hullcheck/primitives.hpp>
#include <hullcheck/proximity_pair.hpp>
#include <hullcheck/queries.hpp>
#include <hullcheck/query_options.hpp>
#include <hullcheck/query_result.hpp>
#include <hullcheck/shape.hpp>
