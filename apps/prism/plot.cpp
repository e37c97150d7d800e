#include "apps/prism/plot.h"

#include <fmt/format.h>
#include <stb_easy_font.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/base/error.h"
#include "core/render/image_output.h"

namespace prism {

namespace {

using Color = std::array<float, 3>;

// Matplotlib's default colour cycle ("tab10").
const Color kPalette[] = {{0.122f, 0.467f, 0.706f}, {1.000f, 0.498f, 0.055f}, {0.173f, 0.627f, 0.173f},
                          {0.839f, 0.153f, 0.157f}, {0.580f, 0.404f, 0.741f}, {0.549f, 0.337f, 0.294f},
                          {0.890f, 0.467f, 0.761f}, {0.498f, 0.498f, 0.498f}, {0.737f, 0.741f, 0.133f},
                          {0.090f, 0.745f, 0.812f}};

class Canvas {
 public:
  Canvas(int w, int h) : w_(w), h_(h), rgb_(size_t(w) * h * 3, 1.f) {}

  void blend(int x, int y, const Color& c, float alpha) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_ || alpha <= 0) return;
    float* p = &rgb_[(size_t(y) * w_ + x) * 3];
    for (int i = 0; i < 3; ++i) p[i] = p[i] * (1 - alpha) + c[i] * alpha;
  }

  void rect(float x0, float y0, float x1, float y1, const Color& c) {
    for (int y = int(std::floor(y0)); y < int(std::ceil(y1)); ++y)
      for (int x = int(std::floor(x0)); x < int(std::ceil(x1)); ++x) blend(x, y, c, 1.f);
  }

  // Anti-aliased segment of the given width: coverage from the pixel centre's distance.
  void line(float x0, float y0, float x1, float y1, float width, const Color& c) {
    const float dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
    const int xa = int(std::floor(std::min(x0, x1) - width)), xb = int(std::ceil(std::max(x0, x1) + width));
    const int ya = int(std::floor(std::min(y0, y1) - width)), yb = int(std::ceil(std::max(y0, y1) + width));
    for (int y = ya; y <= yb; ++y)
      for (int x = xa; x <= xb; ++x) {
        const float px = x + 0.5f - x0, py = y + 0.5f - y0;
        const float t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.f, 1.f) : 0.f;
        const float d = std::hypot(px - t * dx, py - t * dy);
        blend(x, y, c, std::clamp(width / 2 + 0.5f - d, 0.f, 1.f));
      }
  }

  // Text with its top-left corner at (x, y), scaled up from stb_easy_font's ~7-pixel glyphs.
  void text(float x, float y, const std::string& s, float scale, const Color& c) {
    static char buffer[1 << 16];
    std::string copy = s;
    const int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, buffer, sizeof(buffer));
    for (int q = 0; q < quads; ++q) {
      const float* v = reinterpret_cast<const float*>(buffer + q * 64);  // 4 vertices of 16 bytes
      rect(x + v[0] * scale, y + v[1] * scale, x + v[8] * scale, y + v[9] * scale, c);
    }
  }
  static float text_width(const std::string& s, float scale) {
    std::string copy = s;
    return float(stb_easy_font_width(copy.data())) * scale;
  }

  const std::vector<float>& rgb() const { return rgb_; }

 private:
  int w_, h_;
  std::vector<float> rgb_;
};

struct Axis {
  double lo, hi;
  bool log;
  double map(double v) const {
    return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
  }
};

// Data range, widened to whole decades (log) or padded by 5% (linear).
Axis make_axis(const Plot& plot, bool x, bool log) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& s : plot.series)
    for (double v : x ? s.x : s.y)
      if (std::isfinite(v) && (!log || v > 0)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(lo <= hi)) lo = log ? 1 : 0, hi = log ? 10 : 1;
  if (log) return {std::pow(10, std::floor(std::log10(lo))), std::pow(10, std::ceil(std::log10(hi) + 1e-9)), true};
  if (hi == lo) hi = lo + 1;
  const double pad = x ? 0 : 0.05 * (hi - lo);
  return {lo - pad, hi + pad, false};
}

