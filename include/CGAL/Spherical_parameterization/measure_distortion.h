// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_MEASURE_DISTORTION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_MEASURE_DISTORTION_H

#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/input/indexed_triangles.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/assertions.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Statistics of one per-face distortion figure over the faces of a mesh. The mean and the
/// percentile are weighted by the input area of the faces, so that many tiny faces do not
/// outweigh a few large ones. Faces whose value is not finite are left out rather than letting one NaN or
/// infinity hide the rest: a degenerate input or chord triangle has no finite
/// quasi-conformal ratio, a flipped or degenerate face no logarithm of its area ratio. Such
/// faces of the map are counted in `Distortion_report::degenerate` and `flipped` instead.
/// Every statistic is 0 when no face has a finite value.
struct Summary
{
  double mean = 0;           ///< area-weighted mean
  double percentile_95 = 0;  ///< smallest value `v` such that faces with values `<= v` hold 95% of the input area
  double max = 0;            ///< largest value
};

/// \ingroup PkgSphericalParameterizationRef
/// Validity and distortion of a map of a closed triangle mesh onto the unit sphere, as
/// computed by `measure_distortion()`.
///
/// Orientation: the input's own orientation (the sign of its signed volume) is the
/// reference. A face is flipped when the sign of `det(a, b, c)` of its sphere points is the
/// opposite of that orientation, and `degree` is signed so that a valid map reports 1 for
/// outward- and inward-oriented inputs alike.
///
/// The per-face figures compare the input triangle with the chord triangle, the flat
/// triangle spanned by the face's three sphere points. Flat against flat keeps the figures
/// zero (or one) for a mesh inscribed in the sphere and mapped to itself, whereas the
/// geodesic triangle always differs from a flat one by its spherical excess.
struct Distortion_report
{
  std::size_t faces = 0;       ///< number of faces
  std::size_t flipped = 0;     ///< faces with `|det| > 1e-14` and the sign opposite to the input's orientation
  std::size_t degenerate = 0;  ///< faces with `|det(a, b, c)| <= 1e-14`, `det = a . ((b - a) x (c - a))`
  double degree = 0;           ///< signed spherical area / 4 pi, relative to the input orientation
  bool inward_oriented = false;  ///< the input faces point inward (negative signed volume)
  double max_norm_error = 0;   ///< max over points of `| |x| - 1 |`; infinite if a point is not finite

  /// `sigma_max / sigma_min` (>= 1) of the affine map from the input triangle to the chord
  /// triangle, each in its own plane: 1 for a similarity.
  Summary quasi_conformal;
  /// Mean over the three corners of `|angle_chord - angle_input|`, in degrees. The angles are
  /// those of the chord triangle, not the (larger) spherical angles of the geodesic triangle.
  Summary angle_error;
  /// `|log(r)|` with `r = (spherical area / 4 pi) / (input area / total input area)` and the
  /// spherical area signed by the input orientation (flipped faces have no logarithm and are
  /// left out). 0 when every face keeps its share of the area.
  Summary log_area_ratio;
  /// Min over faces of the ratio `r` above; negative when some face is flipped.
  double min_area_ratio = 0;

  /// Stretch (Sander et al., 2001) of the map from the parameter domain (the chord
  /// triangles) to the surface (the input triangles). Both are first scaled to total area
  /// 4 pi, as Sander et al. normalize the parameter and surface areas to the same total, so
  /// that an isometry up to scale has stretch 1. With `Gamma >= gamma` the singular values of
  /// that map on a face: `l2_stretch = sqrt(sum A_in (Gamma^2 + gamma^2) / 2 / sum A_in)`,
  /// with `A_in` the input area. Faces with a degenerate input or chord triangle (infinite
  /// `Gamma`) are left out, like non-finite values in a `Summary`.
  double l2_stretch = 0;
  /// Max over faces of `Gamma` (see `l2_stretch`).
  double linf_stretch = 0;

  /// True if no face is flipped or degenerate, the degree is 1 (to 1e-6) and every point is
  /// on the unit sphere (to 1e-12), which is the validity contract of `Result`.
  bool is_valid() const
  {
    return internal::is_valid_map(flipped, degenerate, degree, max_norm_error);
  }
};

