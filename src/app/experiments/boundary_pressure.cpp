#include "app/experiments/common.h"

namespace sluice::app::experiments {

// --- Figures 2 and 8: snapshot montages ----------------------------------------------------------

void boundary_pressure(Context& c) {
  MontageOptions m;
  m.scene = c.scene.empty() ? c.scenes + "/hydrostatic.json" : c.scene;
  m.times = c.quick ? "0.1" : "3";
  m.vary = "solver.boundary_pressure=extrapolation,mirroring,zero";
  m.cols = 3;  // side by side, as in the thesis
  m.color_by = "pressure";
  m.cell = c.quick ? "120x132" : "240x264";
  if (c.quick) m.set = {"time.duration=0.1"};
  m.title = "Pressure by boundary method";
  c.md += "The hydrostatic tank (`" + m.scene + "`) at t = " + m.times +
          " s, coloured by pressure on one shared scale, once per boundary method. Compare with the thesis' Figure 8: "
          "extrapolation continues the pressure into the wall, zero pressure loads the first fluid rows instead.\n\n";
  montage_figure(c, m, "pressure_by_method.png",
                 "Pressure field for pressure extrapolation, mirroring and zero pressure (thesis Figure 8)");
}

}  // namespace sluice::app::experiments
