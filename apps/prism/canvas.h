#pragma once
// A small RGB canvas for the commands' PNG figures (plots, isolux maps): filled rectangles,
// anti-aliased lines and stb_easy_font's text, in display-encoded values in [0, 1] (write_png's).

#include <stb_easy_font.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace prism {

using Color = std::array<float, 3>;

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

}  // namespace prism
