// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tests of internal::check_input(): one test per error code on meshes built in code, plus
// CGAL's sample meshes when their folder is given as argv[1].
// Usage: test_input_checks [path/to/data/meshes]

#include <CGAL/Spherical_parameterization/internal/input/check_input.h>
#include <CGAL/Spherical_parameterization/internal/input/point_coordinates.h>

#include "test_support.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace SP = CGAL::Spherical_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;

typedef CGAL::Exact_predicates_inexact_constructions_kernel Epick;
typedef CGAL::Simple_cartesian<double> Cartesian;
typedef CGAL::Surface_mesh<Epick::Point_3> Mesh;
typedef CGAL::Surface_mesh<Cartesian::Point_3> Cartesian_mesh;
typedef CGAL::Polyhedron_3<Epick> Polyhedron;
typedef CGAL::Polyhedron_3<Cartesian> Cartesian_polyhedron;

typedef std::vector<std::array<double, 3>> Coordinates;
typedef std::vector<std::vector<std::size_t>> Polygons;

// ---------------------------------------------------------------------------------------
// Harness

using namespace test_support;
std::string data_dir;

template <class M>
SP::internal::Input_report check(const M& m)
{
  const auto vpm = get(CGAL::vertex_point, m);
  using Kernel = typename CGAL::Kernel_traits<typename boost::property_traits<decltype(vpm)>::value_type>::Kernel;
  return SP::internal::check_input(m, [&](auto v) { return SP::internal::point_coordinates(Kernel(), get(vpm, v)); });
}

/// The expected code, a non-empty detail (empty for OK), and every expected word in it.
void expect(const std::string& name, const SP::internal::Input_report& r, SP::Error_code code,
            const std::vector<std::string>& words = {})
{
  std::string why;
  if(r.code != code)
    why = std::string("got \"") + SP::error_message(r.code) + "\", expected \"" + SP::error_message(code) + "\"";
  else if((code == SP::Error_code::OK) != r.detail.empty())
    why = "detail \"" + r.detail + "\" is (non-)empty";
  for(const std::string& w : words)
    if(why.empty() && r.detail.find(w) == std::string::npos)
      why = "detail \"" + r.detail + "\" does not mention \"" + w + "\"";
  if(!r.detail.empty())
    std::cout << "     detail: " << r.detail << std::endl;
  report(name, why.empty(), why);
}

// ---------------------------------------------------------------------------------------
// Meshes built in code

template <class M>
M make_mesh(const Coordinates& xyz, const Polygons& polygons)
{
  typedef typename boost::property_traits<typename boost::property_map<M, CGAL::vertex_point_t>::type>::value_type
      Point;
  std::vector<Point> points;
  for(const auto& c : xyz)
    points.push_back(Point(c[0], c[1], c[2]));
  M m;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, m);
  return m;
}

Coordinates tetrahedron_points() { return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; }
Polygons tetrahedron_faces() { return {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}; }

Coordinates octahedron_points() { return {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}; }
Polygons octahedron_faces()
{
  return {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
}

template <class M>
M tetrahedron(const Coordinates& xyz = tetrahedron_points())
{
  return make_mesh<M>(xyz, tetrahedron_faces());
}

template <class M>
M octahedron(const Coordinates& xyz = octahedron_points())
{
  return make_mesh<M>(xyz, octahedron_faces());
}

/// An n x m grid wrapped around a torus of radii 2 and 1: genus 1.
template <class M>
M torus(std::size_t n, std::size_t m)
{
  Coordinates xyz;
  Polygons polygons;
  const double two_pi = 2 * std::acos(-1.0);
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j = 0; j < m; ++j) {
      const double u = two_pi * double(i) / double(n), v = two_pi * double(j) / double(m);
      xyz.push_back({(2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v)});
      const std::size_t a = i * m + j, b = ((i + 1) % n) * m + j;
      const std::size_t c = ((i + 1) % n) * m + (j + 1) % m, d = i * m + (j + 1) % m;
      polygons.push_back({a, b, c});
      polygons.push_back({a, c, d});
    }
  return make_mesh<M>(xyz, polygons);
}

/// Two tetrahedra, the second mirrored through the origin, so both have a vertex there.
Coordinates two_tetrahedra_points()
{
  Coordinates xyz = tetrahedron_points();
  for(const auto& p : tetrahedron_points())
    xyz.push_back({-p[0], -p[1], -p[2]});
  return xyz;
}

