// PCD bodies that are neither parsed nor copied record by record (pcd_reader.cpp): decompressing
// binary_compressed data, and writing files. The format is PCL's (pointclouds.org, "The PCD file
// format"), version 0.7; files written here read in PCL and the other way round (tests/io).
#include <cstring>
#include <string>
#include <vector>

#include "byte_io.hpp"
#include "formats.hpp"
#include "pcd_format.hpp"
#include "text_io.hpp"

namespace binpick::io::detail {

namespace {

[[noreturn]] void failCorrupt(const std::string& path, const std::string& why) {
  fail(path, "corrupt binary_compressed data: " + why);
}

// LZF (Marc Lehmann's liblzf, the compressor PCL uses), decoded into exactly `size` bytes. Each
// control byte c starts either a literal run (c < 32: the next c + 1 bytes) or a back reference
// (length c >> 5, plus the next byte when that is 7, plus 2; distance ((c & 31) << 8) + the byte
// after, plus 1). Every read and copy is bounds-checked: corrupt input fails, never overruns.
std::vector<std::uint8_t> lzfDecompress(const std::uint8_t* in, std::size_t in_size, std::size_t size,
                                        const std::string& path) {
  std::vector<std::uint8_t> out(size);
  std::size_t ip = 0, op = 0;
  while (ip < in_size) {
    const unsigned control = in[ip++];
    if (control < 32) {
      const std::size_t run = control + 1;
      if (ip + run > in_size || op + run > size) failCorrupt(path, "a literal run overruns the data");
      std::memcpy(out.data() + op, in + ip, run);
      ip += run;
      op += run;
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7) {
      if (ip >= in_size) failCorrupt(path, "a back reference is cut off");
      length += in[ip++];
    }
    if (ip >= in_size) failCorrupt(path, "a back reference is cut off");
    const std::size_t distance = ((control & 0x1fu) << 8) + in[ip++] + 1;
    length += 2;
    if (distance > op || op + length > size) failCorrupt(path, "a back reference points outside the data");
    for (std::size_t i = 0; i < length; ++i, ++op) out[op] = out[op - distance];  // may overlap
  }
  if (op != size) failCorrupt(path, "it does not decompress to the declared points");
  return out;
}

// A binary_compressed body stores each field for all points, then the next field; the binary
// records hold all fields of one point, then the next point.
std::vector<std::uint8_t> pointMajor(const std::vector<std::uint8_t>& fields, const PcdHeader& header) {
  std::vector<std::uint8_t> records(fields.size());
  std::size_t field_start = 0, record_offset = 0;
  for (const PcdField& field : header.fields) {
    const std::size_t bytes = field.size * field.count;
    for (std::uint64_t point = 0; point < header.points; ++point) {
      std::memcpy(records.data() + point * header.pointBytes + record_offset,
                  fields.data() + field_start + point * bytes, bytes);
    }
    field_start += bytes * header.points;
    record_offset += bytes;
  }
  return records;
}

// x y z, then normal_x/y/z and intensity when present (the fields of PCL's PointXYZ,
// PointNormal, PointXYZI or PointXYZINormal, which PCL matches by name), all float.
std::string pcdHeaderFor(const PointCloud& cloud, Encoding encoding) {
  std::string fields = "x y z";
  int count = 3;
  if (cloud.hasNormals()) fields += " normal_x normal_y normal_z", count += 3;
  if (cloud.hasIntensities()) fields += " intensity", count += 1;
  std::string sizes, types, counts;
  for (int i = 0; i < count; ++i) sizes += " 4", types += " F", counts += " 1";
  const bool organized = cloud.isOrganized();
  const std::size_t width = organized ? static_cast<std::size_t>(cloud.width) : cloud.size();
  const std::size_t height = organized ? static_cast<std::size_t>(cloud.height) : 1;
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + fields + "\nSIZE" + sizes + "\nTYPE" +
         types + "\nCOUNT" + counts + "\nWIDTH " + std::to_string(width) + "\nHEIGHT " + std::to_string(height) +
         "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(cloud.size()) + "\nDATA " +
         (encoding == Encoding::Ascii ? "ascii" : "binary") + "\n";
}

// One point's values in field order.
std::vector<float> valuesOf(const PointCloud& cloud, std::size_t i) {
  std::vector<float> values(cloud.points[i].data(), cloud.points[i].data() + 3);
  if (cloud.hasNormals()) values.insert(values.end(), cloud.normals[i].data(), cloud.normals[i].data() + 3);
  if (cloud.hasIntensities()) values.push_back(cloud.intensities[i]);
  return values;
}

bool hasInvalidPoint(const PointCloud& cloud) {
  for (const Eigen::Vector3f& point : cloud.points) {
    if (!point.allFinite()) return true;
  }
  return false;
}

}  // namespace

std::vector<std::uint8_t> decompressPcdBody(std::string_view bytes, const PcdHeader& header, const std::string& path) {
  // checkPcdHeader has read and bounded the two size words after the header.
  const auto* body = reinterpret_cast<const std::uint8_t*>(bytes.data()) + header.bodyOffset;
  const auto compressed = loadScalar<std::uint32_t>(reinterpret_cast<const char*>(body), !kHostIsLittleEndian);
  const std::vector<std::uint8_t> fields =
      lzfDecompress(body + 8, compressed, static_cast<std::size_t>(header.points * header.pointBytes), path);
  return pointMajor(fields, header);
}

void writePcd(const std::string& path, const PointCloud& cloud, Encoding encoding) {
  if (cloud.isOrganized() && cloud.height == 1 && hasInvalidPoint(cloud)) {
    fail(path,
         "a PCD file cannot keep a one-row organized cloud with NaN points (it would read "
         "back as unorganized); write .ply instead");
  }
  std::string bytes = pcdHeaderFor(cloud, encoding);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const std::vector<float> values = valuesOf(cloud, i);
    for (std::size_t v = 0; v < values.size(); ++v) {
      if (encoding == Encoding::Binary) {
        bytes.append(reinterpret_cast<const char*>(&values[v]), sizeof(float));  // host order, as PCL
        continue;
      }
      if (v > 0) bytes += ' ';
      appendNumber(bytes, values[v]);  // the shortest text that reads back to the same float
    }
    if (encoding == Encoding::Ascii) bytes += '\n';
  }
  writeFileBytes(path, bytes);
}

}  // namespace binpick::io::detail
