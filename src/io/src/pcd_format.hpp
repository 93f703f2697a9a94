#pragma once
// Internal: PCD reading. PCL's header parser allocates POINTS x point size straight from the
// header, honours repeated POINTS lines and even keeps parsing "header lines" inside binary data,
// so a corrupt file can make it allocate gigabytes; its ascii parser turns unparseable values into
// 0 and skips malformed lines with only a warning. So we parse and check the header and the ascii
// body ourselves, copy binary records straight from the file, and decompress binary_compressed
// bodies (LZF) and write files in pcd.cpp. No PCL: its io library loads VTK, which the daemon
// that reads models must not carry.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "binpick/io/point_cloud.hpp"

namespace binpick::io::detail {

struct PcdField {
  std::string name;
  std::size_t size = 4;  // bytes per value
  char type = 'F';       // I, U or F
  std::size_t count = 1;
};

enum class PcdData { Ascii, Binary, BinaryCompressed };

struct PcdHeader {
  std::vector<PcdField> fields;
  std::uint64_t width = 0;
  std::uint64_t height = 1;
  std::uint64_t points = 0;
  PcdData data = PcdData::Ascii;
  std::size_t bodyOffset = 0;
  std::uint64_t pointBytes = 0;  // binary size of one point
  bool hasNormals = false;       // normal_x, normal_y and normal_z are all present
  bool hasIntensities = false;   // an `intensity` field is present (one number of any type)
  std::size_t headerLines = 0;   // so ascii body errors can give file line numbers

  const PcdField* find(std::string_view name) const;
  // Byte offset of a field inside one binary point record.
  std::size_t offsetOf(std::string_view name) const;
};

// Parses the header at the start of the file's `bytes`. Throws naming `path` when the header is
// malformed, lacks x/y/z, or claims more points (or compressed bytes) than the file can hold.
PcdHeader checkPcdHeader(std::string_view bytes, const std::string& path);

// The points (and normals, intensities) of an ascii body: one point per line with exactly the
// header's number of values; x/y/z/normals/intensity must be numbers (or nan).
PointCloud readPcdAsciiBody(std::string_view body, const PcdHeader& header, const std::string& path);

// The points (and normals, intensities) of `header.points` point-major binary records starting
// at `records`: the layout of a DATA binary body, and of a binary_compressed body once
// decompressed.
PointCloud readPcdBinaryRecords(const char* records, const PcdHeader& header);

// A binary_compressed body (LZF, stored field by field) decompressed into point-major
// records; the header check has bounded its sizes. Throws naming `path` when it is corrupt.
std::vector<std::uint8_t> decompressPcdBody(std::string_view bytes, const PcdHeader& header, const std::string& path);

}  // namespace binpick::io::detail
