#include "core/render/world.h"

#include <algorithm>
#include <bit>
#include <new>
#include <tuple>

#include "accel/closed_surface.h"
#include "accel/triangle.h"
#include "core/base/error.h"
#include "core/base/first_equal.h"
#include "core/base/frame.h"
#include "core/base/parallel.h"
#include "core/base/rng.h"
#include "materials/metal_fit.h"
#include "spectral/cie.h"
#include "spectral/rgb_to_spectrum.h"

namespace prism {

Accel build_accel(const Scene& scene, const AccelOptions& options) {
  std::vector<AccelMesh> meshes;
  for (const Mesh& m : scene.meshes) meshes.push_back({m.positions, m.indices});
  return Accel(meshes, scene.instances, options);
}

namespace {

// The cofactor matrix of t's linear part: entry (i, j) is the 2x2 minor without row i and column j, signed.
std::array<Vec3f, 3> cofactor(const AffineTransform& t) {
  const auto& a = t.m;
  std::array<Vec3f, 3> c;
  for (int i = 0; i < 3; ++i) {
    const int i0 = (i + 1) % 3, i1 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j0 = (j + 1) % 3, j1 = (j + 2) % 3;
      c[i][j] = a[i0][j0] * a[i1][j1] - a[i0][j1] * a[i1][j0];
    }
  }
  return c;
}

// What shading reads of a mesh besides its material and positions (a hit brings its vertices along,
// AccelHit::v).
auto shading_arrays(const Mesh& m) { return std::tie(m.indices, m.normals, m.uv[0], m.uv[1], m.colors, m.tangents); }

// For every mesh, the first mesh with the same shading arrays, bit for bit, so that a mesh shaded
// from another's arrays gives the very same results (−0 ≠ +0).
std::vector<const Mesh*> attribute_meshes(const std::vector<Mesh>& meshes) {
  const std::vector<uint32_t> first = first_equal(
      uint32_t(meshes.size()),
      [&](uint32_t m) {
        return std::apply([](const auto&... v) { return hash_bytes(v...); }, shading_arrays(meshes[m]));
      },
      [&](uint32_t a, uint32_t b) {
        return std::apply(
            [&](const auto&... x) {
              return std::apply([&](const auto&... y) { return (same_bytes(x, y) && ...); }, shading_arrays(meshes[b]));
            },
            shading_arrays(meshes[a]));
      });
  std::vector<const Mesh*> out;
  for (uint32_t f : first) out.push_back(&meshes[f]);
  return out;
}

}  // namespace

World::World(const Scene& scene, const AccelOptions& accel, LightSamplerKind light_sampler)
    : scene_(scene), features_(analyze_features(scene)), accel_(build_accel(scene, accel)) {
  for (const Instance& inst : scene.instances)
    instance_normals_.push_back({inst.to_world.determinant() < 0, cofactor(inst.to_world)});
  attribute_mesh_ = attribute_meshes(scene.meshes);
  add_enclosures();
  add_lights(light_sampler);
  // The tables a render reads, loaded here rather than at the first hit inside the timed render.
  RgbToSpectrumTable::srgb();
  cie();
  schlick_matched_edge_tints();  // the base-colour metals' table
  // Untextured colours, upsampled once.
  spectra_.resize(scene.materials.size());
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (const auto* pbr = std::get_if<PbrMaterial>(&scene.materials[i].kind)) spectra_[i].emplace(*pbr);
}

// Transformed exactly as the accel transforms the triangles it flattens into world space (and
// hands back with a hit, AccelHit::v), so a light's triangle is the very one rays hit. (A hit on
// an instanced mesh is found in the mesh's space; its barycentrics carry over, as the transform
// is affine.)
std::array<Vec3f, 3> World::world_vertices(const Instance& inst, uint32_t prim) const {
  const Mesh& m = scene_.meshes[inst.mesh];
  std::array<Vec3f, 3> v;
  for (int k = 0; k < 3; ++k) v[k] = inst.to_world.point_rounded(m.positions[m.indices[3 * prim + k]]);
  return v;
}

