// `prism measure SCENE -o OUT.csv (--point … | --points FILE | --grid …)`: illuminance meters
// (core/render/meter.h) at points of the scene, each on a surface of a given normal, in lux with
// its standard error, and with --spectral-bins the spectral irradiance. --grid also writes
// OUT.png, a false-colour map with isolux lines (isolux_map.h).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "apps/prism/commands.h"
#include "apps/prism/isolux_map.h"
#include "apps/prism/scene_setup.h"
#include "core/base/atomic_file.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/number_list.h"
#include "core/render/meter.h"

namespace prism {

namespace {

struct MeasureArgs {
  SceneArgs scene;
  std::vector<std::string> points;
  std::string points_file, grid, output, spectral_bins;
  MeterOptions options;
  bool quiet = false;
};

MeterPoint meter_point(const std::vector<float>& v, const std::string& what) {
  if (v.size() != 6) fail("{}: expected X,Y,Z,NX,NY,NZ (a position and a normal)", what);
  const Vec3f n{v[3], v[4], v[5]};
  if (!(length(n) > 0)) fail("{}: the normal is zero", what);
  return {Vec3f(v[0], v[1], v[2]), normalize(n)};
}

// A grid of nx × ny points at the cells' centres of a rectangle: row 0 at the first corner's far
// edge along the second axis, so that the map reads as the rectangle seen from its normal side.
struct Grid {
  int nx = 0, ny = 0;
  std::vector<MeterPoint> points;
};

Grid rectangle_grid(Vec3f a, Vec3f b, int nx, int ny, const std::string& what) {
  if (nx < 1 || ny < 1 || int64_t(nx) * ny > 4'000'000) fail("{}: the grid needs 1 to 4000000 points", what);
  // The rectangle lies in a plane of constant x, y or z: the axis along which the corners agree.
  int flat = -1;
  for (int c = 0; c < 3; ++c)
    if (a[c] == b[c]) flat = flat < 0 ? c : 3;
  if (flat < 0 || flat == 3)
    fail("{}: the corners must agree in exactly one coordinate (the rectangle's plane: x, y or z = constant)", what);
  const int u = (flat + 1) % 3, v = (flat + 2) % 3;
  // Spans along the plane's axes: for a floor (y constant) x across and z down the map.
  const int across = flat == 1 ? 0 : u, down = flat == 1 ? 2 : v;
  Vec3f n(0, 0, 0);
  n[flat] = 1;
  Grid g{nx, ny, {}};
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      Vec3f p = a;
      p[across] = a[across] + (b[across] - a[across]) * (float(i) + 0.5f) / float(nx);
      p[down] = a[down] + (b[down] - a[down]) * (float(j) + 0.5f) / float(ny);
      g.points.push_back({p, n});
    }
  return g;
}

// --grid NAME:SPACING — the top face (y up) of the bounding box of the glTF nodes of that name
// (else the meshes of that name) in the posed scene, points SPACING apart; or X0,Y0,Z0,X1,Y1,Z1,NX,NY
// — a rectangle between two corners that agree in one coordinate, NX × NY points, normal along that
// axis.
Grid grid_points(const std::string& text, const Scene& scene) {
  const std::string what = "--grid " + text;
  const size_t colon = text.rfind(':');
  if (colon != std::string::npos) {
    const std::string name = text.substr(0, colon);
    const std::vector<double> spacing = parse_numbers(text.substr(colon + 1), what);
    if (spacing.size() != 1 || !(spacing[0] > 0)) fail("{}: expected NAME:SPACING, a positive spacing", what);
    Bounds3f box;
    const auto extend = [&](const Instance& inst) {
      for (const Vec3f& p : scene.meshes[inst.mesh].positions) box.extend(Vec3f(inst.to_world.point(Vec3d(p))));
    };
    for (const NamedInstances& node : scene.named_nodes)
      if (node.node == name)
        for (uint32_t i = node.first; i < node.end; ++i) extend(scene.instances[i]);
    if (box.empty())
      for (const Instance& inst : scene.instances)
        if (scene.meshes[inst.mesh].name == name) extend(inst);
    if (box.empty()) fail("{}: no node or mesh named '{}' in the scene", what, name);
    const float top = box.hi.y + 1e-4f * std::max(1.f, std::abs(box.hi.y));
    // Counts beyond the grid's limit stay beyond it (and get its message) without overflowing an int.
    const auto count = [&](float extent) { return int(std::clamp(std::round(extent / spacing[0]), 1.0, 1e7)); };
    const int nx = count(box.hi.x - box.lo.x), ny = count(box.hi.z - box.lo.z);
    return rectangle_grid({box.lo.x, top, box.lo.z}, {box.hi.x, top, box.hi.z}, nx, ny, what);
  }
  const std::vector<float> v = parse_floats(text, what);
  if (v.size() != 8 || v[6] != std::floor(v[6]) || v[7] != std::floor(v[7]))
    fail("{}: expected NAME:SPACING or X0,Y0,Z0,X1,Y1,Z1,NX,NY", what);
  return rectangle_grid(Vec3f(v[0], v[1], v[2]), Vec3f(v[3], v[4], v[5]), int(std::clamp(v[6], 0.f, 1e7f)),
                        int(std::clamp(v[7], 0.f, 1e7f)), what);
}

// --points FILE: rows x,y,z,nx,ny,nz (a header line and '#' comments allowed).
std::vector<MeterPoint> points_file(const std::string& file) {
  std::ifstream in(file);
  if (!in) fail("--points {}: cannot read it", file);
  std::vector<MeterPoint> out;
  std::string line;
  for (int row = 1; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    if (out.empty() && line.find_first_of("0123456789") != line.find_first_not_of(" \t+-.") &&
        std::isalpha(static_cast<unsigned char>(line[line.find_first_not_of(" \t")])))
      continue;  // a header
    out.push_back(
        meter_point(parse_floats(line, fmt::format("{} line {}", file, row)), fmt::format("{} line {}", file, row)));
  }
  if (out.empty()) fail("--points {}: no points", file);
  return out;
}

void run(const MeasureArgs& args) {
  if (args.quiet) log::set_level(log::Level::warn);
  const int sources = !args.points.empty() + !args.points_file.empty() + !args.grid.empty();
  if (sources != 1) fail("give the points one way: --point (repeatable), --points FILE or --grid");
  MeterOptions options = args.options;
  options.progress = !args.quiet;
  if (!args.spectral_bins.empty()) options.bins = SpectralBins::parse(args.spectral_bins);
  const PreparedScene prepared = prepare_scene(args.scene);
  Grid grid;
  std::vector<MeterPoint> points;
  if (!args.grid.empty()) {
    grid = grid_points(args.grid, prepared.gltf->scene());
    points = grid.points;
  } else if (!args.points_file.empty()) {
    points = points_file(args.points_file);
  } else {
    for (const std::string& p : args.points)
      points.push_back(meter_point(parse_floats(p, "--point " + p), "--point " + p));
  }
  log::info("measuring illuminance at {} points{}", points.size(),
            options.rel_error > 0
                ? fmt::format(" to a relative error of {} (at most {} samples)", options.rel_error, options.spp)
                : fmt::format(" with {} samples each", options.spp));
  const std::vector<MeterReading> readings = measure(*prepared.world, points, options);

  write_atomically(args.output, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    out << "x,y,z,nx,ny,nz,illuminance_lux,std_error_lux";
    for (int b = 0; b < options.bins.count(); ++b)
      out << ",irradiance_" << fmt::format("{:g}", options.bins.centre(b)) << "nm";
    out << '\n';
    for (size_t i = 0; i < points.size(); ++i) {
      const MeterPoint& p = points[i];
      out << fmt::format("{:g},{:g},{:g},{:g},{:g},{:g},{:.9g},{:.3g}", p.p.x, p.p.y, p.p.z, p.n.x, p.n.y, p.n.z,
                         readings[i].illuminance, readings[i].std_error);
      for (double v : readings[i].spectral) out << fmt::format(",{:.6g}", v);
      out << '\n';
    }
    if (!out) throw std::runtime_error("write error");
  });
  std::printf("wrote %s (%zu points)\n", args.output.c_str(), points.size());
  if (!args.grid.empty()) {
    std::vector<double> lux;
    for (const MeterReading& r : readings) lux.push_back(r.illuminance);
    const std::filesystem::path png = std::filesystem::path(args.output).replace_extension(".png");
    write_isolux_png(png, grid.nx, grid.ny, lux,
                     fmt::format("Illuminance, {} ({} x {} points)", args.grid, grid.nx, grid.ny));
    std::printf("wrote %s (isolux map)\n", png.string().c_str());
  }
}

}  // namespace

