// computePixelLighting: the light budget of each camera pixel, independent of the pattern.
#include "sensor/pixel_lighting.hpp"

#include <algorithm>
#include <cmath>

#include "binpick/core/error.hpp"
#include "binpick/core/thread_count.hpp"

namespace binpick::simulation {
namespace {

struct Surface {
  Eigen::Vector3f point;
  Eigen::Vector3f normal;
  float albedo;
};

// Blinn-Phong: the highlight peaks when the normal bisects the directions to the projector and to
// the camera (at the origin of the camera frame).
float highlight(const Surface& s, const Eigen::Vector3f& projector_centre, double shininess) {
  const Eigen::Vector3f to_light = (projector_centre - s.point).normalized();
  const Eigen::Vector3f to_camera = (-s.point).normalized();
  const float n_dot_h = std::max(0.0f, s.normal.dot((to_light + to_camera).normalized()));
  return std::pow(n_dot_h, static_cast<float>(shininess));
}

// Projector defocus grows with the distance from the focal plane in dioptres (thin lens).
float blurSigma(float distance, const PhotometryParams& p) {
  const double defocus = p.defocus_per_dioptre * std::abs(1.0 / distance - 1.0 / p.focus_distance);
  return static_cast<float>(std::hypot(p.min_blur_sigma, defocus));
}

PixelLighting lightPixel(const SensorGeometry& g, std::size_t i, float albedo, const Eigen::Vector3f& projector_centre,
                         const PhotometryParams& p) {
  PixelLighting light;
  light.projector_x = g.projector_pixel[i].x();
  light.projector_y = g.projector_pixel[i].y();
  light.ambient = static_cast<float>(p.ambient) * albedo;
  light.global = static_cast<float>(p.global_light * p.projector_white) * albedo;
  if (!g.lit[i] || g.camera_cosine[i] <= 0.0f) return light;
  const Surface surface{g.point[i], g.normal[i], albedo};
  // Irradiance of a full-white pixel falls with the incidence cosine and the squared distance.
  const float distance = g.projector_distance[i];
  const double falloff = p.reference_distance / distance;
  const float irradiance = static_cast<float>(p.projector_white * falloff * falloff) * g.projector_cosine[i];
  const float specular = static_cast<float>(p.specular) * highlight(surface, projector_centre, p.shininess);
  light.direct = irradiance * (albedo + specular);
  light.blur_sigma = blurSigma(distance, p);
  return light;
}

}  // namespace

std::vector<PixelLighting> computePixelLighting(const SensorGeometry& geometry, const io::RigCalibration& rig,
                                                const PhotometryParams& params, const AlbedoFunction& albedo) {
  params.validate();
  if (!albedo) throw core::Error("computePixelLighting: no albedo function");
  const std::size_t count = static_cast<std::size_t>(geometry.width) * geometry.height;
  if (geometry.object_id.size() != count || geometry.lit.size() != count) {
    throw core::Error("computePixelLighting: the sensor geometry's buffers do not match its size");
  }
  const Eigen::Vector3f projector_centre = rig.T_projector_camera.inverse().translation().cast<float>();
  std::vector<PixelLighting> lighting(count);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(core::resolveThreadCount(params.threads))
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(count); ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (geometry.object_index[i] < 0) continue;
    const float a = std::clamp(
        static_cast<float>(params.albedo_scale) * albedo(geometry.object_id[i], geometry.object_point[i]), 0.0f, 1.0f);
    lighting[i] = lightPixel(geometry, i, a, projector_centre, params);
  }
  return lighting;
}

}  // namespace binpick::simulation
