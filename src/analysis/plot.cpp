#include "analysis/plot.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "io/output.h"

namespace sluice::analysis {

namespace fs = std::filesystem;

bool gnuplot_available() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

std::string gnuplot_quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

std::string gnuplot_png_preamble(const std::string& output, int width, int height) {
  return "set terminal pngcairo size " + std::to_string(width) + "," + std::to_string(height) +
         " enhanced font \"DejaVu Sans,20\" linewidth 2\n"
         "set output " +
         gnuplot_quote(output) +
         "\n"
         "set datafile separator \",\"\n"
         "set grid lc rgb \"#dddddd\"\n"
         "set key top left box opaque\n";
}

std::string run_gnuplot(const std::string& script_path, const std::string& script) {
  write_file_atomic(script_path, script);
  if (!gnuplot_available())
    return "gnuplot not found (Debian package gnuplot-nox; scripts/install-deps.sh installs it)";
  const fs::path p = fs::absolute(script_path);
  // Single quotes around the paths: the shell must not expand anything in them.
  auto sh = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  // gnuplot's messages (warnings included) go to FILE.log beside the script: a warning
  // on the terminal looked like a failure; the log says what it was.
  fs::path log = p;
  log.replace_extension(".log");
  const std::string cmd = "cd " + sh(p.parent_path().string()) + " && gnuplot " + sh(p.filename().string()) + " >" +
                          sh(log.string()) + " 2>&1";
  const int status = std::system(cmd.c_str());
  if (status != 0)
    return "gnuplot failed (status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : status) +
           "; its messages are in " + log.string() + "); rerun by hand: gnuplot " + p.string();
  std::error_code ec;
  if (fs::file_size(log, ec) == 0 && !ec) fs::remove(log, ec);  // nothing to say: no file
  return "";
}

}  // namespace sluice::analysis
