#include "io/output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace sluice {

const char* StatsCsv::header() {
  return "step,time,dt,iterations,avg_error_percent,max_error_percent,density_error_percent,max_cfl,"
         "fluid_particles,frame,ms_neighbors,ms_nonpressure,ms_pressure,ms_integrate,ms_total,ms_boundary,"
         "kinetic_energy,potential_energy,mechanical_energy,boundary_work";
}

StatsCsv::StatsCsv(const std::string& path, bool append)
    : path_(path), tmp_(path + ".tmp"), out_(tmp_, append ? std::ios::app : std::ios::trunc) {
  if (!out_) throw OutputError(tmp_ + ": cannot open for writing: " + std::strerror(errno));
  if (!append) out_ << header() << '\n';
}

StatsCsv::~StatsCsv() {
  if (finished_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(tmp_, ignored);
}

void StatsCsv::finish() {
  out_.close();
  if (!out_ && error_ == 0) error_ = errno ? errno : EIO;
  std::error_code ec;
  std::filesystem::rename(tmp_, path_, ec);
  if (ec) throw OutputError(path_ + ": cannot rename from " + tmp_ + ": " + ec.message());
  finished_ = true;
  if (error_ != 0)
    throw OutputError(path_ + ": write failed: " + std::strerror(error_) + " (the rows before the failure are kept)");
}

void StatsCsv::flush() {
  out_.flush();
  if (!out_ && error_ == 0) {
    error_ = errno ? errno : EIO;
    throw OutputError(tmp_ + ": write failed: " + std::strerror(error_));
  }
}

void StatsCsv::write(const StepStats& s) {
  char line[640];
  std::snprintf(line, sizeof line,
                "%ld,%.9g,%.6g,%d,%.6g,%.6g,%.6g,%.6g,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.10g,%.10g,%.12g,%.10g\n",
                s.step, s.time, s.dt, s.iterations, s.avg_error_percent, s.max_error_percent, s.density_error_percent,
                s.max_cfl, s.fluid_particles, s.frame, s.ms(Phase::Neighbors), s.ms(Phase::NonPressure),
                s.ms(Phase::Pressure), s.ms(Phase::Integrate), s.ms_total, s.ms(Phase::Boundary), s.kinetic_energy,
                s.potential_energy, s.mechanical_energy, s.boundary_work);
  errno = 0;
  out_ << line;
  if (!out_) {
    if (error_ == 0) error_ = errno ? errno : EIO;
    throw OutputError(tmp_ + ": write failed: " + std::strerror(error_));
  }
}

void write_file_atomic(const std::string& path, const std::string& text) {
  write_bytes_atomic(path, text.data(), text.size());
}

void RunTotals::add(const StepStats& s) {
  ++steps;
  simulated_time = s.time;
  sum_iterations += s.iterations;
  sum_avg_error += s.avg_error_percent;
  sum_density_error += s.density_error_percent;
  max_error = std::max(max_error, s.max_error_percent);
  final_energy = s.mechanical_energy;
  boundary_work += s.boundary_work;
  const double ms[6] = {
      s.ms(Phase::Neighbors), s.ms(Phase::NonPressure), s.ms(Phase::Pressure), s.ms(Phase::Integrate), s.ms_total,
      s.ms(Phase::Boundary)};
  for (int k = 0; k < 6; ++k) sum_ms[k] += ms[k];
}

nlohmann::json RunTotals::to_json(long fluid_particles) const {
  const double ns = steps > 0 ? static_cast<double>(steps) : 1.0;
  const double particle_steps = ns * static_cast<double>(std::max(fluid_particles, 1L));
  return {
      {"steps", steps},
      {"simulated_time", simulated_time},
      {"wall_seconds", wall_seconds},
      {"average_iterations", sum_iterations / ns},
      {"average_error_percent", sum_avg_error / ns},
      {"max_error_percent", max_error},
      {"average_density_error_percent", sum_density_error / ns},
      // Mechanical energy [J/m]: its change over the run against the boundaries' work
      // (an inviscid closed tank at rest: drift <= 0; moving boundaries: drift ~ work).
      {"energy",
       {{"initial", initial_energy},
        {"final", steps > 0 ? final_energy : initial_energy},
        {"drift", steps > 0 ? final_energy - initial_energy : 0.0},
        {"boundary_work", boundary_work}}},
      {"us_per_particle_step", 1000.0 * sum_ms[4] / particle_steps},
      {"ms_per_step",
       {{"neighbors", sum_ms[0] / ns},
        {"nonpressure", sum_ms[1] / ns},
        {"pressure", sum_ms[2] / ns},
        {"integrate", sum_ms[3] / ns},
        {"moving_boundaries", sum_ms[5] / ns},
        {"total", sum_ms[4] / ns}}},
  };
}

}  // namespace sluice
