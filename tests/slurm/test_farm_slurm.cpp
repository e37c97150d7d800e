// `prism farm slurm` on a real Slurm cluster: tools/slurm/local_cluster.sh starts a single-node
// cluster on this machine (as root, as CI runs; the test skips where it cannot), a 4-part array
// render plus its merge job give the single render's image bit for bit, so do the 2 parts of
// each of an animation's 2 frames give `prism render --frames`, and after one array
// task is cancelled mid-run, submitting again renders only the missing part and completes the
// image. CTest label `slurm` (run by .ci/run after `make test`, and under `make test-sanitize`).

#include <fmt/format.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "core/render/image_output.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

const std::string kCornell = "\"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\"";
const std::string kCluster = PRISM_SOURCE_DIR "/tools/slurm/local_cluster.sh";

// The standard output of a shell command, and its exit status.
std::pair<std::string, int> shell(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof(buffer), pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  return {out, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

// Stops the cluster it started, whatever the test's outcome.
struct Cluster {
  std::filesystem::path dir;
  ~Cluster() { shell(fmt::format("'{}' stop '{}'", kCluster, dir.string())); }
};

// Waits until the queue has no jobs of that name (they ended one way or another).
void wait_for_queue(const std::string& name = "prism-parts,prism-merge") {
  const auto start = std::chrono::steady_clock::now();
  while (!shell("squeue -h -n " + name).first.empty()) {
    REQUIRE(std::chrono::steady_clock::now() - start < std::chrono::minutes(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

std::vector<float> rgb(const std::filesystem::path& exr) {
  std::vector<float> out;
  for (const char* c : {"R", "G", "B"}) {
    const std::vector<float> v = read_exr_channel(exr, c);
    out.insert(out.end(), v.begin(), v.end());
  }
  return out;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE(
    "slurm: array renders of a still and of 2 animation frames merge to the single render, and resubmission "
    "completes a cancelled one",
    "[slurm]") {
  if (geteuid() != 0) {
    WARN("SKIPPED: starting a local Slurm cluster needs root (CI runs as root)");
    return;
  }
  const auto dir = test::temp_dir("slurm");
  Cluster cluster{dir / "cluster"};
  const auto [started, code] = shell(fmt::format("'{}' start '{}' 2>&1", kCluster, cluster.dir.string()));
  if (code == 77) {
    WARN("SKIPPED: no local Slurm cluster here: " << started);
    return;
  }
  REQUIRE(code == 0);
  setenv("SLURM_CONF", (cluster.dir / "slurm.conf").c_str(), 1);

  const auto single = [&](const std::string& name, const std::string& options) {
    REQUIRE(test::run_prism(
                fmt::format("render {} {} -q -o \"{}\"", kCornell, options, (dir / (name + ".exr")).string())) == 0);
  };
  const auto farm = [&](const std::string& name, const std::string& options) {
    return fmt::format("\"{}\" farm slurm {} --parts 4 {} --out \"{}\"", PRISM_EXECUTABLE, kCornell, options,
                       (dir / name).string());
  };
  {
    INFO("4 parts and the merge");
    const std::string options = "--width 64 --spp 16 --seed 2 --threads 1";
    single("whole", options);
    const auto [out, status] = shell(farm("whole", options));
    INFO(out);
    REQUIRE(status == 0);
    CHECK_THAT(out, Catch::Contains("submitted parts job") && Catch::Contains("submitted merge job"));
    wait_for_queue();
    REQUIRE(std::filesystem::exists(dir / "whole/image.exr"));
    CHECK(same_bits(rgb(dir / "whole/image.exr"), rgb(dir / "whole.exr")));
  }
  {
    INFO("an animation: 2 frames of 2 parts each, one array job, the merge job writes each frame");
    const std::string scene = test::write_animated_triangle(dir).string();
    const std::string options = "--width 16 --height 16 --env 1,1,1 --animation linear --spp 8 --seed 3 --threads 1";
    REQUIRE(test::run_prism(fmt::format("render \"{}\" {} --frames 0:1 --fps 2 -q -o \"{}\"", scene, options,
                                        (dir / "anim.####.exr").string())) == 0);
    const auto [out, status] =
        shell(fmt::format("\"{}\" farm slurm \"{}\" --frames 0:1 --fps 2 --parts 2 {} --out \"{}\"", PRISM_EXECUTABLE,
                          scene, options, (dir / "anim").string()));
    INFO(out);
    REQUIRE(status == 0);
    CHECK_THAT(out, Catch::Contains("array tasks 0-3 of 4"));
    wait_for_queue();
    for (const char* frame : {"0000", "0001"}) {
      INFO("frame " << frame);
      const std::filesystem::path image = dir / fmt::format("anim/image.{}.exr", frame);
      REQUIRE(std::filesystem::exists(image));
      CHECK(same_bits(rgb(image), rgb(dir / fmt::format("anim.{}.exr", frame))));
    }
  }
  {
    INFO("one array task cancelled mid-run, then submitted again");
    // The path tracer's parts of this size take a few seconds each: a cancel lands mid-run.
    const std::string options = "--width 64 --spp 640 --seed 4 --threads 1 --integrator path";
    single("cancel", options);
    // A cancel can come too late: the task had finished, or its SIGTERM came during its last pass,
    // which prism completes, writing the whole part. Then all four parts are there, and submitting
    // again must merge them to the single render; the check starts over in a new folder.
    for (int attempt = 0;; ++attempt) {
      REQUIRE(attempt < 3);
      const std::string name = fmt::format("cancel-{}", attempt);
      REQUIRE(shell(farm(name, options)).second == 0);
      std::string task;
      const auto start = std::chrono::steady_clock::now();
      while (task.empty()) {
        REQUIRE(std::chrono::steady_clock::now() - start < std::chrono::minutes(2));
        // the task started last (to the second), which has the most left to render
        task = shell("squeue -h -t R -n prism-parts -o %i --sort=-S | head -n 1 | tr -d '\\n'").first;
        if (task.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      REQUIRE(shell("scancel " + task).second == 0);
      wait_for_queue("prism-parts");  // the merge job waits for a dependency that can never be met
      const std::string index = task.substr(task.find('_') + 1);
      INFO("task " << task);
      const bool too_late = std::filesystem::exists(dir / name / ("part-" + index + ".prism-part"));
      if (!too_late) CHECK_FALSE(std::filesystem::exists(dir / name / "image.exr"));
      const auto [out, status] = shell(farm(name, options));
      INFO(out);
      REQUIRE(status == 0);
      if (too_late)
        CHECK_THAT(out, Catch::Contains("all 4 part files exist"));
      else
        CHECK_THAT(out, Catch::Contains("array tasks " + index + " of 4") && Catch::Contains("cancelled the earlier"));
      wait_for_queue();
      REQUIRE(std::filesystem::exists(dir / name / "image.exr"));
      CHECK(same_bits(rgb(dir / name / "image.exr"), rgb(dir / "cancel.exr")));
      if (!too_late) break;
      WARN("the cancel of task " << task << " came after its last pass: its part checked, starting over");
    }
  }
}
