#include "tests/support/test_scenes.h"

#include <sys/wait.h>

#include <array>
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/base/error.h"
#include "spectral/color_pipeline.h"

namespace prism::test {

Mesh make_icosphere(const Vec3f& center, float radius, int subdivisions, uint32_t material) {
  const float t = (1.f + std::sqrt(5.f)) / 2.f;
  std::vector<Vec3f> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                          {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<uint32_t, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p = normalize(p);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, uint32_t(v.size()));
      if (inserted) v.push_back(normalize(v[a] + v[b]));
      return it->second;
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (const auto& tri : f) {
      const uint32_t a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f = std::move(next);
  }
  Mesh mesh;
  mesh.name = "icosphere";
  for (const auto& p : v) mesh.positions.push_back(center + p * radius);
  for (const auto& tri : f) mesh.indices.insert(mesh.indices.end(), tri.begin(), tri.end());
  mesh.material = material;
  return mesh;
}

Mesh make_quad(const Vec3f& corner, const Vec3f& u, const Vec3f& v, uint32_t material) {
  Mesh mesh;
  mesh.name = "quad";
  mesh.positions = {corner, corner + u, corner + u + v, corner + v};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.material = material;
  return mesh;
}

CameraDesc look_at(const Vec3f& eye, const Vec3f& target, float yfov_degrees) {
  CameraDesc c;
  c.name = "test camera";
  c.yfov = radians(yfov_degrees);
  const Vec3d back = normalize(Vec3d(eye - target));
  const Vec3d world_up = std::abs(back.y) > 0.99 ? Vec3d(0, 0, 1) : Vec3d(0, 1, 0);
  const Vec3d right = normalize(cross(world_up, back));
  const Vec3d up = cross(back, right);
  for (int r = 0; r < 3; ++r) {
    c.to_world.m[r][0] = right[r];
    c.to_world.m[r][1] = up[r];
    c.to_world.m[r][2] = back[r];
    c.to_world.m[r][3] = eye[r];
  }
  return c;
}

Material diffuse(Rgb albedo, const std::string& name) {
  return Material{.name = name, .kind = DiffuseMaterial{RgbAlbedoSpectrum(albedo)}};
}

uint32_t add_mesh(Scene& scene, Mesh mesh) {
  scene.meshes.push_back(std::move(mesh));
  const uint32_t index = uint32_t(scene.meshes.size() - 1);
  scene.instances.push_back({index, Transform{}});
  return index;
}

Scene emitting_sphere_scene() {
  Scene scene;
  Material m = diffuse({0.5f, 0.5f, 0.5f});
  m.emission = RgbIlluminantSpectrum(Rgb{0.5f, 0.5f, 0.5f});
  m.double_sided = true;
  scene.materials.push_back(m);
  add_mesh(scene, make_icosphere({0, 0, 0}, 1.f, 2, 0));
  return scene;
}

double TestRender::mean(int channel) const { return mean(channel, 0, 0, width, height); }

double TestRender::mean(int channel, int x0, int y0, int x1, int y1) const {
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += rgb[(size_t(y) * width + x) * 3 + channel];
  return sum / (double(x1 - x0) * (y1 - y0));
}

double TestRender::standard_error(int channel, int x0, int y0, int x1, int y1) const {
  const double m = mean(channel, x0, y0, x1, y1);
  double sum_sq = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum_sq += sqr(rgb[(size_t(y) * width + x) * 3 + channel] - m);
  const double n = double(x1 - x0) * (y1 - y0);
  return std::sqrt(sum_sq / (n - 1) / n);
}

MeanDifference mean_difference(const TestRender& a, const TestRender& b, int channel) {
  const size_t n = a.rgb.size() / 3;
  double sum = 0, sum_sq = 0;
  for (size_t i = 0; i < n; ++i) {
    const double d = double(a.rgb[i * 3 + channel]) - b.rgb[i * 3 + channel];
    sum += d;
    sum_sq += d * d;
  }
  const double mean = sum / double(n);
  return {mean, std::sqrt(std::max(0.0, sum_sq / double(n) - mean * mean) / double(n - 1))};
}

void check_mean(const TestRender& img, int x0, int y0, int x1, int y1, double expected, double tolerance) {
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << " over [" << x0 << "," << x1 << ") x [" << y0 << "," << y1 << ")");
    REQUIRE(img.standard_error(c, x0, y0, x1, y1) <= tolerance / 4);
    CHECK(img.mean(c, x0, y0, x1, y1) == Approx(expected).margin(tolerance));
  }
}

TestRender render_rgb(const Scene& scene, const CameraDesc& camera, int width, int height, RenderOptions options) {
  return render_rgb(World(scene), camera, width, height, options);
}

TestRender render_rgb(const World& world, const CameraDesc& camera, int width, int height, RenderOptions options) {
  options.progress = false;
  const RenderResult r = render(world, Camera(camera, width, height), options);
  std::vector<float> rgb = r.state.film.xyz_image();
  ColorPipeline::standard().convert(ColorPipeline::kXyz, ColorPipeline::kDefaultOutput, rgb.data(), rgb.size() / 3);
  return {r.width(), r.height(), std::move(rgb), r.stats()};
}

TestRender render_rgb(const Scene& scene, const CameraDesc& camera, int width, int height, int spp, int max_depth,
                      uint64_t seed, int threads, IntegratorKind integrator) {
  RenderOptions options;
  options.integrator = integrator;
  options.spp = spp;
  options.seed = seed;
  options.threads = threads;
  options.path.max_depth = max_depth;
  return render_rgb(scene, camera, width, height, options);
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = (uint32_t(bytes[i]) << 16) | (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

std::filesystem::path temp_dir(const std::string& name) {
  struct Made {
    std::set<std::filesystem::path> dirs;
    ~Made() {
      if (std::getenv("PRISM_KEEP_TEST_DIRS")) return;
      std::error_code ignored;
      for (const auto& dir : dirs) std::filesystem::remove_all(dir, ignored);
    }
  };
  static Made made;
  const auto dir = std::filesystem::temp_directory_path() / ("prism_test_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  made.dirs.insert(dir);
  return dir;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

int run_prism(const std::string& arguments, std::string* err, std::string* out) {
  const auto dir = temp_dir("run");
  const auto out_file = dir / "stdout.txt", err_file = dir / "stderr.txt";
  const std::string command = std::string("\"") + PRISM_EXECUTABLE + "\" " + arguments + " >\"" + out_file.string() +
                              "\" 2>\"" + err_file.string() + "\"";
  const int status = std::system(command.c_str());
  const auto slurp = [](const std::filesystem::path& file) {
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  if (err) *err = slurp(err_file);
  if (out) *out = slurp(out_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::filesystem::path shared_dir() { return PRISM_SHARED_DIR; }

bool shared_assets_present(const std::filesystem::path& needed) {
  if (std::filesystem::exists(needed.empty() ? shared_dir() : shared_dir() / needed)) return true;
  static bool warned = false;
  if (!warned) WARN("SKIPPED: the shared assets (PRISM_SHARED_DIR) are absent");
  warned = true;
  return false;
}

std::vector<std::filesystem::path> shared_gltf_assets() {
  const auto root = shared_dir() / "assets" / "gltf";
  std::vector<std::filesystem::path> files;
  if (!shared_assets_present("assets/gltf")) return files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
    if (entry.path().extension() == ".gltf" || entry.path().extension() == ".glb") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace prism::test
