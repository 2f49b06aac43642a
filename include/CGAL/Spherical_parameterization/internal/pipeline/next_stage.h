// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_NEXT_STAGE_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_NEXT_STAGE_H

#include <CGAL/Spherical_parameterization/Result.h>

#include <optional>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// What the stages of a level's fold-free minimization found so far: all that `next_stage()`
/// reads.
struct Level_facts
{
  bool is_input = false;           ///< the level is the input mesh
  bool interrupted = false;        ///< the visitor cancelled, or the time ran out
  bool optimistic_ran = true;      ///< false: only the smoothing step ran (see `Robust_pipeline`)
  bool fold_free_minimum = false;  ///< the optimistic stage converged to a fold-free map
  bool folded = false;             ///< the map has flipped or degenerate faces
  bool above_floor = false;        ///< every face is above the fold floor
  bool few_under_floor = false;    ///< the last level before the input, with few faces under the floor
  bool untangled = false;          ///< the local untangling made the map fold-free
  bool patch_sufficed = false;     ///< the floor patch did all that the floor stage could do
};

/// The stage that follows `done` in the fold-free minimization of a level, none when the
/// level is done (doc/DESIGN.md, "The fold-free minimization of a level"):
/// - a fold-free minimum above the floor is the level's result: most meshes end there;
/// - on the input, faces squeezed under the floor are lifted by the floor stage, on their
///   neighbourhood first; deep faces are lifted last;
/// - a minimum folded by a few faces is untangled locally, and kept if that works;
/// - otherwise the continuation restarts from the last fold-free map, with the barrier
///   high, and the input ends with the floor stage.
inline std::optional<Stage> next_stage(Stage done, const Level_facts& f)
{
  if(f.interrupted)
    return std::nullopt;
  switch(done) {
  case Stage::OPTIMISTIC:
    if(f.fold_free_minimum && (f.above_floor || f.few_under_floor))
      return std::nullopt;
    if(f.fold_free_minimum)
      return f.is_input ? Stage::FLOOR_PATCH : Stage::CONTINUATION;
    return f.folded && f.optimistic_ran ? Stage::LOCAL_UNTANGLING : Stage::CONTINUATION;
  case Stage::LOCAL_UNTANGLING:
    if(f.untangled && f.is_input)
      return Stage::FLOOR;
    if(f.untangled && f.above_floor)
      return std::nullopt;
    return Stage::CONTINUATION;
  case Stage::CONTINUATION:
    // A coarser level stops on the continuation's cushion: the next level's splits then
    // start above the floor.
    return f.is_input ? std::optional<Stage>(Stage::FLOOR) : std::nullopt;
  case Stage::FLOOR_PATCH:
    return f.patch_sufficed ? Stage::DEEP_FACES : Stage::FLOOR;
  case Stage::FLOOR:
    return Stage::DEEP_FACES;
  default:
    return std::nullopt;
  }
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PIPELINE_NEXT_STAGE_H
