#pragma once
// Reading and writing meshes and point clouds: PLY (ascii, binary little/big endian), PCD (ascii,
// binary, binary_compressed), STL (ascii, binary), OBJ. Every reader validates what it returns
// and throws binpick::Error naming the file and what was wrong (missing, truncated, corrupt,
// NaN, wrong counts). Free functions without shared state: thread-safe.
#include <string>

#include "binpick/io/point_cloud.hpp"

namespace binpick {

// What a model file holds: a mesh when the file has faces, otherwise only a cloud.
struct ModelGeometry {
  TriangleMesh mesh;  // empty when the file has no faces
  PointCloud cloud;   // the vertices (with normals when the file has them)
  bool hasMesh() const { return !mesh.empty(); }
};

// Dispatches on the extension (.ply .pcd .stl .obj, case-insensitive).
ModelGeometry readModelGeometry(const std::string& path);
// Triangles from a .ply/.stl/.obj; throws when the file has no faces.
TriangleMesh readMesh(const std::string& path);
// Points (and normals when present) from a .ply/.pcd. Organized clouds keep width/height: PCD via
// its WIDTH/HEIGHT, PLY via a header line `obj_info organized WIDTH HEIGHT`. Organized clouds may
// hold NaN points (invalid pixels); unorganized clouds must be finite.
PointCloud readPointCloud(const std::string& path);

enum class Encoding { Ascii, Binary };
// Writes .ply or .pcd by extension; organized clouds keep their grid.
void writePointCloud(const std::string& path, const PointCloud& cloud,
                     Encoding encoding = Encoding::Binary);
// Writes .ply (binary) or .stl (binary) or .obj by extension.
void writeMesh(const std::string& path, const TriangleMesh& mesh);

}  // namespace binpick
