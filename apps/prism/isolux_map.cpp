#include "apps/prism/isolux_map.h"

#include <fmt/format.h>

#include "apps/prism/canvas.h"
#include "apps/prism/plot.h"
#include "core/render/image_output.h"

namespace prism {

namespace {

// Viridis (van der Walt & Smith, matplotlib's default): dark blue to yellow, perceptually even and
// legible in grey, at nine stops (sRGB-encoded).
const Color kViridis[] = {{0.267f, 0.005f, 0.329f}, {0.283f, 0.141f, 0.458f}, {0.254f, 0.265f, 0.530f},
                          {0.207f, 0.372f, 0.553f}, {0.164f, 0.471f, 0.558f}, {0.128f, 0.567f, 0.551f},
                          {0.135f, 0.659f, 0.518f}, {0.267f, 0.749f, 0.441f}, {0.478f, 0.821f, 0.318f},
                          {0.993f, 0.906f, 0.144f}};

Color colormap(double t) {
  t = std::clamp(t, 0.0, 1.0) * (std::size(kViridis) - 1);
  const size_t i = std::min(size_t(t), std::size(kViridis) - 2);
  const float f = float(t - double(i));
  Color c;
  for (int k = 0; k < 3; ++k) c[k] = kViridis[i][k] + f * (kViridis[i + 1][k] - kViridis[i][k]);
  return c;
}

}  // namespace

void write_isolux_png(const std::filesystem::path& file, int nx, int ny, const std::vector<double>& lux,
                      const std::string& title) {
  // The map fills a 600-pixel square, stretched to the grid's aspect, with the legend to its right.
  const float aspect = float(nx) / float(ny);
  const int map_w = aspect >= 1 ? 600 : std::max(60, int(600 * aspect)),
            map_h = aspect >= 1 ? std::max(60, int(600 / aspect)) : 600;
  const int left = 20, top = 44, width = left + map_w + 190, height = top + map_h + 20;
  double lo = INFINITY, hi = -INFINITY;
  for (double v : lux) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(hi > lo)) hi = lo + 1;
  // The reading at map pixel (x, y), bilinear between the points at the cells' centres.
  const auto value = [&](float x, float y) {
    const float gx = std::clamp((x + 0.5f) / float(map_w) * float(nx) - 0.5f, 0.f, float(nx - 1)),
                gy = std::clamp((y + 0.5f) / float(map_h) * float(ny) - 0.5f, 0.f, float(ny - 1));
    const int x0 = std::min(int(gx), nx - 1), y0 = std::min(int(gy), ny - 1);
    const int x1 = std::min(x0 + 1, nx - 1), y1 = std::min(y0 + 1, ny - 1);
    const double fx = gx - float(x0), fy = gy - float(y0);
    const auto at = [&](int i, int j) { return lux[size_t(j) * nx + i]; };
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) + fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
  };
  const std::vector<double> levels = nice_ticks(lo, hi, 8);
  const auto band = [&](double v) { return int(std::upper_bound(levels.begin(), levels.end(), v) - levels.begin()); };
  Canvas canvas(width, height);
  const Color black{0, 0, 0}, white{1, 1, 1};
  std::vector<int> bands(size_t(map_w) * map_h);
  for (int y = 0; y < map_h; ++y)
    for (int x = 0; x < map_w; ++x) {
      const double v = value(float(x), float(y));
      bands[size_t(y) * map_w + x] = band(v);
      canvas.rect(float(left + x), float(top + y), float(left + x + 1), float(top + y + 1),
                  colormap((v - lo) / (hi - lo)));
    }
  // Isolux lines: where the band of level crossings changes between neighbouring pixels.
  for (int y = 0; y < map_h; ++y)
    for (int x = 0; x < map_w; ++x) {
      const int b = bands[size_t(y) * map_w + x];
      if ((x + 1 < map_w && bands[size_t(y) * map_w + x + 1] != b) ||
          (y + 1 < map_h && bands[size_t(y + 1) * map_w + x] != b))
        canvas.blend(left + x, top + y, white, 0.85f);
    }
  canvas.text(float(left), 12, title, 2.5f, black);
  // Legend: the colour scale from lo (bottom) to hi (top), the isolux levels marked and named.
  const float lx = float(left + map_w + 30), bar_w = 24;
  for (int y = 0; y < map_h; ++y)
    canvas.rect(lx, float(top + y), lx + bar_w, float(top + y + 1), colormap(1 - (y + 0.5) / map_h));
  for (double level : levels) {
    const float y = float(top) + float((1 - (level - lo) / (hi - lo)) * map_h);
    canvas.line(lx - 4, y, lx + bar_w + 4, y, 1.5f, black);
    canvas.text(lx + bar_w + 10, y - 6, fmt::format("{:g} lx", level), 2, black);
  }
  canvas.text(lx + bar_w + 10, float(top + map_h) - 6, fmt::format("{:.3g}", lo), 1.5f, black);
  canvas.text(lx + bar_w + 10, float(top) - 6, fmt::format("{:.3g}", hi), 1.5f, black);
  write_png(file, width, height, canvas.rgb());
}

}  // namespace prism
