#include "io/export.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <type_traits>

#include "io/atomic_file.h"

namespace sluice {

namespace fs = std::filesystem;

namespace {

// Indices of fluid particles sorted by their initial id, so exports keep one order.
std::vector<Index> by_id(const FluidParticles& f) {
  std::vector<Index> order(f.id.size());
  for (Index k = 0; k < f.size(); ++k) order[f.id[k]] = k;
  return order;
}

std::vector<Index> in_storage_order(Index n) {
  std::vector<Index> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), Index(0));
  return order;
}

// Nine significant digits, as the CSV export.
void append(std::string& s, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g ", v);
  s += buf;
}

void append(std::string& s, long v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%ld ", v);
  s += buf;
}

std::string frame_file(Index frame, const char* suffix) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "frame_%05d%s", frame, suffix);
  return buf;
}

// A VTK XML PolyData file of points in `order`, each its own vertex cell (what
// ParaView shows as points or glyphs), with ASCII point arrays.
class VtpBuilder {
 public:
  VtpBuilder(std::vector<Index> order, double time) : order_(std::move(order)) {
    s_ = "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n"
         "<FieldData>\n<DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">";
    char exact[32];
    std::snprintf(exact, sizeof exact, "%.17g", time);  // as the collection's timestep
    s_ += exact;
    const std::string n = std::to_string(order_.size());
    s_ += "</DataArray>\n</FieldData>\n<Piece NumberOfPoints=\"" + n + "\" NumberOfVerts=\"" + n +
          "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<PointData Vectors=\"velocity\">\n";
  }

  // A 2D vector per point, written with z = 0 (ParaView's glyphs and filters want three).
  void vectors(const char* name, const std::vector<Vec2>& v) {
    open(name, "Float64", 3);
    for (Index k : order_) {
      append(s_, v[k].x());
      append(s_, v[k].y());
      s_ += "0\n";
    }
    close();
  }

  template <class T>
  void scalars(const char* name, const std::vector<T>& v) {
    open(name, std::is_integral_v<T> ? "Int32" : "Float64", 1);
    for (Index k : order_) {
      if constexpr (std::is_integral_v<T>)
        append(s_, static_cast<long>(v[k]));
      else
        append(s_, static_cast<double>(v[k]));
      s_ += '\n';
    }
    close();
  }

  std::string finish(const std::vector<Vec2>& x) {
    s_ += "</PointData>\n<Points>\n";
    open(nullptr, "Float64", 3);
    for (Index k : order_) {
      append(s_, x[k].x());
      append(s_, x[k].y());
      s_ += "0\n";
    }
    close();
    s_ += "</Points>\n<Verts>\n";
    open("connectivity", "Int32", 1);
    for (size_t i = 0; i < order_.size(); ++i) append(s_, static_cast<long>(i));
    close();
    open("offsets", "Int32", 1);
    for (size_t i = 0; i < order_.size(); ++i) append(s_, static_cast<long>(i + 1));
    close();
    s_ += "</Verts>\n</Piece>\n</PolyData>\n</VTKFile>\n";
    return std::move(s_);
  }

 private:
  void open(const char* name, const char* type, int components) {
    s_ += std::string("<DataArray type=\"") + type + "\"";
    if (name) s_ += std::string(" Name=\"") + name + "\"";
    if (components > 1) s_ += " NumberOfComponents=\"" + std::to_string(components) + "\"";
    s_ += " format=\"ascii\">\n";
  }
  void close() { s_ += "</DataArray>\n"; }

  std::vector<Index> order_;
  std::string s_;
};

}  // namespace

std::string particles_csv(const FluidParticles& f) {
  std::string s = "id,x,y,vx,vy,pressure,density\n";
  s.reserve(s.size() + static_cast<size_t>(f.size()) * 96);
  char line[256];
  for (Index k : by_id(f)) {
    std::snprintf(line, sizeof line, "%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", f.id[k], f.x[k].x(), f.x[k].y(), f.v[k].x(),
                  f.v[k].y(), f.p[k], f.rho[k]);
    s += line;
  }
  return s;
}

std::string fluid_vtp(const FluidParticles& f, double time) {
  VtpBuilder v(by_id(f), time);
  v.vectors("velocity", f.v);
  v.scalars("pressure", f.p);
  v.scalars("density", f.rho);
  v.scalars("id", f.id);
  return v.finish(f.x);
}

std::string boundary_vtp(const BoundaryParticles& b, double time) {
  VtpBuilder v(in_storage_order(b.size()), time);
  v.vectors("velocity", b.v);
  v.scalars("object_id", b.object);
  v.scalars("pressure", b.p);
  v.scalars("volume", b.volume);
  return v.finish(b.x);
}

std::string collection_pvd(const std::vector<std::pair<Index, double>>& frames) {
  std::string s =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
      "byte_order=\"LittleEndian\">\n<Collection>\n";
  char line[256];
  for (const auto& [frame, time] : frames) {
    // Every digit of the time: ParaView's animation steps through these values.
    const char* parts[2][2] = {{"0", "fluid"}, {"1", "boundary"}};
    for (const auto& [part, name] : parts) {
      std::snprintf(line, sizeof line, "<DataSet timestep=\"%.17g\" group=\"\" part=\"%s\" name=\"%s\" file=\"%s\"/>\n",
                    time, part, name, frame_file(frame, (std::string("_") + name + ".vtp").c_str()).c_str());
      s += line;
    }
  }
  return s + "</Collection>\n</VTKFile>\n";
}

ParticleExporter::ParticleExporter(fs::path dir, const std::vector<std::string>& formats) : dir_(std::move(dir)) {
  csv_ = std::find(formats.begin(), formats.end(), "csv") != formats.end();
  vtk_ = std::find(formats.begin(), formats.end(), "vtk") != formats.end();
  if (!enabled()) return;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw OutputError(dir_.string() + ": cannot create directory: " + ec.message());
}

void ParticleExporter::add_earlier(Index frame, double time) {
  if (vtk_) frames_.emplace_back(frame, time);
}

void ParticleExporter::write(Index frame, double time, const FluidParticles& f, const BoundaryParticles& b) {
  auto put = [&](const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    write_bytes_atomic(path, text.data(), text.size());
  };
  if (csv_) put(frame_file(frame, ".csv"), particles_csv(f));
  if (!vtk_) return;
  put(frame_file(frame, "_fluid.vtp"), fluid_vtp(f, time));
  put(frame_file(frame, "_boundary.vtp"), boundary_vtp(b, time));
  // A frame drawn again (the first of a resumed run) replaces its entry.
  std::erase_if(frames_, [&](const auto& e) { return e.first >= frame; });
  frames_.emplace_back(frame, time);
  put(kCollectionFile, collection_pvd(frames_));
}

}  // namespace sluice
