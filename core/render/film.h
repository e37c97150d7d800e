#pragma once
// The film: per pixel, the sum of its CIE XYZ sample estimates (box filter over the pixel's
// area) and their count, the sums of the squares of the samples' X, Y and Z and of their products
// XY, XZ, YZ (so that the variance of any linear combination, an output colour space's channels,
// is known) and the XYZ sum of the pixel's second replicate (if it takes one) for the error
// estimate (error_estimate.h), and on request the first-hit AOV sums and spectral bins.
//
// Every sum is exact: each sample is rounded once to a fixed-point integer (fixed_point.h) and
// integers add associatively. So a film is a pure function of WHICH samples each pixel took,
// whatever their order, the thread count, the pass split, a save and reload in between, or a
// split into sample ranges and tiles rendered apart and merged (Film::merge): the merged
// image equals the single render bit for bit. Every finite sample is added: a value beyond the
// fixed-point range (|value| >= kFixedLimit) goes, rounded to an integer, into the pixel's wide
// sums (WideSum), made for the pixels that meet one. A NaN or infinite estimate counts as invalid
// and is added as 0.

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/base/vec.h"
#include "core/render/fixed_point.h"
#include "core/render/spectral_bins.h"
#include "core/render/splat_buffer.h"
#include "spectral/rgb.h"

namespace prism {

// What the first surface a camera ray hits tells a compositor or denoiser.
enum Aov : uint32_t { kAovAlbedo = 1, kAovNormal = 2, kAovDepth = 4, kAovVariance = 8, kAovSpp = 16 };
// Not a layer: the film also keeps light-tracing splats (splat_buffer.h), sums of XYZ that light
// paths add to any pixel. A pixel's value is (its samples' sum + its splats) / its sample count:
// each of its samples traced one light path, so the count is the number of light paths too.
// The error estimate covers the pixel's own samples only.
constexpr uint32_t kFilmSplats = 1u << 16;

// One camera sample's contribution, as the film stores it.
struct FilmSample {
  Xyz xyz;
  // First hit (when AOVs are on): albedo under D65 as XYZ, shading normal, camera distance.
  Xyz albedo{0, 0, 0};
  Vec3f normal{0, 0, 0};
  float depth = 0;
  bool hit = false;
};

class Film {
 public:
  // aovs: which first-hit AOVs to gather (kAovAlbedo | kAovNormal | kAovDepth; the others are
  // derived from the sums); bins: the spectral bins to gather, or none.
  Film(int width, int height, uint32_t aovs = 0, SpectralBins bins = {});

  // Bytes of sums and counts per pixel of a film made with these aovs and bins (what the
  // constructor allocates), for refusing a frame that would not fit before allocating it; and of
  // the fixed-point fields alone (what a checkpoint stores per pixel, visit_fields).
  static uint64_t bytes_per_pixel(uint32_t aovs, const SpectralBins& bins);
  static uint64_t field_bytes_per_pixel(uint32_t aovs, const SpectralBins& bins);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return size_t(width_) * height_; }
  uint32_t aovs() const { return aovs_; }
  const SpectralBins& bins() const { return bins_; }

  // Adds one sample of pixel p (index y·width + x) from the sampler's replicate 0 or 1. A NaN or
  // Inf estimate counts as a sample of 0; returns false for it (the caller counts it as invalid).
  // Only the thread that renders pixel p may add to it.
  bool add(size_t p, const FilmSample& s, int replicate = 0);
  // One sample value rounded to the film's integers once, for adding it many times.
  struct FixedXyz {
    // 0 where a channel is beyond the fixed-point range, which `wide` holds (cross: XY, XZ, YZ).
    Fixed value[3], square[3], cross[3];
    double wide[3];  // the channels beyond it (0 for the others)
    bool has_wide;
    bool valid;  // false for a NaN or Inf value, whose integers are those of 0
  };
  static FixedXyz to_fixed_xyz(const Xyz& xyz);
  // Adds n samples of one value that hit no surface (zero first-hit AOVs): to the bit what n calls
  // of add would, as their sums are n times the same integers. Returns false if the value is
  // invalid (then all n count as invalid samples of 0).
  bool add_repeated(size_t p, const FixedXyz& xyz, uint32_t n, int replicate = 0);
  // Adds every sum and count of `other` (a film of the same size, AOVs and bins) to this one.
  void merge(const Film& other);
  bool same_layout(const Film& other) const {
    return width_ == other.width_ && height_ == other.height_ && aovs_ == other.aovs_ &&
           bins_.to_string() == other.bins_.to_string();
  }
  // Adds the spectral radiance estimate L(λ)/p(λ) of one wavelength lane to its bin. Lanes a
  // dispersive interface terminated (pdf 0) carry no estimate and must not be added (pbrt-v4
  // PR 550).
  void add_spectral(size_t p, float lambda, double weighted_radiance);

