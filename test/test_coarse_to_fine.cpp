// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The parts of the robust pipeline's coarse-to-fine solve, each against the property it is
// there for: the progressive mesh (a closed genus-0 manifold at every level, undone exactly,
// area shares kept), the fans of the vertex splits, the placement of a split vertex in the
// kernel of its fan, the mean value point, the Moebius boost, the floor patch, the
// two-grid cycle of the input's first step, the Newton system in the tangent charts, the
// stopping rules, and the choice of a level's next stage.
// Meshes built in code only (the `fast` CTest label, also run under the sanitizers).
// Usage: test_coarse_to_fine [ignored arguments]

#include <CGAL/Spherical_parameterization/Balanced_energy.h>
#include <CGAL/Spherical_parameterization/Dirichlet_energy.h>
#include <CGAL/Spherical_parameterization/Sparse_solver_traits.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/Coarse_to_fine.h>
#include <CGAL/Spherical_parameterization/internal/pipeline/Floor_patch.h>
#include <CGAL/Spherical_parameterization/internal/pipeline/next_stage.h>
#include <CGAL/Spherical_parameterization/internal/newton/Newton_solver.h>
#include <CGAL/Spherical_parameterization/internal/newton/Tangent_newton_system.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/Progressive_mesh.h>
#include <CGAL/Spherical_parameterization/internal/energies/Spherical_energy.h>
#include <CGAL/Spherical_parameterization/internal/hierarchy/kernel_placement.h>
#include <CGAL/Spherical_parameterization/internal/validity/map_validity.h>
#include <CGAL/Spherical_parameterization/internal/newton/mobius_boost.h>
#include <CGAL/Spherical_parameterization/remesh_on_icosphere.h>

#include "test_support.h"

#include <CGAL/tags.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace SP = CGAL::Spherical_parameterization;
namespace I = SP::internal;
using namespace test_support;

