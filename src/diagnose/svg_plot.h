// Minimal inline-SVG charts for the HTML report (line/scatter plots with axes, and heat maps).
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace tsrir::diagnose {

struct Series {
  Series() = default;
  Series(std::string label_, std::string colour_, std::vector<double> x_, std::vector<double> y_)
      : label(std::move(label_)), colour(std::move(colour_)), x(std::move(x_)), y(std::move(y_)) {}
  std::string label;
  std::string colour;
  std::vector<double> x, y;
  bool dashed = false;
  bool points = false;          // markers instead of a line
  std::vector<double> y_error;  // optional error bars (points only)
};

struct PlotSpec {
  std::string title, x_label, y_label;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  bool log_x = false;
  std::vector<double> x_markers;   // thin vertical lines (e.g. predicted mode frequencies)
  std::vector<Series> series;
  int width = 520, height = 300;
};

// The legend is drawn above the plot frame (wrapped into rows), never over the data.
std::string svg_plot(const PlotSpec& spec);

// values[row][col], row 0 at the bottom; colour scale from v_min (dark) to v_max (bright), drawn as a
// colour bar on the right labelled `colour_label`, its ticks showing value - colour_offset (e.g. dB
// re the maximum with colour_offset = v_max).
std::string svg_heatmap(const std::string& title, const std::vector<std::vector<double>>& values, double v_min,
                        double v_max, const std::string& x_label, double x_max, const std::string& y_label, double y_max,
                        int width = 380, int height = 220, const std::string& colour_label = "",
                        double colour_offset = 0);

std::string html_escape(const std::string& s);

// The octave-band centres (62.5 Hz .. 8 kHz) as an x axis; a plot over them (log x, 44 Hz-11.3 kHz)
// and its zero line.
std::vector<double> octave_band_axis();
PlotSpec octave_band_plot(const std::string& title, const std::string& y_label);
Series octave_band_zero_line();
// The range of the finite values of all series, widened by `pad` on both sides ([-1 - pad, 1 + pad]
// when there is none).
void finite_range(const std::vector<std::vector<double>>& series, double* lo, double* hi, double pad);

}  // namespace tsrir::diagnose
