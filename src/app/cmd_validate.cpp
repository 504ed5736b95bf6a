// `sluice validate`: its flags; the checks are run_validate (app/validate.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_validate(CLI::App& app) {
  auto val = std::make_shared<ValidateOptions>();
  CLI::App* validatecmd = app.add_subcommand(
      "validate",
      "Validation against known answers: hydrostatic pressure, Martin & Moyce's dam break, Monaghan's elliptical drop");
  validatecmd->add_option("what", val->what, "hydrostatic, dam-break, elliptical-drop, thin-plate or plate-sweep")
      ->required()
      ->check(CLI::IsMember({"hydrostatic", "dam-break", "elliptical-drop", "thin-plate", "plate-sweep"}));
  validatecmd->add_option(
      "--scene", val->scene,
      "Scene file (default scenes/validation/hydrostatic.json, dam_break_martin_moyce.json or elliptical_drop.json; "
      "scenes/hard/thin_plate.json for thin-plate and plate-sweep)");
  validatecmd->add_option("-o,--output", val->output_dir,
                          "Directory for the CSV files and figures (default renders/validation)");
  validatecmd->add_option("--solver", val->solver, "iisph, wcsph or both (default)")
      ->check(CLI::IsMember({"iisph", "wcsph", "both"}));
  validatecmd->add_option(
      "--case", val->only,
      "hydrostatic: only this case, e.g. iisph_mirroring; plate-sweep: e.g. submerged_30deg_x+0.4h");
  validatecmd
      ->add_option("--spacing", val->spacing,
                   "Particle spacing h [m]; dam-break: one or more, comma-separated, coarse to fine (default "
                   "0.04,0.02,0.01); elliptical-drop, thin-plate, plate-sweep: one (default: the scene's)")
      ->delimiter(',')
      ->check(positive_check());
  validatecmd->add_option("--max-rms", val->max_rms, "dam-break: bound on the RMS relative front error (default 0.20)")
      ->check(positive_check());
  validatecmd->add_option("--threads", val->threads, "OpenMP threads")->check(threads_check());
  validatecmd->add_option("--set", val->set, "Override a scene value: path=value")->take_all();
  return {validatecmd, [val] { return run_validate(*val); }};
}

}  // namespace sluice::app
