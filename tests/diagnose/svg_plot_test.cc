// The report's figures are ones a person would keep (issue 32): a spectrogram has a colour bar with
// labelled ticks (relative to the maximum when asked), and a line plot's legend sits above the plot
// frame instead of over the data, wrapping into rows when it is long.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "diagnose/svg_plot.h"

namespace {

using tsrir::diagnose::PlotSpec;
using tsrir::diagnose::Series;

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SvgPlot, HeatmapHasALabelledColourBar) {
  const std::vector<std::vector<double>> v = {{-70, -35, 0}, {-60, -20, -5}};
  const std::string svg = tsrir::diagnose::svg_heatmap("measured", v, -70 + 100, 0 + 100, "time, s", 0.8, "Hz", 8000,
                                                        380, 220, "level, dB re its maximum", 100);
  EXPECT_NE(svg.find(">level, dB re its maximum</text>"), std::string::npos);
  // Ticks of the bar are relative to the offset: 0 at the top, down to -60.
  for (const char* tick : {">0</text>", ">-20</text>", ">-40</text>", ">-60</text>"})
    EXPECT_NE(svg.find(tick), std::string::npos) << tick;
  EXPECT_GE(count(svg, "<rect"), 32u + 2u);  // the 32 steps of the bar and its frame, besides the data
}

TEST(SvgPlot, LegendSitsAboveTheFrame) {
  PlotSpec p;
  p.title = "Energy decay curve";
  p.x_min = 0, p.x_max = 1, p.y_min = -90, p.y_max = 0;
  for (const char* label : {"measured", "baseline simulation, dashed", "extended simulation", "a fourth long series"})
    p.series.push_back(Series{label, "#123456", {0, 1}, {0, -60}});
  const std::string svg = tsrir::diagnose::svg_plot(p);
  std::smatch frame;
  ASSERT_TRUE(std::regex_search(svg, frame, std::regex("<rect x='58' y='([0-9.]+)'")));
  const double frame_top = std::stod(frame[1]);
  size_t labels = 0;
  const std::regex label_text("<text x='[0-9.]+' y='([0-9.]+)'>(measured|baseline simulation, dashed|extended "
                              "simulation|a fourth long series)</text>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label_text); it != std::sregex_iterator(); ++it) {
    ++labels;
    EXPECT_LT(std::stod((*it)[1]), frame_top) << (*it)[2] << " is drawn inside the frame";
  }
  EXPECT_EQ(labels, 4u);
  EXPECT_GT(frame_top, 26 + 14) << "four long labels need a second legend row";
}

}  // namespace
