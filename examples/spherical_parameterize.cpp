// The command line tool: maps a closed genus-0 triangle mesh onto the unit sphere.
//
//   spherical_parameterize [INPUT [OUTPUT]] [--energy NAME] [--weights A [B]]
//                          [--pipeline robust|paper] [--init central|FILE]
//                          [--max-iterations N] [--time-limit SECONDS] [--no-correction]
//                          [--triangulate] [--quiet]
//
// OUTPUT (.off or .obj) has the input's vertices in the same order and the same faces.
// Exit status: 0 for a valid map, 2 for a map that is not valid, 1 for bad input or usage.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/measure_distortion.h>

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

namespace SP = CGAL::Spherical_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

#ifndef SPHERICAL_PARAMETERIZATION_DATA_DIR
#define SPHERICAL_PARAMETERIZATION_DATA_DIR "data"
#endif

namespace {

struct Options
{
  std::string input = std::string(SPHERICAL_PARAMETERIZATION_DATA_DIR) + "/triceratops.off";
  std::string output;
  std::string energy = "combined";
  std::vector<double> weights;
  SP::Pipeline pipeline = SP::Pipeline::ROBUST;
  std::string init = "central";
  int max_iterations = 200;
  double time_limit = 0;
  bool correction = true;
  bool triangulate = false;
  bool quiet = false;
};

const char* usage =
  "usage: spherical_parameterize [INPUT [OUTPUT]] [--energy tutte|dirichlet|area|stretch|mips|combined]\n"
  "         [--weights A [B]] [--pipeline robust|paper] [--init central|FILE] [--max-iterations N]\n"
  "         [--time-limit SECONDS] [--no-correction] [--triangulate] [--quiet]\n";

[[noreturn]] void fail(const std::string& message)
{
  std::cerr << "spherical_parameterize: " << message << "\n";
  std::exit(1);
}

double parse_number(const std::string& flag, const char* text)
{
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if(end == text || *end != '\0')
    fail(flag + " expects a number, got '" + text + "'");
  return value;
}

Options parse_options(int argc, char** argv)
{
  Options o;
  std::vector<std::string> positional;
  for(int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> const char* {
      if(i + 1 >= argc) fail(arg + " expects a value");
      return argv[++i];
    };
    if(arg == "--help" || arg == "-h") { std::cout << usage; std::exit(0); }
    else if(arg == "--energy") o.energy = next();
    else if(arg == "--weights") {
      o.weights.push_back(parse_number(arg, next()));
      if(i + 1 < argc && argv[i + 1][0] != '-') o.weights.push_back(parse_number(arg, next()));
    }
    else if(arg == "--pipeline") {
      const std::string p = next();
      if(p == "robust") o.pipeline = SP::Pipeline::ROBUST;
      else if(p == "paper") o.pipeline = SP::Pipeline::PAPER;
      else fail("--pipeline expects robust or paper");
    }
    else if(arg == "--init") o.init = next();
    else if(arg == "--max-iterations") o.max_iterations = int(parse_number(arg, next()));
    else if(arg == "--time-limit") o.time_limit = parse_number(arg, next());
    else if(arg == "--no-correction") o.correction = false;
    else if(arg == "--triangulate") o.triangulate = true;
    else if(arg == "--quiet") o.quiet = true;
    else if(!arg.empty() && arg[0] == '-') fail("unknown option " + arg + "\n" + usage);
    else positional.push_back(arg);
  }
  if(positional.size() > 2) fail(std::string("too many arguments\n") + usage);
  if(positional.size() >= 1) o.input = positional[0];
  if(positional.size() == 2) o.output = positional[1];
  if(o.output.empty())
    o.output = std::filesystem::path(o.input).stem().string() + "_sphere.off";
  if(o.max_iterations <= 0) fail("--max-iterations must be positive");
  if(!(o.time_limit >= 0)) fail("--time-limit must be non-negative");
  return o;
}

// Reads a polygon mesh; a file that reads as a polygon soup but not as a mesh is named as such.
Mesh read_mesh(const std::string& path)
{
  if(!std::filesystem::exists(path)) fail("cannot open " + path + ": no such file");
  const std::string ext = std::filesystem::path(path).extension().string();
  if(ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
    fail("cannot read " + path + ": unknown extension (use .off, .obj, .ply or .stl)");
  Mesh mesh;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool is_soup = false;
  try {
    if(CGAL::IO::read_polygon_mesh(path, mesh, CGAL::parameters::verbose(false)))
      return mesh;
    is_soup = CGAL::IO::read_polygon_soup(path, points, polygons) && !polygons.empty();
  } catch(const std::exception& e) {
    // CGAL's readers throw (bad_alloc, length_error) on absurd counts in a corrupted header.
    fail("cannot read " + path + ": not a valid mesh file (" + e.what() + ")");
  }
  if(is_soup)
    fail("cannot read " + path + " as a surface: its " + std::to_string(polygons.size()) +
         " faces do not form an oriented 2-manifold (non-manifold vertices or edges, or inconsistent orientation)");
  fail("cannot read " + path + ": not a valid mesh file");
}

std::string quote_status(const SP::Result& r)
{
  std::string s = std::string(r.message());
  if(!r.detail.empty()) s += " (" + r.detail + ")";
  return s;
}

void print_report(const Options& o, const Mesh& mesh, const SP::Result& r, const SP::Distortion_report& d)
{
  std::cout << std::setprecision(4)
            << "input            " << o.input << ": " << mesh.number_of_vertices() << " vertices, "
            << mesh.number_of_faces() << " faces" << (r.inward_oriented ? ", oriented inward" : "") << "\n"
            << "energy           " << o.energy << (o.correction ? "" : " without the d_min correction")
            << ", pipeline " << (o.pipeline == SP::Pipeline::ROBUST ? "robust" : "paper") << "\n"
            << "status           " << quote_status(r) << "\n"
            << "valid map        " << (d.is_valid() ? "yes" : "no") << ": " << d.flipped << " flipped, "
            << d.degenerate << " degenerate, degree " << d.degree << ", max | |x|-1 | " << d.max_norm_error << "\n"
            << "solver           " << r.iterations << " iterations (" << r.stages << "), energy " << r.energy
            << ", " << r.time_seconds << " s\n"
            << "quasi-conformal  mean " << d.quasi_conformal.mean << ", 95% " << d.quasi_conformal.percentile_95
            << ", max " << d.quasi_conformal.max << "\n"
            << "angle error      mean " << d.angle_error.mean << " deg, 95% " << d.angle_error.percentile_95 << " deg\n"
            << "|log area ratio| mean " << d.log_area_ratio.mean << ", 95% " << d.log_area_ratio.percentile_95
            << ", max " << d.log_area_ratio.max << "; smallest area ratio " << d.min_area_ratio << "\n"
            << "stretch          L2 " << d.l2_stretch << ", Linf " << d.linf_stretch << "\n"
            << "output           " << o.output << "\n";
}

// Writes to a temporary file beside the output, then renames it: never a half-written file.
void write_sphere_mesh(const Mesh& sphere, const std::string& path)
{
  const std::string ext = std::filesystem::path(path).extension().string();
  if(ext != ".off" && ext != ".obj") fail("cannot write " + path + ": use .off or .obj");
  const std::string temporary = path + ".tmp" + std::to_string(getpid()) + ext;
  if(!CGAL::IO::write_polygon_mesh(temporary, sphere, CGAL::parameters::stream_precision(17))) {
    std::remove(temporary.c_str());
    fail("cannot write " + path);
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if(error) {
    std::remove(temporary.c_str());
    fail("cannot write " + path + ": " + error.message());
  }
}

template <class NamedParameters>
SP::Result run(const Options& o, const Mesh& mesh, Mesh::Property_map<Mesh::Vertex_index, Point> sphere,
               const NamedParameters& np)
{
  const auto energy = SP::energy_by_name(o.energy, o.weights.size() > 0 ? o.weights[0] : 1.0,
                                         o.weights.size() > 1 ? o.weights[1] : 1.0);
  if(!energy) fail("unknown energy '" + o.energy + "' or weights not positive");
  const bool show_progress = !o.quiet && isatty(STDERR_FILENO);
  auto progress = [show_progress](const SP::Progress& p) {
    if(show_progress)
      std::cerr << "\r" << p.stage << " iteration " << p.iteration << "  energy " << std::setprecision(8) << p.energy
                << "  " << std::setprecision(3) << p.elapsed_seconds << " s   " << std::flush;
    return true;
  };
  const auto parameters =
    SP::parameters::energy(*energy, SP::parameters::pipeline(o.pipeline, SP::parameters::d_min_correction(o.correction, np)))
      .number_of_iterations(o.max_iterations)
      .maximum_running_time(o.time_limit)
      .visitor(progress);
  const SP::Result r = CGAL::spherical_parameterize(mesh, sphere, parameters);
  if(show_progress) std::cerr << "\n";
  return r;
}

} // namespace

int main(int argc, char** argv)
{
  const Options o = parse_options(argc, argv);
  Mesh mesh = read_mesh(o.input);
  if(o.triangulate && !CGAL::is_triangle_mesh(mesh))
    PMP::triangulate_faces(mesh);

  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  SP::Result r;
  if(o.init == "central") {
    r = run(o, mesh, sphere, CGAL::parameters::default_values());
  } else {
    const Mesh start = read_mesh(o.init);
    if(start.number_of_vertices() != mesh.number_of_vertices())
      fail("--init " + o.init + " has " + std::to_string(start.number_of_vertices()) + " vertices, the input " +
           std::to_string(mesh.number_of_vertices()));
    auto initial = mesh.add_property_map<Mesh::Vertex_index, Point>("v:initial", CGAL::ORIGIN).first;
    auto from = start.vertices().begin();
    for(auto v : mesh.vertices()) initial[v] = start.point(*from++);
    r = run(o, mesh, sphere, SP::parameters::initial_sphere_map(initial));
  }

  // Codes before NO_VALID_MAP mean that nothing was solved (bad input or parameters).
  if(r.status != SP::Error_code::OK && r.status < SP::Error_code::NO_VALID_MAP)
    fail(o.input + ": " + quote_status(r));

  const SP::Distortion_report d = SP::measure_distortion(mesh, sphere);
  Mesh sphere_mesh = mesh;
  for(auto v : sphere_mesh.vertices()) sphere_mesh.point(v) = sphere[v];
  write_sphere_mesh(sphere_mesh, o.output);
  if(!o.quiet) print_report(o, mesh, r, d);
  return d.is_valid() ? 0 : 2;
}