void World::add_enclosures() {
  // Only meshes light passes through can have a path on their inside or a light sample into them;
  // the check is left out for the others (it sorts the mesh's vertices and edges).
  std::vector<float> side(scene_.meshes.size(), 0.f);
  std::vector<Bounds3f> bounds(scene_.meshes.size());
  bool any = false;
  for (size_t m = 0; m < scene_.meshes.size(); ++m) {
    const Mesh& mesh = scene_.meshes[m];
    const Material& material = scene_.materials[mesh.material];
    if (!material.transmits() || material.alpha_mode != AlphaMode::opaque) continue;
    side[m] = float(enclosed_side(mesh.positions, mesh.indices));
    if (side[m] == 0) continue;
    for (const Vec3f& p : mesh.positions) bounds[m].extend(p);
    any = true;
  }
  if (!any) return;
  for (const Instance& inst : scene_.instances)
    enclosures_.push_back(side[inst.mesh] == 0
                              ? Enclosure{}
                              : Enclosure{transform_bounds(inst.to_world, bounds[inst.mesh]), side[inst.mesh]});
}

// The distributions of a textured emitter's triangles, per mesh and triangle (null where one is
// not worth having: a triangle of a quarter texel or less); returns each triangle's mean emitted
// luminance over its untextured emission. The sub-triangles, about a quarter texel each, are about
// kBudget in all at most: beyond that, fewer rows for every triangle alike.
std::vector<std::vector<float>> World::add_texels() {
  constexpr double kBudget = 1 << 22;
  constexpr int kMaxRows = 128;
  std::vector<std::pair<uint32_t, uint32_t>> triangles;  // (mesh, prim) of textured emitters
  std::vector<float> footprint;
  std::vector<bool> emits(scene_.meshes.size(), false);
  for (const Instance& inst : scene_.instances) emits[inst.mesh] = true;
  std::vector<std::vector<float>> mean(scene_.meshes.size());
  texels_.resize(scene_.meshes.size());
  double total = 0;
  for (uint32_t m = 0; m < scene_.meshes.size(); ++m) {
    const Mesh& mesh = scene_.meshes[m];
    const Material& material = scene_.materials[mesh.material];
    if (!emits[m] || !material.emission || !material.emission_texture) continue;
    mean[m].assign(mesh.indices.size() / 3, 0.f);
    texels_[m].resize(mesh.indices.size() / 3);
    for (uint32_t p = 0; p < mesh.indices.size() / 3; ++p) {
      triangles.emplace_back(m, p);
      footprint.push_back(TexturedEmission::footprint(mesh, p, material));
      total += std::min<double>(4 * footprint.back(), kMaxRows * kMaxRows);
    }
  }
  const double scale = total > kBudget ? kBudget / total : 1.0;
  parallel_for(int64_t(triangles.size()), [&](int64_t t) {
    const auto [m, p] = triangles[size_t(t)];
    const Mesh& mesh = scene_.meshes[m];
    const Material& material = scene_.materials[mesh.material];
    const int k = std::clamp(int(std::ceil(std::sqrt(4 * footprint[size_t(t)] * scale))), 1, kMaxRows);
    const std::vector<float> w = TexturedEmission::weights(mesh, p, material, k);
    double sum = 0;
    for (float x : w) sum += x;
    mean[m][p] = float(sum / double(w.size()));
    if (k > 1 && sum > 0) texels_[m][p] = std::make_unique<const TexturedEmission>(k, w);
  });
  return mean;
}

