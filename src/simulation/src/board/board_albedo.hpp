// The reflectance a camera pixel sees on a posed board. Internal to binpick::simulation.
#pragma once
#include <Eigen/Geometry>
#include <cstdint>

#include "binpick/io/lens.hpp"
#include "binpick/simulation/calibration_board.hpp"
#include "sensor/pixel_lighting.hpp"

namespace binpick::simulation::detail {

// An AlbedoFunction for a scene of the board (object `board_id`, at T_camera_board) and other
// objects of uniform `other_albedo`. On the print, it returns the print's mean over the camera
// pixel's footprint, the pixel being the one whose ray hits the point: a sensor pixel integrates
// over its area, so the board's edges and corners come out anti-aliased, as real images have
// them. The footprint is the inverse of the projection's Jacobian on the board plane, from
// `samples` x `samples` points. The board's sides and back are plain white. The function keeps
// references to `board` and `camera`, which must outlive it; it is thread-safe.
AlbedoFunction boardPixelAlbedo(const CalibrationBoard& board, const io::LensIntrinsics& camera,
                                const Eigen::Isometry3d& T_camera_board, int32_t board_id, int samples,
                                float other_albedo);

}  // namespace binpick::simulation::detail
