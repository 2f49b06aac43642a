// The command line tool: maps a closed genus-0 triangle mesh onto the unit sphere.
//
//   spherical_parameterize [INPUT [OUTPUT]] [--energy NAME] [--area-preservation T] [--weights A [B]]
//                          [--sample-spacing W] [--pipeline robust|paper] [--init central|FILE]
//                          [--max-iterations N] [--time-limit SECONDS] [--no-correction]
//                          [--triangulate] [--merge-duplicates] [--remove-isolated] [--orient]
//                          [--quiet]
//                          [--remesh-icosphere LEVEL OUT] [--geometry-image N OUT]
//                          [--map-to OTHER_MESH OTHER_SPHERE OUT [--landmarks FILE]]
//                          [--texture equirectangular|octahedral OUT.obj]
//
// INPUT: .off, .obj, .ply, .stl, or a FreeSurfer triangle surface (`lh.white`, ...).
// OUTPUT (.off or .obj) has the input's vertices in the same order and the same faces, unless
// --merge-duplicates, --remove-isolated or --orient repaired them; for a FreeSurfer INPUT,
// an OUTPUT of any other name is a FreeSurfer sphere of radius 100, as FreeSurfer's own, and
// so are the remesh and --map-to's output FreeSurfer surfaces.
// The options after --quiet use the map once it is computed, and write nothing if it is not
// valid (see the usage string below for each).
// Exit status: 0 for a valid map, 2 for a map that is not valid, 1 for bad input or usage
// (every input file and output path is checked before the solve: nothing written).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>
#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/Sphere_point_location.h>
#include <CGAL/Spherical_parameterization/geometry_image.h>
#include <CGAL/Spherical_parameterization/measure_distortion.h>
#include <CGAL/Spherical_parameterization/remesh_on_icosphere.h>
#include <CGAL/Spherical_parameterization/resampling_error.h>
#include <CGAL/Spherical_parameterization/surface_map.h>
#include <CGAL/Spherical_parameterization/texture_coordinates.h>

#include "../tools/process_tuning.h"
#include "freesurfer_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <utility>
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

// What the reading of a mesh repairs, each only when asked: OUTPUT then has the repaired
// vertices or faces, not the input's.
struct Soup_repairs
{
  bool merge_duplicates = false;  // one vertex per distinct point
  bool remove_isolated = false;   // no vertex without a face
  bool orient = false;            // faces oriented consistently
};

struct Options
{
  std::string input = std::string(SPHERICAL_PARAMETERIZATION_DATA_DIR) + "/triceratops.off";
  std::string output;
  std::string energy = "balanced";
  double area_preservation = SP::default_area_preservation;
  std::vector<double> weights;
  double sample_spacing = 0;  // the weight of the Inverse_dirichlet term added to balanced
  SP::Pipeline pipeline = SP::Pipeline::ROBUST;
  std::string init = "central";
  int max_iterations = 200;
  double time_limit = 0;
  bool correction = true;
  bool triangulate = false;
  Soup_repairs repairs;
  bool quiet = false;
  bool freesurfer_input = false;  // INPUT is a FreeSurfer triangle surface
  std::string freesurfer_tags;    // what follows its faces, for the FreeSurfer outputs

  // Uses of the map, each off unless its output path is set.
  int icosphere_level = 0;
  std::string icosphere_output;
  int image_size = 0;
  std::string image_output;
  std::string other_mesh, other_sphere, map_output, landmarks;
  SP::Texture_layout texture_layout = SP::Texture_layout::EQUIRECTANGULAR;
  std::string texture_output;
};