void World::add_lights(LightSamplerKind light_sampler) {
  std::vector<float> powers;
  std::vector<std::optional<LightBounds>> bounds;  // of the finite lights, for a light tree
  std::vector<std::optional<float>> material_luminance(scene_.materials.size());  // once per emitting material
  instance_light_base_.assign(scene_.instances.size(), -1);
  const std::vector<std::vector<float>> texel_mean = add_texels();
  for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
    const Instance& inst = scene_.instances[i];
    const Mesh& mesh = scene_.meshes[inst.mesh];
    const Material& material = scene_.materials[mesh.material];
    if (!material.emission) continue;
    const bool textured = material.emission_texture.has_value();
    // Power by luminance; a textured emission's triangle counts with its texels' mean (and its
    // alpha coverage), texel_mean.
    std::optional<float>& power_luminance = material_luminance[mesh.material];
    if (!power_luminance) {
      power_luminance = spectrum_to_xyz(*material.emission).y;
      // An untextured BLEND surface emits alpha of its light: its factor's share (vertex colours
      // left out; the power only steers light selection).
      const auto* pbr = std::get_if<PbrMaterial>(&material.kind);
      if (!textured && pbr && material.alpha_mode == AlphaMode::blend)
        *power_luminance *= std::clamp(pbr->alpha, 0.f, 1.f);
    }
    instance_light_base_[i] = int(lights_.size());
    for (uint32_t p = 0; p < mesh.indices.size() / 3; ++p) {
      const auto v = world_vertices(inst, p);
      const float area = triangle_area(v[0], v[1], v[2]);
      const Vec3f n = triangle_normal(v[0], v[1], v[2]) * (instance_normals_[i].mirrored ? -1.f : 1.f);
      const TexturedEmission* texels = textured ? texels_[inst.mesh][p].get() : nullptr;
      lights_.push_back(AreaLight{v[0], v[1], v[2], n, area, &material, &mesh, p, material.double_sided, texels});
      // Φ = π · A · L for a one-sided Lambertian emitter; luminance stands in for L.
      const float luminance = *power_luminance * (textured ? texel_mean[inst.mesh][p] : 1.f);
      powers.push_back(area > 0 ? kPi * area * luminance * (material.double_sided ? 2.f : 1.f) : 0.f);
      // Normals in one direction, each emitting over its hemisphere (θ_e = π/2).
      Bounds3f box;
      for (const Vec3f& q : v) box.extend(q);
      bounds.push_back(LightBounds{box, n, powers.back(), 1.f, 0.f, material.double_sided});
    }
  }
  for (const PointLight& pl : scene_.point_lights) {
    lights_.push_back(PointLightSource{pl.position, &pl.intensity});
    powers.push_back(4 * kPi * spectrum_to_xyz(pl.intensity).y);  // Φ = 4π I
    bounds.push_back(LightBounds{Bounds3f{pl.position, pl.position}, {0.f, 0.f, 1.f}, powers.back(), -1.f, 0.f});
  }
  for (const SpotLight& sl : scene_.spot_lights) {
    lights_.push_back(SpotLightSource(sl));
    // Φ ≈ 2π (1 − cos θ_mid) I: the smooth falloff taken as a hard cone at the mean of the inner
    // and outer angles (exact when they are equal).
    const float cos_mid = std::cos((sl.inner_angle + sl.outer_angle) / 2);
    powers.push_back(2 * kPi * (1 - cos_mid) * spectrum_to_xyz(sl.intensity).y);
    // Full intensity within the inner angle (θ_o), falling to none at the outer (θ_o + θ_e).
    bounds.push_back(LightBounds{Bounds3f{sl.position, sl.position}, sl.direction, powers.back(),
                                 std::cos(sl.inner_angle), std::cos(sl.outer_angle - sl.inner_angle)});
  }
  // Infinite lights deliver power π r² × (their irradiance) to a sphere bounding the scene
  // (pbrt-v4 §12.4 and §12.5.1).
  const Bounds3f b = accel_.bounds();
  const float r = b.empty() ? 1.f : 0.5f * length(b.diagonal());
  for (const DirectionalLight& dl : scene_.directional_lights) {
    lights_.push_back(DirectionalLightSource{dl.direction, &dl.illuminance});
    powers.push_back(kPi * r * r * spectrum_to_xyz(dl.illuminance).y);
    bounds.emplace_back();
  }
  if (scene_.environment && scene_.environment_map)
    fail("a scene has either a constant environment or an environment map, not both");
  if (scene_.environment) {
    environment_light_ = int(lights_.size());
    // Every path that escapes evaluates it: a 1-nm table instead of RGB upsampling times D65.
    environment_radiance_ = std::make_unique<const Spectrum>(densely_sampled(*scene_.environment));
    lights_.push_back(EnvironmentLight{environment_radiance_.get()});
    powers.push_back(4 * kPi * kPi * r * r * spectrum_to_xyz(*scene_.environment).y);  // π r² · 4π L
    bounds.emplace_back();
  }
  if (scene_.environment_map) {
    environment_map_ = std::make_unique<const EnvironmentMap>(*scene_.environment_map);
    environment_light_ = int(lights_.size());
    lights_.push_back(EnvironmentMapLight{environment_map_.get()});
    powers.push_back(kPi * r * r * environment_map_->luminance_integral());
    bounds.emplace_back();
  }
  light_sampler_ = LightSampler(light_sampler, bounds, powers);
  std::vector<float> area_powers;
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    (is_delta(lights_[i]) ? delta_lights_ : area_lights_).push_back(i);
    if (!is_delta(lights_[i])) area_powers.push_back(powers[i]);
  }
  area_light_sampler_ = PowerLightSampler(area_powers);
}

