#pragma once
// Internal: the format readers and writers behind geometry_io.hpp, and extension dispatch.
// Loaders parse and check the file's structure (header, counts, sizes, index ranges); the checks
// on the geometry itself (finite values, normals, emptiness) are done once in geometry_io.cpp.
#include <string>

#include "binpick/io/geometry_io.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::io::detail {

enum class FileFormat { Ply, Pcd, Stl, Obj };

// From the extension, case-insensitive; throws naming the path for any other extension.
FileFormat formatOf(const std::string& path);
const char* extensionName(FileFormat format);  // ".ply", ...

// Loaders fill `mesh` only when the file has faces; `cloud` always holds the vertices.
ModelGeometry loadPly(const std::string& path);
ModelGeometry loadStl(const std::string& path);
ModelGeometry loadObj(const std::string& path);
ModelGeometry loadPcd(const std::string& path);

void writePlyCloud(const std::string& path, const PointCloud& cloud, Encoding encoding);
void writePlyMesh(const std::string& path, const TriangleMesh& mesh);
void writeStl(const std::string& path, const TriangleMesh& mesh);
void writeObj(const std::string& path, const TriangleMesh& mesh);
void writePcd(const std::string& path, const PointCloud& cloud, Encoding encoding);

// Makes every normal of a valid point unit length (to 1e-6); throws naming the point when one is
// zero.
void normaliseNormals(PointCloud& cloud, const std::string& path);
// The same check without changing the cloud (writers refuse what readers would refuse).
void requireDirectedNormals(const PointCloud& cloud, const std::string& path);
// Throws when every triangle of a non-empty mesh is degenerate (nothing to render or match).
void requireSomeArea(const TriangleMesh& mesh, const std::string& path);

}  // namespace binpick::io::detail
