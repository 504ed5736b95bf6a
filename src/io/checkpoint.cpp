#include "io/checkpoint.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <type_traits>

namespace sluice {

namespace fs = std::filesystem;

// The format stores the host's bytes as they are; every platform sluice builds for
// is little-endian, and the static_asserts keep it honest.
static_assert(std::endian::native == std::endian::little, "checkpoints are little-endian");
static_assert(sizeof(Vec2) == 2 * sizeof(double), "Vec2 arrays are stored as packed pairs of doubles");

namespace {

constexpr char kMagic[8] = {'S', 'L', 'U', 'I', 'C', 'E', 'C', 'K'};
constexpr size_t kHeaderSize = 8 + 4 + 8 + 8;  // magic, version, scene hash, payload size
constexpr size_t kTrailerSize = 8;             // checksum

std::string hex(std::uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
  return buf;
}

// Appends fixed-size values and arrays (a u64 count, then the elements' bytes).
class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void put_array(const std::vector<T>& a) {
    put(static_cast<std::uint64_t>(a.size()));
    out_.append(reinterpret_cast<const char*>(a.data()), a.size() * sizeof(T));
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

// Reads what Writer wrote; a read past the end is a malformed payload (the checksum
// already passed, so only a writer of another layout produces one).
class Reader {
 public:
  Reader(const char* data, size_t size, const std::string& file) : p_(data), end_(data + size), file_(file) {}
  template <class T>
  void get(T& v, const char* what) {
    need(sizeof v, what);
    std::memcpy(&v, p_, sizeof v);
    p_ += sizeof v;
  }
  template <class T>
  void get_array(std::vector<T>& a, const char* what) {
    std::uint64_t n = 0;
    get(n, what);
    if (n > static_cast<std::uint64_t>(end_ - p_) / sizeof(T)) fail(std::string("ends inside ") + what);
    a.resize(static_cast<size_t>(n));
    if (n > 0) std::memcpy(static_cast<void*>(a.data()), p_, a.size() * sizeof(T));  // data() may be null
    p_ += a.size() * sizeof(T);
  }
  void finish() {
    if (p_ != end_) fail(std::to_string(end_ - p_) + " bytes are left after the last field");
  }

 private:
  void need(size_t n, const char* what) {
    if (static_cast<size_t>(end_ - p_) < n) fail(std::string("ends inside ") + what);
  }
  [[noreturn]] void fail(const std::string& why) {
    throw CheckpointError("checkpoint " + file_ + " has a malformed payload: " + why);
  }
  const char* p_;
  const char* end_;
  std::string file_;
};

void put_totals(Writer& w, const RunTotals& t) {
  w.put(static_cast<std::int64_t>(t.steps));
  for (double d : {t.simulated_time, t.wall_seconds, t.sum_iterations, t.sum_avg_error, t.max_error,
                   t.sum_density_error, t.initial_energy, t.final_energy, t.boundary_work})
    w.put(d);
  for (double d : t.sum_ms) w.put(d);
}

void get_totals(Reader& r, RunTotals& t) {
  std::int64_t steps = 0;
  r.get(steps, "run totals");
  t.steps = static_cast<long>(steps);
  for (double* d : {&t.simulated_time, &t.wall_seconds, &t.sum_iterations, &t.sum_avg_error, &t.max_error,
                    &t.sum_density_error, &t.initial_energy, &t.final_energy, &t.boundary_work})
    r.get(*d, "run totals");
  for (double& d : t.sum_ms) r.get(d, "run totals");
}

void put_step(Writer& w, const StepStats& s) {
  w.put(static_cast<std::int64_t>(s.step));
  w.put(s.time);
  w.put(s.dt);
  w.put(static_cast<std::int32_t>(s.iterations));
  for (double d : {s.avg_error_percent, s.max_error_percent, s.density_error_percent, s.max_cfl, s.kinetic_energy,
                   s.potential_energy, s.mechanical_energy, s.boundary_work})
    w.put(d);
  w.put(s.fluid_particles);
  w.put(s.frame);
  for (double d : {s.ms(Phase::Neighbors), s.ms(Phase::NonPressure), s.ms(Phase::Pressure), s.ms(Phase::Integrate),
                   s.ms_total, s.ms(Phase::Boundary)})
    w.put(d);
}

void get_step(Reader& r, StepStats& s) {
  std::int64_t step = 0;
  std::int32_t iterations = 0;
  r.get(step, "last step");
  s.step = static_cast<long>(step);
  r.get(s.time, "last step");
  r.get(s.dt, "last step");
  r.get(iterations, "last step");
  s.iterations = iterations;
  for (double* d : {&s.avg_error_percent, &s.max_error_percent, &s.density_error_percent, &s.max_cfl, &s.kinetic_energy,
                    &s.potential_energy, &s.mechanical_energy, &s.boundary_work})
    r.get(*d, "last step");
  r.get(s.fluid_particles, "last step");
  r.get(s.frame, "last step");
  for (double* d : {&s.ms(Phase::Neighbors), &s.ms(Phase::NonPressure), &s.ms(Phase::Pressure), &s.ms(Phase::Integrate),
                    &s.ms_total, &s.ms(Phase::Boundary)})
    r.get(*d, "last step");
}

void put_payload(Writer& w, const Checkpoint& c) {
  const SimulationState& s = c.state;
  w.put(s.time);
  w.put(static_cast<std::int64_t>(s.step));
  w.put(s.frame);
  w.put_array(s.fluid.x);
  w.put_array(s.fluid.v);
  w.put_array(s.fluid.rho);
  w.put_array(s.fluid.p);
  w.put_array(s.fluid.id);
  w.put_array(s.boundary_x);
  w.put_array(s.boundary_v);
  w.put_array(s.boundary_a);
  w.put_array(s.boundary_volume);
  w.put_array(s.boundary_p);
  w.put_array(s.near_moving);
  put_totals(w, c.totals);
  put_step(w, c.last_step);
}

void get_payload(Reader& r, Checkpoint& c) {
  SimulationState& s = c.state;
  std::int64_t step = 0;
  r.get(s.time, "time");
  r.get(step, "step");
  s.step = static_cast<long>(step);
  r.get(s.frame, "frame");
  r.get_array(s.fluid.x, "fluid positions");
  r.get_array(s.fluid.v, "fluid velocities");
  r.get_array(s.fluid.rho, "fluid densities");
  r.get_array(s.fluid.p, "fluid pressures");
  r.get_array(s.fluid.id, "fluid ids");
  r.get_array(s.boundary_x, "boundary positions");
  r.get_array(s.boundary_v, "boundary velocities");
  r.get_array(s.boundary_a, "boundary accelerations");
  r.get_array(s.boundary_volume, "boundary volumes");
  r.get_array(s.boundary_p, "boundary pressures");
  r.get_array(s.near_moving, "boundary flags");
  get_totals(r, c.totals);
  get_step(r, c.last_step);
  r.finish();
}

template <class T>
T read_at(const std::string& bytes, size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof v);
  return v;
}

// "checkpoint_00030.bin" -> 30; -1 for any other name.
long frame_of(const fs::path& file) {
  const std::string name = file.filename().string();
  constexpr std::string_view prefix = "checkpoint_", suffix = ".bin";
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::strtol(digits.c_str(), nullptr, 10);
}

std::string checkpoint_name(Index frame) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "checkpoint_%05d.bin", frame);
  return buf;
}

