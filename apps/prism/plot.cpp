#include "apps/prism/plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "apps/prism/canvas.h"
#include "core/base/error.h"
#include "core/render/image_output.h"

namespace prism {

namespace {

// Matplotlib's default colour cycle ("tab10").
const Color kPalette[] = {{0.122f, 0.467f, 0.706f}, {1.000f, 0.498f, 0.055f}, {0.173f, 0.627f, 0.173f},
                          {0.839f, 0.153f, 0.157f}, {0.580f, 0.404f, 0.741f}, {0.549f, 0.337f, 0.294f},
                          {0.890f, 0.467f, 0.761f}, {0.498f, 0.498f, 0.498f}, {0.737f, 0.741f, 0.133f},
                          {0.090f, 0.745f, 0.812f}};

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
  return nice_ticks(a.lo, a.hi, 6);
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int about) {
  std::vector<double> t;
  const double raw = (hi - lo) / about, mag = std::pow(10, std::floor(std::log10(raw)));
  const double step = raw / mag < 2 ? 2 * mag : raw / mag < 5 ? 5 * mag : 10 * mag;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step)
    t.push_back(std::abs(v) < 1e-12 ? 0 : v);
  return t;
}

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
