#pragma once
// Where rays through a lens's image can point, and which pixels can see a box. Internal to
// binpick::simulation. Pure functions: thread-safe.
#include <Eigen/Geometry>

#include "binpick/io/lens.hpp"

namespace binpick::simulation::detail {

// Bounds of the undistorted normalised coordinates (x/z, y/z) of the rays through the image
// area, sampled along its border (pixel edges, half a pixel outside the outer centres), grown by
// `margin` times its size on every side. Outside it, the distortion polynomial may fold points
// from far off-axis back into the image; inside, it is one-to-one for any usable lens.
Eigen::AlignedBox2d normalisedImageBounds(const io::LensIntrinsics& lens, double margin);

// Pixels [u_begin, u_end) x [v_begin, v_end) of an image.
struct PixelRange {
  int u_begin = 0, u_end = 0, v_begin = 0, v_end = 0;
  bool empty() const { return u_begin >= u_end || v_begin >= v_end; }
};

// A range holding every pixel whose ray (through its centre) can meet `box` (camera frame),
// clipped to the image; `field` is normalisedImageBounds of the same lens. A box reaching the
// camera plane (z <= 0) may be seen anywhere: the whole image.
PixelRange pixelsSeeing(const io::LensIntrinsics& lens, const Eigen::AlignedBox2d& field,
                        const Eigen::AlignedBox3d& box);

}  // namespace binpick::simulation::detail
