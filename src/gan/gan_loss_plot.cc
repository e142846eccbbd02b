#include "gan/gan_loss_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "io/atomic_output.h"

namespace tsrir {
namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  return out;
}

// A tick label a person reads: 3 significant digits, no exponent for ordinary magnitudes.
std::string tick_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

// Round ticks (1, 2, 5 x 10^k) covering [lo, hi], about `wanted` of them.
std::vector<double> linear_ticks(double lo, double hi, int wanted) {
  const double raw = (hi - lo) / std::max(1, wanted);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * magnitude >= raw) {
      step = m * magnitude;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) ticks.push_back(t);
  return ticks;
}

// Ticks of a log10 axis spanning [lo, hi] (in log10 units): the decades, with 2 and 5 between them
// when fewer than three decades are spanned; a range too narrow for three of those (early training:
// 3.98 .. 5.4, say) gets round values instead (4, 4.5, 5), not labels like 10^0.6 = 3.98.
std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> ticks;
  const bool fine = hi - lo < 3;
  for (double decade = std::floor(lo); decade <= std::ceil(hi); decade += 1) {
    for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
      const double t = decade + std::log10(m);
      if (t >= lo - 1e-9 && t <= hi + 1e-9) ticks.push_back(t);
    }
  }
  if (ticks.size() >= 3) return ticks;
  ticks.clear();
  for (double v : linear_ticks(std::pow(10.0, lo), std::pow(10.0, hi), 4)) ticks.push_back(std::log10(v));
  return ticks;
}

struct Curve {
  std::string name;
  std::vector<double> step;     // bucket's mean step
  std::vector<double> log10_y;  // log10 of the bucket's mean loss
};

// At most 400 points: bucket means over the finite values. Empty when the column is missing or not
// finite anywhere (a loss not computed in this run: the identity L1 at weight 0).
Curve bucket_curve(const std::string& name, const std::vector<double>& steps, const std::vector<double>* values) {
  Curve c;
  c.name = name;
  if (!values || std::none_of(values->begin(), values->end(), [](double x) { return std::isfinite(x); })) return c;
  const size_t n = steps.size(), buckets = std::min<size_t>(n, 400);
  for (size_t b = 0; b < buckets; ++b) {
    const size_t from = b * n / buckets, to = std::max(from + 1, (b + 1) * n / buckets);
    double sum = 0, step_sum = 0;
    size_t count = 0;
    for (size_t i = from; i < to; ++i)
      if (std::isfinite((*values)[i])) sum += (*values)[i], step_sum += steps[i], ++count;
    if (count == 0) continue;
    c.step.push_back(step_sum / double(count));
    c.log10_y.push_back(std::log10(std::max(sum / double(count), 1e-12)));
  }
  return c;
}

struct Frame {
  double x0, y0, width, height;  // the plot area, in SVG pixels
  double step_lo, step_hi, log_lo, log_hi;
  double x(double step) const { return x0 + width * (step - step_lo) / (step_hi - step_lo); }
  double y(double log10_value) const { return y0 + height * (1 - (log10_value - log_lo) / (log_hi - log_lo)); }
};

void draw_axes(std::ostringstream& svg, const Frame& f) {
  svg << "<rect x='" << f.x0 << "' y='" << f.y0 << "' width='" << f.width << "' height='" << f.height
      << "' fill='none' stroke='#444'/>\n";
  for (double t : log_ticks(f.log_lo, f.log_hi)) {
    const double y = f.y(t);
    svg << "<line x1='" << f.x0 - 4 << "' y1='" << y << "' x2='" << f.x0 + f.width << "' y2='" << y
        << "' stroke='#ddd'/><line x1='" << f.x0 - 4 << "' y1='" << y << "' x2='" << f.x0 << "' y2='" << y
        << "' stroke='#444'/><text x='" << f.x0 - 7 << "' y='" << y + 4 << "' text-anchor='end'>"
        << tick_text(std::pow(10.0, t)) << "</text>\n";
  }
  for (double t : linear_ticks(f.step_lo, f.step_hi, 5)) {
    const double x = f.x(t);
    svg << "<line x1='" << x << "' y1='" << f.y0 + f.height << "' x2='" << x << "' y2='" << f.y0 + f.height + 4
        << "' stroke='#444'/><text x='" << x << "' y='" << f.y0 + f.height + 16 << "' text-anchor='middle'>"
        << tick_text(t) << "</text>\n";
  }
  svg << "<text x='" << f.x0 + f.width / 2 << "' y='" << f.y0 + f.height + 32
      << "' text-anchor='middle'>training step</text>\n<text transform='translate(" << f.x0 - 52 << ","
      << f.y0 + f.height / 2 << ") rotate(-90)' text-anchor='middle'>loss (log scale)</text>\n";
}