  // The sample indices pixel p has taken (the samples of its replicate 0), and those its second
  // replicate took.
  uint32_t samples(size_t p) const { return count_[p]; }
  uint32_t second_replicate_samples(size_t p) const { return second_count_[p]; }
  // Mean of channel c (0, 1, 2: X, Y, Z) of all pixel p's samples, and s²/n with s² their
  // unbiased sample variance: the variance of that mean if the samples were independent.
  double mean(size_t p, int c) const;
  // Adds a thread's light-tracing splats (a film made with kFilmSplats).
  void add_splats(const SplatBuffer& splats);
  double variance_of_mean(size_t p, int c) const;
  // The same for the linear combination w · (X, Y, Z) of the channels (an output space's channel).
  double variance_of_mean(size_t p, const std::array<double, 3>& w) const;
  // Mean of channel c of the samples of pixel p's replicate 0 and of its replicate 1.
  double replicate_mean(size_t p, int c, int replicate) const;
  // The same for the luminance Y.
  double mean_y(size_t p) const { return mean(p, 1); }
  double variance_of_mean(size_t p) const { return variance_of_mean(p, 1); }

  // Interleaved per-pixel means (top row first) of XYZ, of the albedo XYZ and of the normal; the
  // mean depth of the samples that hit (+inf where none did); the spectral bins' mean spectral
  // radiance per nm, bin-major within a pixel.
  std::vector<float> xyz_image() const;
  std::vector<float> albedo_image() const;
  std::vector<float> normal_image() const;
  std::vector<float> depth_image() const;
  std::vector<float> spectral_image() const;

  // The raw fields, in a fixed order, for checkpoint files (to write, and to read back).
  template <typename Visit>
  void visit_fields(Visit&& visit) const {
    visit(sum_), visit(sq_), visit(cross_), visit(count_), visit(second_sum_), visit(second_count_), visit(aov_),
        visit(spectral_), visit(splat_);
  }
  template <typename Visit>
  void visit_fields(Visit&& visit) {
    visit(sum_), visit(sq_), visit(cross_), visit(count_), visit(second_sum_), visit(second_count_), visit(aov_),
        visit(spectral_), visit(splat_);
  }
  // The wide sums of the pixels that have them (see WideSums), for checkpoint files: visit(p,
  // sums) for each such pixel p, in pixel order; wide(p) makes pixel p's to read them into.
  struct WideSums {
    WideSum sum[3], sq[3], cross[3], second_sum[3], splat[3];
    std::vector<WideSum> spectral;  // one per bin, or none
    bool operator==(const WideSums&) const = default;
  };
  template <typename Visit>
  void visit_wide(Visit&& visit) const {
    for (size_t p = 0; p < wide_.size(); ++p)
      if (wide_[p]) visit(p, *wide_[p]);
  }
  WideSums& wide(size_t p);

 private:
  static constexpr int kAovFields = 8;  // albedo XYZ, normal XYZ, depth sum, hit count

  double all_samples(size_t p) const { return std::max(count_[p] + second_count_[p], 1u); }
  // Field f of pixel p's wide sums, 0 where it has none.
  template <typename Field>
  double wide_value(size_t p, const Field& field) const {
    return wide_[p] ? field(*wide_[p]).to_double() : 0.0;
  }

  int width_, height_;
  uint32_t aovs_;
  SpectralBins bins_;
  std::vector<Fixed> sum_;              // XYZ sums of all samples
  std::vector<Fixed> sq_;               // Σ X², Σ Y², Σ Z², at kFixedSquareBits
  std::vector<Fixed> cross_;            // Σ XY, Σ XZ, Σ YZ, at kFixedSquareBits
  std::vector<uint32_t> count_;         // samples of replicate 0
  std::vector<Fixed> second_sum_;       // XYZ sums of replicate 1
  std::vector<uint32_t> second_count_;  // samples of replicate 1
  std::vector<Fixed> aov_;              // kAovFields sums per pixel, when AOVs are on
  std::vector<Fixed> spectral_;         // bins_.count() sums per pixel
  std::vector<Fixed> splat_;            // XYZ splat sums per pixel, with kFilmSplats
  // Per pixel, the sums of its values beyond the fixed-point range, made at the first such value:
  // the sums above are the fixed-point values' only. Each pixel's are its own thread's to make.
  // (A film copies like a value: the copy gets its own wide sums.)
  struct WidePixels : std::vector<std::unique_ptr<WideSums>> {
    using vector::vector;
    WidePixels(const WidePixels& other) : vector(other.size()) { *this = other; }
    WidePixels(WidePixels&&) = default;
    WidePixels& operator=(WidePixels&&) = default;
    WidePixels& operator=(const WidePixels& other) {
      resize(other.size());
      for (size_t p = 0; p < size(); ++p) (*this)[p] = other[p] ? std::make_unique<WideSums>(*other[p]) : nullptr;
      return *this;
    }
  };
  WidePixels wide_;
};

}  // namespace prism
