#include "range_agreement.hpp"

#include "icp.hpp"

namespace binpick::estimation {

RangeAgreement rangeAgreement(const PreparedModel& model, const Eigen::Isometry3f& pose, const LineOfSightMap& map,
                              float tolerance) {
  RangeAgreement agreement;
  const float fine_step = 0.5f * model.step;
  for (uint32_t k : visibleSurfacePoints(model.fine_points, model.fine_normals, fine_step, model.centre, pose)) {
    const Eigen::Vector3f p = pose * model.fine_points[k];
    if (!LineOfSightMap::measurable(p, pose.linear() * model.fine_normals[k])) continue;
    ++agreement.visible;
    const float measured = map.measuredDepth(p);
    if (measured == LineOfSightMap::kUnseen) {
      ++agreement.unseen;
    } else if (p.z() + tolerance < measured) {
      ++agreement.seen_through;
    } else if (p.z() - tolerance <= measured) {
      ++agreement.explained;
    } else {
      ++agreement.hidden;
    }
  }
  return agreement;
}

}  // namespace binpick::estimation
