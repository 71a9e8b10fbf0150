#include "clearance_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <hullcheck/core/errors.hpp>

namespace hullcheck::cli {
namespace {

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '&') {
      out += "&amp;";
    } else {
      out += c;
    }
  }
  return out;
}

// Round tick values over [lo, hi]: multiples of a step of 1, 2 or 5 times a power of ten, about
// `count` intervals of it, and the decimals that print that step exactly.
struct Ticks {
  double first = 0.0;  // the smallest multiple of step >= lo
  double step = 1.0;
  int count = 0;  // ticks first, first + step, ... up to hi
  int decimals = 0;
};

Ticks round_ticks(double lo, double hi, int intervals) {
  Ticks t;
  const double raw = (hi - lo) / intervals;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double mantissa = raw / power;  // in [1, 10)
  t.step = (mantissa <= 1.5 ? 1.0 : mantissa <= 3.0 ? 2.0 : mantissa <= 7.0 ? 5.0 : 10.0) * power;
  t.first = std::ceil(lo / t.step - 1e-9) * t.step;
  t.count = static_cast<int>(std::floor((hi - t.first) / t.step + 1e-9)) + 1;
  t.decimals = std::max(0, -static_cast<int>(std::floor(std::log10(t.step) + 1e-9)));
  return t;
}

// Tick i of `t`, 0 exactly where the multiple is zero (no "-0.000").
double tick(const Ticks& t, int i) {
  const double v = t.first + i * t.step;
  return std::abs(v) < 1e-9 * t.step ? 0.0 : v;
}

}  // namespace

void write_clearance_svg(const std::string& file, const std::string& title,
                         const std::vector<ClearanceSample>& samples) {
  ClearanceCurve curve;
  curve.samples = samples;
  write_clearance_svg(file, title, std::vector<ClearanceCurve>{curve});
}

void write_clearance_svg(const std::string& file, const std::string& title,
                         const std::vector<ClearanceCurve>& curves) {
  std::ofstream out(file);
  if (!out) throw InputError("plot '" + file + "': cannot write");
  const double width = 800, height = 400, left = 70, right = 20, top = 40, bottom = 50;
  double x_max = 0, y_min = 0, y_max = 0;
  for (const ClearanceCurve& curve : curves) {
    for (const ClearanceSample& s : curve.samples) {
      x_max = std::max(x_max, s.position);
      if (std::isfinite(s.clearance)) {
        y_min = std::min(y_min, s.clearance);
        y_max = std::max(y_max, s.clearance);
      }
    }
  }
  if (x_max <= 0) x_max = 1;
  if (y_max <= y_min) y_max = y_min + 1e-3;
  const double pad = 0.05 * (y_max - y_min);
  y_min -= pad;
  y_max += pad;
  const auto px = [&](double x) { return left + (width - left - right) * x / x_max; };
  const auto py = [&](double y) {
    return top + (height - top - bottom) * (y_max - y) / (y_max - y_min);
  };
  char buf[256];
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">"
      << escape(title) << "</text>\n";
  // Axes, ticks and labels.
  std::snprintf(buf, sizeof buf,
                "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"black\"/>\n"
                "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"black\"/>\n",
                left, top, left, height - bottom, left, height - bottom, width - right,
                height - bottom);
  out << buf;
  const Ticks y_ticks = round_ticks(y_min, y_max, 5);
  for (int i = 0; i < y_ticks.count; ++i) {
    const double y = tick(y_ticks, i);
    std::snprintf(buf, sizeof buf,
                  "<text x=\"%g\" y=\"%g\" text-anchor=\"end\">%.*f</text>\n"
                  "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"#ddd\"/>\n",
                  left - 6, py(y) + 4, y_ticks.decimals, y, left, py(y), width - right, py(y));
    out << buf;
  }
  const Ticks x_ticks = round_ticks(0.0, x_max, 5);
  for (int i = 0; i < x_ticks.count; ++i) {
    const double x = tick(x_ticks, i);
    std::snprintf(buf, sizeof buf, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">%.*f</text>\n",
                  px(x), height - bottom + 18, x_ticks.decimals, x);
    out << buf;
  }
  std::snprintf(buf, sizeof buf,
                "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">path length (joint space)</text>\n"
                "<text x=\"16\" y=\"%g\" transform=\"rotate(-90 16 %g)\" "
                "text-anchor=\"middle\">signed clearance (m)</text>\n",
                (left + width - right) / 2, height - 10, (top + height - bottom) / 2,
                (top + height - bottom) / 2);
  out << buf;
  if (y_min < 0 && y_max > 0) {
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"red\" "
                  "stroke-dasharray=\"4 3\"/>\n",
                  left, py(0), width - right, py(0));
    out << buf;
  }
  int legend = 0;
  for (const ClearanceCurve& curve : curves) {
    const std::string color = escape(curve.color);
    out << "<polyline fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1.5\""
        << (curve.dashed ? " stroke-dasharray=\"6 4\"" : "") << " points=\"";
    for (const ClearanceSample& s : curve.samples) {
      if (!std::isfinite(s.clearance)) continue;
      std::snprintf(buf, sizeof buf, "%.2f,%.2f ", px(s.position), py(s.clearance));
      out << buf;
    }
    out << "\"/>\n";
    for (const ClearanceSample& s : curve.samples) {
      if (!s.waypoint || !std::isfinite(s.clearance)) continue;
      std::snprintf(buf, sizeof buf, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"%s\"/>\n",
                    px(s.position), py(s.clearance), s.clearance > 0 ? color.c_str() : "red");
      out << buf;
    }
    if (curve.label.empty()) continue;
    // The legend, top right, one line per labelled curve.
    const double ly = top + 14 + 16 * legend++;
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%g\" y1=\"%g\" x2=\"%g\" y2=\"%g\" stroke=\"%s\" "
                  "stroke-width=\"2\"%s/>\n<text x=\"%g\" y=\"%g\">",
                  width - right - 230, ly - 4, width - right - 200, ly - 4, color.c_str(),
                  curve.dashed ? " stroke-dasharray=\"6 4\"" : "", width - right - 194, ly);
    out << buf << escape(curve.label) << "</text>\n";
  }
  out << "</svg>\n";
  if (!out) throw InputError("plot '" + file + "': write failed");
}

}  // namespace hullcheck::cli