Polygons two_tetrahedra_faces()
{
  Polygons polygons = tetrahedron_faces();
  for(const auto& f : tetrahedron_faces())
    polygons.push_back({f[0] + 4, f[2] + 4, f[1] + 4});
  return polygons;
}

template <class M>
typename boost::graph_traits<M>::vertex_descriptor nth_vertex(const M& m, std::size_t n)
{
  auto it = vertices(m).begin();
  std::advance(it, n);
  return *it;
}

/// The two tetrahedra glued at the origin combinatorially: every halfedge pointing to the
/// second tetrahedron's apex is redirected to the first's. The shared vertex then has two
/// fans, which CGAL's file readers never produce (see the reader test) but the halfedge
/// structures can represent.
template <class M>
M bowtie()
{
  M m = make_mesh<M>(two_tetrahedra_points(), two_tetrahedra_faces());
  const auto keep = nth_vertex(m, 0), merge = nth_vertex(m, 4);
  for(auto h : halfedges(m))
    if(target(h, m) == merge)
      set_target(h, keep, m);
  remove_vertex(merge, m);
  return m;
}

// ---------------------------------------------------------------------------------------
// Tests on built meshes, in the order of the checks

void test_ok()
{
  expect("ok tetrahedron (Surface_mesh, Epick)", check(tetrahedron<Mesh>()), SP::Error_code::OK);
  expect("ok octahedron (Polyhedron_3, Epick)", check(octahedron<Polyhedron>()), SP::Error_code::OK);
  expect("ok octahedron (Surface_mesh, Simple_cartesian)", check(octahedron<Cartesian_mesh>()), SP::Error_code::OK);
  expect("ok tetrahedron (Polyhedron_3, Simple_cartesian)", check(tetrahedron<Cartesian_polyhedron>()),
         SP::Error_code::OK);
  // Both poles moved to the origin: two vertices share a point but no face, so nothing is
  // degenerate and nothing is non-manifold; coincidence is geometry, not combinatorics.
  Coordinates pinched = octahedron_points();
  pinched[4] = pinched[5] = {0, 0, 0};
  expect("ok pinched octahedron (coincident vertices are not flagged)", check(octahedron<Mesh>(pinched)),
         SP::Error_code::OK);
}

void test_empty()
{
  expect("empty mesh", check(Mesh()), SP::Error_code::EMPTY_MESH, {"no face"});
  Mesh points_only;
  for(int i = 0; i < 3; ++i)
    add_vertex(Epick::Point_3(i, 0, 0), points_only);
  expect("empty mesh (vertices but no face)", check(points_only), SP::Error_code::EMPTY_MESH, {"3 vertices"});
  expect("empty mesh (Polyhedron_3)", check(Polyhedron()), SP::Error_code::EMPTY_MESH);
}

void test_invalid()
{
  Mesh m = tetrahedron<Mesh>();
  const auto h = *halfedges(m).begin();
  set_next(h, h, m);  // a one-halfedge loop: circulating naively around its face never ends
  expect("invalid mesh (next(h) == h)", check(m), SP::Error_code::INVALID_MESH, {"halfedge"});

  Polyhedron p = octahedron<Polyhedron>();
  set_face(*halfedges(p).begin(), boost::graph_traits<Polyhedron>::null_face(), p);
  expect("invalid mesh (Polyhedron_3, face link broken)", check(p), SP::Error_code::INVALID_MESH, {"halfedge"});
}

/// Random corruptions of the links must never crash or hang the check, and it may only say
/// OK when CGAL's own validity check agrees.
template <class M>
void fuzz_links(const std::string& name, unsigned seed)
{
  typedef boost::graph_traits<M> GT;
  std::mt19937 random(seed);
  std::size_t runs = 300, consistent = 0;
  for(std::size_t run = 0; run < runs; ++run) {
    M m = octahedron<M>();
    std::vector<typename GT::halfedge_descriptor> hs(halfedges(m).begin(), halfedges(m).end());
    std::vector<typename GT::vertex_descriptor> vs(vertices(m).begin(), vertices(m).end());
    std::vector<typename GT::face_descriptor> fs(faces(m).begin(), faces(m).end());
    fs.push_back(GT::null_face());
    hs.push_back(GT::null_halfedge());
    auto pick = [&random](const auto& range) { return range[random() % range.size()]; };
    const std::size_t changes = 1 + random() % 3;
    for(std::size_t c = 0; c < changes; ++c) {
      const auto h = hs[random() % (hs.size() - 1)];  // never modify the null halfedge
      switch(random() % 5) {
      case 0: set_next(h, hs[random() % (hs.size() - 1)], m); break;
      case 1: set_target(h, pick(vs), m); break;
      case 2: set_face(h, pick(fs), m); break;
      case 3: set_halfedge(pick(vs), pick(hs), m); break;
      default: {
        const auto f = fs[random() % (fs.size() - 1)];
        set_halfedge(f, pick(hs), m);
      }
      }
    }
    const SP::internal::Input_report r = check(m);
    if(r.code != SP::Error_code::OK || CGAL::is_valid_polygon_mesh(m))
      ++consistent;
  }
  report(name, consistent == runs, std::to_string(runs - consistent) + " OK on invalid meshes");
}

