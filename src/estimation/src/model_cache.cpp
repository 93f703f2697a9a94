#include "binpick/estimation/model_cache.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <type_traits>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "boundary.hpp"

namespace binpick::estimation {
namespace {

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "cache layout stores packed vectors");
static_assert(sizeof(PairEntry) == 8, "cache layout stores packed pair entries");

constexpr char kMagic[8] = {'B', 'P', 'P', 'P', 'F', 'M', 'D', 'L'};
constexpr std::size_t kHeaderSize = 16;  // magic, version, 4 bytes of padding: the payload is 8-aligned
constexpr std::size_t kArrayAlignment = 8;

// A checksum at memory speed: four independent multiply-xor lanes over 8-byte words, then the
// tail. A byte-wise FNV-1a took longer than everything else in loading a 200 MB cache. Any one
// changed word changes the result (each step is a bijection of the lane).
uint64_t checksum(const uint8_t* data, std::size_t size) {
  constexpr uint64_t kPrime = 0x100000001b3ULL;
  uint64_t lanes[4] = {0xcbf29ce484222325ULL, 0x84222325cbf29ce4ULL, 0x9e3779b97f4a7c15ULL, 0xc2b2ae3d27d4eb4fULL};
  std::size_t i = 0;
  for (; i + 32 <= size; i += 32) {
    for (int k = 0; k < 4; ++k) {
      uint64_t word;
      std::memcpy(&word, data + i + 8 * k, sizeof(word));
      lanes[k] = (lanes[k] ^ word) * kPrime;
    }
  }
  uint64_t hash = lanes[0] ^ (lanes[1] << 17 | lanes[1] >> 47) ^ (lanes[2] << 31 | lanes[2] >> 33) ^
                  (lanes[3] << 47 | lanes[3] >> 17);
  for (; i < size; ++i) hash = (hash ^ data[i]) * kPrime;
  return (hash ^ size) * kPrime;
}

class Writer {
 public:
  template <class T>
  void put(const T& value) {
    // Eigen's fixed vectors are plain float arrays but not formally trivially copyable.
    static_assert(std::is_standard_layout_v<T>);
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  // The count, then the values from the next 8-aligned offset of the file: a mapped file's arrays
  // are used where they lie.
  template <class Values>
  void putArray(const Values& values) {
    using T = std::remove_cv_t<std::remove_reference_t<decltype(*values.begin())>>;
    put<uint64_t>(values.size());
    bytes.resize(bytes.size() + padding(kHeaderSize + bytes.size()), 0);
    if (values.size() == 0) return;
    const auto* p = reinterpret_cast<const uint8_t*>(&*values.begin());
    bytes.insert(bytes.end(), p, p + values.size() * sizeof(T));
  }
  static std::size_t padding(std::size_t offset) {
    return (kArrayAlignment - offset % kArrayAlignment) % kArrayAlignment;
  }
  std::vector<uint8_t> bytes;
};

// Reads a mapped file with a bounds check on every access: counts come from the file and are
// never trusted.
class Reader {
 public:
  Reader(const uint8_t* file, std::size_t begin, std::size_t end, std::string path)
      : file_(file), at_(begin), end_(end), path_(std::move(path)) {}
  template <class T>
  T get(const char* what) {
    T value;
    std::memcpy(static_cast<void*>(&value), take(sizeof(T), what), sizeof(T));
    return value;
  }
  // An array where it lies in the file.
  template <class T>
  ArrayView<T> view(const char* what) {
    const auto count = get<uint64_t>(what);
    take(Writer::padding(at_), what);
    if (count > (end_ - at_) / sizeof(T)) fail(std::string(what) + " claims more entries than the file holds");
    return {reinterpret_cast<const T*>(take(count * sizeof(T), what)), static_cast<std::size_t>(count)};
  }
  template <class T>
  std::vector<T> getArray(const char* what) {
    const ArrayView<T> values = view<T>(what);
    return std::vector<T>(values.begin(), values.end());
  }
  bool atEnd() const { return at_ == end_; }
  [[noreturn]] void fail(const std::string& why) const { throw core::Error(path_ + ": model cache " + why); }

