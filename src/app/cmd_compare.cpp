// `sluice compare`: its flags; the comparison is run_compare (app/compare.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_compare(CLI::App& app) {
  auto cmp = std::make_shared<CompareOptions>();
  CLI::App* compare = app.add_subcommand(
      "compare",
      "Compare two PNG images; exit 0 when they match, 1 when they differ, 2 usage, 3 unreadable, 4 sizes differ");
  compare->add_option("a", cmp->a, "First PNG")->required();
  compare->add_option("b", cmp->b, "Second PNG")->required();
  compare
      ->add_option("--preset", cmp->preset,
                   "strict: 0 levels, 0 % of pixels (default); tests: sluice's image tests' rule, 8 levels, 0.5 %")
      ->check(CLI::IsMember({"strict", "tests"}));
  compare
      ->add_option("--tolerance", cmp->tolerance,
                   "Channel difference a pixel may have, 0-255 levels (default: the preset's)")
      ->check(CLI::Range(0, 255));
  compare
      ->add_option("--max-fraction", cmp->max_fraction,
                   "Share of compared pixels allowed beyond the tolerance, 0-1 (default: the preset's)")
      ->check(number_check(false, 0, false, 1));  // CLI::Range lets nan through
  compare->add_option("--mask", cmp->mask, "PNG of the images' size: its non-black pixels are ignored");
  compare->add_option("--region", cmp->regions, "Ignore the rectangle x,y,w,h (pixels from the top left; repeatable)")
      ->allow_extra_args(false);  // one rectangle per --region: A.png and B.png may follow
  compare->add_option("--diff", cmp->diff, "Write a diff image here when pixels differ");
  return {compare, [cmp] { return run_compare(*cmp); }};
}

}  // namespace sluice::app
