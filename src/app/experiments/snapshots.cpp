#include "app/experiments/common.h"

namespace sluice::app::experiments {

// --- Figures 2 and 8: snapshot montages ----------------------------------------------------------

void snapshots(Context& c) {
  MontageOptions m;
  m.scene = c.scene_path("dam_break.json");
  m.times = c.quick ? "0,0.25" : "0,0.5,1,1.5,2,2.5,3,3.5";
  m.cols = c.quick ? 2 : 4;
  m.cell = c.quick ? "160x160" : "320x320";
  if (c.quick) m.set = {"spacing=0.04"};
  m.title = "Dam break, coloured by CFL number";
  c.md += "The breaking dam (`" + m.scene + "`) at " + m.times +
          " s, coloured by CFL number. Compare with the thesis' "
          "Figure 2 (130k particles: `--scene scenes/dam_break_130k.json`).\n\n";
  montage_figure(c, m, "dam_break_snapshots.png", "Breaking dam snapshots with their times (thesis Figure 2)");
}

}  // namespace sluice::app::experiments