void add_measure_command(CLI::App& app) {
  auto args = std::make_shared<MeasureArgs>();
  CLI::App* cmd = app.add_subcommand(
      "measure", "Illuminance (lux) at points of a scene, as a lux meter on a surface of a given normal reads it");
  add_scene_options(cmd, args->scene);
  cmd->add_option("-o,--output", args->output, "Output CSV: x,y,z,nx,ny,nz,illuminance_lux,std_error_lux")->required();
  cmd->add_option("--point", args->points, "A meter X,Y,Z,NX,NY,NZ: position and the normal of its surface (repeat)");
  cmd->add_option("--points", args->points_file, "A CSV of meters, one x,y,z,nx,ny,nz per line");
  cmd->add_option("--grid", args->grid,
                  "A grid of meters: NAME:SPACING (the top of the bounding box of a glTF node or mesh, y up) or "
                  "X0,Y0,Z0,X1,Y1,Z1,NX,NY (a rectangle whose corners agree in one coordinate); also writes "
                  "OUTPUT.png, an isolux map");
  cmd->add_option("--spp", args->options.spp, "Samples per point (with --rel-error, the most a point takes)")
      ->default_val(256)
      ->check(positive_count());
  cmd->add_option("--rel-error", args->options.rel_error,
                  "Sample until every point's standard error is below this fraction of its reading")
      ->check(CLI::Range(1e-6, 0.999999));
  cmd->add_option("--spectral-bins", args->spectral_bins,
                  "Also write the spectral irradiance in N equal bins over 360-830 nm, or at edges e0,e1,... (nm)");
  cmd->add_option("--seed", args->options.seed, "Random seed: the same seed gives the same readings")
      ->default_val(0)
      ->check(seed_value());
  cmd->add_option("--threads", args->options.threads, "Worker threads (0: all cores)")
      ->default_val(0)
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-depth", args->options.path.max_depth, "Maximum path length in bounces")
      ->default_val(16)
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("-q,--quiet", args->quiet, "Only warnings and errors; no progress bar");
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
