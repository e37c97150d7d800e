// `prism render` under control: SIGINT and SIGTERM sent to a real render process, time limits,
// checkpoints and --resume, AOV layers and the spectral EXR layout, all through the CLI.

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfStringAttribute.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>
#include <numeric>
#include <sstream>
#include <thread>

#include "core/render/image_output.h"
#include "spectral/cie.h"
#include "tests/support/test_scenes.h"

extern char** environ;

using namespace prism;

namespace {

const std::string kCornell = "\"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\"";

std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A prism process started in the background, its stderr going to a file.
struct Process {
  pid_t pid = -1;
  std::filesystem::path err;

  Process(const std::vector<std::string>& args, const std::filesystem::path& err_file) : err(err_file) {
    std::vector<char*> argv{const_cast<char*>(PRISM_EXECUTABLE)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    REQUIRE(posix_spawn(&pid, PRISM_EXECUTABLE, &actions, nullptr, argv.data(), environ) == 0);
    posix_spawn_file_actions_destroy(&actions);
  }
  // Waits until the log shows `text` (the render has reached that point), for up to two minutes:
  // under AddressSanitizer on a loaded 2-core CI machine, the long render's pass 5 came after 30 s.
  bool wait_for_log(const std::string& text) const {
    for (int i = 0; i < 12000; ++i) {
      if (slurp(err).find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
  int wait() {
    int status = 0;
    waitpid(pid, &status, 0);
    pid = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  ~Process() {
    if (pid > 0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
};

// A render that would take hours, in passes of about a second (the path tracer's 16 spp at
// 320 × 240, 2 threads): long enough that a second signal sent as soon as the first is logged
// arrives within the pass.
std::vector<std::string> long_render(const std::filesystem::path& exr, const std::filesystem::path& png) {
  return {"render",       PRISM_SOURCE_DIR "/data/scenes/cornell.gltf",
          "--width",      "320",
          "--spp",        "1000000",
          "--integrator", "path",
          "-v",           "-o",
          exr.string(),   "--preview",
          png.string()};
}

template <typename Attribute>
auto header_value(const std::filesystem::path& exr, const char* name) {
  Imf::InputFile in(exr.c_str());
  const auto* a = in.header().findTypedAttribute<Attribute>(name);
  REQUIRE(a);
  return a->value();
}

}  // namespace

TEST_CASE("a first SIGINT or SIGTERM finishes the pass and writes the image with its real sample counts") {
  for (int sig : {SIGINT, SIGTERM}) {
    INFO("signal " << sig);
    const auto dir = test::temp_dir("signal_once");
    const auto exr = dir / "out.exr", png = dir / "out.png";
    Process p(long_render(exr, png), dir.parent_path() / ("prism_signal_once_" + std::to_string(getpid()) + ".log"));
    REQUIRE(p.wait_for_log("pass 5:"));
    kill(p.pid, sig);
    const int code = p.wait();
    INFO(slurp(p.err));
    CHECK(code == 0);
    REQUIRE(std::filesystem::exists(exr));
    CHECK(std::filesystem::exists(png));
    CHECK(header_value<Imf::IntAttribute>(exr, "prism.interrupted") == 1);
    const int spp = header_value<Imf::IntAttribute>(exr, "prism.spp");
    CHECK(spp >= 16);
    CHECK(spp < 1000000);
    CHECK(header_value<Imf::IntAttribute>(exr, "prism.sppMin") == spp);
    CHECK(header_value<Imf::DoubleAttribute>(exr, "prism.estimatedRelRmse") > 0);
    CHECK(header_value<Imf::DoubleAttribute>(exr, "prism.estimatedRelRmseRGB") > 0);
    CHECK(slurp(p.err).find("interrupted after pass") != std::string::npos);
    std::filesystem::remove(p.err);
  }
}

TEST_CASE("a second signal aborts at once, leaving no output and no temporary file") {
  for (int sig : {SIGINT, SIGTERM}) {
    INFO("signal " << sig);
    const auto dir = test::temp_dir("signal_twice");
    const auto exr = dir / "out.exr", png = dir / "out.png";
    Process p(long_render(exr, png), dir.parent_path() / ("prism_signal_twice_" + std::to_string(getpid()) + ".log"));
    REQUIRE(p.wait_for_log("pass 5:"));
    kill(p.pid, sig);
    REQUIRE(p.wait_for_log("stopping after this pass"));  // the first signal has arrived
    kill(p.pid, sig);
    CHECK(p.wait() == 128 + sig);
    CHECK(std::filesystem::is_empty(dir));  // neither images nor temporaries
    std::filesystem::remove(p.err);
  }
}

TEST_CASE("render --time-limit stops after a pass and records the samples taken") {
  const auto dir = test::temp_dir("time_limit");
  const auto exr = dir / "out.exr";
  std::string err;
  REQUIRE(test::run_prism(
              "render " + kCornell + " --width 16 --spp 1000000 --time-limit 0.01 -q -o \"" + exr.string() + "\"",
              &err) == 0);
  const int spp = header_value<Imf::IntAttribute>(exr, "prism.spp");
  CHECK(spp >= 1);
  CHECK(spp < 1000000);
  CHECK(header_value<Imf::IntAttribute>(exr, "prism.interrupted") == 0);
  CHECK(header_value<Imf::DoubleAttribute>(exr, "prism.timeLimit") == 0.01);
}

TEST_CASE("render --checkpoint and --resume continue a time-limited render to the image of the straight render") {
  const auto dir = test::temp_dir("resume");
  const auto straight = dir / "straight.exr", out = dir / "out.exr";
  const auto checkpoint = dir / "out.exr.checkpoint";
  const std::string scene = "render " + kCornell + " --width 24 -q ";
  REQUIRE(test::run_prism(scene + "--seed 5 --spp 48 -o \"" + straight.string() + "\"") == 0);
  // Time-limited to its first pass, keeping a checkpoint; then resumed to 48 samples.
  REQUIRE(test::run_prism(scene + "--seed 5 --spp 48 --time-limit 1e-6 --checkpoint 1000 -o \"" + out.string() +
                          "\"") == 0);
  REQUIRE(std::filesystem::exists(checkpoint));
  CHECK(header_value<Imf::IntAttribute>(out, "prism.spp") == 1);
  std::string err;
  CHECK(test::run_prism(scene + "--spp 48 --seed 6 --resume -o \"" + out.string() + "\"", &err) == 1);
  CHECK(err.find("another scene or other options") != std::string::npos);
  REQUIRE(test::run_prism(scene + "--seed 5 --spp 48 --resume -o \"" + out.string() + "\"", &err) == 0);
  CHECK_FALSE(std::filesystem::exists(checkpoint));  // done: nothing left to resume
  CHECK(header_value<Imf::IntAttribute>(out, "prism.spp") == 48);
  CHECK(read_exr(out).rgb == read_exr(straight).rgb);
  CHECK(test::run_prism(scene + "--resume -o \"" + out.string() + "\"", &err) == 1);
  CHECK(err.find("out.exr.checkpoint") != std::string::npos);
}

TEST_CASE("render --aov writes OpenEXR layers named as compositors expect") {
  const auto dir = test::temp_dir("aov");
  const auto exr = dir / "out.exr";
  std::string err;
  REQUIRE(test::run_prism("render " + kCornell + " --width 16 --spp 4 -q --aov albedo,normal,depth,variance,spp -o \"" +
                              exr.string() + "\"",
                          &err) == 0);
  Imf::InputFile in(exr.c_str());
  for (const char* name : {"R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z",
                           "variance.R", "variance.G", "variance.B", "variance.Y", "spp"})
    CHECK(in.header().channels().findChannel(name));
  const auto spp = read_exr_channel(exr, "spp");
  CHECK(std::all_of(spp.begin(), spp.end(), [](float n) { return n == 4; }));
  const auto z = read_exr_channel(exr, "Z");
  CHECK(std::all_of(z.begin(), z.end(), [](float d) { return d > 0; }));
  // The Cornell box's walls are matte colours below 1 (on average: each pixel's estimate is noisy,
  // its wavelengths sampled); its normals are unit vectors.
  const auto albedo = read_exr_channel(exr, "albedo.G");
  const double mean_albedo = std::accumulate(albedo.begin(), albedo.end(), 0.0) / double(albedo.size());
  CHECK(mean_albedo > 0.2);
  CHECK(mean_albedo < 0.9);
  const auto nx = read_exr_channel(exr, "N.X"), ny = read_exr_channel(exr, "N.Y"), nz = read_exr_channel(exr, "N.Z");
  for (size_t i = 0; i < nx.size(); ++i) CHECK(nx[i] * nx[i] + ny[i] * ny[i] + nz[i] * nz[i] == Approx(1).margin(1e-3));
  CHECK(test::run_prism("render " + kCornell + " --aov albedo,glow -o \"" + exr.string() + "\"", &err) == 1);
  CHECK(err.find("glow") != std::string::npos);
}

TEST_CASE("spectral EXR: the bins, integrated against the CIE functions, give the image's XYZ on a dispersive scene") {
  const auto dir = test::temp_dir("spectral");
  const auto exr = dir / "out.exr";
  const int bins = 94;
  std::string err;
  REQUIRE(test::run_prism("render \"" PRISM_SOURCE_DIR "/data/scenes/dispersion.gltf\" --width 32 --spp 16 -q "
                          "--colorspace CIE-XYZ-D65 --spectral-bins " +
                              std::to_string(bins) + " -o \"" + exr.string() + "\"",
                          &err) == 0);
  INFO(err);
  CHECK(header_value<Imf::StringAttribute>(exr, "spectralLayoutVersion") == "1.0");
  CHECK(header_value<Imf::StringAttribute>(exr, "emissiveUnits") == "W.m^-2.sr^-1");
  // 94 bins of 5 nm over 360–830 nm: centres 362.5, 367.5, ...
  const SpectralBins layout = SpectralBins::uniform(bins);
  CHECK(layout.channel_name(0) == "S0.362,5nm");
  const RgbImage xyz = read_exr(exr);  // R, G, B hold X, Y, Z here
  const CieTables& cie = prism::cie();
  const size_t pixels = size_t(xyz.width) * xyz.height;
  std::array<double, 3> from_bins{}, from_image{};
  for (int b = 0; b < bins; ++b) {
    const auto s = read_exr_channel(exr, layout.channel_name(b));
    // ∫ over the bin of x̄, ȳ, z̄ (1-nm steps), over ∫ȳ: the bin's weight in X, Y and Z.
    std::array<double, 3> w{};
    for (float l = layout.edges[b] + 0.5f; l < layout.edges[b + 1]; l += 1.f) {
      w[0] += cie.x(l);
      w[1] += cie.y(l);
      w[2] += cie.z(l);
    }
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c) from_bins[c] += s[p] * w[c] / cie.y_integral;
  }
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) from_image[c] += xyz.rgb[p * 3 + c];
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << ": bins " << from_bins[c] / pixels << ", image " << from_image[c] / pixels);
    // Both come from the same samples: they differ only because the bins weigh each wavelength
    // by its bin's mean CIE value rather than its own, a zero-mean difference that shrinks with
    // the bin width (3.2% at 10 nm, 1.4% at 5 nm in Z, the steepest function, at 16 spp). Lanes
    // leaking past a dispersive interface would add far more.
    CHECK(from_bins[c] == Approx(from_image[c]).epsilon(0.03));
  }
}