// One panel: title and legend above the plot area (never over the data), axes, curves.
void draw_panel(std::ostringstream& svg, const std::string& title, const std::vector<Curve>& curves, Frame f) {
  static const char* colours[2] = {"#1f77b4", "#d62728"};
  double lo = 1e300, hi = -1e300;
  for (const Curve& c : curves)
    for (double v : c.log10_y) lo = std::min(lo, v), hi = std::max(hi, v);
  const double pad = std::max(0.05 * (hi - lo), 0.02);
  f.log_lo = lo - pad, f.log_hi = hi + pad;
  svg << "<text x='" << f.x0 << "' y='" << f.y0 - 22 << "' font-weight='bold'>" << title << "</text>\n";
  double legend_x = f.x0;
  for (size_t c = 0; c < curves.size(); ++c) {
    svg << "<line x1='" << legend_x << "' y1='" << f.y0 - 9 << "' x2='" << legend_x + 18 << "' y2='" << f.y0 - 9
        << "' stroke='" << colours[c % 2] << "' stroke-width='2'/><text x='" << legend_x + 22 << "' y='" << f.y0 - 5
        << "'>" << curves[c].name << "</text>\n";
    legend_x += 40 + 7.0 * curves[c].name.size();
  }
  draw_axes(svg, f);
  for (size_t c = 0; c < curves.size(); ++c) {
    svg << "<polyline fill='none' stroke='" << colours[c % 2] << "' stroke-width='1.3' points='";
    for (size_t i = 0; i < curves[c].step.size(); ++i) svg << f.x(curves[c].step[i]) << ',' << f.y(curves[c].log10_y[i]) << ' ';
    svg << "'/>\n";
  }
}

}  // namespace

bool write_loss_curves_svg(const std::string& loss_log_csv, const std::string& svg_path) {
  std::ifstream in(loss_log_csv);
  std::string line;
  if (!std::getline(in, line)) return false;
  const std::vector<std::string> header = split_csv(line);
  std::vector<std::vector<double>> columns(header.size());
  while (std::getline(in, line)) {
    const auto cells = split_csv(line);
    if (cells.size() != header.size()) continue;
    for (size_t c = 0; c < cells.size(); ++c) columns[c].push_back(std::atof(cells[c].c_str()));
  }
  if (columns.empty() || columns[0].empty()) return false;
  auto column = [&](const std::string& name) -> const std::vector<double>* {
    for (size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) return &columns[c];
    return nullptr;
  };
  struct Family {
    const char* title;
    std::vector<std::string> names;
  };
  const Family families[4] = {{"discriminators (LSGAN)", {"d_real", "d_synthetic"}},
                              {"generators: adversarial", {"adv_real", "adv_synthetic"}},
                              {"cycle L1", {"cycle_l1_real", "cycle_l1_synthetic"}},
                              {"identity L1", {"identity_l1_real", "identity_l1_synthetic"}}};
  const std::vector<double>& steps = columns[0];
  // Only panels with data: a loss family not computed in this run (identity L1 at weight 0) is
  // named in a note instead of drawn as an empty panel.
  std::vector<std::pair<std::string, std::vector<Curve>>> panels;
  std::string not_computed;
  for (const Family& family : families) {
    std::vector<Curve> curves;
    for (const std::string& name : family.names) {
      Curve c = bucket_curve(name, steps, column(name));
      if (!c.step.empty()) curves.push_back(std::move(c));
    }
    if (curves.empty()) not_computed += std::string(not_computed.empty() ? "" : "; ") + family.title;
    else panels.emplace_back(family.title, std::move(curves));
  }
  const double pw = 420, ph = 200, left = 75, right = 25, top = 50, bottom = 50;
  const size_t cols = panels.size() > 1 ? 2 : 1, rows = std::max<size_t>(1, (panels.size() + 1) / 2);
  const double width = cols * (left + pw + right), height = rows * (top + ph + bottom) + 24;
  const double step_lo = steps.front(), step_hi = steps.back() > steps.front() ? steps.back() : steps.front() + 1;
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' fill='white'/>\n";
  for (size_t p = 0; p < panels.size(); ++p) {
    const Frame frame{left + (p % cols) * (left + pw + right), top + (p / cols) * (top + ph + bottom), pw, ph,
                      step_lo, step_hi, 0, 1};
    draw_panel(svg, panels[p].first, panels[p].second, frame);
  }
  svg << "<text x='8' y='" << height - 8 << "' fill='#555'>TS-RIRGAN losses, mean per bucket of "
      << tick_text(std::max(1.0, double(steps.size()) / 400.0)) << " step(s); " << steps.size() << " steps logged"
      << (not_computed.empty() ? "" : "; not computed in this run (weight 0): " + not_computed) << "</text>\n</svg>\n";
  AtomicTextFile out(svg_path);
  out.stream() << svg.str();
  out.commit();
  return true;
}

}  // namespace tsrir
