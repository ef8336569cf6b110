#include "sph/checkpoint.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <iterator>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"

namespace hydrojump::sph {

namespace {

// The payload (magic ... magic) and then its FNV-1a checksum as 16 hex digits, so that a
// byte changed after the write (a damaged disk, an edit) is found, not resumed from.
constexpr char kMagic[8] = {'H', 'J', 'S', 'P', 'H', 'C', 'K', '9'};
constexpr std::size_t kChecksumBytes = 16;

template <class T>
void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}
void put_string(std::ostream& out, const std::string& s) {
  put<std::uint64_t>(out, s.size());
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}
template <class V>
void put_array(std::ostream& out, const V& v) {
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(v[0])));
}

class Reader {
 public:
  Reader(std::istream& in, std::filesystem::path file) : in_(in), file_(std::move(file)) {
    std::error_code error;
    const auto bytes = std::filesystem::file_size(file_, error);
    file_bytes_ = error ? 0 : static_cast<std::uint64_t>(bytes);
  }
  template <class T>
  T get() {
    T v{};
    read(&v, sizeof(T));
    return v;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    // A length the rest of the file cannot hold is damage, not a reason to allocate.
    if (n > remaining_bytes()) fail();
    std::string s(n, '\0');
    read(s.data(), n);
    return s;
  }
  void read(void* p, std::size_t n) {
    in_.read(static_cast<char*>(p), static_cast<std::streamsize>(n));
    if (!in_) fail();
  }
  // Bytes after the read position (2^32 when the file's size is unknown).
  std::uint64_t remaining_bytes() {
    const auto pos = in_.tellg();
    if (file_bytes_ == 0 || pos < 0) return 1ull << 32;
    const auto at = static_cast<std::uint64_t>(pos);
    return at <= file_bytes_ ? file_bytes_ - at : 0;
  }
  [[noreturn]] void fail() const {
    throw std::runtime_error("checkpoint '" + file_.string() + "' is truncated or corrupt");
  }

 private:
  std::istream& in_;
  std::filesystem::path file_;
  std::uint64_t file_bytes_ = 0;
};

}  // namespace

void write_checkpoint(const Checkpoint& c, const std::filesystem::path& file) {
  std::ostringstream out(std::ios::binary);
  {
    out.write(kMagic, sizeof kMagic);
    put_string(out, c.fingerprint);
    put(out, c.clock.time);
    put(out, c.clock.last_dt);
    put(out, c.clock.steps);
    put(out, c.clock.inflow_mass);
    put(out, c.clock.outflow_mass);
    put(out, c.clock.outflow_target_depth);
    put(out, c.clock.held_volume_m2);
    put(out, c.clock.outlier_particles);
    put(out, c.clock.outlier_mass);
    const std::int64_t n = c.particles.size();
    put(out, n);
    c.particles.for_each_real_array([&](const Vector& v) { put_array(out, v); });
    put_array(out, c.particles.id);
    put_array(out, c.particles.type);
    put(out, c.next_output_time);
    put<std::uint8_t>(out, c.last_output_is_end_state ? 1 : 0);
    put<std::uint64_t>(out, c.series.size());
    for (const auto& [t, f] : c.series) {
      put(out, t);
      put_string(out, f);
    }
    for (const auto* rows : {&c.log_rows, &c.gauge_rows, &c.basin_rows}) {
      put<std::uint64_t>(out, rows->size());
      for (const auto& r : *rows) put_string(out, r);
    }
    out.write(kMagic, sizeof kMagic);  // trailer: a complete payload ends with the magic again
  }
  std::string bytes = std::move(out).str();
  bytes += util::fingerprint(bytes);
  util::write_file_atomically(file, bytes);
}

namespace {

// A checkpoint whose structure is intact can still hold values no run writes (a damaged or edited
// file): a clock that is not a finite time >= 0, unknown particle types, non-finite particle state,
// no fluid at all. Resuming from it would run on garbage or not at all, so it is refused by name.
void check_contents(const Checkpoint& c, const std::filesystem::path& file) {
  const auto seconds = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g s", v);
    return std::string(text);
  };
  const auto damaged = [&](const std::string& what) {
    throw std::runtime_error("checkpoint '" + file.string() + "' is damaged: " + what + "; start the run again with --restart");
  };
  const auto& k = c.clock;
  if (!std::isfinite(k.time) || k.time < 0.0) damaged("its time is " + seconds(k.time));
  if (!std::isfinite(k.last_dt) || k.last_dt < 0.0) damaged("its last time step is " + seconds(k.last_dt));
  // Negative, or beyond any run (1e15 steps: thousands of years at a million steps a second).
  if (k.steps < 0 || k.steps > 1'000'000'000'000'000) damaged("its step count " + std::to_string(k.steps) + " is impossible");
  if (!std::isfinite(k.inflow_mass) || !std::isfinite(k.outflow_mass)) damaged("its inflow/outflow mass is not finite");
  if (!std::isfinite(k.outflow_target_depth) || k.outflow_target_depth < 0.0)
    damaged("its outflow target depth is " + std::to_string(k.outflow_target_depth) + " m");
  if (!std::isfinite(k.held_volume_m2) || k.held_volume_m2 < 0.0)
    damaged("its held water volume is " + std::to_string(k.held_volume_m2) + " m^2");
  if (k.outlier_particles < 0 || !std::isfinite(k.outlier_mass) || k.outlier_mass < 0.0)
    damaged("its count of removed density outliers (" + std::to_string(k.outlier_particles) + ", " +
            std::to_string(k.outlier_mass) + " kg/m) is impossible");
  if (!std::isfinite(c.next_output_time) || c.next_output_time < 0.0)
    damaged("its next output time is " + seconds(c.next_output_time));
  Eigen::Index fluid = 0;
  for (Eigen::Index i = 0; i < c.particles.size(); ++i) {
    const auto t = c.particles.type[i];
    if (t > static_cast<std::uint8_t>(ParticleType::moving_wall))
      damaged("particle " + std::to_string(i) + " has the unknown type " + std::to_string(t));
    if (t == static_cast<std::uint8_t>(ParticleType::fluid)) ++fluid;
  }
  if (fluid == 0) damaged("it holds no fluid particle");
  // The integrated state (what the run's own check, diagnose(), watches); derived arrays are rebuilt.
  const auto& ps = c.particles;
  for (const Vector* v : {&ps.x, &ps.z, &ps.u, &ps.w, &ps.rho, &ps.mass})
    if (!v->allFinite()) damaged("a particle's position, velocity, density or mass is not finite (NaN or Inf)");
}

}  // namespace

