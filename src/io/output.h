#pragma once
// Frame sinks of a simulation run that write files: per-step statistics (CSV) and the
// run summary (JSON); particle exports are in io/export.h. Files that are written at once
// go to a temporary name first and are renamed when complete.
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/atomic_file.h"
#include "solver/stats.h"
#include "sph/particles.h"

namespace sluice {

// stats.csv: one row per step; columns documented in docs/cli.md ("Outputs"). The rows go to
// `path.tmp`, renamed to `path` by finish() when the run has ended (completed, unstable
// or failed, as summary.json says), so a stats.csv never belongs to a run still going
// or killed. Destroyed without finish(), it removes the temporary file.
class StatsCsv {
 public:
  // append: continue the rows of an existing `path.tmp`, without a header (a resumed
  // run, after prepare_resumed_stats_csv in app/resume.h).
  explicit StatsCsv(const std::string& path, bool append = false);
  ~StatsCsv();
  StatsCsv(const StatsCsv&) = delete;
  StatsCsv& operator=(const StatsCsv&) = delete;
  void write(const StepStats& s);
  void flush();  // throws OutputError after a failed write
  // Closes the file and renames it to its real name, also after a failed write (the rows
  // before it are kept: a full disk must not lose the run's record); then throws
  // OutputError if a write had failed.
  void finish();
  static const char* header();

 private:
  std::string path_, tmp_;
  std::ofstream out_;
  bool finished_ = false;
  int error_ = 0;  // errno of the first failed write
};

// Writes `text` to `path` through `path.tmp` and a rename (write_bytes_atomic).
void write_file_atomic(const std::string& path, const std::string& text);

// Running totals of a run for summary.json.
struct RunTotals {
  long steps = 0;
  double simulated_time = 0;
  double wall_seconds = 0;
  double sum_iterations = 0;
  double sum_avg_error = 0;
  double max_error = 0;
  double sum_density_error = 0;
  double sum_ms[6] = {0, 0, 0, 0, 0, 0};
  // Mechanical energy at t = 0 (Simulation::mechanical_energy before the first step),
  // after the last step, and the boundaries' work summed over the steps [J/m].
  double initial_energy = 0, final_energy = 0,
         boundary_work = 0;  // neighbours, non-pressure, pressure, integration, total, moving boundaries

  void add(const StepStats& s);
  nlohmann::json to_json(long fluid_particles) const;
};

}  // namespace sluice
