#include "diagnose/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "dsp/bands.h"
#include "util/strings.h"

namespace tsrir::diagnose {
namespace {

std::string f1(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

// Round tick steps (1, 2, 5 x 10^k) giving about `count` ticks.
std::vector<double> ticks(double lo, double hi, int count) {
  std::vector<double> out;
  if (!(hi > lo)) return out;
  const double raw = (hi - lo) / count;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * mag >= raw) { step = m * mag; break; }
  }
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) out.push_back(std::abs(t) < 1e-12 ? 0.0 : t);
  return out;
}

// Viridis-like ramp through 5 anchor colours.
std::string ramp(double u) {
  static const double c[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  u = std::clamp(u, 0.0, 1.0) * 4.0;
  const int i = std::min(3, static_cast<int>(u));
  const double t = u - i;
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(c[i][0] + t * (c[i + 1][0] - c[i][0])),
                static_cast<int>(c[i][1] + t * (c[i + 1][1] - c[i][1])), static_cast<int>(c[i][2] + t * (c[i + 1][2] - c[i][2])));
  return buf;
}

}  // namespace

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;  // the report quotes its attributes with '
      default: out += c;
    }
  }
  return out;
}

// Legend entries laid out left to right in rows above the frame: (x, row) of each labelled series.
std::vector<std::pair<double, int>> legend_layout(const std::vector<Series>& series, double left, double width,
                                                  int* rows) {
  std::vector<std::pair<double, int>> at;
  double x = left;
  int row = 0;
  for (const Series& se : series) {
    if (se.label.empty()) {
      at.emplace_back(0, -1);
      continue;
    }
    const double entry = 28 + 6.2 * se.label.size();
    if (x > left && x + entry > left + width) x = left, ++row;
    at.emplace_back(x, row);
    x += entry + 10;
  }
  *rows = x > left || row > 0 ? row + 1 : 0;
  return at;
}