Checkpoint read_checkpoint(const std::filesystem::path& file) {
  std::error_code kind_error;
  if (std::filesystem::is_directory(file, kind_error))
    throw std::runtime_error("checkpoint '" + file.string() + "' is a directory, not a checkpoint file");
  std::ifstream file_in(file, std::ios::binary);
  if (!file_in) throw std::runtime_error("cannot open checkpoint '" + file.string() + "'");
  std::string bytes((std::istreambuf_iterator<char>(file_in)), std::istreambuf_iterator<char>());
  // The magic first (another version's file is named as such), then the checksum over the payload.
  if (bytes.size() >= sizeof kMagic && std::memcmp(bytes.data(), kMagic, 7) == 0 && bytes[7] != kMagic[7])
    throw std::runtime_error("'" + file.string() + "' is a checkpoint of another hydrojump version (format " +
                             bytes.substr(0, sizeof kMagic) + ", this version reads " +
                             std::string(kMagic, sizeof kMagic) + "): start the run again with --restart");
  if (bytes.size() < 2 * sizeof kMagic + kChecksumBytes || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw std::runtime_error("'" + file.string() + "' is not a hydrojump SPH checkpoint");
  const std::string_view payload(bytes.data(), bytes.size() - kChecksumBytes);
  if (util::fingerprint(payload) != std::string_view(bytes).substr(payload.size()))
    throw std::runtime_error("checkpoint '" + file.string() + "' is truncated or corrupt (its checksum does not match "
                             "its contents: it was changed or damaged after it was written); start the run again "
                             "with --restart");
  bytes.resize(payload.size());
  std::istringstream in(std::move(bytes), std::ios::binary);
  Reader r(in, file);
  char magic[8];
  r.read(magic, sizeof magic);  // checked above
  Checkpoint c;
  c.fingerprint = r.get_string();
  c.clock.time = r.get<double>();
  c.clock.last_dt = r.get<double>();
  c.clock.steps = r.get<std::int64_t>();
  c.clock.inflow_mass = r.get<double>();
  c.clock.outflow_mass = r.get<double>();
  c.clock.outflow_target_depth = r.get<double>();
  c.clock.held_volume_m2 = r.get<double>();
  c.clock.outlier_particles = r.get<std::int64_t>();
  c.clock.outlier_mass = r.get<double>();
  const auto n = r.get<std::int64_t>();
  // Every particle takes at least its real arrays, id and type in the file: a count the file cannot
  // hold is a damaged file, not a reason to allocate memory.
  std::error_code size_error;
  const auto file_bytes = std::filesystem::file_size(file, size_error);
  std::int64_t reals = 0;
  c.particles.for_each_real_array([&](const Vector&) { ++reals; });
  const std::int64_t bytes_per_particle = reals * 8 + 8 + 1;
  if (n < 0 || size_error || n > static_cast<std::int64_t>(file_bytes) / bytes_per_particle) r.fail();
  c.particles.resize(n);
  c.particles.for_each_real_array([&](Vector& v) { r.read(v.data(), static_cast<std::size_t>(n) * sizeof(double)); });
  r.read(c.particles.id.data(), static_cast<std::size_t>(n) * sizeof(std::int64_t));
  r.read(c.particles.type.data(), static_cast<std::size_t>(n));
  c.next_output_time = r.get<double>();
  const auto end_state = r.get<std::uint8_t>();
  if (end_state > 1) r.fail();
  c.last_output_is_end_state = end_state == 1;
  const auto n_series = r.get<std::uint64_t>();
  if (n_series > (1ull << 32)) r.fail();
  for (std::uint64_t k = 0; k < n_series; ++k) {
    const double t = r.get<double>();
    c.series.emplace_back(t, r.get_string());
  }
  for (auto* rows : {&c.log_rows, &c.gauge_rows, &c.basin_rows}) {
    const auto m = r.get<std::uint64_t>();
    if (m > (1ull << 32)) r.fail();
    for (std::uint64_t k = 0; k < m; ++k) rows->push_back(r.get_string());
  }
  r.read(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof magic) != 0) r.fail();
  check_contents(c, file);
  return c;
}

}  // namespace hydrojump::sph
