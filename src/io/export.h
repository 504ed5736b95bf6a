#pragma once
// Particle exports of a run, written by `simulate` and `render` at every frame into
// RUN/particles/ (docs/cli.md, "Outputs"):
//   csv: frame_NNNNN.csv, the fluid (id,x,y,vx,vy,pressure,density);
//   vtk: frame_NNNNN_fluid.vtp and frame_NNNNN_boundary.vtp (VTK XML PolyData), and
//        particles.pvd, the ParaView collection of every frame at its simulated time.
// Every file goes through a temporary name and a rename; particles.pvd is rewritten
// after each frame's files exist, so it is valid when a run stops at any point.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sph/particles.h"

namespace sluice {

// The collection's name inside RUN/particles/.
inline constexpr const char* kCollectionFile = "particles.pvd";

// One row per fluid particle in the scene's initial order: id,x,y,vx,vy,pressure,density.
std::string particles_csv(const FluidParticles& f);
// The fluid as VTK XML PolyData: one vertex per particle in the scene's initial order,
// point arrays velocity, pressure, density, id; the time as FieldData TimeValue.
std::string fluid_vtp(const FluidParticles& f, double time);
// The boundary samples as VTK XML PolyData: point arrays velocity, object_id (the index
// of the sample's object in the scene's `boundaries`), pressure, volume.
std::string boundary_vtp(const BoundaryParticles& b, double time);
// ParaView's collection: each frame's fluid (part 0) and boundary (part 1) file at its time.
std::string collection_pvd(const std::vector<std::pair<Index, double>>& frames);

// Writes the chosen exports of each frame into one folder (created on construction when
// any export is on). Throws OutputError.
class ParticleExporter {
 public:
  ParticleExporter(std::filesystem::path dir, const std::vector<std::string>& formats);
  bool enabled() const { return csv_ || vtk_; }
  // A frame an earlier run wrote (a resumed run continues it): listed in the collection.
  void add_earlier(Index frame, double time);
  void write(Index frame, double time, const FluidParticles& f, const BoundaryParticles& b);

 private:
  std::filesystem::path dir_;
  bool csv_ = false, vtk_ = false;
  std::vector<std::pair<Index, double>> frames_;  // in the collection, by frame
};

}  // namespace sluice