std::string svg_plot(const PlotSpec& p) {
  int legend_rows = 0;
  const double left = 58, right = 12, bottom = 40;
  const double w = p.width - left - right;
  const auto legend = legend_layout(p.series, left, w, &legend_rows);
  const double top = 26 + 14.0 * legend_rows;
  const double h = p.height - 26 - bottom;  // the frame keeps its size; the legend adds height
  const double height = p.height + 14.0 * legend_rows;
  auto tx = [&](double x) {
    if (p.log_x) return left + w * (std::log(x / p.x_min) / std::log(p.x_max / p.x_min));
    return left + w * (x - p.x_min) / (p.x_max - p.x_min);
  };
  auto ty = [&](double y) { return top + h * (1.0 - (std::clamp(y, p.y_min, p.y_max) - p.y_min) / (p.y_max - p.y_min)); };
  std::ostringstream s;
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << p.width << "' height='" << height
    << "' font-family='sans-serif' font-size='11'>";
  s << "<rect x='" << left << "' y='" << top << "' width='" << w << "' height='" << h << "' fill='#fff' stroke='#888'/>";
  s << "<text x='" << p.width / 2 << "' y='16' text-anchor='middle' font-size='13'>" << html_escape(p.title) << "</text>";
  std::vector<double> xt;
  if (p.log_x) {
    for (double v = std::pow(10.0, std::floor(std::log10(p.x_min))); v <= p.x_max; v *= 10.0) {
      for (double m : {1.0, 2.0, 5.0}) {
        if (v * m >= p.x_min && v * m <= p.x_max) xt.push_back(v * m);
      }
    }
  } else {
    xt = ticks(p.x_min, p.x_max, 6);
  }
  for (double t : xt) {
    s << "<line x1='" << f1(tx(t)) << "' y1='" << top << "' x2='" << f1(tx(t)) << "' y2='" << top + h
      << "' stroke='#eee'/><text x='" << f1(tx(t)) << "' y='" << top + h + 14 << "' text-anchor='middle'>"
      << format_double(t, 6) << "</text>";
  }
  for (double t : ticks(p.y_min, p.y_max, 5)) {
    s << "<line x1='" << left << "' y1='" << f1(ty(t)) << "' x2='" << left + w << "' y2='" << f1(ty(t))
      << "' stroke='#eee'/><text x='" << left - 4 << "' y='" << f1(ty(t) + 4) << "' text-anchor='end'>"
      << format_double(t, 4) << "</text>";
  }
  for (double m : p.x_markers) {
    if (m < p.x_min || m > p.x_max) continue;
    s << "<line x1='" << f1(tx(m)) << "' y1='" << top << "' x2='" << f1(tx(m)) << "' y2='" << top + h
      << "' stroke='#d62728' stroke-opacity='0.35' stroke-width='1'/>";
  }
  for (const Series& se : p.series) {
    if (se.points) {
      for (size_t i = 0; i < se.x.size() && i < se.y.size(); ++i) {
        if (!std::isfinite(se.x[i]) || !std::isfinite(se.y[i])) continue;
        if (i < se.y_error.size() && std::isfinite(se.y_error[i])) {
          s << "<line x1='" << f1(tx(se.x[i])) << "' y1='" << f1(ty(se.y[i] - se.y_error[i])) << "' x2='"
            << f1(tx(se.x[i])) << "' y2='" << f1(ty(se.y[i] + se.y_error[i])) << "' stroke='" << se.colour << "'/>";
        }
        s << "<circle cx='" << f1(tx(se.x[i])) << "' cy='" << f1(ty(se.y[i])) << "' r='3' fill='" << se.colour << "'/>";
      }
    } else {
      s << "<polyline fill='none' stroke='" << se.colour << "' stroke-width='1.4'"
        << (se.dashed ? " stroke-dasharray='5,3'" : "") << " points='";
      for (size_t i = 0; i < se.x.size() && i < se.y.size(); ++i) {
        if (std::isfinite(se.x[i]) && std::isfinite(se.y[i]) && se.x[i] >= p.x_min && se.x[i] <= p.x_max) {
          s << f1(tx(se.x[i])) << "," << f1(ty(se.y[i])) << " ";
        }
      }
      s << "'/>";
    }
  }
  // Legend above the frame, between the title and the data.
  for (size_t i = 0; i < p.series.size(); ++i) {
    const Series& se = p.series[i];
    if (legend[i].second < 0) continue;
    const double lx = legend[i].first, ly = 26 + 14.0 * legend[i].second + 8;
    if (se.points) {
      s << "<circle cx='" << lx + 10 << "' cy='" << ly - 4 << "' r='3' fill='" << se.colour << "'/>";
    } else {
      s << "<line x1='" << lx << "' y1='" << ly - 4 << "' x2='" << lx + 20 << "' y2='" << ly - 4 << "' stroke='"
        << se.colour << "' stroke-width='2'" << (se.dashed ? " stroke-dasharray='5,3'" : "") << "/>";
    }
    s << "<text x='" << lx + 24 << "' y='" << ly << "'>" << html_escape(se.label) << "</text>";
  }
  s << "<text x='" << left + w / 2 << "' y='" << height - 6 << "' text-anchor='middle'>" << html_escape(p.x_label)
    << "</text>";
  s << "<text transform='translate(14," << top + h / 2 << ") rotate(-90)' text-anchor='middle'>" << html_escape(p.y_label)
    << "</text></svg>";
  return s.str();
}

