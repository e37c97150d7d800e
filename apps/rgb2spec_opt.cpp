// rgb2spec_opt: fits the sigmoid-polynomial RGB -> spectrum table (spectral/sigmoid_fit.h) and
// writes it in RgbToSpectrumTable's format. The build runs it to generate
// build/data/spectra/srgb_sigmoid.coeff (see apps/CMakeLists.txt).

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/base/clock.h"
#include "core/base/error.h"
#include "core/base/parallel.h"
#include "spectral/sigmoid_fit.h"

namespace {

using namespace prism;

struct NodeError {
  float error = 0;
  Rgb rgb;
};

// The node whose albedo comes back worst, per channel, through the table's lookup and the colour
// of the returned reflectance under D65.
NodeError worst_round_trip(const RgbToSpectrumTable& table) {
  const int res = table.resolution();
  std::vector<NodeError> worst(size_t(3) * res * res);  // one per (l, yi, xi) column
  parallel_for(int64_t(worst.size()), [&](int64_t column) {
    const int l = int(column / (res * res)), yi = int(column / res % res), xi = int(column % res);
    for (int zi = 0; zi < res; ++zi) {
      const Rgb rgb = table_node_rgb(table.z_nodes(), l, zi, yi, xi);
      const Rgb back = reflectance_rgb(table(rgb));
      for (int c = 0; c < 3; ++c)
        if (std::abs(back[c] - rgb[c]) > worst[column].error) worst[column] = {std::abs(back[c] - rgb[c]), rgb};
    }
  });
  return *std::max_element(worst.begin(), worst.end(),
                           [](const NodeError& a, const NodeError& b) { return a.error < b.error; });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Fits the sigmoid-polynomial RGB-to-spectrum table (Jakob & Hanika 2019) for linear Rec.709.");
  int resolution = 64, threads = 0;
  std::string output;
  app.add_option("--resolution", resolution, "Nodes per table axis")->check(CLI::Range(2, 1024));
  app.add_option("--threads", threads, "Worker threads (default: all)");
  app.add_option("output", output, "Table file to write (.coeff)")->required();
  CLI11_PARSE(app, argc, argv);

  try {
    const ThreadLimit limit(threads);
    const auto start = std::chrono::steady_clock::now();
    const RgbToSpectrumTable table = fit_rgb_to_spectrum_table(resolution);
    const double seconds = seconds_since(start);
    table.save(output);
    const NodeError worst = worst_round_trip(table);
    fmt::print("resolution {}: fitted in {:.1f} s; wrote {}\n", resolution, seconds, output);
    fmt::print("worst round-trip error over the grid: {:.2e} per channel, at RGB ({:.4f}, {:.4f}, {:.4f})\n",
               worst.error, worst.rgb.r, worst.rgb.g, worst.rgb.b);
  } catch (const Error& e) {
    fmt::print(stderr, "rgb2spec_opt: {}\n", e.what());
    return 1;
  }
}
