#pragma once
// Pinhole and thin-lens perspective cameras and orthographic ones (glTF conventions: the camera
// looks down its local −z with +y up). Film coordinates: sx ∈ [−1, 1] left to right, sy ∈ [−1, 1]
// bottom to top.

#include <optional>

#include "core/base/frustum.h"
#include "core/base/ray.h"
#include "core/scene/scene.h"

namespace prism {

// A thin lens (pbrt-v4 §5.2.3): a ray leaves a point of the aperture (a disk of this radius, or the
// polygon of `blades` sides inscribed in it) towards the point where the pinhole ray through the
// same film position meets the plane in focus, so that plane is sharp and the rest blurred. Radius
// 0: the pinhole, exactly.
struct ThinLens {
  float radius = 0;          // [scene units]
  float focus_distance = 1;  // along the view axis [scene units]
  int blades = 0;            // 0: round
  float rotation = 0;        // of the first blade's corner [radians]
};

class Camera {
 public:
  Camera(const CameraDesc& desc, int width, int height, const ThinLens& lens = {});

  // The ray through film position (x, y) in pixels, (0, 0) = top-left corner of the image, from
  // the aperture point u_lens picks (a thin lens's: a 2D sample of its own).
  Ray generate_ray(float x, float y, Vec2f u_lens = {}) const;
  bool has_lens() const { return lens_.radius > 0; }
  const ThinLens& lens() const { return lens_; }
  // A region holding every ray generate_ray gives for x in [x0, x1], y in [y0, y1] (with rounding);
  // a pinhole's or an orthographic camera's only.
  Frustum frustum(int x0, int y0, int x1, int y1) const;

  // For light tracing (bidirectional methods): how a point p is seen by the camera through the
  // aperture point u_lens picks (pbrt-v4 §5.2 We and SampleWi; Veach 1997 §10.2), if it is inside
  // the frame.
  struct Connection {
    Vec2f raster;  // film position, pixels
    Vec3f point;   // where the camera ray through p starts: the eye or the lens, or the orthographic film
    Vec3f w;       // unit, from p towards `point`
    // Density of the camera's rays through p, per unit film area in pixels and per unit area
    // across the ray at p: 1 / (A_pixel · cos³θ · d²) for a pinhole, with A_pixel a pixel's area
    // on the image plane at distance 1; 1 / A_pixel for an orthographic camera. A thin lens's is
    // the pinhole's from the lens point: its We over the density of the lens point, whose
    // 1 / lens area cancels.
    float importance;
  };
  std::optional<Connection> connect(const Vec3f& p, Vec2f u_lens = {}) const;
  // The density of `ray` among the camera's rays, per unit film area in pixels: solid-angle
  // 1 / (A_pixel · cos³θ) for a pinhole, area 1 / A_pixel for an orthographic camera.
  float ray_density(const Ray& ray) const;
  bool perspective() const { return projection_ == CameraDesc::Projection::perspective; }

  int width() const { return width_; }
  int height() const { return height_; }
  // FNV-1a of the projection, position, axes, extents and lens: equal cameras, equal hashes (for
  // the fingerprint of checkpoints and part files).
  uint64_t hash() const;

 private:
  CameraDesc::Projection projection_;
  Vec3f eye_, forward_, right_, up_;
  float half_w_, half_h_;  // perspective: tangents of the half angles; orthographic: half extents
  float pixel_area_;       // on the image plane at distance 1, or of the orthographic film
  int width_, height_;
  ThinLens lens_;

  Vec3f lens_point(Vec2f u) const;  // on the aperture, in the scene
};

// The thin lens a camera's LensDesc makes for an image of `size`: the radius from the f-number
// and the focal length the field of view makes on the sensor (f = w_sensor / (2 tan(fov_x / 2)),
// r = f / 2N; scene units are metres, sensor millimetres), the plane in focus through the named
// node's origin, or at the given distance, or through the centre of the scene's bounds. Fails,
// naming the camera, on an orthographic camera or a focus behind it.
ThinLens thin_lens(const CameraDesc& desc, const Scene& scene, Vec2i size);

// A camera that frames the whole scene: looks at the bounds' centre from the direction
// (1, 1, 1)/√3 with a 45° vertical field of view, from the nearest distance at which all eight
// corners are inside the frustum, plus 2%.
CameraDesc framing_camera(const Bounds3f& bounds, float aspect);

// Image size from the requested width / height (0 = not given) and the camera's aspect ratio.
Vec2i resolve_resolution(int width, int height, const CameraDesc& camera, int default_width = 640);

}  // namespace prism
