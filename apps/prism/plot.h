#pragma once
// Line plots as PNG images, self-contained (stb only): axes with ticks and labels, linear or
// logarithmic scales, one coloured polyline per series, a legend. For `prism fresnel --plot`
// and `prism converge`.

#include <filesystem>
#include <string>
#include <vector>

namespace prism {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  bool dashed = false;
  int color = -1;  // index into the palette; −1: the series' own index
};

struct Plot {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<PlotSeries> series;
  int width = 960, height = 640;
};

void write_plot_png(const std::filesystem::path& file, const Plot& plot);

// Round values from lo to hi in steps of 1, 2 or 5 times a power of ten, about `about` of them.
std::vector<double> nice_ticks(double lo, double hi, int about);

}  // namespace prism
