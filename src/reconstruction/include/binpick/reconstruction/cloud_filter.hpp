#pragma once
// Optional clean-up of an organized cloud after triangulation, in this order: a depth range, a
// crop box, depth noise removal (the points the decoder measured noisily onto the median of their
// 3x3 neighbourhood's surface, those far from it removed), the removal of points that stand off their
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
  // Noise removal: each noisy point moves along its ray to the median camera z of itself and, for
  // each line of its 3x3 neighbourhood through it (row, column, diagonals) whose two ends lie
  // within median_reach of it, the mean of the two ends (the surface's depth at the point where
  // it is locally a plane, however steep; a line with an end across a depth edge takes no part).
  // A point farther than median_max_pull from that median does not lie on its neighbours'
  // surface and is removed (a noise or decoding outlier; status DepthEdge). Halves the depth noise
  // of dark and glossy surfaces, which then hold together as patches for the speckle filter, and
  // takes the tail of that noise away. Metres, not pixel footprints: a point moves by less than
  // median_max_pull whatever the resolution, and a step higher than median_reach is never
  // smoothed across. median_reach = 0 turns it off. Under harsh light it keeps 86% of the parts'
  // pixels with no point 5 mm off (82% without); clean captures keep their points as measured
  // (median_min_noise; docs/reconstruction.md).
  double median_reach = 0.0045;     // metres
  double median_max_pull = 0.0032;  // metres
  // Only points at most this bright (cloud.intensities, the white image on [0, 1]; every point of
  // a cloud without intensities) are smoothed or removed: the noise is the dark surfaces', and
  // bright ones keep their points as measured (the dark parts of the harsh preset are at 0.07 to
  // 0.15, the clean parts at 0.2 to 0.8).
  double median_max_intensity = 0.2;
  // ... and only points whose column the sensor noise leaves at least this uncertain (the
  // decoder's DecodedCapture::column_noise given to filterCloud; standard deviation, projector
  // pixels, 0.3 px is about 0.7 mm of depth at 0.9 m on the virtual rig): clean captures (below
  // 0.3 but for a few hundred dark points) keep their points as measured. A cloud filtered
  // without the column noise is smoothed only with median_min_noise = 0 (every dark point).
  double median_min_noise = 0.3;
  // A point this noisy or more (projector pixels) on no line of its neighbourhood's surface has
  // nothing to be smoothed or checked with, and is removed (status DepthEdge): one sigma of 0.6 px
  // is about 1.5 mm of depth, and alone such a point is 5 mm off once in a few hundred. Needs the
  // column noise.
  double median_lone_max_noise = 0.6;
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
  // Edge pixels on the other side (part of the depth-edge removal, after the test above): a pixel
  // gathers light over its area and its lens's blur, so beside a lit surface's edge where its
  // projector shadow falls (or nothing is seen, or a dimmer surface lies at another depth) a
  // pixel whose centre sees that other side can still decode the edge's light; its point lands
  // beside the edge on the lit surface's extension, centimetres off the surface the pixel sees
  // (the surface looks a pixel or more wider), and the test above keeps it. Along any of the 8
  // neighbour directions, a point with the other side (a pixel in projector shadow, status unlit,
  // or a point off its depth by more than edge_max_jump footprints a pixel) within
  // edge_side_reach pixels behind it and its own surface next ahead (within 2 pixels) is removed
  // (depth_edge) when its brightness (white image, cloud.intensities) is less than halfway from
  // the other side's to that neighbour's: its centre sees the other side. Sides less than
  // edge_side_min_contrast apart in brightness are not judged. Clouds without intensities skip
  // it; edge_side_reach = 0 (or edge_max_jump = 0) turns it off.
  int edge_side_reach = 3;               // pixels
  double edge_side_min_contrast = 0.02;  // white image, [0, 1]
  // Speckle removal: 4-connected neighbours belong to one patch when their camera z differs by
  // at most speckle_max_step; patches of fewer than speckle_min_pixels points are removed.
  // speckle_min_pixels = 0 turns it off.
  double speckle_max_step = 0.002;  // metres
  int speckle_min_pixels = 50;
  // A capture decoded to whole codes (no phase images) puts neighbours on one smooth surface a
  // code apart, and a code spans the depth PointPrecision::code_depth gives at each point: 7 to
  // 9 mm for a rig 3.5 m from the scene coding 2 projector pixels per code, 1.7 mm at 0.9 m on the
  // virtual rig. The speckle step and the depth-edge reach of a point are at least this many
  // codes' depth there. 0: the fixed steps above alone.
  double min_step_in_codes = 1.5;
  int threads = 0;        // 0: all cores
  void validate() const;  // throws core::Error naming the field
};

// How precisely each point was decoded, where known; each image empty or CV_32FC1 of the
// cloud's size.
struct PointPrecision {
  // The decoder's DecodedCapture::column_noise: limits noise removal to the noisy points
  // (CloudFilterParams::median_min_noise; without it, noise removal runs only with
  // median_min_noise = 0).
  cv::Mat column_noise;
  // For a capture decoded to whole codes: the camera z one code spans at each point, metres
  // (TriangulatedCloud::depth_per_projector_px times the code step); raises the speckle and
  // depth-edge steps there (CloudFilterParams::min_step_in_codes).
  cv::Mat code_depth;
};

// `cloud` must be organized and `status` CV_8UC1 of its size (throws core::Error otherwise).
void filterCloud(io::PointCloud& cloud, cv::Mat& status, const CloudFilterParams& params,
                 const PointPrecision& precision = {});

}  // namespace binpick::reconstruction