void test_not_triangle()
{
  Mesh cube;
  CGAL::make_hexahedron(Epick::Point_3(0, 0, 0), Epick::Point_3(1, 0, 0), Epick::Point_3(1, 1, 0),
                        Epick::Point_3(0, 1, 0), Epick::Point_3(0, 1, 1), Epick::Point_3(0, 0, 1),
                        Epick::Point_3(1, 0, 1), Epick::Point_3(1, 1, 1), cube);
  expect("not triangle mesh (quad cube)", check(cube), SP::Error_code::NOT_TRIANGLE_MESH,
         {"face 0", "4 vertices", "6 non-triangular faces", "--triangulate"});
  // A pentagon among triangles: the example face is the first non-triangle.
  Polygons polygons = {{0, 1, 2}, {0, 2, 3, 4, 5}, {0, 5, 4, 3, 1}, {1, 3, 2}};
  Coordinates xyz = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 2, 1}, {0, 1, 2}, {-1, 0, 1}};
  expect("not triangle mesh (pentagons)", check(make_mesh<Polyhedron>(xyz, polygons)),
         SP::Error_code::NOT_TRIANGLE_MESH, {"face 1", "5 vertices", "2 non-triangular faces"});
}

void test_non_finite()
{
  Coordinates nan = tetrahedron_points();
  nan[3][2] = std::numeric_limits<double>::quiet_NaN();
  expect("non-finite input (NaN)", check(tetrahedron<Mesh>(nan)), SP::Error_code::NON_FINITE_INPUT, {"vertex 3"});
  Coordinates inf = tetrahedron_points();
  inf[1][0] = -std::numeric_limits<double>::infinity();
  expect("non-finite input (-inf, Simple_cartesian)", check(tetrahedron<Cartesian_mesh>(inf)),
         SP::Error_code::NON_FINITE_INPUT, {"vertex 1"});
  Coordinates huge = tetrahedron_points();
  huge[2][1] = 1e200;
  expect("non-finite input (1e200, Polyhedron_3)", check(tetrahedron<Polyhedron>(huge)),
         SP::Error_code::NON_FINITE_INPUT, {"vertex 2", "1e150"});
  Coordinates large = tetrahedron_points();
  large[2][1] = 1e149;
  expect("finite input (1e149 is accepted)", check(tetrahedron<Mesh>(large)), SP::Error_code::OK);
}

void test_isolated()
{
  Mesh m = tetrahedron<Mesh>();
  add_vertex(Epick::Point_3(5, 5, 5), m);
  expect("isolated vertices", check(m), SP::Error_code::ISOLATED_VERTICES, {"1 isolated vertex", "vertex 4"});
  Polyhedron p = octahedron<Polyhedron>();
  put(get(CGAL::vertex_point, p), add_vertex(p), Epick::Point_3(5, 5, 5));
  put(get(CGAL::vertex_point, p), add_vertex(p), Epick::Point_3(6, 5, 5));
  expect("isolated vertices (Polyhedron_3)", check(p), SP::Error_code::ISOLATED_VERTICES,
         {"2 isolated vertices", "vertex 6"});
}

void test_not_closed()
{
  Polygons three_faces = tetrahedron_faces();
  three_faces.pop_back();
  expect("not closed (tetrahedron missing a face)", check(make_mesh<Mesh>(tetrahedron_points(), three_faces)),
         SP::Error_code::NOT_CLOSED, {"3 border edges"});
}

void test_non_manifold()
{
  expect("non-manifold vertex (Surface_mesh)", check(bowtie<Mesh>()), SP::Error_code::NON_MANIFOLD,
         {"vertex 0", "1 non-manifold vertex"});
  expect("non-manifold vertex (Polyhedron_3)", check(bowtie<Polyhedron>()), SP::Error_code::NON_MANIFOLD,
         {"vertex 0", "3 of its 6 halfedges"});
}

