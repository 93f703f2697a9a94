#pragma once
// Optional clean-up of an organized cloud after triangulation, in this order: a depth range, a
// crop box, depth noise removal (off by default: dark points onto the median of their 3x3
// neighbourhood's surface, those far from it removed), the removal of points that stand off their
// neighbours' surface (depth edges: mixed pixels that see a near and a far surface at once, and
// lone misdecoded points, and edge pixels that see the shadow beside a lit edge), and the removal
// of small isolated patches (speckle: stray points from misdecoded pixels, usually at depth edges
// and on dark or glossy spots). Removed points become NaN and their pixels get the status that
// removed them. Stateless: thread-safe.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "binpick/io/point_cloud.hpp"

namespace binpick::reconstruction {

struct CloudFilterParams {
  // Camera z range, metres; 0 / infinity keep everything.
  double min_depth = 0.0;
  double max_depth = 1e9;
  // Axis-aligned box in the camera frame, metres; an empty box (the default) keeps everything.
  Eigen::AlignedBox3d crop;
  // Noise removal: each point moves along its ray to the median camera z of itself and its
  // 8-neighbours within median_reach of it (the others lie across a depth edge); a point farther
  // than median_max_pull from that median does not lie on its neighbours' surface and is removed
  // (a noise or decoding outlier; status DepthEdge). Halves the depth noise of dark and glossy
  // surfaces, which then hold together as patches for the speckle filter. Metres, not pixel
  // footprints: a point moves by less than median_max_pull whatever the resolution, and a step
  // higher than median_reach is never smoothed across. median_reach = 0 (the default) turns it
  // off: under harsh light 0.0045 keeps 85% of the parts' pixels with no point 5 mm off (81%
  // without), but on the clean test piles it left a point 5 mm off, cost coverage at half
  // resolution and detections (docs/reconstruction.md).
  double median_reach = 0.0;        // metres (0.0045 under harsh light)
  double median_max_pull = 0.0032;  // metres
  // Only points at most this bright (cloud.intensities, the white image on [0, 1]; every point of
  // a cloud without intensities) are smoothed or removed: the noise is the dark surfaces', and
  // bright ones keep their points as measured (the dark parts of the harsh preset are at 0.07 to
  // 0.15, the clean parts at 0.2 to 0.8).
  double median_max_intensity = 0.2;
  // Depth-edge removal: a point with fewer than edge_min_support of its 8-neighbours within
  // edge_max_jump pixel footprints of its camera z (a footprint: z over the focal length in
  // pixels, measured on the cloud; 8 footprints are 4.5 mm at 0.9 m for a 1600 px lens) is removed: mixed pixels at
  // depth edges (they see neither surface; a veil of them is one pixel wide) and lone misdecoded points. The last
  // pixels of a near surface keep their surface beside them, and a plane up to about 80 degrees from the view keeps its
  // neighbours. Points with fewer than edge_min_neighbours finite neighbours are left to the
  // speckle filter. edge_max_jump = 0 turns it off.
  double edge_max_jump = 8.0;  // pixel footprints
  int edge_min_neighbours = 3;
  int edge_min_support = 3;
  // Edge pixels on the dark side (part of the depth-edge removal, after the test above): a pixel
  // gathers light over its area and its lens's blur, so beside a lit surface's edge where its
  // projector shadow falls (or where nothing is seen) a pixel whose centre sees the dark side
  // still decodes the edge's light; its point lands beside the edge on the lit surface's
  // extension, centimetres off the shadowed surface the pixel sees (the surface looks a pixel or
  // more wider), and the test above keeps it. Along any of the 8 neighbour directions, a point
  // with a pixel in projector shadow (status unlit) within edge_side_reach pixels behind it and
  // its own surface next ahead (within 2 pixels, a depth step of at most edge_max_jump footprints
  // a pixel) is removed (depth_edge) when its brightness (white image, cloud.intensities) is less
  // than halfway from the dark pixel's to that neighbour's: its centre sees the dark side. Sides
  // less than edge_side_min_contrast apart in brightness are not judged. Clouds without
  // intensities skip it; edge_side_reach = 0 (or edge_max_jump = 0) turns it off.
  int edge_side_reach = 3;               // pixels
  double edge_side_min_contrast = 0.02;  // white image, [0, 1]
  // Speckle removal: 4-connected neighbours belong to one patch when their camera z differs by
  // at most speckle_max_step; patches of fewer than speckle_min_pixels points are removed.
  // speckle_min_pixels = 0 turns it off.
  double speckle_max_step = 0.002;  // metres
  int speckle_min_pixels = 50;
  int threads = 0;        // 0: all cores
  void validate() const;  // throws core::Error naming the field
};

// `cloud` must be organized and `status` CV_8UC1 of its size (throws core::Error otherwise).
void filterCloud(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params);

}  // namespace binpick::reconstruction