const char* usage =
  "usage: spherical_parameterize [INPUT [OUTPUT]]\n"
  "         [--energy balanced|tutte|dirichlet|area|stretch|mips|combined|area_distortion|\n"
  "                   inverse_dirichlet|symmetric_dirichlet]\n"
  "         [--area-preservation T] [--weights A [B]] [--sample-spacing W] [--pipeline robust|paper]\n"
  "         [--init central|FILE]\n"
  "         [--max-iterations N]\n"
  "         [--time-limit SECONDS] [--no-correction] [--triangulate] [--merge-duplicates]\n"
  "         [--remove-isolated] [--orient] [--quiet]\n"
  "         [--remesh-icosphere LEVEL OUT] [--geometry-image N OUT]\n"
  "         [--map-to OTHER_MESH OTHER_SPHERE OUT [--landmarks FILE]]\n"
  "         [--texture equirectangular|octahedral OUT.obj]\n"
  "  INPUT                          .off, .obj, .ply, .stl, or a FreeSurfer triangle surface (lh.white, ...)\n"
  "  OUTPUT                         .off or .obj: the map, on the unit sphere; for a FreeSurfer INPUT, any\n"
  "                                 other name writes a FreeSurfer sphere of radius 100 (float32)\n"
  "  --energy NAME                  default balanced: (1 - T) conformal + T area distortion\n"
  "  --area-preservation T          the balanced energy's knob, from 0 (conformal) to 1 (equal-area);\n"
  "                                 default 0.5, which keeps protrusions for a resampling\n"
  "  --weights A [B]                the energy's weights instead (balanced and combined: A on the\n"
  "                                 angles, B on the areas; symmetric_dirichlet: A on the map's\n"
  "                                 Dirichlet energy, B on its inverse's)\n"
  "  --sample-spacing W             adds W times the inverse map's Dirichlet energy to the balanced\n"
  "                                 energy: a resampling's samples then stay close on the surface in\n"
  "                                 every direction, which the sharp tips of low-poly models need\n"
  "                                 (0.2 for models of a few thousand faces or fewer; default 0)\n"
  "  --triangulate                  split the input's polygons into triangles\n"
  "  --merge-duplicates             weld the vertices that share a point (a mesh split at its seams,\n"
  "                                 or one with a copy of each vertex per face); OUTPUT then has one\n"
  "                                 vertex per distinct point, in the order of their first copies\n"
  "  --remove-isolated              drop the vertices that no face uses; OUTPUT then has the others,\n"
  "                                 in their order\n"
  "  --orient                       read a soup whose faces are not consistently oriented (CGAL's\n"
  "                                 orient_polygon_soup); OUTPUT then has the reoriented faces, and\n"
  "                                 the vertices it had to duplicate at non-manifold points last\n"
  "Uses of the map (written only if the map is valid):\n"
  "  --remesh-icosphere LEVEL OUT   the surface resampled on a geodesic icosphere of subdivision LEVEL\n"
  "                                 (0 to 9: 20 * 4^LEVEL faces); OUT .off or .obj (or FreeSurfer's\n"
  "                                 format, as OUTPUT); prints the distance from the input's vertices\n"
  "                                 and face centroids to it\n"
  "  --geometry-image N OUT         the surface sampled on an N x N octahedral grid (N odd, 3 to 4097);\n"
  "                                 OUT .pfm: the float image (x, y, z per pixel, bottom row first),\n"
  "                                 OUT .off or .obj: its closed mesh\n"
  "  --map-to OTHER_MESH OTHER_SPHERE OUT\n"
  "                                 INPUT with every vertex moved to its image on OTHER_MESH, through\n"
  "                                 both sphere maps (OTHER_SPHERE: the map of OTHER_MESH as this tool\n"
  "                                 writes it, or FreeSurfer's sphere of it); OUT .off or .obj (or\n"
  "                                 FreeSurfer's format, as OUTPUT)\n"
  "  --landmarks FILE               for --map-to: lines 'I J' pairing vertex I of INPUT with vertex J\n"
  "                                 of OTHER_MESH (0-based); the spheres are rotated to match them\n"
  "  --texture LAYOUT OUT.obj       INPUT with texture coordinates from the sphere, vertices split on\n"
  "                                 the seam (LAYOUT equirectangular or octahedral)\n";

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

int parse_integer(const std::string& flag, const char* text, int low, int high)
{
  const double value = parse_number(flag, text);
  if(value != std::floor(value) || value < low || value > high)
    fail(flag + " expects an integer from " + std::to_string(low) + " to " + std::to_string(high) + ", got '" + text + "'");
  return int(value);
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
    else if(arg == "--area-preservation") {
      o.area_preservation = parse_number(arg, next());
      if(!(o.area_preservation >= 0 && o.area_preservation <= 1)) fail("--area-preservation expects a number from 0 to 1");
    }
    else if(arg == "--weights") {
      o.weights.push_back(parse_number(arg, next()));
      if(i + 1 < argc && argv[i + 1][0] != '-') o.weights.push_back(parse_number(arg, next()));
    }
    else if(arg == "--sample-spacing") {
      o.sample_spacing = parse_number(arg, next());
      if(!(o.sample_spacing >= 0)) fail("--sample-spacing expects a number 0 or more");
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
    else if(arg == "--merge-duplicates") o.repairs.merge_duplicates = true;
    else if(arg == "--remove-isolated") o.repairs.remove_isolated = true;
    else if(arg == "--orient") o.repairs.orient = true;
    else if(arg == "--quiet") o.quiet = true;
    else if(arg == "--remesh-icosphere") {
      o.icosphere_level = parse_integer(arg, next(), 0, 9);
      o.icosphere_output = next();
    }
    else if(arg == "--geometry-image") {
      o.image_size = parse_integer(arg, next(), 3, 4097);
      if(o.image_size % 2 == 0) fail("--geometry-image expects an odd size (the grid must contain the fold lines)");
      o.image_output = next();
    }
    else if(arg == "--map-to") {
      o.other_mesh = next();
      o.other_sphere = next();
      o.map_output = next();
    }
    else if(arg == "--landmarks") o.landmarks = next();
    else if(arg == "--texture") {
      const std::string layout = next();
      if(layout == "equirectangular") o.texture_layout = SP::Texture_layout::EQUIRECTANGULAR;
      else if(layout == "octahedral") o.texture_layout = SP::Texture_layout::OCTAHEDRAL;
      else fail("--texture expects equirectangular or octahedral");
      o.texture_output = next();
    }
    else if(!arg.empty() && arg[0] == '-') fail("unknown option " + arg + "\n" + usage);
    else positional.push_back(arg);
  }
  if(positional.size() > 2) fail(std::string("too many arguments\n") + usage);
  if(positional.size() >= 1) o.input = positional[0];
  if(positional.size() == 2) o.output = positional[1];
  if(o.output.empty())
    o.output = std::filesystem::path(o.input).stem().string() + "_sphere.off";
  if(o.max_iterations <= 0) fail("--max-iterations must be positive");
  if(!o.landmarks.empty() && o.map_output.empty()) fail("--landmarks goes with --map-to");
  if(!(o.time_limit >= 0)) fail("--time-limit must be non-negative");
  if(o.sample_spacing > 0 && o.energy != "balanced") fail("--sample-spacing adds to the balanced energy only");
  o.freesurfer_input = freesurfer::file_kind(o.input) == freesurfer::File_kind::TRIANGLES;
  return o;
}