namespace {

// A subdivided icosahedron with its vertices pushed radially by up to 5%: the points'
// central projection is a map.
I::Triangle_soup bumpy_icosphere(int level)
{
  SP::Icosphere sphere = SP::make_icosphere(level);
  for(auto& p : sphere.points) p *= 1 + 0.05 * uniform(-1, 1);
  return I::make_triangle_soup(sphere.points, sphere.faces);
}

// A subdivided icosahedron with its vertices pushed radially by `bumps`, and a long thin
// finger grown out of it (a protrusion, like a leg), so that the decimation meets both.
I::Triangle_soup bumpy_sphere_with_finger(int level, double bumps)
{
  SP::Icosphere sphere = SP::make_icosphere(level);
  I::Points p = std::move(sphere.points);
  I::Faces f = std::move(sphere.faces);
  // The finger: the vertices within a small cap around +z are pulled out along z.
  for(auto& q : p) {
    const double cap = q.z() - 0.9;
    if(cap > 0) q *= 1 + 40 * cap;
    q *= 1 + bumps * uniform(-1, 1);
  }
  return I::make_triangle_soup(p, f);
}

// V - E + F and that every directed edge has exactly one reverse: a closed 2-manifold sphere.
bool is_closed_manifold_sphere(const I::Faces& faces, const std::vector<char>& face_alive, std::size_t vertices,
                               std::string& why)
{
  std::map<std::pair<int, int>, int> directed;
  std::size_t count = 0;
  for(std::size_t k = 0; k < faces.size(); ++k) {
    if(!face_alive[k]) continue;
    ++count;
    const auto& t = faces[k];
    if(t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) { why = "a face repeats a vertex"; return false; }
    for(int i = 0; i < 3; ++i)
      ++directed[{t[i], t[(i + 1) % 3]}];
  }
  for(const auto& [edge, n] : directed)
    if(n != 1 || !directed.count({edge.second, edge.first})) { why = "an edge is not shared by two faces"; return false; }
  const long euler = long(vertices) - long(directed.size() / 2) + long(count);
  if(euler != 2) { why = "Euler characteristic " + std::to_string(euler); return false; }
  return true;
}

double sum_alive(const std::vector<double>& values, const std::vector<char>& alive)
{
  double s = 0;
  for(std::size_t k = 0; k < values.size(); ++k)
    if(alive[k]) s += values[k];
  return s;
}

void test_progressive_mesh()
{
  const I::Triangle_soup soup = bumpy_sphere_with_finger(3, 0.02);
  const I::Progressive_mesh pm(soup, 8);
  report("progressive mesh: collapses down to the target (" + std::to_string(soup.number_of_vertices()) + " -> " +
           std::to_string(pm.number_of_coarse_vertices()) + " vertices)",
         pm.number_of_coarse_vertices() <= 8);

  I::Refinement refinement(pm);
  bool manifold = true, area_kept = true, fans_ok = true;
  std::string why;
  I::Fan fan;
  const std::size_t checks = 12, stride = std::max<std::size_t>(1, pm.splits().size() / checks);
  for(std::size_t k = 0; refinement.splits_left() > 0; ++k) {
    if(k % stride == 0) {
      manifold = manifold && is_closed_manifold_sphere(refinement.faces(), refinement.face_alive(),
                                                       refinement.number_of_vertices(), why);
      const double total = sum_alive(refinement.represented_areas(), refinement.face_alive());
      area_kept = area_kept && std::abs(total - 4 * M_PI) < 1e-9 * 4 * M_PI;
    }
    const I::Vertex_split& split = refinement.split_next();
    refinement.fan(split, fan);
    // Every pair (p, q) is a face (u, p, q) of the mesh, in this orientation.
    std::set<std::array<int, 3>> faces;
    for(std::size_t f = 0; f < refinement.faces().size(); ++f)
      if(refinement.face_alive()[f]) {
        auto t = refinement.faces()[f];
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        faces.insert(t);
      }
    for(const auto& [p, q] : fan) {
      std::array<int, 3> t{split.removed, p, q};
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      fans_ok = fans_ok && faces.count(t) == 1;
    }
    fans_ok = fans_ok && fan.size() >= 3;
  }
  report("progressive mesh: every level is a closed 2-manifold of Euler characteristic 2", manifold, why);
  report("progressive mesh: the areas faces stand for add up to the input's 4 pi at every level", area_kept);
  report("refinement: the fan of a split vertex lists its faces (u, p, q), oriented", fans_ok);

  bool same = refinement.number_of_vertices() == soup.number_of_vertices();
  for(std::size_t f = 0; f < soup.faces.size(); ++f)
    same = same && refinement.face_alive()[f] && refinement.faces()[f] == soup.faces[f] &&
           std::abs(refinement.represented_areas()[f] - soup.face_area(f)) <= 1e-12;
  report("refinement: undoing every collapse gives back the input's faces and areas exactly", same);

  std::vector<int> to_input;
  const I::Triangle_soup coarse = I::level_soup(soup, I::Refinement(pm), to_input);
  double oriented = 0;  // signed volume of the coarse level: the input's outward orientation
  for(const auto& t : coarse.faces)
    oriented += coarse.points[t[0]].dot(coarse.points[t[1]].cross(coarse.points[t[2]]));
  report("level soup: the coarsest level keeps the input's outward orientation", oriented > 0);
}

// A fan around `center` on the sphere: `k` ring points at angular radius `radius`, angles
// jittered, and the radius of every other point scaled by `reflex` (< 1: a star, not convex).
I::Points ring_points(const Eigen::Vector3d& center, int k, double radius, double reflex)
{
  const Eigen::Matrix<double, 3, 2> basis = I::tangent_basis(center);
  I::Points ring;
  for(int i = 0; i < k; ++i) {
    const double angle = 2 * M_PI * (i + uniform(-0.2, 0.2)) / k;
    const double r = radius * (i % 2 ? reflex : 1.0);
    ring.push_back((center + std::tan(r) * (basis * Eigen::Vector2d(std::cos(angle), std::sin(angle)))).normalized());
  }
  return ring;
}

I::Fan fan_of_ring(int first, int k)
{
  I::Fan fan;
  for(int i = 0; i < k; ++i)
    fan.push_back({first + i, first + (i + 1) % k});
  return fan;
}

void test_kernel_placement()
{
  int star_inside = 0, convex_inside = 0, empty_reported = 0;
  const int trials = 40;
  for(int n = 0; n < trials; ++n) {
    const Eigen::Vector3d center = random_unit_vector();
    const int k = 5 + n % 6;
    // A bad guess, outside the ring, so the kernel centroid has to be found.
    const Eigen::Vector3d outside = ring_points(center, 1, 0.3, 1.0)[0];
    I::Points convex = ring_points(center, k, 0.05, 1.0);
    convex_inside += I::fan_clearance(I::place_in_kernel(convex, fan_of_ring(0, k), outside), convex, fan_of_ring(0, k)) > 0;
    I::Points star = ring_points(center, k + k % 2, 0.05, 0.35);
    const I::Fan star_fan = fan_of_ring(0, k + k % 2);
    star_inside += I::fan_clearance(I::place_in_kernel(star, star_fan, outside), star, star_fan) > 0;
    // A bow tie, (0,0) (1,1) (1,0) (0,1): no point sees all its edges from the left.
    I::Points bow_tie;
    for(const Eigen::Vector2d& corner : {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)})
      bow_tie.push_back((center + 0.05 * (I::tangent_basis(center) * corner)).normalized());
    const I::Fan bow_tie_fan = fan_of_ring(0, 4);
    empty_reported += !(I::fan_clearance(I::place_in_kernel(bow_tie, bow_tie_fan, center), bow_tie, bow_tie_fan) > 0);
  }
  report("kernel placement: inside every convex fan, from a guess outside it", convex_inside == trials,
         str(convex_inside) + " of " + str(trials));
  report("kernel placement: inside every star-shaped, non-convex fan", star_inside == trials,
         str(star_inside) + " of " + str(trials));
  report("kernel placement: a fan with an empty kernel is reported (clearance not positive)", empty_reported == trials,
         str(empty_reported) + " of " + str(trials));
}

