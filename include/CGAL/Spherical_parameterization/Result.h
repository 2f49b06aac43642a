// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H
#define CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H

#include <CGAL/Spherical_parameterization/Error_code.h>

#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// The stages of a solve (the user manual's "The robust pipeline" describes each).
enum class Stage
{
  TUTTE,             ///< Tutte's energy with the `d_min` barrier, from a folded start, until fold-free
  UNTANGLING,        ///< the untangling energy of Garanzha et al., in rounds, until fold-free
  PLAIN,             ///< the chosen energy with no fold-free guarantee (paper pipeline, or no fold-free start)
  OPTIMISTIC,        ///< the chosen energy alone, from a fold-free map
  LOCAL_UNTANGLING,  ///< the folded faces untangled on their neighbourhood, the rest held
  CONTINUATION,      ///< the chosen energy plus the fold barrier far above the floor, steps capped
  FLOOR_PATCH,       ///< the floor stage on the neighbourhood of the faces under the floor
  FLOOR,             ///< the chosen energy plus the fold barrier at the floor, steps capped
  DEEP_FACES         ///< faces far under the floor lifted on their one-ring
};

/// \ingroup PkgSphericalParameterizationRef
/// The name of a stage, as `Progress::stage` gives it: "tutte", "untangle", "plain",
/// "optimistic", "local untangling", "continuation", "floor patch", "floor", "deep faces".
inline const char* stage_name(Stage stage)
{
  switch(stage) {
  case Stage::TUTTE: return "tutte";
  case Stage::UNTANGLING: return "untangle";
  case Stage::PLAIN: return "plain";
  case Stage::OPTIMISTIC: return "optimistic";
  case Stage::LOCAL_UNTANGLING: return "local untangling";
  case Stage::CONTINUATION: return "continuation";
  case Stage::FLOOR_PATCH: return "floor patch";
  case Stage::FLOOR: return "floor";
  case Stage::DEEP_FACES: return "deep faces";
  }
  return "unknown";
}

/// \ingroup PkgSphericalParameterizationRef
/// One stage run by a solve, on one level of the coarse-to-fine hierarchy or on the input.
struct Stage_report
{
  Stage stage = Stage::PLAIN;      ///< which stage
  std::size_t level_vertices = 0;  ///< vertices of the mesh it ran on (the input's, or a coarser level's)
  bool input_level = false;        ///< it ran on the input mesh (or on a patch of it)
  std::size_t iterations = 0;      ///< its Newton iterations

  /// Same stage, on the same level, with as many iterations.
  friend bool operator==(const Stage_report& a, const Stage_report& b)
  {
    return a.stage == b.stage && a.level_vertices == b.level_vertices && a.input_level == b.input_level &&
           a.iterations == b.iterations;
  }
};

/// \ingroup PkgSphericalParameterizationRef
/// What a solve returns. A map is valid when every point is on the unit sphere (to 1e-12),
/// no face is flipped or degenerate (`|det(a, b, c)| > 1e-14`, with the sign of the input's
/// orientation) and the degree is 1 (relative to that orientation).
struct Result
{
  Error_code status = Error_code::OK;  ///< `OK`, or what went wrong
  std::string detail;             ///< what and where: "12 border edges", "2 flipped faces", ...

  bool valid = false;             ///< the map written is a valid embedding
  std::size_t iterations = 0;     ///< Newton iterations, all stages
  double energy = 0;              ///< final value of the chosen energy (input scaled to area 4 pi)
  std::size_t flipped = 0;        ///< faces whose orientation is opposite to the input's
  std::size_t degenerate = 0;     ///< faces with `|det| <= 1e-14`
  double degree = 0;              ///< signed spherical area / 4 pi, relative to the input orientation
  bool inward_oriented = false;   ///< the input's faces are oriented towards its inside
  double min_area_ratio = 0;      ///< min over faces of (spherical area share / input area share)
  double time_seconds = 0;        ///< wall time of the solve
  std::vector<Stage_report> stages;  ///< the stages run, in their order

  /// The message of `status`.
  const char* message() const { return error_message(status); }
  /// True if the map is valid (status `OK` or `NOT_CONVERGED`, or a time limit or
  /// cancellation that came after a valid map).
  bool is_valid() const { return valid; }

  /// The stages on one line, level by level with their vertex counts, for instance
  /// "500v: tutte 2, optimistic 18 | 1500v: optimistic 18 | input 2832v: optimistic 11".
  std::string stage_summary() const
  {
    std::string s;
    for(std::size_t i = 0; i < stages.size(); ++i) {
      const Stage_report& r = stages[i];
      const bool new_level = i == 0 || r.level_vertices != stages[i - 1].level_vertices ||
                             r.input_level != stages[i - 1].input_level;
      if(new_level)
        s += (i == 0 ? "" : " | ") + std::string(r.input_level ? "input " : "") + std::to_string(r.level_vertices) +
             "v: ";
      else
        s += ", ";
      s += std::string(stage_name(r.stage)) + " " + std::to_string(r.iterations);
    }
    return s;
  }
};

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_RESULT_H
