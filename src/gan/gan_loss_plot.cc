#include "gan/gan_loss_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
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
    for (size_t c = 0; c < header.size(); ++c) {
      if (header[c] == name) return &columns[c];
    }
    return nullptr;
  };
  struct Panel {
    const char* title;
    std::vector<std::string> names;
  };
  const Panel panels[4] = {{"discriminators (LSGAN, x5)", {"d_real", "d_synthetic"}},
                           {"generators: adversarial", {"adv_real", "adv_synthetic"}},
                           {"cycle L1", {"cycle_l1_real", "cycle_l1_synthetic"}},
                           {"identity L1", {"identity_l1_real", "identity_l1_synthetic"}}};
  const char* colours[2] = {"#1f77b4", "#d62728"};
  const std::vector<double>& steps = columns[0];
  const size_t n = steps.size(), buckets = std::min<size_t>(n, 400);
  const double pw = 440, ph = 220, margin = 50;
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << 2 * (pw + margin) + margin << "' height='"
      << 2 * (ph + margin) + margin << "' font-family='sans-serif' font-size='11'>\n";
  for (int p = 0; p < 4; ++p) {
    const double x0 = margin + (p % 2) * (pw + margin), y0 = margin + (p / 2) * (ph + margin);
    std::vector<std::vector<double>> curves;
    double lo = 1e300, hi = -1e300;
    for (const auto& name : panels[p].names) {
      const std::vector<double>* v = column(name);
      std::vector<double> curve;
      // A column of "nan" is a loss not computed in this run (the identity L1 at weight 0):
      // no curve. A bucket's mean is over its finite values.
      if (v && std::any_of(v->begin(), v->end(), [](double x) { return std::isfinite(x); })) {
        for (size_t b = 0; b < buckets; ++b) {
          const size_t from = b * n / buckets, to = std::max(from + 1, (b + 1) * n / buckets);
          double sum = 0;
          size_t count = 0;
          for (size_t i = from; i < to; ++i) {
            if (std::isfinite((*v)[i])) sum += (*v)[i], ++count;
          }
          const double mean = std::max(count > 0 ? sum / double(count) : 0.0, 1e-12);
          curve.push_back(std::log10(mean));
          lo = std::min(lo, curve.back()), hi = std::max(hi, curve.back());
        }
      }
      curves.push_back(curve);
    }
    if (lo > hi) lo = 0, hi = 1;  // no curve in this panel
    if (!(hi > lo)) hi = lo + 1;
    svg << "<rect x='" << x0 << "' y='" << y0 << "' width='" << pw << "' height='" << ph
        << "' fill='none' stroke='#888'/>\n<text x='" << x0 << "' y='" << y0 - 6 << "'>" << panels[p].title
        << " (log10; steps " << steps.front() << ".." << steps.back() << ")</text>\n";
    svg << "<text x='" << x0 - 4 << "' y='" << y0 + 10 << "' text-anchor='end'>" << std::pow(10.0, hi)
        << "</text><text x='" << x0 - 4 << "' y='" << y0 + ph << "' text-anchor='end'>" << std::pow(10.0, lo)
        << "</text>\n";
    for (size_t c = 0; c < curves.size(); ++c) {
      if (curves[c].empty()) {
        svg << "<text x='" << x0 + pw - 4 << "' y='" << y0 + 14 + 13 * c << "' text-anchor='end' fill='"
            << colours[c] << "'>" << panels[p].names[c] << ": not computed</text>\n";
        continue;
      }
      svg << "<polyline fill='none' stroke='" << colours[c] << "' points='";
      for (size_t b = 0; b < curves[c].size(); ++b) {
        const double x = x0 + pw * (curves[c].size() > 1 ? double(b) / double(curves[c].size() - 1) : 0.0);
        const double y = y0 + ph * (1.0 - (curves[c][b] - lo) / (hi - lo));
        svg << x << ',' << y << ' ';
      }
      svg << "'/>\n<text x='" << x0 + pw - 4 << "' y='" << y0 + 14 + 13 * c << "' text-anchor='end' fill='"
          << colours[c] << "'>" << panels[p].names[c] << "</text>\n";
    }
  }
  svg << "</svg>\n";
  AtomicTextFile out(svg_path);
  out.stream() << svg.str();
  out.commit();
  return true;
}

}  // namespace tsrir