void test_mean_value_point()
{
  // A planar input fan and its image by a small similarity onto the sphere near `center`:
  // the mean value point reproduces the image of the centre vertex (linear precision).
  double worst = 0;
  for(int n = 0; n < 20; ++n) {
    const int k = 4 + n % 7;
    I::Points input{Eigen::Vector3d::Zero()};
    for(int i = 0; i < k; ++i) {
      const double angle = 2 * M_PI * (i + uniform(-0.3, 0.3)) / k;
      input.push_back(uniform(0.5, 2.0) * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0));
    }
    const Eigen::Vector3d center = random_unit_vector();
    const Eigen::Matrix<double, 3, 2> basis = I::tangent_basis(center);
    const double scale = 1e-3;
    I::Points sphere(input.size());
    for(std::size_t i = 0; i < input.size(); ++i)
      sphere[i] = center + scale * (basis * input[i].head<2>());  // on the tangent plane
    const I::Fan fan = fan_of_ring(1, k);
    const Eigen::Vector3d got = I::mean_value_point(0, input, sphere, fan);
    worst = std::max(worst, (got - center.normalized()).norm() / scale);
  }
  report("mean value point: reproduces the centre of a planar fan mapped by a similarity (rel 1e-9)", worst < 1e-9,
         "relative error " + str(worst));

  // A flat-folded input fan, as marching cubes leave some: its four faces in one plane, the
  // first turning by theta and the three others back, so the first corner is half the total
  // angle. Scaled to 2 pi, that corner is pi and its weight tan(pi / 2) of either sign; the
  // point must stay by its ring all the same.
  int near_ring = 0;
  const int trials = 40;
  for(int n = 0; n < trials; ++n) {
    const Eigen::Vector3d normal = random_unit_vector();
    const Eigen::Matrix<double, 3, 2> plane = I::tangent_basis(normal);
    const double theta = uniform(2.0, 3.05), back = uniform(0.3, 0.7) * theta, last = uniform(0.1, 0.9) * back;
    I::Points input{Eigen::Vector3d::Zero()};
    for(const double angle : {0.0, theta, back, last})
      input.push_back(uniform(0.5, 2.0) * (plane * Eigen::Vector2d(std::cos(angle), std::sin(angle))));
    const Eigen::Vector3d center = random_unit_vector();
    I::Points sphere{center};
    for(const Eigen::Vector3d& p : ring_points(center, 4, 0.05, 1.0))
      sphere.push_back(p);
    const Eigen::Vector3d got = I::mean_value_point(0, input, sphere, fan_of_ring(1, 4));
    near_ring += got.allFinite() && got.dot(center) > std::cos(0.1);
  }
  report("mean value point: by its ring for a flat-folded fan (a corner of half the total angle)",
         near_ring == trials, str(near_ring) + " of " + str(trials));
}