namespace {

// A normal under an instance's transform is its product with the cofactor matrix of the linear
// part, which is the inverse transpose times the determinant (the caller normalises it and turns
// it to the geometric normal's side, which restores length and sign).
Vec3f transform_normal(const std::array<Vec3f, 3>& cofactor, const Vec3f& n) {
  Vec3f r(0, 0, 0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i] += cofactor[i][j] * n[j];
  return r;
}

}  // namespace

void World::surface_point(const Ray& ray, const AccelHit& hit, SurfaceInteraction& si) const {
  const Instance& instance = scene_.instances[hit.instance];
  const Mesh& m = scene_.meshes[instance.mesh];
  const InstanceNormals& normals = instance_normals_[hit.instance];
  const auto& v = hit.v;  // as world_vertices(instance, hit.prim), from the accel's leaf
  const float b[3] = {hit.b0, hit.b1, hit.b2};
  si.p = v[0] * b[0] + v[1] * b[1] + v[2] * b[2];
  si.p_error = (abs(v[0] * b[0]) + abs(v[1] * b[1]) + abs(v[2] * b[2])) * gamma(7);
  si.n = triangle_normal(v[0], v[1], v[2]) * (normals.mirrored ? -1.f : 1.f);
  si.ns = si.n;
  si.wo = -ray.d;
  si.t = hit.t;
  si.material = &scene_.materials[m.material];
  si.instance = hit.instance;
  si.prim = hit.prim;
  // The hull's side where the centroid is clearly off the plane (not where rounding could flip it: a thin plate).
  if (const auto hull = accel_.hull(hit.instance, hit.prim))
    if (const float side = dot(hull->centroid - si.p, si.n); std::abs(side) > 1e-4f * length(hull->centroid - si.p))
      si.hull_side = side, si.hull_skip = hull->skip;
  ::new (&si.at) SurfacePoint(attribute_mesh_[instance.mesh]->attributes_at(hit.prim, b));  // in place (intersect)
  if (const auto& spectra = spectra_[m.material]) si.at.spectra = &*spectra;
}

void World::shade(SurfaceInteraction& si, const AccelHit& hit) const {
  const Instance& instance = scene_.instances[hit.instance];
  const Mesh& m = *attribute_mesh_[instance.mesh];
  const InstanceNormals& normals = instance_normals_[hit.instance];
  const float b[3] = {hit.b0, hit.b1, hit.b2};
  if (!m.normals.empty()) {
    const Vec3f ns = transform_normal(normals.cofactor, m.interpolate(m.normals, hit.prim, b));
    const float len = length(ns);
    // The shading normal is taken on the geometric normal's side; a zero one falls back to it.
    if (len > 0 && std::isfinite(len)) si.ns = face_forward(ns / len, si.n);
  }
  const Material& material = *si.material;
  const auto* pbr = std::get_if<PbrMaterial>(&material.kind);
  const bool anisotropic = pbr && pbr->anisotropic();
  const bool coat_map = pbr && pbr->clearcoat && pbr->clearcoat->normal_texture;
  if (m.tangents.empty() || !(material.normal_texture || anisotropic || coat_map)) return;
  // The tangent frame (glTF §3.9.3): T, and B = sign · N × T, both ⊥ the normal n they turn about.
  const auto t4 = m.interpolate(m.tangents, hit.prim, b);
  const Vec3f t_world(instance.to_world.vector(Vec3d(t4[0], t4[1], t4[2])));
  const float sign = (t4[3] < 0) != normals.mirrored ? -1.f : 1.f;
  const auto tangent_about = [&](const Vec3f& n) -> std::optional<Vec3f> {
    const Vec3f t = t_world - n * dot(n, t_world);
    if (length_squared(t) == 0) return std::nullopt;
    return normalize(t);
  };
  // Tangent-space normal map: n = normalize(T x + B y + N z) about the interpolated normal; the
  // base's, and a clear coat's own (KHR_materials_clearcoat).
  const Vec3f ns = si.ns;
  const auto map_normal = [&](const Texture& texture, float scale) -> std::optional<Vec3f> {
    const auto c = texture.lookup(si.at.uv[texture.texcoord], false);
    const Vec3f local((2 * c[0] - 1) * scale, (2 * c[1] - 1) * scale, 2 * c[2] - 1);
    const auto tn = tangent_about(ns);
    if (!tn || length_squared(local) == 0) return std::nullopt;
    const Vec3f mapped = *tn * local.x + cross(ns, *tn) * sign * local.y + ns * local.z;
    if (length_squared(mapped) == 0 || !is_finite(mapped)) return std::nullopt;
    return face_forward(normalize(mapped), si.n);
  };
  if (material.normal_texture)
    if (const auto n = map_normal(*material.normal_texture, material.normal_scale)) si.ns = *n;
  if (anisotropic)
    // KHR_materials_anisotropy: the direction T d.x + B d.y, in the plane of the (mapped) normal.
    if (const auto tn = tangent_about(si.ns)) {
      const Vec2f d = pbr->anisotropy_direction(si.at);
      const Vec3f a = *tn * d.x + cross(si.ns, *tn) * sign * d.y;
      if (length_squared(a) > 0 && is_finite(a)) si.tangent = normalize(a);
    }
  if (coat_map)
    if (const auto n = map_normal(*pbr->clearcoat->normal_texture, pbr->clearcoat->normal_scale))
      si.at.coat_normal = si.shading_frame().to_local(*n);  // in the frame the BSDF sees
}