 private:
  const uint8_t* take(std::size_t size, const char* what) {
    if (size > end_ - at_) fail(std::string("is truncated in ") + what);
    const uint8_t* at = file_ + at_;
    at_ += size;
    return at;
  }
  const uint8_t* file_;
  std::size_t at_;
  std::size_t end_;
  std::string path_;
};

using Affine = std::array<float, 12>;  // a twin's 3x4 [R t], column-major

std::vector<Affine> affines(const std::vector<Eigen::Isometry3f>& turns) {
  std::vector<Affine> out;
  for (const Eigen::Isometry3f& turn : turns) {
    Affine a;
    Eigen::Map<Eigen::Matrix<float, 3, 4>>(a.data()) = turn.affine();
    out.push_back(a);
  }
  return out;
}

std::vector<Eigen::Isometry3f> isometries(const std::vector<Affine>& stored, Reader& r) {
  std::vector<Eigen::Isometry3f> turns;
  for (const Affine& a : stored) {
    Eigen::Isometry3f turn = Eigen::Isometry3f::Identity();
    turn.affine() = Eigen::Map<const Eigen::Matrix<float, 3, 4>>(a.data());
    const Eigen::Matrix3f rotation = turn.linear();
    if (!turn.matrix().allFinite() || !(rotation * rotation.transpose()).isIdentity(1e-3f)) {
      r.fail("has a near symmetry that is no rotation");
    }
    turns.push_back(turn);
  }
  return turns;
}

void putParams(Writer& w, const ModelParams& p) {
  w.put(p.sampling_ratio);
  w.put(p.angle_step_deg);
  w.put(p.dense_samples_per_step2);
  w.put(p.normal_radius_ratio);
  w.put(p.normal_cluster_angle_deg);
  w.put(p.max_pairs_per_feature);
  w.put(p.seed);
  w.put<uint32_t>(p.reduce_by_symmetry ? 1 : 0);
}

ModelParams getParams(Reader& r) {
  ModelParams p;
  p.sampling_ratio = r.get<float>("params");
  p.angle_step_deg = r.get<float>("params");
  p.dense_samples_per_step2 = r.get<float>("params");
  p.normal_radius_ratio = r.get<float>("params");
  p.normal_cluster_angle_deg = r.get<float>("params");
  p.max_pairs_per_feature = r.get<uint32_t>("params");
  p.seed = r.get<uint64_t>("params");
  p.reduce_by_symmetry = r.get<uint32_t>("params") != 0;
  return p;
}

bool sameParams(const ModelParams& a, const ModelParams& b) {
  return a.sampling_ratio == b.sampling_ratio && a.angle_step_deg == b.angle_step_deg &&
         a.dense_samples_per_step2 == b.dense_samples_per_step2 && a.normal_radius_ratio == b.normal_radius_ratio &&
         a.normal_cluster_angle_deg == b.normal_cluster_angle_deg &&
         a.max_pairs_per_feature == b.max_pairs_per_feature && a.seed == b.seed &&
         a.reduce_by_symmetry == b.reduce_by_symmetry;
}

void checkPoints(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals,
                 const std::string& what, Reader& r) {
  if (points.size() != normals.size() || points.size() < 4) r.fail("has inconsistent " + what + " counts");
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite() || std::abs(normals[i].norm() - 1.0f) > 1e-3f) {
      r.fail("has an invalid " + what + " at index " + std::to_string(i));
    }
  }
}

void checkGeometry(const PreparedModel& m, Reader& r) {
  checkPoints(m.points, m.normals, "point and normal", r);
  checkPoints(m.fine_points, m.fine_normals, "fine point and normal", r);
  if (!(m.diameter > 0.0f) || !std::isfinite(m.diameter) ||
      std::abs(m.step - m.params.sampling_ratio * m.diameter) > 1e-5f * m.diameter || !m.centre.allFinite()) {
    r.fail("has an invalid diameter, step or centre");
  }
  const ModelSymmetry& s = m.symmetry;
  if (s.turns < 0 || (s.turns == 1) != s.axis.isZero() || (s.turns != 1 && std::abs(s.axis.norm() - 1.0f) > 1e-3f) ||
      (s.flips && s.turns == 1)) {
    r.fail("has an invalid symmetry");
  }
  if (m.reference_count < 1 || m.reference_count > m.points.size()) r.fail("has an invalid reference count");
}