void test_mobius_boost()
{
  double norm_error = 0, derivative_error = 0;
  int orientation_kept = 0;
  const int trials = 50;
  for(int n = 0; n < trials; ++n) {
    const Eigen::Vector3d b = uniform(0, 0.6) * random_unit_vector();
    const Eigen::Vector3d x = random_unit_vector();
    norm_error = std::max(norm_error, std::abs(I::mobius_boost(b, x).norm() - 1));
    const double h = 1e-6;
    const Eigen::Vector3d derivative = (I::mobius_boost(h * b, x) - I::mobius_boost(-h * b, x)) / (2 * h);
    derivative_error = std::max(derivative_error, (derivative - 2 * (b - b.dot(x) * x)).norm());
    // A small triangle keeps its orientation.
    const Eigen::Matrix<double, 3, 2> basis = I::tangent_basis(x);
    const Eigen::Vector3d p = x, q = (x + 1e-3 * basis.col(0)).normalized(), r = (x + 1e-3 * basis.col(1)).normalized();
    const Eigen::Vector3d mp = I::mobius_boost(b, p), mq = I::mobius_boost(b, q), mr = I::mobius_boost(b, r);
    orientation_kept += (p.dot(q.cross(r)) > 0) == (mp.dot(mq.cross(mr)) > 0);
  }
  report("Moebius boost: maps the sphere onto itself (1e-14)", norm_error < 1e-14, str(norm_error));
  report("Moebius boost: its derivative at 0 is 2 (b - (b.x) x) (1e-8)", derivative_error < 1e-8, str(derivative_error));
  report("Moebius boost: keeps the orientation of small triangles", orientation_kept == trials);

  // The Dirichlet energy of a round sphere's own map is lowest unboosted; a boosted copy
  // comes back by boost steps alone, the energy going down at each.
  const I::Triangle_soup soup = bumpy_sphere_with_finger(2, 0.0);
  I::Triangle_soup round = soup;
  for(auto& p : round.points) p.normalize();
  const I::Spherical_energy<SP::Dirichlet_energy> energy(round, SP::Dirichlet_energy());
  I::Points x = round.points;
  for(auto& p : x) p = I::mobius_boost(Eigen::Vector3d(0.3, -0.2, 0.1), p);
  double e = energy.value(x);
  const double start = e;
  bool decreasing = true, reported = true;
  for(int step = 0; step < 8; ++step) {
    const double before = e;
    if(!I::boost_step(x, [&](const I::Points& y) { return energy.value(y); }, e)) break;
    decreasing = decreasing && e < before;
    reported = reported && e == energy.value(x);
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for(const auto& p : x) centroid += p;
  centroid /= double(x.size());
  const double unboosted = energy.value(round.points);
  report("boost steps: the energy decreases at every step", decreasing);
  report("boost steps: the energy they return is the boosted map's", reported);
  report("boost steps: a boosted map comes back to the unboosted energy (rel 1e-6)",
         (e - unboosted) <= 1e-6 * unboosted, "start " + str(start, 8) + ", end " + str(e, 8) + ", unboosted " + str(unboosted, 8));

  // An energy quartic around the map boosted by 0.5 towards e_z: the Newton step of the finite
  // differences goes less than half the way (0.22 on 2000 points spread over the sphere); one
  // boost step must go past 0.3 by doubling its step while the energy keeps falling (0.44
  // there), and report the map's energy.
  I::Points spread;  // a Fibonacci spiral
  for(int i = 0; i < 2000; ++i) {
    const double z = -1 + 2 * (i + 0.5) / 2000, r = std::sqrt(1 - z * z), angle = 2.39996 * i;
    spread.emplace_back(r * std::cos(angle), r * std::sin(angle), z);
  }
  I::Points target = spread;
  for(auto& p : target) p = I::mobius_boost(Eigen::Vector3d(0, 0, 0.5), p);
  const auto quartic = [&](const I::Points& y) {
    double sum = 0;
    for(std::size_t v = 0; v < y.size(); ++v) sum += (y[v] - target[v]).squaredNorm() * (y[v] - target[v]).squaredNorm();
    return sum;
  };
  I::Points slid = spread, boosted_03 = spread;
  for(auto& p : boosted_03) p = I::mobius_boost(Eigen::Vector3d(0, 0, 0.3), p);
  double slide = quartic(slid);
  const bool moved = I::boost_step(slid, quartic, slide);
  report("boost steps: one step follows a slide past its Newton step (energy under that of a boost of 0.3)",
         moved && slide < quartic(boosted_03) && slide == quartic(slid),
         "after one step " + str(slide, 8) + ", boost of 0.3 " + str(quartic(boosted_03), 8));
}

// The floor patch: the neighbourhood of the faces a fold barrier holds, minimized with the
// rest of the map held. It holds every face around its free vertices, so that its energy
// changes as the whole map's does; its held vertices do not move; the barrier lifts its faces.
void test_floor_patch()
{
  const I::Triangle_soup soup = bumpy_sphere_with_finger(3, 0.05);
  const I::Points x = SP::make_icosphere(3).points;  // the bumps and the finger are radial: a map
  using Newton = I::Newton_solver<SP::Eigen_sparse_LDLT_traits, CGAL::Sequential_tag>;
  Newton whole(soup);
  auto face_scale = [&](const I::Triangle_soup& s, const I::Points& y, std::size_t f) {
    const auto& t = s.faces[f];
    const SP::Chord_triangle<double> chord(y[t[0]], y[t[1]], y[t[2]]);
    return I::Fold_barrier::scale(chord, chord.determinant(), I::Fold_barrier::Face_data(s.reference_triangle(f)));
  };
  std::vector<double> scales;
  for(std::size_t f = 0; f < soup.faces.size(); ++f)
    scales.push_back(face_scale(soup, x, f));
  std::sort(scales.begin(), scales.end());
  const double floor = 2 * scales[4];  // the finger's faces, squeezed by the projection
  const std::vector<int> under = whole.faces_under_floor(x, floor);
  report("floor patch: the faces under the floor are found", under.size() >= 5 && under.size() < soup.faces.size() / 4,
         str(under.size()) + " of " + str(soup.faces.size()));

  const I::Floor_patch patch = I::make_floor_patch(soup, under, 2);
  std::vector<char> is_free(soup.number_of_vertices(), 0);
  for(std::size_t i = 0; i < patch.free_vertices; ++i) is_free[patch.to_input[i]] = 1;
  bool seeds_free = true;
  for(int f : under)
    for(int v : soup.faces[f]) seeds_free = seeds_free && is_free[v];
  std::set<std::array<int, 3>> around_free, in_patch;
  for(const auto& t : soup.faces)
    if(is_free[t[0]] || is_free[t[1]] || is_free[t[2]]) around_free.insert(t);
  for(const auto& t : patch.soup.faces)
    in_patch.insert({patch.to_input[t[0]], patch.to_input[t[1]], patch.to_input[t[2]]});
  report("floor patch: the vertices of the faces under the floor are free", seeds_free);
  report("floor patch: its faces are exactly the faces around its free vertices", in_patch == around_free,
         str(in_patch.size()) + " against " + str(around_free.size()));
  report("floor patch: some vertices are held, and fewer are free than in the mesh",
         patch.free_vertices < patch.to_input.size() && patch.free_vertices < soup.number_of_vertices());

  I::Points y(patch.to_input.size());
  for(std::size_t i = 0; i < y.size(); ++i) y[i] = x[patch.to_input[i]];
  const I::Points start = y;
  const I::Spherical_energy<SP::Dirichlet_energy> patch_energy(patch.soup, SP::Dirichlet_energy());
  const I::Spherical_energy<SP::Dirichlet_energy> whole_energy(soup, SP::Dirichlet_energy());
  Newton solver(patch.soup, patch.free_vertices);
  I::Newton_options options;
  options.keep_fold_free = true;
  options.fold_floor = floor;
  auto no_visitor = [](const SP::Progress&) { return true; };
  const I::Newton_outcome out = solver.minimize(patch_energy, y, options, no_visitor);

  bool held_kept = true;
  for(std::size_t i = patch.free_vertices; i < y.size(); ++i) held_kept = held_kept && y[i] == start[i];
  I::Points x_after = x;
  for(std::size_t i = 0; i < y.size(); ++i) x_after[patch.to_input[i]] = y[i];
  const double whole_change = whole_energy.value(x_after) - whole_energy.value(x);
  const double patch_change = patch_energy.value(y) - patch_energy.value(start);
  double lowest_before = std::numeric_limits<double>::infinity(), lowest_after = lowest_before;
  for(std::size_t f = 0; f < patch.soup.faces.size(); ++f) {
    lowest_before = std::min(lowest_before, face_scale(patch.soup, start, f));
    lowest_after = std::min(lowest_after, face_scale(patch.soup, y, f));
  }
  report("floor patch: the solve ran and stopped converged", out.iterations > 0 && out.stop == I::Newton_stop::CONVERGED,
         str(out.iterations) + " iterations, stop " + str(int(out.stop)));
  report("floor patch: the held vertices did not move", held_kept);
  report("floor patch: the whole map's energy changes as the patch's (1e-12)",
         std::abs(whole_change - patch_change) <= 1e-12 * whole_energy.value(x),
         str(whole_change, 8) + " against " + str(patch_change, 8));
  report("floor patch: fold-free, and its lowest face lifted towards the floor",
         I::count_bad_faces(patch.soup.faces, y) == 0 && lowest_after > lowest_before && lowest_after > 0.5 * floor,
         "lowest share of the floor " + str(lowest_before / floor) + " -> " + str(lowest_after / floor));
}

// The splits of one pass are placed in parallel (`Coarse_to_fine::refine()`): the batches of
// `Refinement::independent_splits()` are independent (no vertex of a batch in the ring of
// another of the batch), and the parallel placement gives the sequential one's points, bit
// for bit. Icosphere level 6 (41k vertices): batches above TBB's grain of 512.
void test_parallel_splits()
{
  using Newton = I::Newton_solver<SP::Eigen_sparse_LDLT_traits, CGAL::Sequential_tag>;
  const I::Triangle_soup soup = bumpy_icosphere(6);
  const I::Progressive_mesh pm(soup, 200);

  I::Refinement refinement(pm);
  std::vector<int> batch_of(soup.number_of_vertices(), -1);  // of each split vertex
  bool independent = true;
  int batches = 0;
  std::size_t largest = 0;
  I::Fan fan;
  for(; refinement.splits_left() > 0; ++batches) {
    const std::size_t batch = refinement.independent_splits();
    largest = std::max(largest, batch);
    std::vector<I::Fan> fans;
    for(std::size_t k = 0; k < batch; ++k) {
      const I::Vertex_split& split = refinement.split_next();
      batch_of[split.removed] = batches;
      refinement.fan(split, fan);
      fans.push_back(fan);
    }
    for(const I::Fan& f : fans)
      for(const auto& [p, q] : f)
        independent = independent && batch_of[p] != batches && batch_of[q] != batches;
  }
  report("refinement: the splits of each batch are independent (" + std::to_string(batches) + " batches, the largest " +
           std::to_string(largest) + ")",
         independent && batches > 1 && largest > 512);

#ifdef CGAL_LINKED_WITH_TBB
  auto refined = [&](auto concurrency) {
    I::Coarse_to_fine<Newton, decltype(concurrency)> levels(soup, pm, 3);
    I::Points x(soup.number_of_vertices(), Eigen::Vector3d::Zero());
    for(std::size_t v = 0; v < x.size(); ++v)
      if(pm.coarse_vertex_alive()[v])
        x[v] = soup.points[v].normalized();
    while(levels.refine(x)) {
    }
    return x;
  };
  const I::Points sequential = refined(CGAL::Sequential_tag()), parallel = refined(CGAL::Parallel_tag());
  report("refinement: the splits placed in parallel land where the sequential placement puts them", sequential == parallel);
#else
  skip("[parallel splits]", "built without TBB");
#endif
}

// The two-grid cycle of the input's first step (`Coarse_to_fine::coarse_correction()`): its
// restriction is the transpose of its prolongation, and after the splits from a converged
// level its step lowers the energy below block Jacobi's alone, the smooth error included.
void test_two_grid_cycle()
{
  using Newton = I::Newton_solver<SP::Eigen_sparse_LDLT_traits, CGAL::Sequential_tag>;
  const I::Triangle_soup soup = bumpy_icosphere(4);
  const I::Progressive_mesh pm(soup, 200);
  I::Coarse_to_fine<Newton> levels(soup, pm, 3, true);
  const SP::Dirichlet_energy dirichlet;
  auto no_visitor = [](const SP::Progress&) { return true; };
  I::Newton_options options;
  options.tolerance = 1e-9;
  I::Points x(soup.number_of_vertices(), Eigen::Vector3d::Zero()), level_x;
  // Every level solved from the splits of the last; the coarsest from its points' central
  // projection (the bumps are radial: a map).
  I::Level<Newton>* level = levels.level();
  level_x = level->soup.points;
  for(auto& p : level_x) p.normalize();
  bool converged = true;
  bool last_flagged = true;  // `last_before_input()` true exactly on the level the input follows
  std::size_t levels_solved = 0;
  for(;; ++levels_solved) {
    const I::Spherical_energy<SP::Dirichlet_energy> energy(level->soup, dirichlet);
    converged = converged && level->solver->minimize(energy, level_x, options, no_visitor).stop == I::Newton_stop::CONVERGED;
    level->scatter(level_x, x);
    const bool flagged = levels.last_before_input();
    const bool into_input = !levels.refine(x) || !(level = levels.level());
    last_flagged = last_flagged && flagged == into_input;
    if(into_input)
      break;
    level->gather(x, level_x);
  }
  report("two-grid cycle: every level before the input converged", converged);
  report("coarse to fine: only the last of " + std::to_string(levels_solved + 1) + " levels is flagged the last before the input",
         last_flagged && levels_solved > 0);

  // The restriction, as the transpose of the prolongation: <P a, b> = <a, P^T b>.
  const std::size_t n = soup.number_of_vertices();
  std::vector<Eigen::Vector3d> a(n), b(n);
  for(std::size_t v = 0; v < n; ++v) {
    a[v] = Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    b[v] = Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
  }
  std::vector<Eigen::Vector3d> prolongated = a, restricted = b;
  levels.split_rings().spread(prolongated);
  levels.split_rings().transpose_spread(restricted);
  double left = 0, right = 0;
  for(std::size_t v = 0; v < n; ++v) {
    left += prolongated[v].dot(b[v]);
    right += a[v].dot(restricted[v]);
  }
  report("two-grid cycle: the restriction is the transpose of the prolongation", std::abs(left - right) <= 1e-12 * std::abs(left),
         str(left, 15) + " against " + str(right, 15));

  // One smoothing step from the splits, with and without the coarse correction.
  const I::Spherical_energy<SP::Dirichlet_energy> energy(soup, dirichlet);
  const I::Coarse_correction coarse_correction = [&levels](const auto& map, const auto& gradient, auto& step) {
    return levels.coarse_correction(map, gradient, step);
  };
  options.max_iterations = 1;
  options.smoothing_iterations = 1;
  Newton input(soup);
  I::Points jacobi = x, two_grid = x;
  input.minimize(energy, jacobi, options, no_visitor);
  options.coarse_correction = &coarse_correction;
  input.minimize(energy, two_grid, options, no_visitor);
  const double start = energy.value(x), after_jacobi = energy.value(jacobi), after_two_grid = energy.value(two_grid);
  report("two-grid cycle: its step lowers the energy further than block Jacobi's",
         after_two_grid < after_jacobi && after_jacobi < start,
         str(start, 8) + " -> " + str(after_jacobi, 8) + " (block Jacobi), " + str(after_two_grid, 8) + " (two-grid)");
  std::vector<Eigen::Vector3d> unused;
  report("two-grid cycle: the last level is freed after its one use",
         !levels.coarse_correction(x, std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Zero()), unused));
}

