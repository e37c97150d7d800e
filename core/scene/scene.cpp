#include "core/scene/scene.h"

namespace prism {

SurfacePoint Mesh::attributes_at(uint32_t prim, const float b[3]) const {
  SurfacePoint at;
  for (int set = 0; set < 2; ++set)
    if (!uv[set].empty()) at.uv[set] = interpolate(uv[set], prim, b);
  if (!colors.empty()) at.vertex_color = interpolate(colors, prim, b);
  return at;
}

Bounds3f Scene::world_bounds() const {
  std::vector<Bounds3f> mesh_bounds(meshes.size());
  for (size_t m = 0; m < meshes.size(); ++m)
    for (const Vec3f& p : meshes[m].positions) mesh_bounds[m].extend(p);
  Bounds3f b;
  for (const Instance& inst : instances) {
    const Bounds3f& mb = mesh_bounds[inst.mesh];
    if (mb.empty()) continue;
    for (int corner = 0; corner < 8; ++corner) b.extend(Vec3f(inst.to_world.point(Vec3d(mb.corner(corner)))));
  }
  for (const PointLight& l : point_lights) b.extend(l.position);
  for (const SpotLight& l : spot_lights) b.extend(l.position);
  return b;
}

void generate_tangents(Mesh& mesh, int uv_set) {
  const auto& uv = mesh.uv[uv_set];
  if (uv.size() != mesh.positions.size()) return;
  std::vector<Vec3d> tan(mesh.positions.size()), bitan(mesh.positions.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    const Vec3d e1(mesh.positions[i1] - mesh.positions[i0]), e2(mesh.positions[i2] - mesh.positions[i0]);
    const double du1 = uv[i1].x - uv[i0].x, dv1 = uv[i1].y - uv[i0].y;
    const double du2 = uv[i2].x - uv[i0].x, dv2 = uv[i2].y - uv[i0].y;
    const double det = du1 * dv2 - du2 * dv1;
    if (det == 0 || !std::isfinite(det)) continue;
    // Solve [e1 e2] = [T B] [du1 du2; dv1 dv2] for the directions of increasing u and v.
    const Vec3d T = (e1 * dv2 - e2 * dv1) / det, B = (e2 * du1 - e1 * du2) / det;
    for (uint32_t i : {i0, i1, i2}) tan[i] += T, bitan[i] += B;
  }
  mesh.tangents.assign(mesh.positions.size(), {1, 0, 0, 1});
  for (size_t i = 0; i < tan.size(); ++i) {
    const Vec3d n = mesh.normals.empty() ? Vec3d(0, 0, 0) : Vec3d(mesh.normals[i]);
    Vec3d t = tan[i] - n * dot(n, tan[i]);  // Gram–Schmidt against the normal
    if (length(t) == 0) continue;
    t = normalize(t);
    const double sign = dot(cross(n, t), bitan[i]) < 0 ? -1 : 1;
    mesh.tangents[i] = {float(t.x), float(t.y), float(t.z), float(sign)};
  }
}

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const Instance& inst : instances) n += meshes[inst.mesh].indices.size() / 3;
  return n;
}

}  // namespace prism