bool World::cut_away(const SurfaceInteraction& si, const Ray& ray, bool keep_blend) const {
  const Material& m = *si.material;
  if (m.alpha_mode == AlphaMode::opaque || (keep_blend && m.alpha_mode == AlphaMode::blend)) return false;
  if (m.alpha_mode == AlphaMode::mask) return m.coverage(si.at) == 0;
  const float opacity = m.opacity(si.at);
  const uint64_t h = hash_ints(std::bit_cast<uint32_t>(ray.o.x), std::bit_cast<uint32_t>(ray.o.y),
                               std::bit_cast<uint32_t>(ray.o.z), std::bit_cast<uint32_t>(ray.d.x),
                               std::bit_cast<uint32_t>(ray.d.y), std::bit_cast<uint32_t>(ray.d.z), si.prim);
  return float(h >> 40) * 0x1p-24f >= opacity;
}

std::optional<SurfaceInteraction> World::intersect(const Ray& ray, bool keep_blend) const {
  // The hit is made where it is returned: every return names `si`, so the caller's object is `si`.
  // (Made apart and copied there, the copy read back with wide loads the fields just stored one by
  // one, which x86 cannot forward: most of this function's time went to the stalls.)
  std::optional<SurfaceInteraction> si(std::in_place);
  std::optional<Ray> rest;  // past cut-away surfaces, what is left of the ray beyond them
  float travelled = 0;
  for (;;) {
    const Ray& r = rest ? *rest : ray;
    AccelHit hit;
    if (!accel_.intersect(r, hit)) break;
    surface_point(r, hit, *si);
    if (!features_.alpha || !cut_away(*si, r, keep_blend)) {
      shade(*si, hit);
      si->t += travelled;
      return si;
    }
    if (!rest) rest = ray;
    travelled += step_beyond(*si, *rest);
    if (!(rest->tmax > 0)) break;
    si.emplace();  // fresh for the next surface (surface_point fills a new one)
  }
  si.reset();
  return si;
}

float World::transmittance(const Ray& shadow_ray) const {
  if (!features_.alpha) return accel_.occluded(shadow_ray) ? 0.f : 1.f;
  Ray ray = shadow_ray;
  float T = 1;
  for (;;) {
    AccelHit hit;
    if (!accel_.intersect(ray, hit)) return T;
    SurfaceInteraction si;
    surface_point(ray, hit, si);
    const Material& m = *si.material;
    if (m.alpha_mode == AlphaMode::opaque) return 0;
    const float opacity = m.opacity(si.at);
    if (m.alpha_mode == AlphaMode::mask ? opacity >= m.alpha_cutoff : (T *= 1 - opacity) <= 0) return 0;
    step_beyond(si, ray);
    if (!(ray.tmax > 0)) return T;
  }
}

float World::step_beyond(const SurfaceInteraction& si, Ray& ray) {
  const Vec3f o = offset_ray_origin(si.p, si.p_error, si.n, ray.d);
  const float step = length(o - ray.o);
  ray = {o, ray.d, ray.tmax - step};
  return step;
}

}  // namespace prism