// The Newton system in the tangent charts is the exact gradient and Hessian of the energy
// pulled back by the retraction, `u -> E(normalize(x + B u))`: against central differences
// of the energy, with some vertices held (a patch), whose rows and columns it leaves out. Its
// projection of an exact assembly is the projected assembly, bit for bit.
void test_tangent_newton_system()
{
  const I::Triangle_soup soup = bumpy_icosphere(1);
  I::Points x = SP::make_icosphere(1).points;
  for(auto& p : x) p = (p + 0.2 * Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1))).normalized();
  const I::Spherical_energy<SP::Balanced_energy> energy(soup, SP::balanced_energy());
  const std::size_t held = 5, free = soup.number_of_vertices() - held;
  using System = I::Tangent_newton_system<CGAL::Sequential_tag>;
  System system(soup.faces, soup.number_of_vertices(), free);
  system.update_bases(x);
  auto face_jet = [&](std::size_t f, bool& held) {
    held = false;
    return energy.face<SP::Triangle_jet>(f, x);
  };
  system.assemble(x, face_jet, false, false);
  const Eigen::MatrixXd lower = Eigen::MatrixXd(system.matrix());
  const Eigen::MatrixXd hessian = lower.selfadjointView<Eigen::Lower>();

  const int size = int(2 * free);
  I::Points moved(x.size());
  auto pulled_back = [&](const System::Vector& u) {
    system.step_to(x, u, 1, moved);
    return energy.value(moved);
  };
  auto unit = [&](int i) { return System::Vector(System::Vector::Unit(size, i)); };
  const double h = 1e-4;
  double gradient_error = 0, hessian_error = 0;
  for(int i = 0; i < size; ++i) {
    const double difference = (pulled_back(h * unit(i)) - pulled_back(-h * unit(i))) / (2 * h);
    gradient_error = std::max(gradient_error, std::abs(difference - system.gradient()[i]));
    for(int j = 0; j <= i; ++j) {
      const System::Vector a = h * unit(i), b = h * unit(j);
      const double second = (pulled_back(a + b) - pulled_back(a - b) - pulled_back(b - a) + pulled_back(-a - b)) / (4 * h * h);
      hessian_error = std::max(hessian_error, std::abs(second - hessian(i, j)));
    }
  }
  gradient_error /= system.gradient().cwiseAbs().maxCoeff();
  hessian_error /= hessian.cwiseAbs().maxCoeff();
  report("tangent Newton system: gradient matches central differences of the pulled back energy (rel 1e-6)",
         gradient_error <= 1e-6 && system.gradient().size() == size, "rel. err. " + str(gradient_error));
  report("tangent Newton system: Hessian matches second differences, retraction term included (rel 1e-5)",
         hessian_error <= 1e-5 && hessian.rows() == size, "rel. err. " + str(hessian_error));

  for(bool drop_rotations : {false, true}) {
    system.assemble(x, face_jet, true, drop_rotations);
    const System::Vector projected_gradient = system.gradient();
    const Eigen::MatrixXd projected = Eigen::MatrixXd(system.matrix());
    system.assemble(x, face_jet, false, drop_rotations);
    system.project_assembled_faces(x, drop_rotations);
    report(std::string("tangent Newton system: an exact assembly projected afterwards is the projected assembly") +
             (drop_rotations ? " (rotations' curvature dropped)" : ""),
           Eigen::MatrixXd(system.matrix()) == projected && system.gradient() == projected_gradient &&
             (projected - lower).norm() > 1e-3 * lower.norm());
  }
}