// A pair table where it lies in the mapped file.
PpfHashTable getTable(Reader& r, const std::shared_ptr<const core::MappedFile>& mapped, const PreparedModel& m,
                      const std::string& what) {
  const ArrayView<uint32_t> offsets = r.view<uint32_t>((what + " offsets").c_str());
  const ArrayView<PairEntry> entries = r.view<PairEntry>((what + " entries").c_str());
  if (static_cast<int64_t>(offsets.size()) != m.quantizer().keyCount() + 1) {
    r.fail(what + " does not match its parameters");
  }
  try {
    return PpfHashTable(mapped, offsets, entries, static_cast<uint32_t>(m.reference_count));
  } catch (const core::Error& e) {
    r.fail(e.what());
  }
}

// The outline's model side: its crease angle (0: none kept), creases and table.
void putBoundary(Writer& w, const PreparedModel& model) {
  const bool kept = model.boundary != nullptr;
  w.put<float>(kept ? model.boundary_crease_angle_deg : 0.0f);
  if (!kept) return;
  w.putArray(model.boundary->creases.points);
  w.putArray(model.boundary->creases.directions);
  w.putArray(model.boundary->table.offsets());
  w.putArray(model.boundary->table.entries());
}

void getBoundary(Reader& r, const std::shared_ptr<const core::MappedFile>& mapped, PreparedModel& m) {
  m.boundary_crease_angle_deg = r.get<float>("boundary");
  if (m.boundary_crease_angle_deg == 0.0f) return;
  if (!(m.boundary_crease_angle_deg > 0.0f && m.boundary_crease_angle_deg < 180.0f)) {
    r.fail("has an invalid crease angle");
  }
  auto boundary = std::make_shared<BoundaryModel>();
  boundary->creases.points = r.getArray<Eigen::Vector3f>("creases");
  boundary->creases.directions = r.getArray<Eigen::Vector3f>("crease directions");
  const BoundaryPoints& creases = boundary->creases;
  if (creases.points.size() != creases.directions.size()) r.fail("has inconsistent crease counts");
  for (std::size_t i = 0; i < creases.size(); ++i) {
    if (!creases.points[i].allFinite() || std::abs(creases.directions[i].norm() - 1.0f) > 1e-3f) {
      r.fail("has an invalid crease at index " + std::to_string(i));
    }
  }
  boundary->table = getTable(r, mapped, m, "boundary table");
  m.boundary = std::move(boundary);
}

}  // namespace

void saveModelCache(const PreparedModel& model, uint64_t source_fingerprint, const std::string& path) {
  Writer w;
  putParams(w, model.params);
  w.put(source_fingerprint);
  w.put(model.diameter);
  w.put(model.step);
  w.put(model.centre);
  w.put(model.symmetry.axis);
  w.put<int32_t>(model.symmetry.turns);
  w.put<int32_t>(model.symmetry.flips ? 1 : 0);
  w.put<uint64_t>(model.referenceCount());
  w.putArray(model.points);
  w.putArray(model.normals);
  w.putArray(model.fine_points);
  w.putArray(model.fine_normals);
  w.putArray(affines(model.near_symmetries.turned));
  w.putArray(affines(model.near_symmetries.slid));
  w.putArray(model.table.offsets());
  w.putArray(model.table.entries());
  putBoundary(w, model);
  // Atomically: a crash never leaves a half-written cache behind, and services sharing a cache
  // never write into one file (nor into one that another maps).
  std::string file(kMagic, sizeof(kMagic));
  file.append(reinterpret_cast<const char*>(&kModelCacheVersion), sizeof(kModelCacheVersion));
  file.append(kHeaderSize - file.size(), '\0');
  file.append(reinterpret_cast<const char*>(w.bytes.data()), w.bytes.size());
  const uint64_t sum =
      checksum(reinterpret_cast<const uint8_t*>(file.data()) + sizeof(kMagic), file.size() - sizeof(kMagic));
  file.append(reinterpret_cast<const char*>(&sum), sizeof(sum));
  core::writeFileAtomically(path, file);
}

