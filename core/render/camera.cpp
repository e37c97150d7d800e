#include "core/render/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/checksum.h"
#include "core/base/error.h"
#include "core/base/log.h"
#include "core/base/warp.h"

namespace prism {

Camera::Camera(const CameraDesc& desc, int width, int height, const ThinLens& lens)
    : projection_(desc.projection), width_(width), height_(height), lens_(lens) {
  if (width <= 0 || height <= 0) fail("image size {}x{} is not positive", width, height);
  if (lens.radius > 0 && projection_ != CameraDesc::Projection::perspective)
    fail("camera '{}': depth of field needs a perspective camera", desc.name);
  if (!(lens.radius >= 0 && std::isfinite(lens.radius) && lens.focus_distance > 0 &&
        std::isfinite(lens.focus_distance)))
    fail("camera '{}': lens radius {} and focus distance {} must be finite, the distance positive", desc.name,
         lens.radius, lens.focus_distance);
  // Position and axes of the camera node, with any scale or shear removed.
  eye_ = Vec3f(desc.to_world.point({0, 0, 0}));
  const Vec3d f = desc.to_world.vector({0, 0, -1}), u = desc.to_world.vector({0, 1, 0});
  forward_ = Vec3f(normalize(f));
  right_ = Vec3f(normalize(cross(f, u)));
  up_ = cross(right_, forward_);
  if (!is_finite(eye_) || !is_finite(forward_) || !is_finite(right_))
    fail("camera '{}' has a degenerate transform", desc.name);
  const float aspect = float(width) / float(height);
  if (projection_ == CameraDesc::Projection::perspective) {
    half_h_ = std::tan(desc.yfov / 2);
    half_w_ = half_h_ * aspect;
  } else {
    half_h_ = desc.ymag;
    half_w_ = desc.ymag * aspect;
  }
  pixel_area_ = (2.f * half_w_ / float(width)) * (2.f * half_h_ / float(height));
}

Vec3f Camera::lens_point(Vec2f u) const {
  const Vec2f a = (lens_.blades >= 3 ? sample_uniform_polygon(u, lens_.blades, lens_.rotation)
                                     : sample_uniform_disk_concentric(u)) *
                  lens_.radius;
  return eye_ + right_ * a.x + up_ * a.y;
}

Ray Camera::generate_ray(float x, float y, Vec2f u_lens) const {
  const float sx = 2.f * x / float(width_) - 1.f;
  const float sy = 1.f - 2.f * y / float(height_);
  if (projection_ == CameraDesc::Projection::orthographic)
    return {eye_ + right_ * (sx * half_w_) + up_ * (sy * half_h_), forward_, kInfinity};
  const Vec3f d = forward_ + right_ * (sx * half_w_) + up_ * (sy * half_h_);
  if (!has_lens()) return {eye_, normalize(d), kInfinity};
  // From the lens point to where the pinhole ray meets the plane in focus (d's forward part is 1).
  const Vec3f origin = lens_point(u_lens);
  return {origin, normalize(eye_ + d * lens_.focus_distance - origin), kInfinity};
}

Frustum Camera::frustum(int x0, int y0, int x1, int y1) const {
  // The film rectangle in units of the image plane (at distance 1, or the orthographic film's),
  // widened beyond generate_ray's rounding: of the film position (a 2^-23 of the image's width
  // or height), and of the direction or origin (a few 2^-24 of the plane's extent).
  const double pw = 2.0 * half_w_ / width_, ph = 2.0 * half_h_ / height_;
  const double mx = (0.01 + width_ * 0x1p-20) * pw + 1e-5 * (1 + half_w_ + half_h_);
  const double my = (0.01 + height_ * 0x1p-20) * ph + 1e-5 * (1 + half_w_ + half_h_);
  const double left = -half_w_ + x0 * pw - mx, right = -half_w_ + x1 * pw + mx;
  const double top = half_h_ - y0 * ph + my, bottom = half_h_ - y1 * ph - my;
  const Vec3d R(right_), U(up_), F(forward_);
  Frustum f;
  f.origin = Vec3d(eye_);
  const auto add = [&](const Vec3d& n, double d) {
    const double l = length(n);
    f.planes[f.count++] = {n / l, d / l};
  };
  if (perspective()) {  // planes through the eye: a direction F + a R + c U has left ≤ a ≤ right, bottom ≤ c ≤ top
    add(F * left - R, 0), add(R - F * right, 0), add(F * bottom - U, 0), add(U - F * top, 0);
  } else {  // the origin on the film within the rectangle, the direction F
    add(-R, -left), add(R, right), add(-U, -bottom), add(U, top), add(-F, 0);
  }
  return f;
}

std::optional<Camera::Connection> Camera::connect(const Vec3f& p, Vec2f u_lens) const {
  const Vec3f from = has_lens() ? lens_point(u_lens) : eye_;
  const Vec3f d = p - from;
  const float z = dot(d, forward_);
  if (!(z > 0.f)) return std::nullopt;
  const bool pinhole = perspective();
  // The film position is the pinhole's of the point where the ray from the lens through p meets
  // the plane in focus (for the pinhole itself, of p).
  const Vec3f seen = has_lens() ? from + d * (lens_.focus_distance / z) - eye_ : d;
  const float depth = has_lens() ? lens_.focus_distance : z;
  const float sx = dot(seen, right_) / (pinhole ? depth * half_w_ : half_w_);
  const float sy = dot(seen, up_) / (pinhole ? depth * half_h_ : half_h_);
  const Vec2f r{(sx + 1.f) * 0.5f * float(width_), (1.f - sy) * 0.5f * float(height_)};
  if (!(r.x >= 0.f && r.x < float(width_) && r.y >= 0.f && r.y < float(height_))) return std::nullopt;
  if (!pinhole) return Connection{r, p - forward_ * z, -forward_, 1.f / pixel_area_};
  const float d2 = length_squared(d), distance = std::sqrt(d2);
  const Vec3f w = d / -distance;
  return Connection{r, from, w, ray_density({from, -w, kInfinity}) / d2};
}

float Camera::ray_density(const Ray& ray) const {
  if (!perspective()) return 1.f / pixel_area_;
  const float cos_theta = dot(ray.d, forward_);
  return cos_theta > 0.f ? 1.f / (pixel_area_ * cos_theta * cos_theta * cos_theta) : 0.f;
}

uint64_t Camera::hash() const {
  Checksum sum;
  const auto add = [&](const auto& v) { sum.add(&v, sizeof(v)); };
  add(projection_), add(eye_), add(forward_), add(right_), add(up_), add(half_w_), add(half_h_), add(width_),
      add(height_);
  if (has_lens()) add(lens_.radius), add(lens_.focus_distance), add(lens_.blades), add(lens_.rotation);
  return sum.h;
}

ThinLens thin_lens(const CameraDesc& desc, const Scene& scene, Vec2i size) {
  const LensDesc& l = desc.lens;
  const std::string what = fmt::format("{}: camera '{}'", scene.source.string(), desc.name);
  if (!l.f_number && !l.radius) {
    if (l.focus_distance || l.focus_node || l.blades || l.blade_rotation)
      log::warn("{}: a focus or aperture shape without an aperture (f-number or lens radius): a pinhole", what);
    return {};
  }
  if (desc.projection != CameraDesc::Projection::perspective)
    fail("{}: depth of field needs a perspective camera", what);
  ThinLens lens;
  if (l.radius) {
    lens.radius = *l.radius;
  } else {
    const float tan_half_x = std::tan(desc.yfov / 2) * float(size.x) / float(size.y);
    const float focal_length = l.sensor_width.value_or(36.f) * 1e-3f / (2 * tan_half_x);
    lens.radius = focal_length / (2 * *l.f_number);
  }
  const Vec3f eye(desc.to_world.point({0, 0, 0})), forward(normalize(desc.to_world.vector({0, 0, -1})));
  if (l.focus_node) {
    const auto it = std::find_if(scene.node_origins.begin(), scene.node_origins.end(),
                                 [&](const auto& node) { return node.first == *l.focus_node; });
    if (it == scene.node_origins.end()) fail("{}: no node named '{}' to focus on", what, *l.focus_node);
    lens.focus_distance = dot(it->second - eye, forward);
    if (!(lens.focus_distance > 0))
      fail("{}: the node '{}' to focus on is not in front of the camera", what, *l.focus_node);
  } else if (l.focus_distance) {
    lens.focus_distance = *l.focus_distance;
  } else {
    const float depth = dot(scene.world_bounds().centroid() - eye, forward);
    lens.focus_distance = depth > 0 ? depth : 1.f;
  }
  const int blades = l.blades.value_or(0);
  if (blades == 1 || blades == 2 || blades < 0)
    fail("{}: an aperture of {} blades (0: round, or at least 3)", what, blades);
  lens.blades = blades;
  lens.rotation = radians(l.blade_rotation.value_or(0.f));
  return lens;
}

CameraDesc framing_camera(const Bounds3f& bounds, float aspect) {
  CameraDesc c;
  c.name = "framing camera";
  c.yfov = radians(45.f);
  c.aspect = aspect;
  const Vec3d center(bounds.centroid());
  const Vec3d back = normalize(Vec3d(1, 1, 1));  // from the target towards the eye
  const Vec3d right = normalize(cross(Vec3d(0, 1, 0), back));
  const Vec3d up = cross(back, right);
  const double tan_y = std::tan(c.yfov / 2), tan_x = tan_y * aspect;
  // Each corner q must satisfy |q·right| ≤ tan_x · depth and |q·up| ≤ tan_y · depth, where
  // depth = distance − q·back; the smallest distance meeting all eight is the answer.
  double distance = 0;
  for (int i = 0; i < 8; ++i) {
    const Vec3d corner((i & 1 ? bounds.hi : bounds.lo).x, (i & 2 ? bounds.hi : bounds.lo).y,
                       (i & 4 ? bounds.hi : bounds.lo).z);
    const Vec3d q = corner - center;
    distance = std::max({distance, dot(q, back) + abs_dot(q, right) / tan_x, dot(q, back) + abs_dot(q, up) / tan_y});
  }
  if (!(distance > 0)) distance = 1;
  const Vec3d eye = center + back * (distance * 1.02);
  // Columns: right, up, back (= local +z, since the camera looks down −z), eye.
  Transform& m = c.to_world;
  for (int r = 0; r < 3; ++r) {
    m.m[r][0] = right[r];
    m.m[r][1] = up[r];
    m.m[r][2] = back[r];
    m.m[r][3] = eye[r];
  }
  return c;
}

Vec2i resolve_resolution(int width, int height, const CameraDesc& camera, int default_width) {
  const double aspect = camera.aspect.value_or(1.f);
  // A side from the other and the aspect, within [1, INT_MAX] even for an extreme aspect.
  const auto side = [](double v) {
    return int(std::clamp(std::round(v), 1.0, double(std::numeric_limits<int>::max())));
  };
  if (width > 0 && height > 0) return {width, height};
  if (width > 0) return {width, side(width / aspect)};
  if (height > 0) return {side(height * aspect), height};
  return {default_width, side(default_width / aspect)};
}

}  // namespace prism
