// PCD through PCL, the only file that includes PCL headers (they are slow to compile): PCL
// decompresses binary_compressed bodies and writes files. Header checks and the other bodies are
// ours (pcd_header.cpp, pcd_reader.cpp, pcd_ascii.cpp): see pcd_format.hpp for why.
#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "byte_io.hpp"
#include "formats.hpp"
#include "pcd_format.hpp"

namespace binpick::io_detail {

namespace {

std::uint8_t pclDatatype(const PcdField& field) {
  using Field = pcl::PCLPointField;
  if (field.type == 'F') return field.size == 8 ? Field::FLOAT64 : Field::FLOAT32;
  const bool isSigned = field.type == 'I';
  switch (field.size) {
    case 1:
      return isSigned ? Field::INT8 : Field::UINT8;
    case 2:
      return isSigned ? Field::INT16 : Field::UINT16;
    case 4:
      return isSigned ? Field::INT32 : Field::UINT32;
    default:
      return isSigned ? Field::INT64 : Field::UINT64;
  }
}

// What PCL's own readHeader would have produced, built from our checked header: field layout,
// grid, and a data buffer of the size the header check accepted.
pcl::PCLPointCloud2 emptyBlobFor(const PcdHeader& header) {
  pcl::PCLPointCloud2 blob;
  std::uint32_t offset = 0;
  for (const PcdField& field : header.fields) {
    pcl::PCLPointField pclField;
    pclField.name = field.name;
    pclField.offset = offset;
    pclField.datatype = pclDatatype(field);
    pclField.count = static_cast<std::uint32_t>(field.count);
    blob.fields.push_back(pclField);
    offset += static_cast<std::uint32_t>(field.size * field.count);
  }
  blob.width = static_cast<std::uint32_t>(header.width);
  blob.height = static_cast<std::uint32_t>(header.height);
  blob.point_step = offset;
  blob.row_step = offset * blob.width;
  blob.data.resize(header.points * header.pointBytes);
  return blob;
}

void appendFloatField(pcl::PCLPointCloud2& blob, const char* name) {
  pcl::PCLPointField field;
  field.name = name;
  field.offset = blob.point_step;
  field.datatype = pcl::PCLPointField::FLOAT32;
  field.count = 1;
  blob.fields.push_back(field);
  blob.point_step += sizeof(float);
}

// The fields of a cloud, in record order: x y z, then normal_x/y/z and intensity when present
// (the fields of pcl::PointXYZ, PointNormal, PointXYZI or PointXYZINormal, which PCL matches by
// name), all float.
pcl::PCLPointCloud2 blobLayoutFor(const PointCloud& cloud) {
  pcl::PCLPointCloud2 blob;
  const bool organized = cloud.isOrganized();
  blob.width = organized ? cloud.width : static_cast<std::uint32_t>(cloud.size());
  blob.height = organized ? cloud.height : 1;
  for (const char* name : {"x", "y", "z"}) appendFloatField(blob, name);
  if (cloud.hasNormals()) {
    for (const char* name : {"normal_x", "normal_y", "normal_z"}) appendFloatField(blob, name);
  }
  if (cloud.hasIntensities()) appendFloatField(blob, "intensity");
  blob.row_step = blob.point_step * blob.width;
  return blob;
}

std::uint8_t* copyFloats(std::uint8_t* out, const float* values, std::size_t count) {
  std::memcpy(out, values, count * sizeof(float));
  return out + count * sizeof(float);
}

pcl::PCLPointCloud2 toBlob(const PointCloud& cloud) {
  pcl::PCLPointCloud2 blob = blobLayoutFor(cloud);
  blob.is_dense = true;
  blob.data.resize(std::size_t{blob.point_step} * cloud.size());
  std::uint8_t* out = blob.data.data();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    out = copyFloats(out, cloud.points[i].data(), 3);
    if (cloud.hasNormals()) out = copyFloats(out, cloud.normals[i].data(), 3);
    if (cloud.hasIntensities()) out = copyFloats(out, &cloud.intensities[i], 1);
    blob.is_dense = blob.is_dense && cloud.points[i].allFinite();
  }
  return blob;
}

}  // namespace

std::vector<std::uint8_t> decompressPcdBody(std::string_view bytes, const PcdHeader& header,
                                            const std::string& path) {
  pcl::PCLPointCloud2 blob = emptyBlobFor(header);
  int status = -1;
  try {
    status = pcl::PCDReader().readBodyBinary(reinterpret_cast<const unsigned char*>(bytes.data()),
                                             blob, pcl::PCDReader::PCD_V7, true,
                                             static_cast<unsigned int>(header.bodyOffset));
  } catch (const std::exception& error) {
    fail(path, std::string("PCL failed to decompress the data: ") + error.what());
  }
  if (status < 0 || blob.data.size() != header.points * header.pointBytes) {
    fail(path, "corrupt binary_compressed data: it does not decompress to the declared points");
  }
  return std::move(blob.data);
}

void writePcd(const std::string& path, const PointCloud& cloud, Encoding encoding) {
  const pcl::PCLPointCloud2 blob = toBlob(cloud);
  if (cloud.isOrganized() && cloud.height == 1 && !blob.is_dense) {
    fail(path,
         "a PCD file cannot keep a one-row organized cloud with NaN points (it would read "
         "back as unorganized); write .ply instead");
  }
  int status = -1;
  try {
    pcl::PCDWriter writer;
    // 9 significant digits make every float round-trip through ascii.
    status = encoding == Encoding::Ascii ? writer.writeASCII(path, blob, Eigen::Vector4f::Zero(),
                                                             Eigen::Quaternionf::Identity(), 9)
                                         : writer.writeBinary(path, blob);
  } catch (const std::exception& error) {
    fail(path, std::string("PCL failed to write the file: ") + error.what());
  }
  if (status < 0) {
    fail(path, "PCL could not write the file (does the directory exist and is it writable?)");
  }
}

}  // namespace binpick::io_detail