CachedModel loadModelCache(const std::string& path) {
  const std::shared_ptr<const core::MappedFile> mapped = core::MappedFile::open(path);
  const uint8_t* bytes = mapped->data();
  const std::size_t size = mapped->size();
  if (size < kHeaderSize + sizeof(uint64_t) || std::memcmp(bytes, kMagic, sizeof(kMagic)) != 0) {
    throw core::Error(path + ": not a binpick model cache");
  }
  uint32_t version = 0;
  std::memcpy(&version, bytes + sizeof(kMagic), sizeof(version));
  if (version != kModelCacheVersion) {
    throw core::Error(path + ": model cache version " + std::to_string(version) + ", this build reads " +
                      std::to_string(kModelCacheVersion) + "; rebuild it");
  }
  const std::size_t payload_end = size - sizeof(uint64_t);
  uint64_t stored_checksum = 0;
  std::memcpy(&stored_checksum, bytes + payload_end, sizeof(stored_checksum));
  if (checksum(bytes + sizeof(kMagic), payload_end - sizeof(kMagic)) != stored_checksum) {
    throw core::Error(path + ": model cache checksum mismatch (corrupt or truncated)");
  }

  Reader r(bytes, kHeaderSize, payload_end, path);
  CachedModel cached;
  PreparedModel& m = cached.model;
  m.params = getParams(r);
  try {
    m.params.validate();
  } catch (const core::Error& e) {
    r.fail(std::string("holds invalid ") + e.what());
  }
  cached.source_fingerprint = r.get<uint64_t>("fingerprint");
  m.diameter = r.get<float>("diameter");
  m.step = r.get<float>("step");
  m.centre = r.get<Eigen::Vector3f>("centre");
  m.symmetry.axis = r.get<Eigen::Vector3f>("symmetry");
  m.symmetry.turns = r.get<int32_t>("symmetry");
  m.symmetry.flips = r.get<int32_t>("symmetry") != 0;
  m.reference_count = r.get<uint64_t>("reference count");
  m.points = r.getArray<Eigen::Vector3f>("points");
  m.normals = r.getArray<Eigen::Vector3f>("normals");
  m.fine_points = r.getArray<Eigen::Vector3f>("fine points");
  m.fine_normals = r.getArray<Eigen::Vector3f>("fine normals");
  checkGeometry(m, r);
  m.near_symmetries.turned = isometries(r.getArray<Affine>("near symmetries"), r);
  m.near_symmetries.slid = isometries(r.getArray<Affine>("near symmetries"), r);
  m.table = getTable(r, mapped, m, "table");
  getBoundary(r, mapped, m);
  if (!r.atEnd()) r.fail("has trailing bytes");
  return cached;
}

uint64_t fingerprintFile(const std::string& path) {
  const std::shared_ptr<const core::MappedFile> file = core::MappedFile::open(path);
  return checksum(file->data(), file->size());
}

PreparedModel loadOrPrepareModel(const std::string& model_path, const ModelParams& params,
                                 const std::string& cache_path, bool* reused, std::string* write_problem) {
  const uint64_t fingerprint = fingerprintFile(model_path);
  if (reused) *reused = false;
  if (write_problem) write_problem->clear();
  std::error_code unreadable;  // a path that cannot even be looked at is no cache either
  if (std::filesystem::exists(cache_path, unreadable)) {
    try {
      CachedModel cached = loadModelCache(cache_path);
      if (cached.source_fingerprint == fingerprint && sameParams(cached.model.params, params)) {
        if (reused) *reused = true;
        return std::move(cached.model);
      }
    } catch (const core::Error&) {
      // An unusable cache is rebuilt below; the model file itself is the source of truth.
    }
  }
  PreparedModel model = prepareModel(io::readModelGeometry(model_path), params);
  try {
    saveModelCache(model, fingerprint, cache_path);
  } catch (const core::Error& e) {
    if (!write_problem) throw;
    *write_problem = e.what();
  }
  return model;
}

}  // namespace binpick::estimation
