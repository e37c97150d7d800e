#pragma once
// Scenes, cameras and helpers built in code for the test suites.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/render/renderer.h"
#include "core/scene/scene.h"

namespace prism::test {

// Closed icosphere with flat faces wound counter-clockwise seen from outside (no vertex normals).
Mesh make_icosphere(const Vec3f& center, float radius, int subdivisions, uint32_t material);

// Quad (two triangles) at corner + s·u + t·v, s, t ∈ [0, 1]; front side = cross(u, v).
Mesh make_quad(const Vec3f& corner, const Vec3f& u, const Vec3f& v, uint32_t material);

// Perspective camera at eye looking at target.
CameraDesc look_at(const Vec3f& eye, const Vec3f& target, float yfov_degrees);

Material diffuse(Rgb albedo, const std::string& name = "diffuse");

// A closed, double-sided sphere of radius 1 at the origin, albedo 0.5 and emitting 0.5: seen from
// inside, every pixel's radiance is Le / (1 − albedo) = 1 exactly.
Scene emitting_sphere_scene();

// Adds a mesh with one identity instance; returns the mesh index.
uint32_t add_mesh(Scene& scene, Mesh mesh);

struct TestRender {
  int width, height;
  std::vector<float> rgb;  // linear Rec.709, interleaved
  RenderStats stats;

  double mean(int channel) const;
  // Mean of one channel over the pixels in the rectangle [x0,x1) × [y0,y1).
  double mean(int channel, int x0, int y0, int x1, int y1) const;
  // Standard error of that mean, from the spread of the (independent) pixel estimates.
  double standard_error(int channel, int x0, int y0, int x1, int y1) const;
};

// Checks that every channel's mean over [x0,x1) × [y0,y1) is expected ± tolerance, after
// requiring the estimate's standard error to be at most tolerance / 4: a true answer then fails
// with probability below 1e-4, and a noisy render cannot pass by luck.
void check_mean(const TestRender& img, int x0, int y0, int x1, int y1, double expected, double tolerance);

// Mean of one channel's per-pixel difference a − b over the whole image, with its standard
// error from the spread of the differences: the images' shared structure cancels, so this
// measures the noise of two independent renders of the same scene.
struct MeanDifference {
  double difference, standard_error;
};
MeanDifference mean_difference(const TestRender& a, const TestRender& b, int channel);

TestRender render_rgb(const Scene& scene, const CameraDesc& camera, int width, int height, RenderOptions options);
TestRender render_rgb(const World& world, const CameraDesc& camera, int width, int height, RenderOptions options);
TestRender render_rgb(const Scene& scene, const CameraDesc& camera, int width, int height, int spp, int max_depth = 64,
                      uint64_t seed = 1, int threads = 0, IntegratorKind integrator = IntegratorKind::path);

// RFC 4648 base64 of bytes (for data URIs in generated glTF files).
std::string base64(const std::vector<unsigned char>& bytes);

// A fresh empty folder for a test's files, removed when the test program ends (kept when the
// environment sets PRISM_KEEP_TEST_DIRS, to look at them).
std::filesystem::path temp_dir(const std::string& name);

// The message of the prism::Error that f throws, or "(no error)".
std::string error_of(const std::function<void()>& f);

// Runs the prism executable with arguments; returns its exit code, stderr in `err` and stdout
// in `out` when given.
int run_prism(const std::string& arguments, std::string* err = nullptr, std::string* out = nullptr);

// The shared assets (PRISM_SHARED_DIR): developer assets the project never needs to build or pass
// its tests. shared_dir() is their folder.
std::filesystem::path shared_dir();
// Whether `needed` (a path inside the shared assets; their folder itself by default) exists. When
// it does not, warns "SKIPPED: the shared assets (PRISM_SHARED_DIR) are absent" (once per test
// program), which CTest counts as a skipped test, and returns false: a test that uses the shared
// assets returns at once.
bool shared_assets_present(const std::filesystem::path& needed = {});
// Every .gltf and .glb below the shared assets' assets/gltf, or none (a skip, as above) when the
// shared assets are absent.
std::vector<std::filesystem::path> shared_gltf_assets();

}  // namespace prism::test
