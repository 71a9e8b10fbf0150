// A clearance profile along a path as a self-contained SVG plot.
#pragma once

#include <string>
#include <vector>

namespace hullcheck::cli {

/// One sample of the profile.
struct ClearanceSample {
  double position;   ///< Joint-space arc length from the start (rad/m mixed, as OMPL's).
  double clearance;  ///< Signed clearance, m.
  bool waypoint;     ///< A path waypoint (drawn as a dot) rather than an interpolated state.
};

/// One line of a plot: its samples, legend label (none when empty), colour and dash.
struct ClearanceCurve {
  std::string label;
  std::string color = "#1f77b4";
  bool dashed = false;
  std::vector<ClearanceSample> samples;
};

/// Writes an SVG plot of the curves (position on x, clearance on y, waypoints as dots, the zero
/// line in red, a legend of the labelled curves) titled `title` to `file`. Throws InputError
/// when the file cannot be written.
void write_clearance_svg(const std::string& file, const std::string& title,
                         const std::vector<ClearanceCurve>& curves);

/// Writes an SVG line plot of `samples` (position on x, clearance on y, the zero line in red)
/// titled `title` to `file`. Throws InputError when the file cannot be written.
void write_clearance_svg(const std::string& file, const std::string& title,
                         const std::vector<ClearanceSample>& samples);

}  // namespace hullcheck::cli