namespace internal {

/// One face's value of a figure with its weight (the input area).
struct Weighted_value
{
  double value;
  double weight;
};

/// The area-weighted statistics of `values`, skipping the non-finite ones. Sorting makes it
/// O(n log n); `values` is reordered.
inline Summary summarize(std::vector<Weighted_value>& values)
{
  Summary s;
  values.erase(std::remove_if(values.begin(), values.end(),
                              [](const Weighted_value& v) { return !std::isfinite(v.value); }),
               values.end());
  if(values.empty())
    return s;
  std::sort(values.begin(), values.end(),
            [](const Weighted_value& l, const Weighted_value& r) { return l.value < r.value; });
  double total = 0, weighted = 0;
  for(const Weighted_value& v : values) {
    total += v.weight;
    weighted += v.weight * v.value;
  }
  s.mean = total > 0 ? weighted / total : 0;
  s.max = values.back().value;
  s.percentile_95 = s.max;  // also the answer if rounding keeps the running sum below 95%
  double running = 0;
  for(const Weighted_value& v : values) {
    running += v.weight;
    if(running >= 0.95 * total) {
      s.percentile_95 = v.value;
      break;
    }
  }
  return s;
}

/// The edge vectors `p1 - p0` and `p2 - p0` as columns, in 2D coordinates of the triangle's
/// own plane with the first edge along the x axis. The determinant is twice the area, never
/// negative: orientation is judged by `det(a, b, c)`, not here.
inline Eigen::Matrix2d planar_edges(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2)
{
  const Eigen::Vector3d u = p1 - p0, v = p2 - p0;
  const double length = u.norm();
  Eigen::Matrix2d e;
  e << length, u.dot(v) / length,
       0,      u.cross(v).norm() / length;
  return e;
}

/// Singular values `(sigma_max, sigma_min)` of a 2x2 matrix, in closed form. `sigma_min` is
/// taken as `|det| / sigma_max` because the difference formula loses its digits when the
/// matrix is nearly singular.
inline std::pair<double, double> singular_values(const Eigen::Matrix2d& m)
{
  const double e = (m(0, 0) + m(1, 1)) / 2, f = (m(0, 0) - m(1, 1)) / 2;
  const double g = (m(1, 0) + m(0, 1)) / 2, h = (m(1, 0) - m(0, 1)) / 2;
  const double largest = std::hypot(e, h) + std::hypot(f, g);
  return {largest, std::abs(m.determinant()) / largest};
}

/// The angle of the triangle at `p`, between the edges to `q` and `r`; 0, not NaN, for a
/// zero-length edge.
inline double corner_angle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r)
{
  const Eigen::Vector3d u = q - p, v = r - p;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

/// Mean over the corners of `|angle(chord) - angle(input)|`, in degrees.
inline double angle_error(const std::array<Eigen::Vector3d, 3>& input, const std::array<Eigen::Vector3d, 3>& chord)
{
  double sum = 0;
  for(int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    sum += std::abs(corner_angle(chord[i], chord[j], chord[k]) - corner_angle(input[i], input[j], input[k]));
  }
  return sum / 3 * 180 / M_PI;
}

/// Total area of the chord triangles, to scale them to total area 4 pi for the stretch.
inline double chord_area(const Faces& faces, const Points& x)
{
  double area = 0;
  for(const auto& t : faces)
    area += 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
  return area;
}

/// The per-face values of every figure, gathered for the summaries.
struct Face_figures
{
  std::vector<Weighted_value> quasi_conformal, angle_error, log_area_ratio;
  double stretch_sum = 0, stretch_weight = 0, linf_stretch = 0;
};

/// Adds face `f`; the soup's points and the chord triangles both have total area 4 pi once
/// the chord triangles are multiplied by `chord_scale`, so area shares are plain ratios.
inline void add_face(const Triangle_soup& soup, const Points& x, std::size_t f, double chord_scale, Face_figures& out)
{
  const auto& t = soup.faces[f];
  const std::array<Eigen::Vector3d, 3> input{soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]};
  const std::array<Eigen::Vector3d, 3> chord{x[t[0]], x[t[1]], x[t[2]]};
  const double area = soup.face_area(f);

  const double ratio = signed_spherical_area(chord[0], chord[1], chord[2]) / area;
  out.log_area_ratio.push_back({std::abs(std::log(ratio)), area});
  out.angle_error.push_back({angle_error(input, chord), area});

  // Input -> chord is J = C E^-1; its inverse, chord -> input, has singular values 1/sigma.
  const Eigen::Matrix2d jacobian = planar_edges(chord[0], chord[1], chord[2]) *
                                   planar_edges(input[0], input[1], input[2]).inverse();
  const std::pair<double, double> sigma = singular_values(jacobian);
  out.quasi_conformal.push_back({sigma.first / sigma.second, area});
  const double big = 1 / (chord_scale * sigma.second), small = 1 / (chord_scale * sigma.first);
  if(std::isfinite(big) && std::isfinite(small)) {
    out.stretch_sum += area * (big * big + small * small) / 2;
    out.stretch_weight += area;
    out.linf_stretch = std::max(out.linf_stretch, big);
  }
}

