// Input and output of CollisionChecker::check_motion: a straight joint-space motion proven
// collision-free at every point, or the first contact along it.
#pragma once

#include <string>

namespace hullcheck {

/// How a motion check ended.
enum class MotionVerdict {
  kFree,         ///< Every configuration of the motion keeps clearance > min_clearance.
  kContact,      ///< Proven to collide: some configuration has a checked pair within
                 ///< min_clearance (m) of touching, or overlapping.
  kNearContact,  ///< Not proven free: a configuration has a pair within min_clearance +
                 ///< resolution / 100 of touching, and no finer test was made (see
                 ///< MotionCheckOptions); none within min_clearance was found.
  kStateBudget,  ///< max_states configurations were evaluated before a decision.
};

/// Tolerances and budget of CollisionChecker::check_motion.
struct MotionCheckOptions {
  /// m, >= 0: clearances at or below this count as contact (1e-6: touching shapes).
  double min_clearance = 1e-6;
  /// m, > 0: the finest relative motion the search resolves. An interval is split while some
  /// undecided pair can move more than this within it, and below that only while the pair's
  /// clearance at the interval's middle exceeds min_clearance by more than resolution / 100
  /// (its proven window then decides it in a few more intervals). So a motion passing within
  /// min_clearance + resolution / 100 of contact may be rejected (kNearContact), one passing at
  /// min_clearance or closer always is. Also bounds how far last_free lies before the contact.
  double resolution = 1e-4;
  /// Configurations evaluated at most (one forward kinematics each); >= 1.
  int max_states = 100000;
  /// true: on a contact, search on for the first one, so that `contact` and `last_free` locate
  /// it within `resolution`. false: stop at the first contact found (a yes/no answer, as OMPL's
  /// checkMotion(s1, s2) needs; cheaper): the end state is checked first (is_valid; a
  /// collision there is reported as the contact at 1), then intervals are examined level by
  /// level, as OMPL's discrete validator orders its states, so a contact is found at the coarsest
  /// level holding one (when the first level needed many exact queries, the midpoints of the next
  /// three levels are first probed for collision a block at a time, is_valid_batch's way, the
  /// first colliding one in level order being the contact); last_free is 0 and `contact` the
  /// state found, not necessarily the first.
  bool locate_contact = true;
  /// Yes/no mode only: test the end state first (is_valid), since a planner's new state, most
  /// often the motion's end, collides more often than the rest of it. A caller whose end state
  /// is known valid (the motion starts at the state just validated and ends at an existing one)
  /// sets it false: whether the motion is proven free does not change, only the order of the
  /// work (with a valid end state, the same verdict; with a colliding one, a contact found
  /// elsewhere, or near contact).
  bool end_first = true;
};

/// Throws InputError, prefixed with `who`, unless min_clearance is finite and >= 0, resolution
/// finite and > 0 and max_states >= 1.
void validate(const MotionCheckOptions& options, const std::string& who);

/// Result of CollisionChecker::check_motion. Fractions are of the motion: t in [0, 1] is the
/// configuration q0 + t (q1 - q0).
struct MotionCheckResult {
  MotionVerdict verdict = MotionVerdict::kFree;
  /// [0, last_free] is proven free (clearance > min_clearance everywhere); 1 when kFree.
  double last_free = 1.0;
  /// kContact / kNearContact: the fraction of the first configuration the search found within
  /// min_clearance + resolution of touching, with last_free <= contact and no checked pair
  /// moving more than `resolution` (by the lever-arm bound) between the two. So the first
  /// contact of the motion lies after last_free, and when it lies before `contact` it is within
  /// that travel of it. 1 when kFree; last_free when kStateBudget.
  double contact = 1.0;
  int states = 0;         ///< Configurations evaluated (forward kinematics each).
  int exact_queries = 0;  ///< GJK queries run (pairs or bounding hulls the balls did not decide).

  bool free() const { return verdict == MotionVerdict::kFree; }
};

}  // namespace hullcheck
