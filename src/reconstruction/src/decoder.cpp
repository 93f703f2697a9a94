// decodeCapture: checks, then every row in parallel.
#include "binpick/reconstruction/decoder.hpp"

#include <algorithm>

#include "binpick/io/thread_count.hpp"
#include "capture_layout.hpp"
#include "capture_light_check.hpp"
#include "decode_plan.hpp"
#include "row_decoder.hpp"

namespace binpick::reconstruction {
namespace {

DecodedCapture allocate(const detail::CaptureLayout& layout) {
  DecodedCapture decoded;
  decoded.width = layout.width;
  decoded.height = layout.height;
  decoded.column.create(layout.height, layout.width, CV_32FC1);
  if (layout.rows.present) decoded.row.create(layout.height, layout.width, CV_32FC1);
  decoded.status.create(layout.height, layout.width, CV_8UC1);
  decoded.intensity.create(layout.height, layout.width, CV_32FC1);
  decoded.has_phase = layout.columns.hasPhase();
  return decoded;
}

detail::RowOutput outputOf(DecodedCapture& decoded) {
  detail::RowOutput out;
  out.column = decoded.column.ptr<float>(0);
  out.row = decoded.row.empty() ? nullptr : decoded.row.ptr<float>(0);
  out.status = decoded.status.ptr<uint8_t>(0);
  out.intensity = decoded.intensity.ptr<float>(0);
  return out;
}

// The tile loops run over consecutive pixels across rows: every image must be one block.
Capture withContinuousImages(const Capture& capture) {
  Capture continuous = capture;
  for (cv::Mat& image : continuous.images) {
    if (!image.isContinuous()) image = image.clone();
  }
  return continuous;
}

// Tiles are independent: the result does not depend on the thread count.
template <typename Pixel>
void decodeTiles(const Capture& capture, const detail::DecodePlan& plan, int threads, DecodedCapture& decoded) {
  const std::size_t pixels = static_cast<std::size_t>(plan.layout.width) * static_cast<std::size_t>(plan.layout.height);
  const auto tiles = static_cast<long>((pixels + detail::kTilePixels - 1) / detail::kTilePixels);
  const detail::RowOutput out = outputOf(decoded);
#pragma omp parallel num_threads(threads)
  {
    detail::RowScratch<detail::WorkType<Pixel>> scratch;
#pragma omp for schedule(static, 4)
    for (long tile = 0; tile < tiles; ++tile) {
      const std::size_t offset = static_cast<std::size_t>(tile) * detail::kTilePixels;
      const int count = static_cast<int>(std::min<std::size_t>(detail::kTilePixels, pixels - offset));
      detail::decodeTile<Pixel>(capture, plan, offset, count, scratch, out);
    }
  }
}

}  // namespace

DecodedCapture decodeCapture(const Capture& capture, const DecodeParams& params) {
  params.validate();
  const detail::DecodePlan plan = detail::makeDecodePlan(detail::captureLayout(capture), params);
  detail::checkCaptureLight(capture, plan, params);
  DecodedCapture decoded = allocate(plan.layout);
  const int threads = resolveThreadCount(params.threads);
  const Capture continuous = withContinuousImages(capture);
  if (plan.layout.bit_depth == 8) {
    decodeTiles<uint8_t>(continuous, plan, threads, decoded);
  } else {
    decodeTiles<uint16_t>(continuous, plan, threads, decoded);
  }
  return decoded;
}

}  // namespace binpick::reconstruction