std::string svg_heatmap(const std::string& title, const std::vector<std::vector<double>>& v, double v_min, double v_max,
                        const std::string& x_label, double x_max, const std::string& y_label, double y_max, int width,
                        int height, const std::string& colour_label, double colour_offset) {
  const double left = 46, right = 62, top = 22, bottom = 34;  // right: the colour bar and its labels
  const double w = width - left - right, h = height - top - bottom;
  std::ostringstream s;
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
    << "' font-family='sans-serif' font-size='11'>";
  s << "<text x='" << width / 2 << "' y='15' text-anchor='middle' font-size='12'>" << html_escape(title) << "</text>";
  const size_t rows = v.size(), cols = rows ? v[0].size() : 0;
  if (rows && cols) {
    const double cw = w / cols, ch = h / rows;
    // Colours quantised to 32 steps and equal neighbours in a row merged into one rectangle
    // (keeps a report with several spectrograms small).
    auto colour = [&](size_t r, size_t c) {
      const double u = (v[r][c] - v_min) / (v_max - v_min);
      return ramp(std::round((std::isfinite(u) ? std::clamp(u, 0.0, 1.0) : 0.0) * 32.0) / 32.0);
    };
    for (size_t r = 0; r < rows; ++r) {
      for (size_t c = 0; c < cols;) {
        const std::string fill = colour(r, c);
        size_t e = c + 1;
        while (e < cols && colour(r, e) == fill) ++e;
        s << "<rect x='" << f1(left + c * cw) << "' y='" << f1(top + h - (r + 1) * ch) << "' width='"
          << f1((e - c) * cw + 0.6) << "' height='" << f1(ch + 0.6) << "' fill='" << fill << "'/>";
        c = e;
      }
    }
  }
  s << "<rect x='" << left << "' y='" << top << "' width='" << w << "' height='" << h << "' fill='none' stroke='#444'/>";
  for (double t : ticks(0, x_max, 5)) {
    s << "<text x='" << f1(left + w * t / x_max) << "' y='" << top + h + 13 << "' text-anchor='middle'>" << format_double(t, 3)
      << "</text>";
  }
  for (double t : ticks(0, y_max, 4)) {
    s << "<text x='" << left - 3 << "' y='" << f1(top + h - h * t / y_max + 4) << "' text-anchor='end'>"
      << format_double(t, 4) << "</text>";
  }
  s << "<text x='" << left + w / 2 << "' y='" << height - 4 << "' text-anchor='middle'>" << html_escape(x_label) << "</text>";
  s << "<text transform='translate(11," << top + h / 2 << ") rotate(-90)' text-anchor='middle'>" << html_escape(y_label)
    << "</text>";
  // Colour bar: the ramp from v_min (bottom) to v_max (top) in 32 steps, with ticks.
  const double bx = left + w + 10, bw = 10;
  for (int k = 0; k < 32; ++k)
    s << "<rect x='" << bx << "' y='" << f1(top + h - (k + 1) * h / 32) << "' width='" << bw << "' height='"
      << f1(h / 32 + 0.6) << "' fill='" << ramp((k + 0.5) / 32) << "'/>";
  s << "<rect x='" << bx << "' y='" << top << "' width='" << bw << "' height='" << h << "' fill='none' stroke='#444'/>";
  if (v_max > v_min) {
    for (double t : ticks(v_min - colour_offset, v_max - colour_offset, 4)) {
      const double y = top + h - h * (t + colour_offset - v_min) / (v_max - v_min);
      s << "<line x1='" << bx + bw << "' y1='" << f1(y) << "' x2='" << bx + bw + 3 << "' y2='" << f1(y)
        << "' stroke='#444'/><text x='" << bx + bw + 5 << "' y='" << f1(y + 4) << "'>" << format_double(t, 3) << "</text>";
    }
  }
  if (!colour_label.empty())
    s << "<text transform='translate(" << width - 4 << "," << top + h / 2 << ") rotate(-90)' text-anchor='middle'>"
      << html_escape(colour_label) << "</text>";
  s << "</svg>";
  return s.str();
}

std::vector<double> octave_band_axis() { return std::vector<double>(kOctaveCentersHz.begin(), kOctaveCentersHz.end()); }

PlotSpec octave_band_plot(const std::string& title, const std::string& y_label) {
  PlotSpec p;
  p.title = title;
  p.x_label = "octave band, Hz";
  p.y_label = y_label;
  p.log_x = true;
  p.x_min = 44;
  p.x_max = 11300;
  return p;
}

Series octave_band_zero_line() { return Series{"", "#999", {44, 11300}, {0, 0}}; }

void finite_range(const std::vector<std::vector<double>>& series, double* lo, double* hi, double pad) {
  *lo = INFINITY;
  *hi = -INFINITY;
  for (const auto& s : series) {
    for (double v : s) {
      if (std::isfinite(v)) { *lo = std::min(*lo, v); *hi = std::max(*hi, v); }
    }
  }
  if (!std::isfinite(*lo)) { *lo = -1; *hi = 1; }
  *lo -= pad;
  *hi += pad;
}

}  // namespace tsrir::diagnose