// The slow capped tail: a fold-free stage stops once its last capped steps gained less than
// half the threshold each on average; not on fewer capped steps, nor on faster gains.
void test_slow_capped_tail()
{
  const std::size_t window = I::capped_tail_window;
  const double threshold = 1e-4;
  auto tail = [&](double gain_per_iteration) {
    std::vector<double> history{10.0};
    for(std::size_t i = 0; i < window + 2; ++i)
      history.push_back(history.back() - gain_per_iteration * threshold);
    return history;
  };
  report("slow capped tail: stops when the capped steps gain 0.45 of the threshold each",
         I::slow_capped_tail(tail(0.45), window, threshold));
  report("slow capped tail: goes on when they gain 0.55 of it each", !I::slow_capped_tail(tail(0.55), window, threshold));
  report("slow capped tail: goes on when fewer of the last steps were capped",
         !I::slow_capped_tail(tail(0.45), window - 1, threshold));
  report("slow capped tail: goes on with too short a history",
         !I::slow_capped_tail(std::vector<double>(window, 10.0), window + 1, threshold));
}

// The choice of the next stage of a level's fold-free minimization, against the design:
// every path of doc/DESIGN.md's "The fold-free minimization of a level", and nothing after
// an interruption.
void test_next_stage()
{
  using SP::Stage;
  auto next = [](Stage done, I::Level_facts f) { return I::next_stage(done, f); };
  auto input = [] { I::Level_facts f; f.is_input = true; return f; };
  I::Level_facts f;

  f = input(); f.fold_free_minimum = true; f.above_floor = true;
  report("next stage: a fold-free minimum above the floor is the level's result", !next(Stage::OPTIMISTIC, f));
  f = I::Level_facts(); f.fold_free_minimum = true; f.few_under_floor = true;
  report("next stage: so is the last coarser level's with few faces under the floor", !next(Stage::OPTIMISTIC, f));
  f = input(); f.fold_free_minimum = true;
  report("next stage: the input's fold-free minimum under the floor goes to the floor patch",
         next(Stage::OPTIMISTIC, f) == Stage::FLOOR_PATCH);
  f = I::Level_facts(); f.fold_free_minimum = true;
  report("next stage: a coarser level's goes to the continuation", next(Stage::OPTIMISTIC, f) == Stage::CONTINUATION);
  f = input(); f.folded = true;
  report("next stage: a folded minimum is untangled locally", next(Stage::OPTIMISTIC, f) == Stage::LOCAL_UNTANGLING);
  f = I::Level_facts(); f.folded = true; f.optimistic_ran = false;
  report("next stage: not after the smoothing step alone: the continuation",
         next(Stage::OPTIMISTIC, f) == Stage::CONTINUATION);
  f = input(); f.folded = true; f.untangled = true;
  report("next stage: the input untangled locally goes to the floor stage", next(Stage::LOCAL_UNTANGLING, f) == Stage::FLOOR);
  f = I::Level_facts(); f.folded = true; f.untangled = true; f.above_floor = true;
  report("next stage: a coarser level untangled above the floor is done", !next(Stage::LOCAL_UNTANGLING, f));
  f = I::Level_facts(); f.folded = true; f.untangled = true;
  report("next stage: under the floor it goes to the continuation",
         next(Stage::LOCAL_UNTANGLING, f) == Stage::CONTINUATION);
  f = input(); f.folded = true;
  report("next stage: a failed local untangling goes to the continuation",
         next(Stage::LOCAL_UNTANGLING, f) == Stage::CONTINUATION);
  report("next stage: the input's continuation ends on the floor stage", next(Stage::CONTINUATION, input()) == Stage::FLOOR);
  report("next stage: a coarser level stops on the continuation's cushion", !next(Stage::CONTINUATION, I::Level_facts()));
  f = input(); f.patch_sufficed = true;
  report("next stage: a sufficient floor patch skips the floor stage", next(Stage::FLOOR_PATCH, f) == Stage::DEEP_FACES);
  report("next stage: else the floor stage follows it", next(Stage::FLOOR_PATCH, input()) == Stage::FLOOR);
  report("next stage: deep faces after the floor stage", next(Stage::FLOOR, input()) == Stage::DEEP_FACES);
  report("next stage: nothing after the deep faces", !next(Stage::DEEP_FACES, input()));
  bool nothing_after_interruption = true;
  for(Stage done : {Stage::OPTIMISTIC, Stage::LOCAL_UNTANGLING, Stage::CONTINUATION, Stage::FLOOR_PATCH, Stage::FLOOR}) {
    f = input(); f.interrupted = true; f.folded = true;
    nothing_after_interruption = nothing_after_interruption && !next(done, f);
  }
  report("next stage: nothing after an interruption", nothing_after_interruption);
}

} // namespace

int main()
{
  rng.seed(7);
  test_progressive_mesh();
  test_kernel_placement();
  test_mean_value_point();
  test_mobius_boost();
  test_floor_patch();
  test_two_grid_cycle();
  test_parallel_splits();
  test_tangent_newton_system();
  test_slow_capped_tail();
  test_next_stage();
  std::cout << passed << " passed, " << failed << " failed" << std::endl;
  return failed == 0 ? 0 : 1;
}