// Tick positions: decades on a log axis; 1-2-5 steps giving about six ticks on a linear one.
std::vector<double> ticks(const Axis& a) {
  std::vector<double> t;
  if (a.log) {
    for (double v = a.lo; v <= a.hi * 1.0001; v *= 10) t.push_back(v);
    return t;
  }
  const double raw = (a.hi - a.lo) / 6, mag = std::pow(10, std::floor(std::log10(raw)));
  const double step = raw / mag < 2 ? 2 * mag : raw / mag < 5 ? 5 * mag : 10 * mag;
  for (double v = std::ceil(a.lo / step) * step; v <= a.hi + 1e-9 * step; v += step)
    t.push_back(std::abs(v) < 1e-12 ? 0 : v);
  return t;
}

}  // namespace

void write_plot_png(const std::filesystem::path& file, const Plot& plot) {
  Canvas canvas(plot.width, plot.height);
  const Color black{0, 0, 0}, grid{0.88f, 0.88f, 0.88f};
  const float left = 90, right = float(plot.width) - 30, top = 50, bottom = float(plot.height) - 70;
  const Axis ax = make_axis(plot, true, plot.log_x), ay = make_axis(plot, false, plot.log_y);
  const auto px = [&](double v) { return left + float(ax.map(v)) * (right - left); };
  const auto py = [&](double v) { return bottom - float(ay.map(v)) * (bottom - top); };

  for (double t : ticks(ax)) {
    canvas.line(px(t), top, px(t), bottom, 1, grid);
    const std::string label = fmt::format("{:g}", t);
    canvas.text(px(t) - Canvas::text_width(label, 2) / 2, bottom + 8, label, 2, black);
  }
  for (double t : ticks(ay)) {
    canvas.line(left, py(t), right, py(t), 1, grid);
    const std::string label = fmt::format("{:g}", t);
    canvas.text(left - 8 - Canvas::text_width(label, 2), py(t) - 6, label, 2, black);
  }
  canvas.line(left, bottom, right, bottom, 1.5f, black);
  canvas.line(left, top, left, bottom, 1.5f, black);
  canvas.text((left + right) / 2 - Canvas::text_width(plot.x_label, 2) / 2, bottom + 36, plot.x_label, 2, black);
  canvas.text(left, 34, plot.y_label, 2, black);
  canvas.text((left + right) / 2 - Canvas::text_width(plot.title, 2.5f) / 2, 10, plot.title, 2.5f, black);

  const auto color_of = [&](size_t i) {
    const int k = plot.series[i].color >= 0 ? plot.series[i].color : int(i);
    return kPalette[size_t(k) % std::size(kPalette)];
  };
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    const Color c = color_of(i);
    float dash = 0;
    for (size_t k = 1; k < s.x.size(); ++k) {
      const double x0 = s.x[k - 1], y0 = s.y[k - 1], x1 = s.x[k], y1 = s.y[k];
      if (!(std::isfinite(y0) && std::isfinite(y1)) || (plot.log_y && (y0 <= 0 || y1 <= 0))) continue;
      const float a = px(x0), b = py(y0), cx = px(x1), cy = py(y1);
      dash += std::hypot(cx - a, cy - b);
      if (!s.dashed || std::fmod(dash, 16.f) < 10.f) canvas.line(a, b, cx, cy, 2.f, c);
    }
  }
  // Legend, top right, on a white box over the curves.
  float legend_width = 0;
  for (const auto& s : plot.series) legend_width = std::max(legend_width, Canvas::text_width(s.label, 2));
  const float lx = right - legend_width - 60, ly = top + 8;
  canvas.rect(lx - 8, ly - 6, right - 4, ly + 22 * float(plot.series.size()) + 2, {1, 1, 1});
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const float y = ly + 22 * float(i);
    for (float x = lx; x < lx + 30; x += plot.series[i].dashed ? 16 : 30)
      canvas.line(x, y + 6, std::min(x + (plot.series[i].dashed ? 10.f : 30.f), lx + 30), y + 6, 2.5f, color_of(i));
    canvas.text(lx + 38, y, plot.series[i].label, 2, black);
  }
  write_png(file, plot.width, plot.height, canvas.rgb());
}

}  // namespace prism
