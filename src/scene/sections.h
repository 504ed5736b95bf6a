#pragma once
// The readers of a scene's sections, each over a Reader of its object (json_reader.h):
// settings (read_settings.cpp), fluid blocks and boundary objects (read_shapes.cpp) and
// their motion (read_motion.cpp).
#include <string>

#include "core/shapes.h"
#include "scene/json_reader.h"
#include "scene/scene.h"

namespace sluice::scene_detail {

SolverSettings read_solver(Reader& r, const Context& ctx);
TimeSettings read_time(Reader& r, const Context& ctx);
StabilityLimits read_stability(Reader& r);
OutputSettings read_output(Reader& r, const Context& ctx, const std::string& name);
RenderSettings read_render(Reader& r, const Context& ctx);

// The name becomes a folder (renders/<name>) and a file (<name>.mp4): it must stay one
// path component, so that a scene cannot write outside its output directory.
void check_name(const Context& ctx, const std::string& name);

shapes::FluidShape read_fluid_block(Reader& r, const Context& ctx);

// One boundary object (the index names it when it has no name); fills obj's name, shape
// and motion.
shapes::BoundaryShape read_boundary(Reader& r, const Context& ctx, std::size_t index, double h, BoundaryObject& obj);

// The optional "motion" key of a boundary object.
void read_object_motion(Reader& r, const Context& ctx, BoundaryObject& obj);

// What a boundary would cost: the samples BoundaryShape::sample() makes, layer by layer
// as it does (offset layers of a container grow), and the pieces of one fluid spacing
// that curve(h) cuts for the removal of covered fluid. Computed without making them, so
// that a typo in a spacing, a layer spacing or a coordinate is refused before it takes
// the machine's memory.
struct BoundaryCost {
  double samples = 0, curve_pieces = 0;
};

BoundaryCost boundary_cost(const shapes::BoundaryShape& b, double h);

// Guard against absurd sample counts (e.g. a spacing typo): refuses a boundary whose
// cost alone, or with the objects before it (`total`, this one included), passes the limit.
void check_boundary_cost(const Context& ctx, const std::string& path, const BoundaryCost& cost,
                         const BoundaryCost& total);

}  // namespace sluice::scene_detail
