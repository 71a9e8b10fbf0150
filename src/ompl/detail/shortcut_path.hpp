// One pass of OMPL's random shortcuts, across the OMPL versions hullcheck supports (private to
// the ompl layer's sources).
#pragma once

#include <ompl/config.h>
#include <ompl/geometric/PathSimplifier.h>

namespace hullcheck::detail {

/// PathSimplifier::shortcutPath, renamed partialShortcutPath in OMPL 1.7 (same arguments and
/// meaning: up to max_steps attempts, stopping after max_empty_steps failed ones; 0 lets OMPL
/// choose from the path's size). True when the path changed. Shortcuts are accepted only when
/// the simplifier's objective does not get worse and the motion validator passes them.
inline bool shortcut_path(::ompl::geometric::PathSimplifier& simplifier,
                          ::ompl::geometric::PathGeometric& path, unsigned max_steps = 0,
                          unsigned max_empty_steps = 0) {
#if OMPL_VERSION_VALUE >= 1007000
  return simplifier.partialShortcutPath(path, max_steps, max_empty_steps);
#else
  return simplifier.shortcutPath(path, max_steps, max_empty_steps);
#endif
}

}  // namespace hullcheck::detail