std::string extension(const std::string& path) { return std::filesystem::path(path).extension().string(); }

// True if every polygon has at least three distinct vertices, all of them among the points:
// what CGAL's orientation of soups takes for granted.
bool is_indexed_soup(std::size_t point_count, const std::vector<std::vector<std::size_t>>& polygons)
{
  for(std::vector<std::size_t> polygon : polygons) {
    std::sort(polygon.begin(), polygon.end());
    if(polygon.size() < 3 || polygon.back() >= point_count ||
       std::adjacent_find(polygon.begin(), polygon.end()) != polygon.end())
      return false;
  }
  return true;
}

// Removes the points that no polygon uses, the others kept in their order; returns how many.
std::size_t remove_unused_points(std::vector<Point>& points, std::vector<std::vector<std::size_t>>& polygons)
{
  const std::size_t unused = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> new_index(points.size(), unused);
  for(const auto& polygon : polygons)
    for(std::size_t i : polygon)
      new_index[i] = 0;
  std::size_t kept = 0;
  for(std::size_t i = 0; i < points.size(); ++i)
    if(new_index[i] != unused) {
      new_index[i] = kept;
      points[kept++] = points[i];
    }
  const std::size_t removed = points.size() - kept;
  points.resize(kept);
  for(auto& polygon : polygons)
    for(std::size_t& i : polygon)
      i = new_index[i];
  return removed;
}

bool all_finite(const std::vector<Point>& points)
{
  return std::all_of(points.begin(), points.end(), [](const Point& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
  });
}

// The soup as a mesh, one vertex per point in their order and the faces added one by one, as
// CGAL's readers build theirs: several times cheaper than the soup's own checks on a large
// surface. False, `mesh` cleared, at a face that would not keep the mesh an oriented
// 2-manifold; those checks then say why.
bool build_face_by_face(const std::vector<Point>& points, const std::vector<std::vector<std::size_t>>& polygons,
                        Mesh& mesh)
{
  mesh.clear();
  mesh.reserve(Mesh::size_type(points.size()), Mesh::size_type(3 * polygons.size() / 2),
               Mesh::size_type(polygons.size()));
  for(const Point& p : points) mesh.add_vertex(p);
  std::vector<Mesh::Vertex_index> corners;
  for(const std::vector<std::size_t>& polygon : polygons) {
    corners.clear();
    for(std::size_t i : polygon) corners.push_back(Mesh::Vertex_index(Mesh::size_type(i)));
    if(CGAL::Euler::add_face(corners, mesh) == Mesh::null_face()) {
      mesh.clear();
      return false;
    }
  }
  return true;
}

// The points and faces of a FreeSurfer triangle surface, as a soup, and its tags.
void read_freesurfer_soup(const std::string& path, std::vector<Point>& points,
                          std::vector<std::vector<std::size_t>>& polygons, std::string& tags)
{
  try {
    freesurfer::Surface surface = freesurfer::read_surface(path);
    points.reserve(surface.points.size());
    for(const auto& p : surface.points) points.emplace_back(p[0], p[1], p[2]);
    polygons = std::move(surface.triangles);
    tags = std::move(surface.tags);
  } catch(const std::exception& e) {
    fail("cannot read " + path + ": " + e.what());
  }
  if(polygons.empty())
    fail("cannot read " + path + ": a FreeSurfer surface without faces");
}

