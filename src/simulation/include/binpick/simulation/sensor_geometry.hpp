#pragma once
// The geometry a structured-light rig sees, per camera pixel: what the pixel's ray hits, and how
// that point stands towards the projector (where it lands in the projector image, whether light
// reaches it, at what angle and distance). The image-formation step turns this into intensities.
//
// The camera sits at the origin of the camera frame; the rays go through the pixel centres with
// the camera's lens distortion (LensIntrinsics::rayThroughPixel). Functions are stateless and
// thread-safe; each call uses `threads` OpenMP threads, and its result does not depend on how
// many.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "binpick/io/rig_calibration.hpp"
#include "binpick/simulation/ray_caster.hpp"

namespace binpick::simulation {

struct SensorGeometryParams {
  int threads = 0;  // OpenMP threads; 0: all hardware threads
  // The shadow ray towards the projector starts this far off the surface, along its normal, so
  // that it cannot hit the surface it leaves through rounding. Metres; shifts shadow edges by
  // about as much.
  double shadow_ray_offset = 1e-5;

  // Throws core::Error naming the bad field.
  void validate() const;
};

// Image-sized buffers, row-major (index v * width + u). Where the pixel's ray hits nothing, the
// floats are NaN, the ids -1 and the flags 0.
struct SensorGeometry {
  int width = 0;
  int height = 0;

  // Camera side.
  std::vector<float> depth;                   // z of the hit point, camera frame, metres
  std::vector<Eigen::Vector3f> point;         // hit point, camera frame
  std::vector<Eigen::Vector3f> normal;        // unit outward geometric normal, camera frame
  std::vector<Eigen::Vector3f> object_point;  // hit point in the frame of the object hit
  std::vector<int32_t> object_id;             // RenderObject::id of the object seen
  std::vector<int32_t> object_index;          // its position in the RayCaster's object list
  // Cosine between the normal and the direction from the point to the camera (negative for a
  // surface seen from behind).
  std::vector<float> camera_cosine;

  // Projector side.
  // Where the point lands in the projector image (lens distortion included); NaN also when the
  // point is not in front of the projector.
  std::vector<Eigen::Vector2f> projector_pixel;
  // 1 when the point is in the projector's field of view: projector_pixel within the image
  // ([-0.5, width - 0.5) x [-0.5, height - 0.5), pixel centres at integers).
  std::vector<uint8_t> in_projector_image;
  // Cosine between the normal and the direction from the point to the projector centre: the
  // incidence factor of the irradiance (negative when the surface faces away).
  std::vector<float> projector_cosine;
  std::vector<float> projector_distance;  // metres from the point to the projector centre
  // 1 when projector light reaches the point: in the projector image, facing the projector
  // (projector_cosine > 0) and no surface between the two.
  std::vector<uint8_t> lit;

  std::size_t index(int u, int v) const { return static_cast<std::size_t>(v) * width + u; }
};

// Casts every camera pixel of `rig` into `scene` (built in the camera frame). Throws
// core::Error on an invalid rig or params.
SensorGeometry computeSensorGeometry(const io::RigCalibration& rig, const RayCaster& scene,
                                     const SensorGeometryParams& params = {});

// The same for any points of the camera image (pixel centres at integers, lens distortion
// included), one ray each: sub-pixel samples. The result holds them row-major as given, `width`
// per row (points.size() must be a multiple of it). Throws core::Error on an invalid rig or
// params, or a width that does not divide the points.
SensorGeometry computeSensorGeometryAt(const io::RigCalibration& rig, const RayCaster& scene,
                                       const std::vector<Eigen::Vector2d>& image_points, int width,
                                       const SensorGeometryParams& params = {});

}  // namespace binpick::simulation
