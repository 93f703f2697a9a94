// Prepared-model cache files: exact round trip, and rejection of every kind of damaged file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "binpick/estimation/detector.hpp"
#include "binpick/estimation/model_cache.hpp"
#include "binpick/evaluation/evaluation.hpp"
#include "binpick/io/geometry_io.hpp"
#include "binpick/simulation/pile.hpp"
#include "boundary.hpp"
#include "estimation_test_support.hpp"

namespace binpick::estimation {
namespace {

namespace fs = std::filesystem;
using testing::cachedModel;
using testing::errorMessage;
using testing::smallModel;

std::vector<uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

template <class Values>
bool sameBytes(const Values& a, const Values& b) {
  return a.size() == b.size() && std::memcmp(&*a.begin(), &*b.begin(), a.size() * sizeof(*a.begin())) == 0;
}

bool sameTurns(const std::vector<Eigen::Isometry3f>& a, const std::vector<Eigen::Isometry3f>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!(a[k].matrix() == b[k].matrix())) return false;
  }
  return true;
}

void expectIdenticalModels(const PreparedModel& a, const PreparedModel& b) {
  EXPECT_TRUE(sameBytes(a.points, b.points));
  EXPECT_TRUE(sameBytes(a.normals, b.normals));
  EXPECT_EQ(a.diameter, b.diameter);
  EXPECT_EQ(a.step, b.step);
  EXPECT_TRUE(a.centre == b.centre);
  EXPECT_EQ(a.params.sampling_ratio, b.params.sampling_ratio);
  EXPECT_EQ(a.params.angle_step_deg, b.params.angle_step_deg);
  EXPECT_EQ(a.params.dense_samples_per_step2, b.params.dense_samples_per_step2);
  EXPECT_EQ(a.params.normal_radius_ratio, b.params.normal_radius_ratio);
  EXPECT_EQ(a.params.normal_cluster_angle_deg, b.params.normal_cluster_angle_deg);
  EXPECT_EQ(a.params.max_pairs_per_feature, b.params.max_pairs_per_feature);
  EXPECT_EQ(a.params.seed, b.params.seed);
  EXPECT_EQ(a.params.reduce_by_symmetry, b.params.reduce_by_symmetry);
  EXPECT_TRUE(a.symmetry.axis == b.symmetry.axis);
  EXPECT_EQ(a.symmetry.turns, b.symmetry.turns);
  EXPECT_EQ(a.symmetry.flips, b.symmetry.flips);
  EXPECT_EQ(a.referenceCount(), b.referenceCount());
  EXPECT_TRUE(sameTurns(a.near_symmetries.turned, b.near_symmetries.turned));
  EXPECT_TRUE(sameTurns(a.near_symmetries.slid, b.near_symmetries.slid));
  EXPECT_EQ(a.table.offsets(), b.table.offsets());
  EXPECT_TRUE(sameBytes(a.table.entries(), b.table.entries()));
  EXPECT_EQ(a.boundary_crease_angle_deg, b.boundary_crease_angle_deg);
  ASSERT_EQ(a.boundary == nullptr, b.boundary == nullptr);
  if (a.boundary) {
    EXPECT_TRUE(sameBytes(a.boundary->creases.points, b.boundary->creases.points));
    EXPECT_TRUE(sameBytes(a.boundary->creases.directions, b.boundary->creases.directions));
    EXPECT_EQ(a.boundary->table.offsets(), b.boundary->table.offsets());
    EXPECT_TRUE(sameBytes(a.boundary->table.entries(), b.boundary->table.entries()));
  }
}