void test_not_connected()
{
  // The two apexes coincide in space but are distinct vertices: two components, not a
  // non-manifold vertex.
  expect("not connected (two tetrahedra touching at a point)",
         check(make_mesh<Mesh>(two_tetrahedra_points(), two_tetrahedra_faces())), SP::Error_code::NOT_CONNECTED,
         {"2 connected components"});
}

void test_genus()
{
  expect("not genus 0 (torus)", check(torus<Mesh>(12, 8)), SP::Error_code::NOT_GENUS_ZERO, {"genus 1"});
  expect("not genus 0 (torus, Polyhedron_3)", check(torus<Polyhedron>(5, 3)), SP::Error_code::NOT_GENUS_ZERO,
         {"genus 1", "Euler characteristic 0"});
}

void test_degenerate()
{
  // Zero-area faces are accepted (their reference triangles are mollified); only a surface
  // without any area is refused.
  Coordinates collinear = tetrahedron_points();
  collinear[3] = {0.5, 0, 0};  // on the segment from vertex 0 to vertex 1: face {0, 1, 3} is flat
  expect("a flat face (collinear points) is accepted", check(tetrahedron<Mesh>(collinear)), SP::Error_code::OK);
  Coordinates repeated = tetrahedron_points();
  repeated[3] = repeated[0];  // faces {0, 1, 3} and {0, 3, 2} have a repeated point
  expect("faces with a repeated point are accepted (Polyhedron_3)", check(tetrahedron<Polyhedron>(repeated)),
         SP::Error_code::OK);
  const Coordinates on_a_line{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  expect("no area (every point on a line)", check(tetrahedron<Mesh>(on_a_line)), SP::Error_code::DEGENERATE_INPUT,
         {"every face has zero area"});
  const Coordinates one_point{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  expect("no area (every point the same, Polyhedron_3)", check(tetrahedron<Polyhedron>(one_point)),
         SP::Error_code::DEGENERATE_INPUT, {"every face has zero area"});
}

void test_order()
{
  // First failing check wins: NaN on a quad mesh reports the quads.
  Coordinates xyz = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {std::nan(""), 1, 0}, {0, 0, 1}};
  Polygons pyramid = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  expect("order: not triangle before non-finite", check(make_mesh<Mesh>(xyz, pyramid)),
         SP::Error_code::NOT_TRIANGLE_MESH);
  // An open mesh with an isolated vertex reports the isolated vertex.
  Polygons three_faces = tetrahedron_faces();
  three_faces.pop_back();
  Coordinates five = tetrahedron_points();
  five.push_back({3, 3, 3});
  expect("order: isolated vertices before border", check(make_mesh<Mesh>(five, three_faces)),
         SP::Error_code::ISOLATED_VERTICES, {"vertex 4"});
  // Two tori: components are reported before the genus.
  Mesh two = torus<Mesh>(6, 4);
  Mesh other = torus<Mesh>(5, 3);
  two.join(other);
  expect("order: not connected before genus", check(two), SP::Error_code::NOT_CONNECTED, {"2 connected"});
}

// ---------------------------------------------------------------------------------------
// CGAL's sample meshes

bool file_exists(const std::string& path) { return std::ifstream(path).good(); }

template <class M> std::string type_name();
template <> std::string type_name<Mesh>() { return "Surface_mesh"; }
template <> std::string type_name<Cartesian_mesh>() { return "Surface_mesh, Simple_cartesian"; }
template <> std::string type_name<Polyhedron>() { return "Polyhedron_3"; }

/// Reads `file` with CGAL::IO::read_polygon_mesh (which does not repair the soup) and
/// checks it, or prints SKIP when the data folder or the file is absent.
template <class M>
void expect_file(const std::string& file, SP::Error_code code, const std::vector<std::string>& words = {},
                 bool triangulate = false)
{
  const std::string name = "file " + file + " (" + type_name<M>() + (triangulate ? ", triangulated)" : ")");
  const std::string path = data_dir + "/" + file;
  if(data_dir.empty() || !file_exists(path)) {
    skip(name, data_dir.empty() ? "no data folder given" : "file not found");
    return;
  }
  M m;
  if(!CGAL::IO::read_polygon_mesh(path, m)) {
    report(name, false, "cannot read " + path);
    return;
  }
  if(triangulate)
    PMP::triangulate_faces(m);
  expect(name, check(m), code, words);
}

void test_files()
{
  expect_file<Mesh>("triceratops.off", SP::Error_code::OK);
  expect_file<Polyhedron>("triceratops.off", SP::Error_code::OK);
  expect_file<Cartesian_mesh>("sphere.off", SP::Error_code::OK);
  expect_file<Mesh>("cube_quad.off", SP::Error_code::NOT_TRIANGLE_MESH, {"4 vertices", "--triangulate"});
  expect_file<Mesh>("cube_quad.off", SP::Error_code::OK, {}, true);
  expect_file<Mesh>("cube-ouvert.off", SP::Error_code::ISOLATED_VERTICES, {"1 isolated vertex", "vertex 8"});
  expect_file<Mesh>("elephant-with-holes.off", SP::Error_code::NOT_CLOSED, {"1353 border edges"});
  expect_file<Polyhedron>("mesh_with_border.off", SP::Error_code::NOT_CLOSED, {"80 border edges"});
  // blobby_3cc.off has 3 components, but they are open: the border is reported first.
  expect_file<Mesh>("blobby_3cc.off", SP::Error_code::NOT_CLOSED, {"219 border edges"});
  expect_file<Mesh>("knot2.off", SP::Error_code::NOT_CONNECTED, {"2 connected components"});
  expect_file<Mesh>("bones.off", SP::Error_code::NOT_CONNECTED, {"26 connected components"});
  expect_file<Mesh>("knot1.off", SP::Error_code::NOT_GENUS_ZERO, {"genus 1"});
  expect_file<Mesh>("eight.off", SP::Error_code::NOT_GENUS_ZERO, {"genus 2"});
  expect_file<Polyhedron>("elephant.off", SP::Error_code::NOT_GENUS_ZERO, {"genus 3"});
  expect_file<Mesh>("double-torus-example.off", SP::Error_code::NOT_TRIANGLE_MESH, {"4 vertices"});
  expect_file<Mesh>("double-torus-example.off", SP::Error_code::NOT_GENUS_ZERO, {"genus 2"}, true);
  expect_file<Mesh>("3torus.off", SP::Error_code::NOT_GENUS_ZERO, {"genus 3"}, true);
}

/// How the two readers treat a vertex shared by two closed fans: the BGL reader refuses
/// the file, the PMP reader (which repairs and orients the soup) duplicates the vertex, so
/// the mesh never reaches check_input() as NON_MANIFOLD but as NOT_CONNECTED.
void test_reader_non_manifold()
{
  const std::string path = (std::filesystem::temp_directory_path() / "test_input_checks_bowtie.off").string();
  {
    std::ofstream out(path);
    out << "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n"
        << "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 4 5\n3 0 6 4\n3 0 5 6\n3 4 6 5\n";
  }
  Mesh bgl;
  report("reader: CGAL::IO::read_polygon_mesh refuses a non-manifold vertex", !CGAL::IO::read_polygon_mesh(path, bgl));
  Mesh pmp;
  const bool read = PMP::IO::read_polygon_mesh(path, pmp);
  std::remove(path.c_str());
  if(!read) {
    report("reader: PMP::IO::read_polygon_mesh splits a non-manifold vertex", false, "cannot read");
    return;
  }
  expect("reader: PMP::IO::read_polygon_mesh splits a non-manifold vertex", check(pmp),
         SP::Error_code::NOT_CONNECTED, {"2 connected components"});
}

int main(int argc, char** argv)
{
  if(argc > 1)
    data_dir = argv[1];

  test_ok();
  test_empty();
  test_invalid();
  fuzz_links<Mesh>("invalid mesh fuzz (Surface_mesh): no crash, no hang, no false OK", 1);
  fuzz_links<Polyhedron>("invalid mesh fuzz (Polyhedron_3): no crash, no hang, no false OK", 2);
  test_not_triangle();
  test_non_finite();
  test_isolated();
  test_not_closed();
  test_non_manifold();
  test_not_connected();
  test_genus();
  test_degenerate();
  test_order();
  test_files();
  test_reader_non_manifold();

  if(skipped != 0)
    std::cout << skipped << " skipped" << std::endl;
  std::cout << passed << " passed, " << failed << " failed" << std::endl;
  // Every skip here is a file of the data folder that is absent.
  return exit_status(skipped != 0);
}
