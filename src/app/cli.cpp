#include "app/cli.h"

#include <cerrno>
#include <cstdlib>

namespace sluice::app {

CLI::Validator number_check(bool integer, double lo, bool lo_open, double hi) {
  std::string allowed = std::string(integer ? "an integer " : "a number ") + (lo_open ? "> " : ">= ") +
                        std::to_string(static_cast<long long>(lo));
  if (hi != HUGE_VAL) allowed += " and <= " + std::to_string(static_cast<long long>(hi));
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const double v = integer ? static_cast<double>(std::strtoll(begin, &end, 10)) : std::strtod(begin, &end);
        const bool ok =
            end != begin && *end == '\0' && errno == 0 && std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi;
        return ok ? std::string() : "expected " + allowed + ", got '" + text + "'";
      },
      allowed);
}

CLI::Validator positive_check() { return number_check(false, 0, true); }
CLI::Validator threads_check() { return number_check(true, 1, false, 4096); }

void add_export_option(CLI::App* cmd, std::vector<std::string>& exports) {
  cmd->add_option("--export", exports,
                  "Particle exports at every frame: csv, vtk (VTK XML .vtp and a ParaView .pvd); "
                  "default: the scene's output.export")
      ->delimiter(',')
      ->check(CLI::IsMember({"csv", "vtk"}));
}

void add_checkpoint_options(CLI::App* cmd, int& every, std::string& resume, const std::string& scene) {
  cmd->add_option("--checkpoint-every", every, "Write a checkpoint every N frames to DIR/checkpoints (newest two kept)")
      ->check(number_check(true, 1, false));
  CLI::Option* res = cmd->add_option(
      "--resume", resume, "Continue the interrupted run in DIR from its newest checkpoint, with its scene and flags");
  for (CLI::Option* opt : cmd->get_options()) {
    const std::string name = opt->get_name();
    if (opt != res && name != "scene" && name != "--help" && name != "--threads" && name != "--quiet" &&
        name != "--checkpoint-every")
      res->excludes(opt);
  }
  cmd->callback([cmd, &resume, &scene] {
    if (scene.empty() && resume.empty()) throw CLI::RequiredError(cmd->get_name() + ": SCENE (or --resume DIR)");
  });
}

void add_image_options(CLI::App* cmd, ImageOptions& io) {
  cmd->add_option("--resolution", io.resolution,
                  "Image size WxH (default: the scene's render.resolution, 1280x720; even sizes for video)");
  cmd->add_option("--color-by", io.color_by,
                  "Field: cfl (|v| dt / spacing), speed, pressure, density_error (default: render.color_by, cfl)")
      ->check(CLI::IsMember({"cfl", "speed", "pressure", "density_error"}));
  cmd->add_option("--colormap", io.colormap,
                  "spectrum (blue to red), viridis, turbo (default: render.colormap, spectrum)")
      ->check(CLI::IsMember({"spectrum", "viridis", "turbo"}));
  cmd->add_option("--range", io.range,
                  "Colour range lo:hi, or auto (fixed for the run from the scene: cfl 0:1, speed 0:sqrt(2 g H), "
                  "pressure 0:rho0 g H, density_error 0:1; default: render.range)");
  cmd->add_option("--overlay", io.overlay,
                  "Overlay line above the scene: full (time, frame, step, iterations; default), time, none")
      ->check(CLI::IsMember({"full", "time", "none"}));
  cmd->add_flag("--no-overlay", io.no_overlay, "The same as --overlay none");
  cmd->add_option("--title", io.title, "Title line above the scene (UTF-8)");
  cmd->add_option("--particle-scale", io.particle_scale,
                  "Disc diameter as a multiple of the particle spacing (default 1; > 0, <= 10)")
      ->check(number_check(false, 0, true, 10));
  cmd->add_option("--background", io.background,
                  "Background colour: #rrggbb or a name (white, black, grey, ...; default white)");
  cmd->add_option("--object-color", io.object_colors,
                  "Colour of a boundary object: NAME=COLOUR (repeatable; default grey walls, slate moving objects)")
      ->take_all();
  cmd->add_flag("--no-colorbar", io.no_colorbar, "No colorbar");
  cmd->add_option("--msaa", io.msaa, "Multisampling: 0 (default) or 4")->check(CLI::IsMember({0, 4}));
  cmd->add_option("--egl", io.egl, "EGL platform: auto (default: surfaceless, then device), surfaceless, device")
      ->check(CLI::IsMember({"auto", "surfaceless", "device"}));
}

}  // namespace sluice::app
