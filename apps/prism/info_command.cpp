// `prism info SCENE`: what a glTF file holds and what Prism makes of it: scenes, cameras,
// material variants, animations, extensions (and what Prism does with each), the built scene's
// triangles, instances, bounds and features.

#include "apps/prism/commands.h"
#include "apps/prism/scene_setup.h"
#include "core/base/log.h"
#include "core/scene/scene_features.h"

namespace prism {

namespace {

struct InfoArgs {
  std::string scene;
  GltfOptions gltf;
};

std::string quoted(const std::string& name) { return name.empty() ? "(unnamed)" : "'" + name + "'"; }

void run(const InfoArgs& args) {
  GltfScene gltf(args.scene, args.gltf);
  const GltfSummary s = gltf.summary();
  const Scene& scene = gltf.scene();
  fmt::print("{}\n", args.scene);
  fmt::print("scenes: {}\n", s.scenes.size());
  for (size_t i = 0; i < s.scenes.size(); ++i)
    fmt::print("  {} {}{}\n", i, quoted(s.scenes[i]), int(i) == s.scene ? "  (shown)" : "");
  fmt::print("cameras: {} ({} placed in the scene)\n", s.cameras.size(), scene.cameras.size());
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    const CameraDesc& c = scene.cameras[i];
    if (c.projection == CameraDesc::Projection::perspective)
      fmt::print("  {} {} perspective, vertical field of view {:.1f} deg\n", i, quoted(c.name), c.yfov * 180 / kPi);
    else
      fmt::print("  {} {} orthographic, {} x {}\n", i, quoted(c.name), 2 * c.xmag, 2 * c.ymag);
  }
  fmt::print("material variants: {}\n", s.variants.size());
  for (const std::string& v : s.variants) fmt::print("  {}\n", quoted(v));
  fmt::print("animations: {}\n", s.animations.size());
  for (size_t i = 0; i < s.animations.size(); ++i)
    fmt::print("  {} {}: {:.3f} s ({:.3f} to {:.3f} s), {} channels\n", i, quoted(s.animations[i].name),
               s.animations[i].end - s.animations[i].start, s.animations[i].start, s.animations[i].end,
               s.animations[i].channels);
  fmt::print("skins: {}, meshes with morph targets: {}\n", s.skins, s.morphed_meshes);
  fmt::print("extensions: {}\n", s.extensions.size());
  for (const GltfSummary::Extension& e : s.extensions)
    fmt::print("  {} ({}): {}\n", e.name, e.required ? "required" : "used",
               e.handling.empty() ? "not supported, ignored" : e.handling);
  fmt::print("triangles: {} in {} instances of {} meshes\n", scene.triangle_count(), scene.instances.size(),
             scene.meshes.size());
  const Bounds3f b = scene.world_bounds();
  if (!b.empty())
    fmt::print("bounds: ({:.4g}, {:.4g}, {:.4g}) to ({:.4g}, {:.4g}, {:.4g})\n", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y,
               b.hi.z);
  fmt::print("materials: {}, lights: {} point, {} spot, {} directional\n", scene.materials.size(),
             scene.point_lights.size(), scene.spot_lights.size(), scene.directional_lights.size());
  fmt::print("features: {}\n", analyze_features(scene).to_string());
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand("info", "List what a glTF file holds and what Prism does with it");
  cmd->add_option("scene", args->scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  add_gltf_options(cmd, args->gltf);
  cmd->callback([args] { run(*args); });
}

}  // namespace prism