// Reads a polygon mesh; a file that reads as a polygon soup but not as a mesh is named as such,
// unless the `repairs` asked for make it one. A FreeSurfer surface's tags go to
// `freesurfer_tags` if given.
Mesh read_mesh(const std::string& path, const Soup_repairs& repairs = {}, std::string* freesurfer_tags = nullptr)
{
  if(!std::filesystem::exists(path)) fail("cannot open " + path + ": no such file");
  Mesh mesh;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  const freesurfer::File_kind kind = freesurfer::file_kind(path);
  if(kind == freesurfer::File_kind::QUADRANGLES)
    fail("cannot read " + path + ": FreeSurfer's quadrangle format is not read (write the surface as triangles, "
         "as mris_convert does)");
  if(kind == freesurfer::File_kind::TRIANGLES) {
    std::string tags;
    read_freesurfer_soup(path, points, polygons, tags);
    if(freesurfer_tags)
      *freesurfer_tags = std::move(tags);
  } else {
    const std::string ext = extension(path);
    if(ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
      fail("cannot read " + path + ": unknown extension (use .off, .obj, .ply, .stl or a FreeSurfer surface)");
    bool is_soup = false;
    try {
      if(!repairs.merge_duplicates && !repairs.remove_isolated && CGAL::IO::read_polygon_mesh(path, mesh, CGAL::parameters::verbose(false)))
        return mesh;
      is_soup = CGAL::IO::read_polygon_soup(path, points, polygons) && !polygons.empty();
    } catch(const std::exception& e) {
      // CGAL's readers throw (bad_alloc, length_error) on absurd counts in a corrupted header.
      fail("cannot read " + path + ": not a valid mesh file (" + e.what() + ")");
    }
    if(!is_soup)
      fail("cannot read " + path + ": not a valid mesh file");
  }
  const std::string not_a_surface = "cannot read " + path + " as a surface: its " + std::to_string(polygons.size()) + " faces ";
  // Checked before the repairs, which take it for granted.
  const std::string not_indexed = "include one with fewer than three distinct vertices or a vertex index out of range";
  if(!is_indexed_soup(points.size(), polygons))
    fail(not_a_surface + not_indexed);
  if(repairs.remove_isolated) {
    const std::size_t removed = remove_unused_points(points, polygons);
    std::cerr << "spherical_parameterize: --remove-isolated removed " << removed << " vertices of " << path << "\n";
  }
  // Points compare lexicographically, and a NaN compares equal to any point: such a file is
  // left for the package's check of the input to refuse.
  if(repairs.merge_duplicates && all_finite(points)) {
    const std::size_t welded = PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
    std::cerr << "spherical_parameterize: --merge-duplicates welded " << welded << " vertices of " << path << "\n";
    if(welded > 0 && !is_indexed_soup(points.size(), polygons))  // a face lost a corner to the welding
      fail(not_a_surface + not_indexed);
  }
  const std::string why = "do not form an oriented 2-manifold (non-manifold vertices or edges, or inconsistent orientation)";
  const std::size_t read_points = points.size();
  if(repairs.orient)
    PMP::orient_polygon_soup(points, polygons);  // appends the points it duplicates
  if(!build_face_by_face(points, polygons, mesh)) {
    if(!PMP::is_polygon_soup_a_polygon_mesh(polygons))
      fail(not_a_surface + why + (repairs.orient ? ", even after --orient" : "; the option --orient can repair it"));
    mesh.clear();
    PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  }
  if(points.size() > read_points)
    std::cerr << "spherical_parameterize: --orient duplicated " << points.size() - read_points
              << " vertices of " << path << " at non-manifold points\n";
  return mesh;
}

// FreeSurfer's spheres (`mris_sphere`) have this radius; the tool reads and writes theirs so.
constexpr double freesurfer_sphere_radius = 100;

// A sphere map read from a file (--init, OTHER_SPHERE); a FreeSurfer sphere is scaled to the
// unit sphere.
Mesh read_sphere_mesh(const std::string& path)
{
  Mesh sphere = read_mesh(path);
  if(freesurfer::file_kind(path) == freesurfer::File_kind::TRIANGLES)
    for(auto v : sphere.vertices()) {
      const Point& p = sphere.point(v);
      const double r = std::sqrt((p - CGAL::ORIGIN).squared_length());
      if(r > 0) sphere.point(v) = CGAL::ORIGIN + (p - CGAL::ORIGIN) / r;
    }
  return sphere;
}

// The number of vertices whose point another vertex has already.
std::size_t shared_points(const Mesh& mesh)
{
  std::set<Point> seen;
  std::size_t shared = 0;
  for(auto v : mesh.vertices())
    shared += !seen.insert(mesh.point(v)).second;
  return shared;
}

std::string quote_status(const SP::Result& r)
{
  std::string s = std::string(r.message());
  if(!r.detail.empty()) s += " (" + r.detail + ")";
  if(r.status == SP::Error_code::NOT_CONVERGED && std::isfinite(r.energy))
    s += "; --max-iterations N raises it";
  return s;
}

void print_report(const Options& o, const Mesh& mesh, const SP::Result& r, const SP::Distortion_report& d)
{
  std::cout << std::setprecision(4)
            << "input            " << o.input << ": " << mesh.number_of_vertices() << " vertices, "
            << mesh.number_of_faces() << " faces" << (r.inward_oriented ? ", oriented inward" : "") << "\n"
            << "energy           " << o.energy
            << (o.energy == "balanced" && o.weights.empty() ? " (area preservation " + std::to_string(o.area_preservation) + ")" : "")
            << (o.sample_spacing > 0 ? ", sample spacing " + std::to_string(o.sample_spacing) : "")
            << (o.correction ? "" : " without the d_min correction")
            << ", pipeline " << (o.pipeline == SP::Pipeline::ROBUST ? "robust" : "paper") << "\n"
            << "status           " << quote_status(r) << "\n"
            << "valid map        " << (d.is_valid() ? "yes" : "no") << ": " << d.flipped << " flipped, "
            << d.degenerate << " degenerate, degree " << d.degree << ", max | |x|-1 | " << d.max_norm_error << "\n"
            << "solver           " << r.iterations << " iterations (" << r.stage_summary() << "), energy " << r.energy
            << ", " << r.time_seconds << " s\n"
            << "quasi-conformal  mean " << d.quasi_conformal.mean << ", 95% " << d.quasi_conformal.percentile_95
            << ", max " << d.quasi_conformal.max << "\n"
            << "angle error      mean " << d.angle_error.mean << " deg, 95% " << d.angle_error.percentile_95 << " deg\n"
            << "|log area ratio| mean " << d.log_area_ratio.mean << ", 95% " << d.log_area_ratio.percentile_95
            << ", max " << d.log_area_ratio.max << "; smallest area ratio " << d.min_area_ratio << "\n"
            << "stretch          L2 " << d.l2_stretch << ", Linf " << d.linf_stretch << "\n"
            << "output           " << o.output << "\n";
}

// A face whose share of the sphere is under this fraction of its share of the input is lost
// to any resampling of the map at a resolution that the input's own faces would survive.
constexpr double squeezed_area_ratio = 1e-3;

void warn_if_squeezed(const Options& o, const SP::Distortion_report& d)
{
  if(!d.is_valid() || !(d.min_area_ratio < squeezed_area_ratio))
    return;
  std::cerr << "spherical_parameterize: warning: the map is valid but squeezes some faces to " << d.min_area_ratio
            << " of their share of the area (under " << squeezed_area_ratio
            << "): a resampling of the sphere loses those parts. ";
  if(o.energy == "balanced" && o.weights.empty() && o.area_preservation < 1)
    std::cerr << "A higher --area-preservation (now " << o.area_preservation << ") keeps them.\n";
  else
    std::cerr << "The default energy (--energy balanced) keeps them.\n";
}

// Writes to a temporary file beside the output, then renames it: never a half-written file.
void write_atomically(const std::string& path, const std::function<bool(const std::string&)>& write)
{
  const std::string temporary = path + ".tmp" + std::to_string(getpid()) + extension(path);
  if(!write(temporary)) {
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

// `path` ends in .off or .obj (`check_output_paths()`).
void write_mesh(const Mesh& mesh, const std::string& path)
{
  write_atomically(path, [&mesh](const std::string& file) {
    return CGAL::IO::write_polygon_mesh(file, mesh, CGAL::parameters::stream_precision(17));
  });
}

void write_stream(const std::string& path, std::ios::openmode mode, const std::function<bool(std::ostream&)>& write)
{
  write_atomically(path, [&](const std::string& file) {
    std::ofstream out(file, mode);
    return out && write(out) && bool(out.flush());
  });
}

// Fails unless `path` ends in one of `extensions` (any name if there are none) and its folder
// exists.
void check_output_path(const std::string& flag, const std::string& path, const std::vector<std::string>& extensions)
{
  const std::filesystem::path file(path);
  if(!extensions.empty() && std::find(extensions.begin(), extensions.end(), extension(path)) == extensions.end()) {
    std::string allowed;
    for(const std::string& e : extensions) allowed += (allowed.empty() ? "" : ", ") + e;
    fail("cannot write " + path + flag + ": use " + allowed);
  }
  std::error_code error;
  if(file.has_parent_path() && !std::filesystem::is_directory(file.parent_path(), error))
    fail("cannot write " + path + flag + ": no folder " + file.parent_path().string());
}

// The path made absolute and canonical as far as it exists (`o.off` and `./o.off` alike);
// normalized as written where that fails (a folder it may not read).
std::filesystem::path comparable_path(const std::string& path)
{
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(path, error);
  if(error)
    return std::filesystem::path(path).lexically_normal();
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, error);
  return error ? absolute.lexically_normal() : canonical;
}

// True if the two paths name the same file, existing or not.
bool same_file(const std::string& a, const std::string& b) { return comparable_path(a) == comparable_path(b); }

// True if the mesh output `path` (OUTPUT, --remesh-icosphere's, --map-to's) is a FreeSurfer
// surface: the input is one, and `path` is not named as another mesh format (FreeSurfer's
// names are free: `lh.sphere`, `lh.ico7.white`).
bool writes_freesurfer(const Options& o, const std::string& path)
{
  const std::string ext = extension(path);
  return o.freesurfer_input && ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl";
}

// Every output is checked before the solve, so that a wrong path costs no solve and leaves no
// partial set of outputs behind; none may be a file the tool reads, or another output.
void check_output_paths(const Options& o)
{
  const auto mesh_formats = [&o](const std::string& path) {
    return writes_freesurfer(o, path) ? std::vector<std::string>{} : std::vector<std::string>{".off", ".obj"};
  };
  check_output_path("", o.output, mesh_formats(o.output));
  if(!o.icosphere_output.empty()) check_output_path(" (--remesh-icosphere)", o.icosphere_output, mesh_formats(o.icosphere_output));
  if(!o.image_output.empty()) check_output_path(" (--geometry-image)", o.image_output, {".pfm", ".off", ".obj"});
  if(!o.map_output.empty()) check_output_path(" (--map-to)", o.map_output, mesh_formats(o.map_output));
  if(!o.texture_output.empty()) check_output_path(" (--texture)", o.texture_output, {".obj"});

  std::vector<std::string> outputs{o.output, o.icosphere_output, o.image_output, o.map_output, o.texture_output};
  const std::vector<std::string> inputs{o.input, o.init, o.other_mesh, o.other_sphere, o.landmarks};
  outputs.erase(std::remove(outputs.begin(), outputs.end(), std::string()), outputs.end());
  for(std::size_t i = 0; i < outputs.size(); ++i) {
    for(const std::string& input : inputs)
      if(!input.empty() && same_file(outputs[i], input))
        fail("cannot write " + outputs[i] + ": the tool reads that file");
    for(std::size_t j = 0; j < i; ++j)
      if(same_file(outputs[i], outputs[j]))
        fail("cannot write " + outputs[i] + " twice");
  }
}
// The faces of `mesh` with `points`, one per vertex, as a FreeSurfer surface with the input's
// tags (its volume geometry: the outputs are in the input's space, or on a sphere centred in
// it).
void write_freesurfer(const Options& o, const Mesh& mesh, const std::vector<std::array<double, 3>>& points,
                      const std::string& path)
{
  std::vector<std::array<std::size_t, 3>> triangles;
  triangles.reserve(mesh.number_of_faces());
  for(auto f : mesh.faces()) {
    std::array<std::size_t, 3> t;
    std::size_t k = 0;
    for(auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) t[k++] = std::size_t(v);
    triangles.push_back(t);
  }
  write_stream(path, std::ios::binary, [&](std::ostream& out) {
    return freesurfer::write_surface(out, points, triangles, o.freesurfer_tags, "spherical_parameterize");
  });
}

// A mesh output, as FreeSurfer's format or by its extension (`writes_freesurfer()`).
void write_surface(const Options& o, const Mesh& mesh, const std::string& path)
{
  if(!writes_freesurfer(o, path)) {
    write_mesh(mesh, path);
    return;
  }
  std::vector<std::array<double, 3>> points;
  points.reserve(mesh.number_of_vertices());
  for(auto v : mesh.vertices()) points.push_back({mesh.point(v).x(), mesh.point(v).y(), mesh.point(v).z()});
  write_freesurfer(o, mesh, points, path);
}

// The energy of the options: the balanced energy at the knob, unless weights are given.
std::optional<SP::Energy_mix> energy_of(const Options& o)
{
  if(o.energy == "balanced" && o.weights.empty())
    return SP::energy_by_name("balanced", 1 - o.area_preservation, o.area_preservation, o.sample_spacing);
  return SP::energy_by_name(o.energy, o.weights.size() > 0 ? o.weights[0] : 1.0,
                            o.weights.size() > 1 ? o.weights[1] : 1.0, o.sample_spacing);
}

template <class NamedParameters>
SP::Result run(const Options& o, const Mesh& mesh, Mesh::Property_map<Mesh::Vertex_index, Point> sphere,
               const NamedParameters& np)
{
  const auto energy = energy_of(o);
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

// ---------------------------------------------------------------------------------------
// Uses of a valid map

using Sphere_map = Mesh::Property_map<Mesh::Vertex_index, Point>;
using Point_location = SP::Sphere_point_location<Mesh>;

// Writes the remesh and, unless quiet, how far the input's vertices and face centroids are
// from it: what the resampling lost.
void write_icosphere_remesh(const Options& o, const Mesh& mesh, const Point_location& location)
{
  Mesh remeshed;
  if(!SP::remesh_on_icosphere(location, o.icosphere_level, remeshed))
    fail("the icosphere remesh is not a valid surface mesh");
  write_surface(o, remeshed, o.icosphere_output);
  if(o.quiet)
    return;
  const SP::Resampling_error error = SP::distance_to_resampled(mesh, remeshed);
  std::cout << "icosphere remesh " << o.icosphere_output << ": level " << o.icosphere_level << ", "
            << remeshed.number_of_vertices() << " vertices, " << remeshed.number_of_faces() << " faces\n"
            << "                 distance to the input: mean " << 100 * error.mean << "%, max " << 100 * error.max
            << "% of the bounding box diagonal\n";
}

void write_geometry_image(const Options& o, const Point_location& location)
{
  const SP::Geometry_image image = SP::make_geometry_image(location, o.image_size);
  if(extension(o.image_output) == ".pfm") {
    write_stream(o.image_output, std::ios::binary,
                 [&image](std::ostream& out) { return SP::write_geometry_image_PFM(out, image); });
  } else {
    Mesh mesh;
    if(!SP::geometry_image_to_mesh(image, mesh))
      fail("the geometry image mesh is not a valid surface mesh");
    write_mesh(mesh, o.image_output);
  }
  if(!o.quiet)
    std::cout << "geometry image   " << o.image_output << ": " << o.image_size << " x " << o.image_size
              << " octahedral samples\n";
}

// Lines "I J": vertex I of the input, vertex J of the other mesh; '#' starts a comment.
std::vector<std::pair<Mesh::Vertex_index, Mesh::Vertex_index>> read_landmarks(const Options& o, std::size_t vertices_a,
                                                                              std::size_t vertices_b)
{
  std::ifstream in(o.landmarks);
  if(!in) fail("cannot open " + o.landmarks);
  std::vector<std::pair<Mesh::Vertex_index, Mesh::Vertex_index>> pairs;
  std::string line;
  for(int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream fields(line);
    long long i, j;
    std::string rest;
    if(!(fields >> i)) continue;  // blank line or comment
    if(!(fields >> j) || (fields >> rest) || i < 0 || j < 0 || std::size_t(i) >= vertices_a || std::size_t(j) >= vertices_b)
      fail(o.landmarks + ":" + std::to_string(number) + ": expected two vertex indices 'I J' below " +
           std::to_string(vertices_a) + " and " + std::to_string(vertices_b));
    pairs.emplace_back(Mesh::Vertex_index(std::uint32_t(i)), Mesh::Vertex_index(std::uint32_t(j)));
  }
  return pairs;
}

// Root mean square angle, in degrees, between the landmarks of the input rotated and those of the other sphere.
template <class Landmarks>
double landmark_misfit(const Sphere_map& a, const Sphere_map& b, const Landmarks& landmarks, const Eigen::Matrix3d& r)
{
  double sum = 0;
  for(const auto& pair : landmarks) {
    const Point &p = a[pair.first], &q = b[pair.second];
    const Eigen::Vector3d x = (r * Eigen::Vector3d(p.x(), p.y(), p.z())).normalized();
    const Eigen::Vector3d y = Eigen::Vector3d(q.x(), q.y(), q.z()).normalized();
    sum += CGAL::square(std::atan2(x.cross(y).norm(), x.dot(y)));
  }
  return landmarks.empty() ? 0 : std::sqrt(sum / landmarks.size()) * 180 / M_PI;
}

// The other surface of --map-to with its sphere map and the landmarks, read and checked
// before the solve.
struct Other_surface
{
  Mesh mesh;
  Sphere_map sphere;  // a property of `mesh`: filled in place, never copied
  std::vector<std::pair<Mesh::Vertex_index, Mesh::Vertex_index>> landmarks;
};

void read_other_surface(const Options& o, std::size_t input_vertices, Other_surface& other)
{
  other.mesh = read_mesh(o.other_mesh, o.repairs);
  const Mesh other_points_on_sphere = read_sphere_mesh(o.other_sphere);
  if(other_points_on_sphere.number_of_vertices() != other.mesh.number_of_vertices() ||
     other_points_on_sphere.number_of_faces() != other.mesh.number_of_faces())
    fail(o.other_sphere + " does not have the vertices and faces of " + o.other_mesh);
  other.sphere = other.mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  auto on_sphere = other_points_on_sphere.vertices().begin();
  for(auto v : other.mesh.vertices()) other.sphere[v] = other_points_on_sphere.point(*on_sphere++);
  if(!CGAL::is_triangle_mesh(other.mesh) || !SP::measure_distortion(other.mesh, other.sphere).is_valid())
    fail(o.other_sphere + " is not a valid sphere map of " + o.other_mesh);
  if(!o.landmarks.empty())
    other.landmarks = read_landmarks(o, input_vertices, other.mesh.number_of_vertices());
}

void write_map_to_other(const Options& o, const Mesh& mesh, const Sphere_map& sphere, const Other_surface& other)
{
  const Sphere_map& other_sphere = other.sphere;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double misfit = 0;
  if(!o.landmarks.empty()) {
    rotation = SP::rotation_from_landmarks(sphere, other_sphere, other.landmarks);
    misfit = landmark_misfit(sphere, other_sphere, other.landmarks, rotation);
  }
  const Point_location on_other(other.mesh, other_sphere);
  Mesh mapped = mesh;  // same vertex indices: the images go straight into its points
  SP::map_to_surface(mesh, sphere, on_other, mapped.points(), rotation);
  write_surface(o, mapped, o.map_output);
  if(!o.quiet)
    std::cout << "map to surface   " << o.map_output << ": the input's vertices on " << o.other_mesh
              << (o.landmarks.empty() ? std::string() : ", spheres aligned at the landmarks (rms misfit " +
                                                          std::to_string(misfit) + " deg)")
              << "\n";
}

void write_textured_obj(const Options& o, const Mesh& mesh, const Sphere_map& sphere)
{
  const SP::Seamed_texture_coordinates texture = SP::seamed_texture_coordinates(mesh, sphere, o.texture_layout);
  const char* layout = o.texture_layout == SP::Texture_layout::OCTAHEDRAL ? "octahedral" : "equirectangular";
  write_stream(o.texture_output, std::ios::out, [&](std::ostream& out) {
    out << "# " << o.input << " with " << layout << " texture coordinates from its spherical map\n";
    return SP::write_textured_OBJ(out, mesh, texture);
  });
  if(!o.quiet)
    std::cout << "texture          " << o.texture_output << ": " << layout << ", " << texture.uv.size()
              << " texture coordinates, " << texture.seam_faces << " faces across the seam, "
              << texture.singular_faces << " around a singular point\n";
}

// OUTPUT as FreeSurfer's spheres are: radius 100, float32. The rounding to float32 may flip
// faces that the map squeezes to a sliver; the tool says so, and where the exact map is.
void write_freesurfer_sphere(const Options& o, const Mesh& mesh, const Sphere_map& sphere,
                             const SP::Distortion_report& exact)
{
  std::vector<std::array<double, 3>> scaled;
  std::vector<Point> rounded;  // the map as the file has it, back on the unit sphere
  scaled.reserve(mesh.number_of_vertices());
  rounded.reserve(mesh.number_of_vertices());
  for(auto v : mesh.vertices()) {
    const Point& p = sphere[v];
    scaled.push_back({freesurfer_sphere_radius * p.x(), freesurfer_sphere_radius * p.y(), freesurfer_sphere_radius * p.z()});
    const auto& q = scaled.back();
    rounded.emplace_back(float(q[0]) / freesurfer_sphere_radius, float(q[1]) / freesurfer_sphere_radius,
                         float(q[2]) / freesurfer_sphere_radius);
  }
  write_freesurfer(o, mesh, scaled, o.output);
  const SP::Distortion_report r = SP::measure_distortion(mesh, CGAL::make_property_map(rounded));
  const std::size_t lost = r.flipped + r.degenerate, had = exact.flipped + exact.degenerate;
  if(lost > had)
    std::cerr << "spherical_parameterize: warning: rounded to float32 for " << o.output << ", " << lost - had
              << " more faces are flipped or degenerate than in the map; an OUTPUT ending in .off has the exact map\n";
}

bool uses_the_map(const Options& o)
{
  return !o.icosphere_output.empty() || !o.image_output.empty() || !o.map_output.empty() || !o.texture_output.empty();
}

void use_the_map(const Options& o, const Mesh& mesh, const Sphere_map& sphere, const Other_surface& other)
{
  if(!o.map_output.empty())
    write_map_to_other(o, mesh, sphere, other);
  if(!o.texture_output.empty())
    write_textured_obj(o, mesh, sphere);
  if(o.icosphere_output.empty() && o.image_output.empty())
    return;
  const Point_location location(mesh, sphere);
  if(!o.icosphere_output.empty())
    write_icosphere_remesh(o, mesh, location);
  if(!o.image_output.empty())
    write_geometry_image(o, location);
}

} // namespace

int main(int argc, char** argv)
{
  // This program owns its process, and tunes it for CHOLMOD (tools/process_tuning.h): its
  // OpenMP regions inline, OpenBLAS one thread short of the cores.
  process_tuning::enable();
  Options o = parse_options(argc, argv);
  check_output_paths(o);
  Mesh mesh = read_mesh(o.input, o.repairs, &o.freesurfer_tags);
  if(o.triangulate && !CGAL::is_triangle_mesh(mesh))
    PMP::triangulate_faces(mesh);
  Other_surface other;
  if(!o.map_output.empty())
    read_other_surface(o, mesh.number_of_vertices(), other);

  auto sphere = mesh.add_property_map<Mesh::Vertex_index, Point>("v:sphere", CGAL::ORIGIN).first;
  SP::Result r;
  if(o.init == "central") {
    r = run(o, mesh, sphere, CGAL::parameters::default_values());
  } else {
    const Mesh start = read_sphere_mesh(o.init);
    if(start.number_of_vertices() != mesh.number_of_vertices())
      fail("--init " + o.init + " has " + std::to_string(start.number_of_vertices()) + " vertices, the input " +
           std::to_string(mesh.number_of_vertices()));
    auto initial = mesh.add_property_map<Mesh::Vertex_index, Point>("v:initial", CGAL::ORIGIN).first;
    auto from = start.vertices().begin();
    for(auto v : mesh.vertices()) initial[v] = start.point(*from++);
    r = run(o, mesh, sphere, SP::parameters::initial_sphere_map(initial));
  }

  // Codes before NO_VALID_MAP mean that nothing was solved (bad input or parameters).
  if(r.status != SP::Error_code::OK && r.status < SP::Error_code::NO_VALID_MAP) {
    // An open or split mesh whose pieces meet at copies of the same points, as exporters
    // that split vertices at seams leave them.
    const bool split = r.status == SP::Error_code::NOT_CLOSED || r.status == SP::Error_code::NOT_CONNECTED ||
                       r.status == SP::Error_code::NOT_GENUS_ZERO;
    const std::size_t shared = split && !o.repairs.merge_duplicates ? shared_points(mesh) : 0;
    const bool isolated = r.status == SP::Error_code::ISOLATED_VERTICES && !o.repairs.remove_isolated;
    fail(o.input + ": " + quote_status(r) +
         (shared ? "; " + std::to_string(shared) + " vertices share their point with another: the option "
                   "--merge-duplicates welds them" : "") +
         (isolated ? "; the option --remove-isolated drops them" : ""));
  }

  const SP::Distortion_report d = SP::measure_distortion(mesh, sphere);
  if(writes_freesurfer(o, o.output)) {
    write_freesurfer_sphere(o, mesh, sphere, d);
  } else {
    Mesh sphere_mesh = mesh;
    for(auto v : sphere_mesh.vertices()) sphere_mesh.point(v) = sphere[v];
    write_mesh(sphere_mesh, o.output);
  }
  if(!o.quiet) {
    print_report(o, mesh, r, d);
    warn_if_squeezed(o, d);
  }
  if(d.is_valid())
    use_the_map(o, mesh, sphere, other);
  else if(uses_the_map(o))
    std::cerr << "spherical_parameterize: the map is not valid: remesh, geometry image, map and texture not written\n";
  return d.is_valid() ? 0 : 2;
}