/// The report of the map `x` of `soup`, whose faces are already oriented outward.
inline Distortion_report measure_soup(const Triangle_soup& soup, const Points& x)
{
  Distortion_report report;
  report.faces = soup.faces.size();
  report.inward_oriented = soup.inward;
  // The soup's faces are reversed for inward input, so the check is already relative to
  // the input orientation.
  const Map_validity validity = check_map(soup.faces, x);
  report.flipped = validity.flipped;
  report.degenerate = validity.degenerate;
  report.degree = validity.degree;
  report.max_norm_error = validity.finite ? validity.max_norm_error : std::numeric_limits<double>::infinity();

  Face_figures figures;
  const double chord_scale = std::sqrt(4 * M_PI / chord_area(soup.faces, x));
  for(std::size_t f = 0; f < soup.faces.size(); ++f)
    add_face(soup, x, f, chord_scale, figures);
  report.quasi_conformal = summarize(figures.quasi_conformal);
  report.angle_error = summarize(figures.angle_error);
  report.log_area_ratio = summarize(figures.log_area_ratio);
  const double smallest = min_area_ratio(soup, x);
  report.min_area_ratio = std::isfinite(smallest) ? smallest : 0;
  if(figures.stretch_weight > 0)
    report.l2_stretch = std::sqrt(figures.stretch_sum / figures.stretch_weight);
  report.linf_stretch = figures.linf_stretch;
  return report;
}


} // namespace internal

/// \ingroup PkgSphericalParameterizationRef
/// Validity and distortion of the map sending `input_points[i]` to `sphere_points[i]`, for the
/// triangles `faces` (indices into both arrays) as the user oriented them. This is the form the
/// solver and the benchmark work on. Runs in O(F log F) for F faces.
/// \pre the arrays have the same size, the indices are in range and the input has positive area.
inline Distortion_report measure_distortion(const std::vector<Eigen::Vector3d>& input_points,
                                            const std::vector<Eigen::Vector3d>& sphere_points,
                                            const std::vector<std::array<int, 3>>& faces)
{
  CGAL_precondition(input_points.size() == sphere_points.size());
  if(faces.empty())
    return Distortion_report();
  // The soup detects the orientation, reverses inward faces and scales the input to area 4 pi.
  const internal::Triangle_soup soup = internal::make_triangle_soup(input_points, faces);
  return internal::measure_soup(soup, sphere_points);
}

/// \ingroup PkgSphericalParameterizationRef
/// Validity and distortion of the map `sphere_map` of the closed triangle mesh `tm` onto the
/// unit sphere (see `Distortion_report` for the definitions). Points of any kernel are read
/// through `CGAL::to_double()`.
///
/// \tparam TriangleMesh a model of `FaceListGraph`
/// \tparam SphereMap a readable property map `vertex_descriptor -> Point_3`
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map} the input positions;
///     default `get(CGAL::vertex_point, tm)` \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \pre `tm` is a triangle mesh with positive area.
template <class TriangleMesh, class SphereMap, class NamedParameters = CGAL::parameters::Default_named_parameters>
Distortion_report measure_distortion(const TriangleMesh& tm, const SphereMap& sphere_map,
                                     const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  const auto vpm = choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point),
                                    get_const_property_map(CGAL::vertex_point, tm));

  const internal::Indexed_triangles<TriangleMesh> mesh = internal::indexed_triangles(tm);
  std::vector<Eigen::Vector3d> points, sphere_points;
  for(vertex_descriptor v : mesh.vertices) {
    points.push_back(internal::to_eigen(get(vpm, v)));
    sphere_points.push_back(internal::to_eigen(get(sphere_map, v)));
  }
  return measure_distortion(points, sphere_points, mesh.triangles);
}

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_MEASURE_DISTORTION_H
