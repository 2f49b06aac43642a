// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_PIPELINE_SETTINGS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_PIPELINE_SETTINGS_H

#include <cstddef>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The settings of the robust pipeline, with their defaults and the reason for each. The
/// measurements behind the values are in doc/DESIGN.md, under the stage that uses them.
struct Pipeline_settings
{
  // Coarse to fine (internal::Coarse_to_fine)

  /// Vertices of the coarsest level: small enough for its robust stages to cost nothing,
  /// large enough to carry the shape's protrusions. Inputs up to twice this are solved directly.
  std::size_t coarse_vertices = 500;
  /// Growth of the vertex count from one level to the next: fewer levels cost more
  /// iterations per level, more levels more set-up.
  double level_ratio = 3;
  /// Cap on each stage of a level between the coarsest and the input: such a level is only
  /// a start for the next, which redoes any long slide.
  std::size_t level_iterations = 40;
  /// Tolerance of the levels between the coarsest and the input, at least: looser cost the
  /// input level more, tighter gain nothing.
  double level_tolerance = 1e-5;
  /// From this input size on, the input starts differently after its splits: its Newton
  /// shift starts lower, and its first step is a two-grid cycle with the last level's
  /// factorization, which reaches the smooth error block Jacobi does not (energies without an
  /// area barrier), or `input_smoothing_steps` block Jacobi steps (energies with one).
  std::size_t large_input_vertices = 50000;
  /// For energies with an area barrier (the default). There a two-grid cycle's coarse step
  /// flips some of the input's faces, where the area term is infinite, so the line search
  /// cuts it to 1/128 to 1/4 of its length and the cycle does no better than block Jacobi;
  /// and their projected Newton steps converge linearly, so block Jacobi steps, each about a
  /// third of a Newton iteration's cost, pay.
  std::size_t input_smoothing_steps = 3;
  /// On a large input, the first shift is this over its vertex count (about a fifth of the
  /// smooth modes' curvature, 7 / n of the mean diagonal)...
  double large_input_shift_numerator = 1.5;
  /// ... but at least this: smaller shifts slow the largest inputs down.
  double large_input_min_shift = 1e-5;

  // The fold-free minimization of a level

  /// The floor `t0` of the fold barrier (`Fold_barrier`): faces of a fold-free minimum with a
  /// scale under it are held by the barrier. It bounds the area distortion of the
  /// paper's energies from below where they would squeeze faces out.
  double fold_floor = 1e-7;
  /// The continuation's barrier sits this many floors up, so that the large moves happen
  /// while the squeezed faces are still large and well conditioned.
  double continuation_floor_factor = 1000;
  /// The continuation's tolerance, at least: it only prepares the floor stage.
  double continuation_tolerance = 1e-4;
  /// Weights of the barrier's weak outer layer (`Fold_barrier::energy()`) in the continuation
  /// on coarser levels and on the input, and in the floor stage: it lets Newton's model see the
  /// faces coming down to the barrier one step before they cap the step.
  double level_outer_barrier_weight = 3e-2;
  double input_outer_barrier_weight = 1e-2;
  double floor_outer_barrier_weight = 1e-3;
  /// In the continuation, faces under their area floor are measured as faces of the floor's
  /// area and held from this activation: no energy term orients them.
  double floored_activation = 1e-1;
  /// Folded iterates in a row after which an optimistic stage stops: its minimum may be
  /// fold-free after passing through folds, but a fold that lasts is not undone.
  std::size_t max_folded_iterations = 5;
  /// The same on the input after a level whose optimistic stage was rejected: there the
  /// input's stage folds from its first iterate on protrusion meshes. An iterate whose folded
  /// faces at most halve does not count (isosurfaces unfold so, protrusions do not).
  std::size_t input_max_folded_iterations = 2;
  /// The last level before the input keeps its fold-free minimum if at most this share of
  /// its faces is under the floor: the input's splits stay fold-free near a few such faces,
  /// and the input lifts its own on a patch.
  double few_under_floor_share = 1e-3;

  // Patches of a map (internal::Floor_patch)

  /// Rings of vertices freed around the seed faces of a patch.
  int patch_rings = 3;
  /// Local untangling is for a few folded faces, not for the protrusions' thousands, whose
  /// fold the continuation undoes: at most this share of the vertices is freed.
  double max_untangled_share = 0.05;
  /// Rounds of the untangling energy on a patch: patches untangle in the first or not at all.
  int local_untangling_rounds = 3;
  /// The floor patch frees at most this share of the input's vertices; beyond, the floor
  /// stage on the whole map is as cheap.
  double max_floor_patch_share = 0.25;
  /// The floor patch runs to a tolerance this many times tighter, relative to the whole
  /// map's energy: its iterations are cheap, and what it adds then decides whether the floor
  /// stage on the whole map can gain anything.
  double floor_patch_tightening = 100;
  /// Faces under this share of their activation after the floor stage are deep: their
  /// barrier weighs less than the tolerance, so the stage does not lift them.
  double deep_face_share = 1e-2;
  /// Deep faces are lifted on their one-ring to a tolerance this many times tighter (each
  /// Newton step on a log barrier gains about twice the barrier's weight)...
  double deep_faces_tightening = 1e4;
  /// ... in at most this many iterations: the lift takes about 20, the rest is a slide the
  /// user's tolerance does not ask for.
  std::size_t deep_lift_iterations = 40;

  // Untangling (internal::Untangling_energy)

  /// Iterations per round: each round only has to reach a fold-free map, not converge.
  std::size_t untangling_round_iterations = 20;
  /// Rounds on a whole level, each dividing epsilon by `untangling_epsilon_decay`.
  int untangling_rounds = 40;
  double untangling_epsilon_decay = 10;
  double untangling_min_epsilon = 1e-12;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_PIPELINE_SETTINGS_H
