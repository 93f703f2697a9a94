// Public entry points: extension dispatch plus the checks every file goes through, so each format
// loader only has to get the file structure right.
#include "binpick/io/geometry_io.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <utility>

#include "byte_io.hpp"
#include "formats.hpp"

namespace binpick::io {

namespace detail {

FileFormat formatOf(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".ply") return FileFormat::Ply;
  if (extension == ".pcd") return FileFormat::Pcd;
  if (extension == ".stl") return FileFormat::Stl;
  if (extension == ".obj") return FileFormat::Obj;
  fail(path, (extension.empty() ? std::string("no file extension") : "unknown file extension '" + extension + "'") +
                 "; expected .ply, .pcd, .stl or .obj");
}

const char* extensionName(FileFormat format) {
  switch (format) {
    case FileFormat::Ply: return ".ply";
    case FileFormat::Pcd: return ".pcd";
    case FileFormat::Stl: return ".stl";
    case FileFormat::Obj: return ".obj";
  }
  return "?";
}

}  // namespace detail

namespace {

using detail::extensionName;
using detail::fail;
using detail::FileFormat;

ModelGeometry load(const std::string& path, FileFormat format) {
  switch (format) {
    case FileFormat::Ply: return detail::loadPly(path);
    case FileFormat::Pcd: return detail::loadPcd(path);
    case FileFormat::Stl: return detail::loadStl(path);
    case FileFormat::Obj: return detail::loadObj(path);
  }
  fail(path, "unsupported format");
}

// Mesh checks come first so that a bad mesh vertex is reported as a vertex, not as a point.
void checkGeometry(ModelGeometry& geometry, const std::string& path) {
  if (geometry.cloud.empty()) fail(path, "the file has no points");
  if (geometry.hasMesh()) {
    validateMesh(geometry.mesh, path);
    detail::requireSomeArea(geometry.mesh, path);
  }
  validateCloud(geometry.cloud, path);
  detail::normaliseNormals(geometry.cloud, path);
}

}  // namespace

ModelGeometry readModelGeometry(const std::string& path) {
  ModelGeometry geometry = load(path, detail::formatOf(path));
  checkGeometry(geometry, path);
  return geometry;
}

TriangleMesh readMesh(const std::string& path) {
  const FileFormat format = detail::formatOf(path);
  if (format == FileFormat::Pcd) {
    fail(path, "a .pcd file holds no faces; readMesh reads .ply, .stl and .obj");
  }
  ModelGeometry geometry = load(path, format);
  if (!geometry.hasMesh()) fail(path, "the file has no faces");
  checkGeometry(geometry, path);
  return std::move(geometry.mesh);
}

PointCloud readPointCloud(const std::string& path) {
  const FileFormat format = detail::formatOf(path);
  if (format == FileFormat::Stl || format == FileFormat::Obj) {
    fail(path, std::string("readPointCloud reads .ply and .pcd, not ") + extensionName(format) +
                   "; use readModelGeometry for mesh files");
  }
  ModelGeometry geometry = load(path, format);
  checkGeometry(geometry, path);
  return std::move(geometry.cloud);
}

void writePointCloud(const std::string& path, const PointCloud& cloud, Encoding encoding) {
  const FileFormat format = detail::formatOf(path);
  if (format != FileFormat::Ply && format != FileFormat::Pcd) {
    fail(path, std::string("writePointCloud writes .ply and .pcd, not ") + extensionName(format));
  }
  // Refuse what the readers would refuse, so every file we write can be read back.
  if (cloud.empty()) fail(path, "refusing to write a cloud with no points");
  validateCloud(cloud, path);
  detail::requireDirectedNormals(cloud, path);
  if (format == FileFormat::Ply) {
    detail::writePlyCloud(path, cloud, encoding);
  } else {
    detail::writePcd(path, cloud, encoding);
  }
}

void writeMesh(const std::string& path, const TriangleMesh& mesh) {
  const FileFormat format = detail::formatOf(path);
  if (format == FileFormat::Pcd) fail(path, "writeMesh writes .ply, .stl and .obj, not .pcd");
  if (mesh.empty()) fail(path, "refusing to write a mesh with no triangles");
  validateMesh(mesh, path);
  detail::requireSomeArea(mesh, path);
  switch (format) {
    case FileFormat::Ply: detail::writePlyMesh(path, mesh); break;
    case FileFormat::Stl: detail::writeStl(path, mesh); break;
    case FileFormat::Obj: detail::writeObj(path, mesh); break;
    case FileFormat::Pcd: break;
  }
}

}  // namespace binpick::io
