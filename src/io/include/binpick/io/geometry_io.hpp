#pragma once
// Reading and writing meshes and point clouds: PLY (ascii, binary little/big endian), PCD (ascii,
// binary, binary_compressed), STL (ascii, binary), OBJ. Every reader validates what it returns
// and throws core::Error naming the file and what was wrong (missing, truncated, corrupt,
// NaN, wrong counts). Free functions without shared state: thread-safe.
//
// Errors: every message is "PATH: what was wrong", PATH exactly as passed in, e.g.
//   "model.ply: face 12 refers to vertex 900 but the file has 800 vertices"
//   "part.obj: line 40: face refers to vertex 9 but the file has 8 vertices"
//   "scan.pcd: point 17 is not finite (nan, 0.5, 1) (NaN points are only allowed in ...)"
// Counts in headers are checked against the file size before anything is allocated, so corrupt
// files fail with a message, never with std::bad_alloc.
//
// What the readers guarantee about their results:
// - at least one point; a mesh from readMesh has at least one face and non-zero total area;
// - mesh vertices are finite and triangle indices in range;
// - an unorganized cloud is finite; an organized cloud may hold NaN points (invalid pixels) but
//   never inf; a point with any NaN coordinate counts as invalid;
// - normals (PLY nx/ny/nz, PCD normal_x/y/z) are unit length for every valid point: they are
//   normalised on reading (left bit-identical when already unit to 1e-6), and a zero normal is an
//   error naming the point; normals of invalid pixels are returned as stored;
// - intensities (PLY vertex property `intensity`, PCD field `intensity`, any numeric type) are
//   read and written, one per point: converted to float but not rescaled (a PLY `uchar intensity`
//   of 200 reads as 200.0f), finite for every valid point; those of invalid pixels are returned
//   as stored (NaN included);
// - STL corners with identical coordinates are merged into shared vertices; polygons (PLY, OBJ)
//   are fan-triangulated; OBJ texture coordinates and normals are ignored.
// Formats: PLY vertex x/y/z and intensity may be any numeric type; other properties and elements
// are skipped. PCD x/y/z and normals must be float or double; intensity may be any type.
// Binary STL is recognised by its size (84 + 50 x triangles) even when it starts with "solid".
// PCD files with HEIGHT 1 are unorganized (as in PCL), so a one-row organized grid cannot be
// stored in PCD; use PLY for that.
#include <string>

#include "binpick/io/point_cloud.hpp"

namespace binpick::io {

// What a model file holds: a mesh when the file has faces, otherwise only a cloud.
struct ModelGeometry {
  TriangleMesh mesh;  // empty when the file has no faces
  PointCloud cloud;   // the vertices (with normals and intensities when the file has them)
  bool hasMesh() const { return !mesh.empty(); }
};

// Dispatches on the extension (.ply .pcd .stl .obj, case-insensitive; anything else throws).
// Files with faces give the mesh and its vertices as the cloud (with PLY normals and intensities
// when present); PLY without faces, PCD, and OBJ with only `v` lines give only the cloud.
ModelGeometry readModelGeometry(const std::string& path);
// Triangles from a .ply/.stl/.obj; throws when the file has no faces (and for .pcd).
TriangleMesh readMesh(const std::string& path);
// Points (and normals, intensities when present) from a .ply/.pcd (throws for .stl/.obj: use
// readModelGeometry). Organized clouds keep width/height: PCD via its WIDTH/HEIGHT (HEIGHT > 1),
// PLY via a header line `obj_info organized WIDTH HEIGHT`. Organized clouds may hold NaN points
// (invalid pixels); unorganized clouds must be finite.
PointCloud readPointCloud(const std::string& path);

// Binary round-trips every float bit (NaN pixels included). Ascii writes the shortest decimal text
// that reads back to the same float (PLY and PCD).
enum class Encoding { Ascii, Binary };
// Writes .ply (binary little endian or ascii; organized grid as `obj_info organized W H`) or .pcd
// (binary or ascii, as PCL writes them; grid as WIDTH/HEIGHT) by extension, with normals (PLY nx ny nz, PCD
// normal_x/y/z) and intensities (PLY `property float intensity` after the coordinates and normals,
// PCD float field `intensity`) when the cloud has them. Refuses, with the same errors, any cloud
// the readers would reject (empty, NaN in an unorganized cloud, zero normal, non-finite intensity
// of a valid point, width x height != size, normal or intensity count != size), so every written
// file reads back.
void writePointCloud(const std::string& path, const PointCloud& cloud, Encoding encoding = Encoding::Binary);
// Writes .ply (binary) or .stl (binary) or .obj by extension. Refuses empty meshes, bad indices,
// non-finite vertices and meshes whose faces all have zero area.
void writeMesh(const std::string& path, const TriangleMesh& mesh);

}  // namespace binpick::io
