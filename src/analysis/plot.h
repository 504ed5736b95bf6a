#pragma once
// Figures through gnuplot (Debian's gnuplot-nox): a command writes its data as CSV and a
// gnuplot script next to it, then runs the script, so a reader can restyle the figure by
// editing the script and rerunning `gnuplot FILE.gp`.
#include <string>

namespace sluice::analysis {

// True when a `gnuplot` executable is on PATH.
bool gnuplot_available();

// Writes `script` to `script_path` and runs gnuplot on it from the script's directory.
// Returns "" on success; otherwise a one-line reason (gnuplot missing, or its exit status
// and the script to rerun by hand). The figure is optional next to the data, so callers
// report the reason instead of failing the command.
std::string run_gnuplot(const std::string& script_path, const std::string& script);

// The preamble shared by every figure: a PNG (pngcairo) of `width` x `height` pixels and
// fonts readable at paper size; `output` is relative to the script's directory.
std::string gnuplot_png_preamble(const std::string& output, int width = 1200, int height = 800);

// Quotes a string for a gnuplot script (titles, file names).
std::string gnuplot_quote(const std::string& s);

}  // namespace sluice::analysis