class ModelCache : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() / ("binpick_test_estimation_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  // Expects loadModelCache to reject the file with a core::Error naming it.
  void expectRejected(const fs::path& path, const std::string& what) {
    SCOPED_TRACE(what);
    const std::string message = errorMessage([&] { loadModelCache(path.string()); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << "message: " << message;
  }

  fs::path dir;
};

TEST_F(ModelCache, RoundTripIsExactAndDetectsTheSame) {
  const PreparedModel& model = smallModel();
  const fs::path path = dir / "clamp.bpmodel";
  saveModelCache(model, 0x1234567890abcdefULL, path.string());
  EXPECT_FALSE(fs::exists(path.string() + ".partial")) << "the temporary file is moved into place";
  const CachedModel loaded = loadModelCache(path.string());
  EXPECT_EQ(loaded.source_fingerprint, 0x1234567890abcdefULL);
  expectIdenticalModels(model, loaded.model);

  // Saving the loaded model gives the same bytes.
  const fs::path again = dir / "again.bpmodel";
  saveModelCache(loaded.model, 0x1234567890abcdefULL, again.string());
  EXPECT_EQ(readBytes(path), readBytes(again));

  // The same detections, bit for bit, from a small pile.
  simulation::PileParams pile;
  pile.objects = 4;
  pile.seed = 8;
  pile.rig.camera = pile.rig.camera.scaled(0.5);
  const simulation::PileScene scene = simulation::generatePile(simulation::makePart("clamp").mesh, pile);
  DetectorParams params;
  params.selection.max_objects = 4;
  params.scene.crop = evaluation::binInterior(scene, pile);
  params.threads = 2;
  const DetectionResult a = Detector(model, params).detect(scene.cloud);
  const DetectionResult b = Detector(loaded.model, params).detect(scene.cloud);
  ASSERT_FALSE(a.detections.empty());
  ASSERT_EQ(a.detections.size(), b.detections.size());
  for (std::size_t k = 0; k < a.detections.size(); ++k) {
    EXPECT_TRUE(a.detections[k].T_camera_model.matrix() == b.detections[k].T_camera_model.matrix());
    EXPECT_EQ(a.detections[k].score, b.detections[k].score);
    EXPECT_EQ(a.detections[k].votes, b.detections[k].votes);
  }
}

// The table is used where it lies in the mapped file: a cache rewritten by another process (files
// are replaced whole) leaves a loaded model as it was.
TEST_F(ModelCache, ALoadedModelOutlivesItsCacheFileBeingReplaced) {
  const fs::path path = dir / "shared.bpmodel";
  saveModelCache(smallModel(), 1, path.string());
  const CachedModel loaded = loadModelCache(path.string());
  saveModelCache(cachedModel("l_bracket", 0.08f), 2, path.string());
  fs::remove(path);
  expectIdenticalModels(smallModel(), loaded.model);
}

TEST_F(ModelCache, RejectsDamagedFilesWithTheirName) {
  const fs::path good = dir / "good.bpmodel";
  saveModelCache(smallModel(), 42, good.string());
  const std::vector<uint8_t> bytes = readBytes(good);
  ASSERT_GT(bytes.size(), 1000u);

  // Truncated at several lengths, down to inside the magic.
  for (std::size_t length :
       {std::size_t{3}, std::size_t{8}, std::size_t{12}, std::size_t{19}, std::size_t{20}, std::size_t{40},
        std::size_t{100}, bytes.size() / 2, bytes.size() - 9, bytes.size() - 8, bytes.size() - 1}) {
    const fs::path path = dir / ("truncated_" + std::to_string(length) + ".bpmodel");
    writeBytes(path, std::vector<uint8_t>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(length)));
    expectRejected(path, "truncated to " + std::to_string(length));
  }
  // One flipped byte anywhere after the header (payload and checksum).
  for (std::size_t offset : {std::size_t{12}, std::size_t{20}, std::size_t{45}, std::size_t{200}, bytes.size() / 3,
                             bytes.size() - 20, bytes.size() - 9, bytes.size() - 1}) {
    std::vector<uint8_t> flipped = bytes;
    flipped[offset] ^= 0x10;
    const fs::path path = dir / ("flipped_" + std::to_string(offset) + ".bpmodel");
    writeBytes(path, flipped);
    expectRejected(path, "byte flipped at " + std::to_string(offset));
  }
  // Trailing garbage.
  std::vector<uint8_t> longer = bytes;
  longer.insert(longer.end(), {1, 2, 3, 4});
  writeBytes(dir / "longer.bpmodel", longer);
  expectRejected(dir / "longer.bpmodel", "trailing bytes");
  // Wrong magic: another file format.
  const fs::path ply = dir / "clamp.ply";
  io::writeMesh(ply.string(), simulation::makePart("clamp").mesh);
  expectRejected(ply, "a PLY file");
  std::vector<uint8_t> magic = bytes;
  magic[0] = 'X';
  writeBytes(dir / "magic.bpmodel", magic);
  expectRejected(dir / "magic.bpmodel", "wrong magic");
  // A future version (bytes 8..11, little endian), otherwise intact.
  std::vector<uint8_t> future = bytes;
  const uint32_t version = kModelCacheVersion + 1;
  std::memcpy(future.data() + 8, &version, sizeof(version));
  writeBytes(dir / "future.bpmodel", future);
  expectRejected(dir / "future.bpmodel", "future version");
  // A cache from an older build (read and copied, before the mapped layout): one line that says so.
  std::vector<uint8_t> older = bytes;
  const uint32_t version_3 = 3;
  std::memcpy(older.data() + 8, &version_3, sizeof(version_3));
  writeBytes(dir / "older.bpmodel", older);
  const std::string message = errorMessage([&] { loadModelCache((dir / "older.bpmodel").string()); });
  EXPECT_EQ(message, (dir / "older.bpmodel").string() + ": model cache version 3, this build reads " +
                         std::to_string(kModelCacheVersion) + "; rebuild it");
  // Empty and missing files.
  writeBytes(dir / "empty.bpmodel", {});
  expectRejected(dir / "empty.bpmodel", "empty file");
  expectRejected(dir / "missing.bpmodel", "missing file");
}

// Files whose checksum is right but whose content is not (a crafted or buggy writer): the counts
// and indices are checked, never trusted. The checksum is re-signed with FNV-1a 64, which is what
// fingerprintFile computes; the first assertion checks that this is the cache's checksum too.
TEST_F(ModelCache, RejectsConsistentlySignedFilesWithBadContent) {
  const PreparedModel& model = smallModel();
  const fs::path good = dir / "good.bpmodel";
  saveModelCache(model, 42, good.string());
  const std::vector<uint8_t> bytes = readBytes(good);
  const std::size_t signed_from = 8, header = 16, checksum_at = bytes.size() - 8;
  const auto resign = [&](std::vector<uint8_t> changed, const std::string& name) {
    writeBytes(dir / "payload", std::vector<uint8_t>(changed.begin() + signed_from, changed.begin() + checksum_at));
    const uint64_t checksum = fingerprintFile((dir / "payload").string());
    std::memcpy(changed.data() + checksum_at, &checksum, sizeof(checksum));
    writeBytes(dir / name, changed);
    return dir / name;
  };
  ASSERT_EQ(readBytes(resign(bytes, "resigned.bpmodel")), bytes)
      << "the cache checksum is the file fingerprint's, of all after the magic";
  EXPECT_NO_THROW(loadModelCache((dir / "resigned.bpmodel").string()));

  // Layout: magic, version, padding | params (36), fingerprint (8), diameter, step (8), centre (12),
  // symmetry axis, turns and flips (20), reference count (8), points (count + 12 n, 8-aligned), normals,
  // fine points and normals, near symmetries, offsets (count + 4 k), entries (count + 8 e), the
  // outline's crease angle, creases, offsets and entries | checksum.
  const std::size_t reference_count_at = header + 36 + 8 + 8 + 12 + 20;
  const std::size_t points_count_at = reference_count_at + 8;
  ASSERT_TRUE(model.boundary != nullptr);
  ASSERT_GT(model.boundary->table.pairCount(), 0u);
  const std::size_t entries_at = checksum_at - 8 * model.boundary->table.pairCount();  // the outline's table, last
  uint64_t stored_count = 0;
  std::memcpy(&stored_count, bytes.data() + points_count_at, sizeof(stored_count));
  ASSERT_EQ(stored_count, model.size()) << "layout assumption";

  std::vector<uint8_t> changed = bytes;
  const uint64_t huge = uint64_t{1} << 61;
  std::memcpy(changed.data() + points_count_at, &huge, sizeof(huge));
  expectRejected(resign(changed, "huge_count.bpmodel"), "a point count larger than the file");

  changed = bytes;
  const uint32_t past = 0xffffffffu;
  std::memcpy(changed.data() + entries_at, &past, sizeof(past));
  expectRejected(resign(changed, "bad_entry.bpmodel"), "an entry referring past the points");

  changed = bytes;
  const float nan = std::nanf("");
  const std::size_t first_point_at = (points_count_at + 8 + 7) / 8 * 8;  // arrays start 8-aligned
  std::memcpy(changed.data() + first_point_at, &nan, sizeof(nan));
  expectRejected(resign(changed, "nan_point.bpmodel"), "a NaN model point");

  changed = bytes;
  const float zero = 0.0f;
  std::memcpy(changed.data() + header, &zero, sizeof(zero));  // sampling_ratio
  expectRejected(resign(changed, "bad_params.bpmodel"), "invalid params");

  changed = bytes;
  const uint64_t more_references = model.size() + 1;
  std::memcpy(changed.data() + reference_count_at, &more_references, sizeof(more_references));
  expectRejected(resign(changed, "more_references.bpmodel"), "more references than points");

  changed = bytes;
  const int32_t turns_without_axis = 12;
  std::memcpy(changed.data() + reference_count_at - 8, &turns_without_axis, sizeof(turns_without_axis));
  expectRejected(resign(changed, "turns_without_axis.bpmodel"), "a symmetry without an axis");
}

TEST_F(ModelCache, RejectsADirectoryAndUnwritablePathsWithBinpickError) {
  expectRejected(dir, "a directory instead of a file");
  EXPECT_NE(errorMessage([&] { fingerprintFile(dir.string()); }).find(dir.string()), std::string::npos);
  const std::string unwritable = (dir / "no_such_directory" / "model.bpmodel").string();
  EXPECT_NE(errorMessage([&] { saveModelCache(smallModel(), 1, unwritable); }).find(unwritable), std::string::npos);
}

TEST_F(ModelCache, AnUnwritableCacheIsReportedInsteadOfThrownWhenTheCallerAsks) {
  const fs::path source = dir / "clamp.ply";
  io::writeMesh(source.string(), simulation::makePart("clamp").mesh);
  ModelParams params;
  params.sampling_ratio = 0.08f;
  const std::string unwritable = (dir / "no_such_directory" / "clamp.bpmodel").string();
  EXPECT_NE(errorMessage([&] { loadOrPrepareModel(source.string(), params, unwritable); }).find(unwritable),
            std::string::npos);

  std::string problem = "left over";
  bool reused = true;
  const PreparedModel model = loadOrPrepareModel(source.string(), params, unwritable, &reused, &problem);
  EXPECT_FALSE(reused);
  EXPECT_GT(model.size(), 0u);
  EXPECT_NE(problem.find(unwritable), std::string::npos) << problem;
  EXPECT_FALSE(fs::exists(unwritable));

  const std::string writable = (dir / "clamp.bpmodel").string();
  loadOrPrepareModel(source.string(), params, writable, &reused, &problem);
  EXPECT_TRUE(problem.empty()) << problem;
  EXPECT_TRUE(fs::exists(writable));
}

TEST_F(ModelCache, LoadOrPrepareReusesOnlyAValidMatchingCache) {
  const fs::path source = dir / "clamp.ply";
  const fs::path cache = dir / "clamp.bpmodel";
  io::writeMesh(source.string(), simulation::makePart("clamp").mesh);
  ModelParams params;
  params.sampling_ratio = 0.08f;

  bool reused = true;
  const PreparedModel built = loadOrPrepareModel(source.string(), params, cache.string(), &reused);
  EXPECT_FALSE(reused);
  ASSERT_TRUE(fs::exists(cache));
  EXPECT_EQ(loadModelCache(cache.string()).source_fingerprint, fingerprintFile(source.string()));

  const PreparedModel again = loadOrPrepareModel(source.string(), params, cache.string(), &reused);
  EXPECT_TRUE(reused);
  expectIdenticalModels(built, again);
  EXPECT_NO_THROW(loadOrPrepareModel(source.string(), params, cache.string()));  // reused may be null

  // Other params: rebuilt, and the cache now holds the new params.
  ModelParams coarser = params;
  coarser.angle_step_deg = 15.0f;
  const PreparedModel other = loadOrPrepareModel(source.string(), coarser, cache.string(), &reused);
  EXPECT_FALSE(reused);
  EXPECT_EQ(other.params.angle_step_deg, 15.0f);
  EXPECT_EQ(loadModelCache(cache.string()).model.params.angle_step_deg, 15.0f);
  loadOrPrepareModel(source.string(), coarser, cache.string(), &reused);
  EXPECT_TRUE(reused);
  loadOrPrepareModel(source.string(), params, cache.string(), &reused);
  EXPECT_FALSE(reused);

  // A corrupt cache: rebuilt and rewritten, then reused.
  std::vector<uint8_t> bytes = readBytes(cache);
  bytes[bytes.size() / 2] ^= 0xff;
  writeBytes(cache, bytes);
  const PreparedModel repaired = loadOrPrepareModel(source.string(), params, cache.string(), &reused);
  EXPECT_FALSE(reused);
  expectIdenticalModels(built, repaired);
  EXPECT_NO_THROW(loadModelCache(cache.string()));
  loadOrPrepareModel(source.string(), params, cache.string(), &reused);
  EXPECT_TRUE(reused);

  // Another source file (same name, other bytes): rebuilt.
  io::TriangleMesh moved = simulation::makePart("clamp").mesh;
  for (auto& v : moved.vertices) v.x() += 0.001f;
  io::writeMesh(source.string(), moved);
  loadOrPrepareModel(source.string(), params, cache.string(), &reused);
  EXPECT_FALSE(reused);

  // A missing source is an error naming it, even with a valid cache.
  const std::string missing = (dir / "missing.ply").string();
  EXPECT_NE(errorMessage([&] { loadOrPrepareModel(missing, params, cache.string()); }).find(missing),
            std::string::npos);
  EXPECT_NE(errorMessage([&] { fingerprintFile(missing); }).find(missing), std::string::npos);
}

}  // namespace
}  // namespace binpick::estimation
