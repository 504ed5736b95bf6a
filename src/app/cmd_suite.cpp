// `sluice suite`: its flags; the cases are run_suite (app/suite.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_suite(CLI::App& app) {
  auto suite = std::make_shared<SuiteOptions>();
  CLI::App* suitecmd =
      app.add_subcommand("suite", "Run the hard-case suite with both solvers; print a pass/fail table");
  suitecmd->add_option("file", suite->file, "Suite file (default scenes/hard/suite.json)");
  suitecmd->add_flag("--short", suite->quick, "The short version of every case (what CI runs)");
  suitecmd->add_option("--solver", suite->solver, "iisph, wcsph or both (default)")
      ->check(CLI::IsMember({"iisph", "wcsph", "both"}));
  suitecmd->add_option("--case", suite->only, "Run only this case");
  suitecmd->add_option("--threads", suite->threads, "OpenMP threads")->check(threads_check());
  suitecmd->add_option("--csv", suite->csv, "CSV output file (default renders/suite/suite.csv)");
  return {suitecmd, [suite] { return run_suite(*suite); }};
}

}  // namespace sluice::app
