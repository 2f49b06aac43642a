// A visitor: called after every Newton iteration with a Progress, it prints the progress and
// stops the solve early, once the energy no longer decreases by more than a relative
// THRESHOLD per iteration, or after MAX_ITERATIONS. Stopping early trades the last bit of
// distortion for time: the map returned is valid, only not fully converged.
//
//   progress_visitor [INPUT [THRESHOLD [MAX_ITERATIONS]]]   (defaults: data/triceratops.off, 1e-3, 30)
//
// Exit status 0 if and only if the map is valid.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

struct Early_stop
{
  double threshold = 1e-3;         // relative decrease of the energy per iteration
  std::size_t max_iterations = 30;  // in all stages

  std::string stage;           // the stage of the previous call
  double previous_energy = 0;  // its energy
  const char* reason = "";     // why the solve was stopped, if it was

  bool operator()(const SP::Progress& p)
  {
    // Energies of different stages (Tutte, untangling, yours) are not comparable, so the
    // decrease is measured within a stage only.
    const bool same_stage = stage == p.stage;
    const double decrease = same_stage ? (previous_energy - p.energy) / std::abs(p.energy) : HUGE_VAL;
    stage = p.stage;
    previous_energy = p.energy;
    std::printf("%-12s iteration %3zu  energy %-12.6g  relative decrease %-10.3g  step %-6.3g  %.2f s\n", p.stage,
                p.iteration, p.energy, same_stage ? decrease : std::nan(""), p.step, p.elapsed_seconds);

    // The start-up stages may leave folds behind them, so let them run: a stop in any other
    // stage of the robust pipeline returns a valid map.
    if(stage == "tutte" || stage == "untangle" || stage == "local untangling" || stage == "plain")
      return true;
    if(decrease < threshold) { reason = "the decrease fell below the threshold"; return false; }
    if(p.iteration >= max_iterations) { reason = "the iteration budget is spent"; return false; }
    return true;
  }
};

int main(int argc, char** argv)
{
  const std::string input = argc > 1 ? argv[1] : SPHERICAL_PARAMETERIZATION_DATA_DIR "/triceratops.off";
  Early_stop visitor;
  if(argc > 2) visitor.threshold = std::atof(argv[2]);
  if(argc > 3) visitor.max_iterations = std::size_t(std::atol(argv[3]));
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(input, mesh) || is_empty(mesh)) {
    std::cerr << "cannot read " << input << "\n";
    return 1;
  }

  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  // The solver keeps its own copy of a visitor given by value; std::ref lets this one keep
  // its state (here, the reason for stopping) for after the call.
  const SP::Result r = CGAL::spherical_parameterize(mesh, sphere, CGAL::parameters::visitor(std::ref(visitor)));

  // A cancelled solve reports CANCELLED, with a valid map if one was reached before the stop.
  std::cout << "status " << r.message() << (*visitor.reason ? std::string(": ") + visitor.reason : "") << "; "
            << r.iterations << " iterations (" << r.stage_summary() << "), valid map: " << (r.is_valid() ? "yes" : "no")
            << ", smallest area ratio " << r.min_area_ratio << "\n";
  return r.is_valid() ? 0 : 1;
}
