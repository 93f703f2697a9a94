#include "binpick/estimation/model_cache.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <type_traits>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"

namespace binpick::estimation {
namespace {

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "cache layout stores packed vectors");
static_assert(sizeof(PairEntry) == 8, "cache layout stores packed pair entries");

constexpr char kMagic[8] = {'B', 'P', 'P', 'P', 'F', 'M', 'D', 'L'};

uint64_t fnv1a(const uint8_t* data, std::size_t size, uint64_t hash = 0xcbf29ce484222325ULL) {
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= data[i];
    hash *= 0x100000001b3ULL;
  }
  return hash;
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
  template <class T>
  void putArray(const std::vector<T>& values) {
    put<uint64_t>(values.size());
    const auto* p = reinterpret_cast<const uint8_t*>(values.data());
    bytes.insert(bytes.end(), p, p + values.size() * sizeof(T));
  }
  std::vector<uint8_t> bytes;
};

// Reads with a bounds check on every access: counts come from the file and are never trusted.
class Reader {
 public:
  Reader(const std::vector<uint8_t>& bytes, std::size_t begin, std::size_t end, std::string path)
      : bytes_(bytes), at_(begin), end_(end), path_(std::move(path)) {}
  template <class T>
  T get(const char* what) {
    T value;
    take(&value, sizeof(T), what);
    return value;
  }
  template <class T>
  std::vector<T> getArray(const char* what) {
    const auto count = get<uint64_t>(what);
    if (count > (end_ - at_) / sizeof(T)) fail(std::string(what) + " claims more entries than the file holds");
    std::vector<T> values(count);
    take(values.data(), count * sizeof(T), what);
    return values;
  }
  bool atEnd() const { return at_ == end_; }
  [[noreturn]] void fail(const std::string& why) const { throw core::Error(path_ + ": model cache " + why); }

 private:
  void take(void* out, std::size_t size, const char* what) {
    if (size > end_ - at_) fail(std::string("is truncated in ") + what);
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  const std::vector<uint8_t>& bytes_;
  std::size_t at_;
  std::size_t end_;
  std::string path_;
};

std::vector<uint8_t> readAll(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw core::Error(path + ": not a readable file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::Error(path + ": cannot open");
  try {
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
  } catch (const std::exception& e) {
    throw core::Error(path + ": cannot read: " + e.what());
  }
}

void putParams(Writer& w, const ModelParams& p) {
  w.put(p.sampling_ratio);
  w.put(p.angle_step_deg);
  w.put(p.dense_samples_per_step2);
  w.put(p.normal_radius_ratio);
  w.put(p.normal_cluster_angle_deg);
  w.put(p.max_pairs_per_feature);
  w.put(p.seed);
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
  return p;
}

bool sameParams(const ModelParams& a, const ModelParams& b) {
  return a.sampling_ratio == b.sampling_ratio && a.angle_step_deg == b.angle_step_deg &&
         a.dense_samples_per_step2 == b.dense_samples_per_step2 && a.normal_radius_ratio == b.normal_radius_ratio &&
         a.normal_cluster_angle_deg == b.normal_cluster_angle_deg &&
         a.max_pairs_per_feature == b.max_pairs_per_feature && a.seed == b.seed;
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
}

}  // namespace

void saveModelCache(const PreparedModel& model, uint64_t source_fingerprint, const std::string& path) {
  Writer w;
  putParams(w, model.params);
  w.put(source_fingerprint);
  w.put(model.diameter);
  w.put(model.step);
  w.put(model.centre);
  w.putArray(model.points);
  w.putArray(model.normals);
  w.putArray(model.fine_points);
  w.putArray(model.fine_normals);
  w.putArray(model.table.offsets());
  w.putArray(model.table.entries());
  const uint64_t checksum = fnv1a(w.bytes.data(), w.bytes.size());

  // Atomically: a crash never leaves a half-written cache behind, and services sharing a cache
  // never write into one file.
  std::string file(kMagic, sizeof(kMagic));
  file.append(reinterpret_cast<const char*>(&kModelCacheVersion), sizeof(kModelCacheVersion));
  file.append(reinterpret_cast<const char*>(w.bytes.data()), w.bytes.size());
  file.append(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
  core::writeFileAtomically(path, file);
}

CachedModel loadModelCache(const std::string& path) {
  const std::vector<uint8_t> bytes = readAll(path);
  const std::size_t header = sizeof(kMagic) + sizeof(uint32_t);
  if (bytes.size() < header + sizeof(uint64_t) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    throw core::Error(path + ": not a binpick model cache");
  }
  uint32_t version = 0;
  std::memcpy(&version, bytes.data() + sizeof(kMagic), sizeof(version));
  if (version != kModelCacheVersion) {
    throw core::Error(path + ": model cache version " + std::to_string(version) + ", this build reads " +
                      std::to_string(kModelCacheVersion) + "; rebuild it");
  }
  const std::size_t payload_end = bytes.size() - sizeof(uint64_t);
  uint64_t stored_checksum = 0;
  std::memcpy(&stored_checksum, bytes.data() + payload_end, sizeof(stored_checksum));
  if (fnv1a(bytes.data() + header, payload_end - header) != stored_checksum) {
    throw core::Error(path + ": model cache checksum mismatch (corrupt or truncated)");
  }

  Reader r(bytes, header, payload_end, path);
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
  m.points = r.getArray<Eigen::Vector3f>("points");
  m.normals = r.getArray<Eigen::Vector3f>("normals");
  m.fine_points = r.getArray<Eigen::Vector3f>("fine points");
  m.fine_normals = r.getArray<Eigen::Vector3f>("fine normals");
  checkGeometry(m, r);
  auto offsets = r.getArray<uint32_t>("table offsets");
  auto entries = r.getArray<PairEntry>("table entries");
  if (!r.atEnd()) r.fail("has trailing bytes");
  if (static_cast<int64_t>(offsets.size()) != m.quantizer().keyCount() + 1)
    r.fail("table does not match its parameters");
  try {
    m.table = PpfHashTable(std::move(offsets), std::move(entries), static_cast<uint32_t>(m.points.size()));
  } catch (const core::Error& e) {
    r.fail(e.what());
  }
  return cached;
}

uint64_t fingerprintFile(const std::string& path) {
  const std::vector<uint8_t> bytes = readAll(path);
  return fnv1a(bytes.data(), bytes.size());
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