// Writes through a temporary name, flushed to the disk before the rename (and the
// directory after it), so that the name only ever holds a complete file, even after
// a power cut.
void write_durably(const fs::path& path, const std::string& bytes) {
  const std::string tmp = path.string() + ".tmp";
  auto fail = [&](const std::string& what) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw OutputError(path.string() + ": " + what + ": " + why);
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError(tmp + ": cannot open for writing: " + std::strerror(errno));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      fail("write failed (disk full?)");
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) {
    ::close(fd);
    fail("fsync failed");
  }
  if (::close(fd) != 0) fail("close failed");
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail("cannot rename from " + tmp);
  // The rename is durable once the directory is; a failure here loses nothing now.
  const int dir = ::open(path.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

}  // namespace

std::uint64_t fnv1a64(const void* data, size_t n, std::uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

std::uint64_t scene_hash(const Scene& scene) {
  const std::string params = scene.resolved.dump();
  std::uint64_t h = fnv1a64(params.data(), params.size());
  h = fnv1a64(scene.fluid_x.data(), scene.fluid_x.size() * sizeof(Vec2), h);
  h = fnv1a64(scene.fluid_v.data(), scene.fluid_v.size() * sizeof(Vec2), h);
  h = fnv1a64(scene.boundary_x.data(), scene.boundary_x.size() * sizeof(Vec2), h);
  h = fnv1a64(scene.boundary_object.data(), scene.boundary_object.size() * sizeof(Index), h);
  return h;
}

std::string encode_checkpoint(const Checkpoint& c, std::uint64_t scene_hash) {
  // One buffer: the header with a placeholder size, the payload, then the real size
  // (no second copy of a megabyte-sized payload).
  Writer w;
  w.bytes().append(kMagic, sizeof kMagic);
  w.put(kCheckpointVersion);
  w.put(scene_hash);
  w.put(std::uint64_t{0});
  put_payload(w, c);
  const std::uint64_t payload_size = w.bytes().size() - kHeaderSize;
  std::memcpy(w.bytes().data() + kHeaderSize - sizeof payload_size, &payload_size, sizeof payload_size);
  w.put(fnv1a64(w.bytes().data(), w.bytes().size()));
  return std::move(w.bytes());
}

Checkpoint decode_checkpoint(const std::string& bytes, const std::string& file, std::uint64_t hash) {
  const std::string name = "checkpoint " + file;
  const size_t size = bytes.size();
  const size_t magic_part = std::min(size, sizeof kMagic);
  // A file that does not start like a checkpoint is not one, however long it is.
  if (std::memcmp(bytes.data(), kMagic, magic_part) != 0)
    throw CheckpointError(name + " is not a sluice checkpoint (it does not start with SLUICECK)");
  if (size < kHeaderSize + kTrailerSize)
    throw CheckpointError(name + " is truncated: " + std::to_string(size) + " bytes, shorter than its header");
  const auto version = read_at<std::uint32_t>(bytes, 8);
  if (version != kCheckpointVersion)
    throw CheckpointError(name + " has format version " + std::to_string(version) + "; this sluice reads version " +
                          std::to_string(kCheckpointVersion));
  const auto payload_size = read_at<std::uint64_t>(bytes, 20);
  const std::uint64_t expected = kHeaderSize + payload_size + kTrailerSize;
  if (payload_size > size || size != expected)
    throw CheckpointError(name + (size < expected ? " is truncated: " : " has trailing bytes: ") +
                          std::to_string(size) + " bytes where its header announces " + std::to_string(expected));
  const auto stored = read_at<std::uint64_t>(bytes, size - kTrailerSize);
  const std::uint64_t computed = fnv1a64(bytes.data(), size - kTrailerSize);
  if (stored != computed)
    throw CheckpointError(name + " is corrupt: checksum mismatch (stored " + hex(stored) + ", computed " +
                          hex(computed) + ")");
  const auto written_for = read_at<std::uint64_t>(bytes, 12);
  if (written_for != hash)
    throw CheckpointError(name + " was written for a different scene (hash " + hex(written_for) + ", this scene " +
                          hex(hash) + ")");
  Checkpoint c;
  Reader r(bytes.data() + kHeaderSize, static_cast<size_t>(payload_size), file);
  get_payload(r, c);
  return c;
}

fs::path checkpoint_directory(const fs::path& run_dir) { return run_dir / "checkpoints"; }

std::vector<fs::path> list_checkpoints(const fs::path& run_dir) {
  std::vector<std::pair<long, fs::path>> found;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(checkpoint_directory(run_dir), ec)) {
    const long frame = frame_of(e.path());
    if (frame >= 0 && e.is_regular_file()) found.emplace_back(frame, e.path());
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<fs::path> files;
  for (auto& f : found) files.push_back(std::move(f.second));
  return files;
}

size_t write_checkpoint(const fs::path& run_dir, const Checkpoint& c, std::uint64_t hash, int keep) {
  const fs::path dir = checkpoint_directory(run_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw OutputError(dir.string() + ": cannot create directory: " + ec.message());
  const std::string bytes = encode_checkpoint(c, hash);
  write_durably(dir / checkpoint_name(c.state.frame), bytes);
  // Only now, with the new one complete, may the oldest go.
  const std::vector<fs::path> all = list_checkpoints(run_dir);
  for (size_t k = static_cast<size_t>(std::max(keep, 1)); k < all.size(); ++k) fs::remove(all[k], ec);
  return bytes.size();
}

Checkpoint read_checkpoint(const fs::path& file, std::uint64_t hash) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CheckpointError("checkpoint " + file.string() + " cannot be read: " + std::strerror(errno));
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw CheckpointError("checkpoint " + file.string() + " cannot be read: read error");
  return decode_checkpoint(bytes.str(), file.string(), hash);
}

LoadedCheckpoint load_newest_checkpoint(const fs::path& run_dir, std::uint64_t hash) {
  const std::vector<fs::path> files = list_checkpoints(run_dir);
  if (files.empty())
    throw CheckpointError(checkpoint_directory(run_dir).string() +
                          " holds no checkpoint_NNNNN.bin (was the run started with --checkpoint-every?)");
  LoadedCheckpoint out;
  for (const fs::path& f : files) {
    try {
      out.checkpoint = read_checkpoint(f, hash);
      out.file = f;
      return out;
    } catch (const CheckpointError& e) {
      out.rejected.push_back(e.what());
    }
  }
  std::string message = "no usable checkpoint in " + checkpoint_directory(run_dir).string() + ":";
  for (const std::string& r : out.rejected) message += "\n  " + r;
  throw CheckpointError(message);
}

void truncate_stats_csv(const fs::path& path, long step) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw CheckpointError(path.string() + " cannot be read: the resumed run must continue its rows (" +
                          std::strerror(errno) + ")");
  std::ostringstream buf;
  buf << in.rdbuf();
  const std::string text = buf.str();
  const std::string header = std::string(StatsCsv::header()) + "\n";
  if (text.compare(0, header.size(), header) != 0)
    throw CheckpointError(path.string() + " does not start with this sluice's stats.csv header");
  size_t pos = header.size();
  long last = 0;
  while (pos < text.size()) {
    const size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) break;  // a row cut off when the run stopped
    last = std::strtol(text.c_str() + pos, nullptr, 10);
    pos = eol + 1;
    if (last == step) {
      in.close();
      std::error_code ec;
      fs::resize_file(path, pos, ec);
      if (ec) throw OutputError(path.string() + ": cannot truncate: " + ec.message());
      return;
    }
    if (last > step) break;
  }
  throw CheckpointError(path.string() + " has no row for step " + std::to_string(step) +
                        " of the checkpoint (its last complete row is step " + std::to_string(last) +
                        "): it does not belong to this checkpoint");
}

}  // namespace sluice
