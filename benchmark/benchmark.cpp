// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Benchmark of CGAL::spherical_parameterize(): time, memory, validity and distortion per
// (mesh, energy), against a yardstick measured in the same process: one sparse Cholesky
// factorization and solve of the mesh's cotangent Laplacian.
//
// Usage:
//   benchmark [--repeats N] [--energies balanced,tutte,dirichlet,combined] [--pipeline robust|paper]
//             [--max-seconds S] [--no-fork] [--same-input] [--json FILE] [--csv FILE] MESH...
// A MESH ending in "@loopN" (e.g. bunny00.off@loop2) is Loop-subdivided N times after reading;
// "@decimateN" then collapses edges until N% of them are left (a decimated scan's obtuse and
// long faces); "@sliversN" and "@needlesN" add N nearly degenerate faces of each kind
// (mesh_defects.h).
// "tube:capsuleL" and "tube:helixT" are long tubes built in code (synthetic_shapes.h),
// "tube:cylinderN" a CAD-like cylinder of needles with fan caps, and
// "iso:metaballsN", "iso:starfishN", "iso:cortexN", "iso:foldedN" and "iso:latticeR" isosurfaces made by
// marching tetrahedra.
//
// Each run is done in a forked child process, so that its peak memory (ru_maxrss of the
// child) belongs to that run alone; see README.md.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/subdivision_method_3.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_ratio_stop_predicate.h>

#include <CGAL/spherical_parameterize.h>
#include <CGAL/Spherical_parameterization/Balanced_energy.h>
#include <CGAL/Spherical_parameterization/Energy_mix.h>
#include <CGAL/Spherical_parameterization/measure_distortion.h>
#include <CGAL/Spherical_parameterization/resampling_error.h>

#include "../tools/process_tuning.h"
#include "mesh_defects.h"
#include "synthetic_shapes.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace SP = CGAL::Spherical_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using vertex_descriptor = Mesh::Vertex_index;
using Clock = std::chrono::steady_clock;

namespace {

// ---------------------------------------------------------------------------------------
// Command line

struct Options
{
  std::optional<int> repeats;  // default: 3, or 1 above 200k faces
  std::vector<std::string> energies{"balanced", "tutte", "dirichlet", "combined"};
  std::string pipeline = "robust";
  double max_seconds = 0;  // 0: unlimited
  bool fork_runs = true;
  bool turn_repeats = true;  // the repeats after the first on turned inputs (see turn())
  std::string json, csv;
  std::vector<std::string> meshes;
};

void usage(const char* program)
{
  std::cerr << "usage: " << program
            << " [--repeats N] [--energies balanced,tutte,dirichlet,combined] [--pipeline robust|paper]\n"
               "       [--max-seconds S] [--no-fork] [--same-input] [--json FILE] [--csv FILE] MESH...\n"
               "The repeats after the first run on the input turned by fixed rotations (the rounding,\n"
               "and so the solver's path, changes); --same-input repeats the input as read.\n"
               "A MESH path ending in @loopN is Loop-subdivided N times before timing; @decimateN then\n"
               "collapses edges until N% of them are left; @sliversN and @needlesN split N faces into\n"
               "slivers or needles (e.g. cow.off@needles50).\n"
               "A MESH tube:capsuleL or tube:helixT is built: a straight tube L radii long, or a thin\n"
               "tube coiled T times (e.g. tube:helix4, 112k faces); tube:cylinderN is a cylinder with N\n"
               "vertices on each of five rings and fan caps, as CAD tessellations make it (needles).\n"
               "A MESH iso:metaballsN, iso:starfishN, iso:cortexN, iso:foldedN, iso:figureN or\n"
               "iso:latticeR is an isosurface by marching tetrahedra: blobs, a ball with five thin arms,\n"
               "a ball folded by narrow creases or by deeper ones that lean (not star-shaped), a standing\n"
               "figure with fingers, on a grid of N cubes a side, or the sphere of squared radius R\n"
               "through points of the integer grid (clusters of near-duplicate vertices).\n"
               "A MESH shape:spikesN is a ball with N spikes two radii long and 0.04 radian wide, like\n"
               "a sea urchin (82k faces); shape:whiteL and shape:pialL are brain surfaces, thin folds\n"
               "on a core or narrow grooves in a shell, over the icosphere of level L (7: 328k faces).\n";
}

std::vector<std::string> split(const std::string& s, char separator)
{
  std::vector<std::string> parts;
  std::stringstream stream(s);
  std::string part;
  while(std::getline(stream, part, separator))
    if(!part.empty())
      parts.push_back(part);
  return parts;
}

// An energy as NAME, NAME:A, NAME:A:B or NAME:A:B:C, the arguments of `energy_by_name()`
// (e.g. combined:1:30, balanced:0.5:0.5:0.2); "balanced" alone is the default energy,
// `balanced_energy()`.
std::optional<SP::Energy_mix> energy_from_spec(const std::string& spec)
{
  const std::vector<std::string> parts = split(spec, ':');
  if(parts.empty() || parts.size() > 4)
    return std::nullopt;
  if(parts.size() == 1 && parts[0] == "balanced")
    return SP::energy_by_name("balanced", 1 - SP::default_area_preservation, SP::default_area_preservation);
  const double a = parts.size() > 1 ? std::atof(parts[1].c_str()) : 1;
  const double b = parts.size() > 2 ? std::atof(parts[2].c_str()) : 1;
  const double c = parts.size() > 3 ? std::atof(parts[3].c_str()) : 0;
  return SP::energy_by_name(parts[0], a, b, c);
}

bool parse_options(int argc, char** argv, Options& options)
{
  for(int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::string& out) {
      if(i + 1 >= argc) {
        std::cerr << "missing value after " << arg << '\n';
        return false;
      }
      out = argv[++i];
      return true;
    };
    std::string v;
    if(arg == "--repeats") {
      if(!value(v)) return false;
      options.repeats = std::atoi(v.c_str());
      if(*options.repeats < 1) {
        std::cerr << "--repeats must be at least 1\n";
        return false;
      }
    } else if(arg == "--energies") {
      if(!value(v)) return false;
      options.energies = split(v, ',');
    } else if(arg == "--pipeline") {
      if(!value(options.pipeline)) return false;
      if(options.pipeline != "robust" && options.pipeline != "paper") {
        std::cerr << "--pipeline must be robust or paper\n";
        return false;
      }
    } else if(arg == "--max-seconds") {
      if(!value(v)) return false;
      options.max_seconds = std::atof(v.c_str());
    } else if(arg == "--no-fork") {
      options.fork_runs = false;
    } else if(arg == "--same-input") {
      options.turn_repeats = false;
    } else if(arg == "--json") {
      if(!value(options.json)) return false;
    } else if(arg == "--csv") {
      if(!value(options.csv)) return false;
    } else if(arg == "-h" || arg == "--help") {
      return false;
    } else if(!arg.empty() && arg[0] == '-') {
      std::cerr << "unknown option " << arg << '\n';
      return false;
    } else {
      options.meshes.push_back(arg);
    }
  }
  for(const std::string& e : options.energies)
    if(!energy_from_spec(e)) {
      std::cerr << "unknown energy " << e << '\n';
      return false;
    }
  return !options.meshes.empty() && !options.energies.empty();
}

// ---------------------------------------------------------------------------------------
// Memory

// Resident set size now, in kB, from /proc/self/statm (second field, in pages).
long current_rss_kb()
{
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  if(!(statm >> size >> resident))
    return 0;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

// Peak resident set size of this process so far, in kB (Linux reports ru_maxrss in kB).
long peak_rss_kb()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

// ---------------------------------------------------------------------------------------
// One run

// What one run reports; plain data, so that a forked child can send it through a pipe.
struct Run_record
{
  bool ran = false;          // the child finished and reported
  int status = 0;            // SP::Error_code
  char detail[200] = "";
  char stages[1000] = "";  // a run through every level of the largest meshes needs about a third
  double seconds = 0;
  std::size_t iterations = 0;
  double energy = 0;
  long rss_before_kb = 0;    // statm right before the call
  long peak_rss_kb = 0;      // ru_maxrss right after the call (before measuring distortion)
  long rss_after_kb = 0;     // statm right after the call
  bool solver_valid = false;  // the solver's own verdict, only to cross-check
  // From measure_distortion():
  bool valid = false;
  std::size_t flipped = 0, degenerate = 0;
  double degree = 0, max_norm_error = 0;
  double qc_mean = 0, qc_p95 = 0, log_area_mean = 0, min_area_ratio = 0, l2_stretch = 0, angle_mean = 0;
  // From resampling_error() on the icosphere of level 6, for a valid map (else -1).
  double resampling_mean = -1, resampling_max = -1;
};

void copy_string(char* out, std::size_t size, const std::string& s)
{
  std::snprintf(out, size, "%s", s.c_str());
}

Run_record run_once(Mesh& mesh, const SP::Energy_mix& energy, SP::Pipeline pipeline, double max_seconds)
{
  Run_record record;
  auto sphere = mesh.add_property_map<vertex_descriptor, Point>("v:benchmark_sphere", Point(0, 0, 0)).first;
  record.rss_before_kb = current_rss_kb();
  const Clock::time_point start = Clock::now();
  const SP::Result result = CGAL::spherical_parameterize(
    mesh, sphere,
    SP::parameters::pipeline(pipeline, SP::parameters::energy(energy)).maximum_running_time(max_seconds));
  record.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  record.peak_rss_kb = peak_rss_kb();
  record.rss_after_kb = current_rss_kb();

  record.ran = true;
  record.status = int(result.status);
  copy_string(record.detail, sizeof(record.detail), result.detail);
  copy_string(record.stages, sizeof(record.stages), result.stage_summary());
  record.iterations = result.iterations;
  record.energy = result.energy;
  record.solver_valid = result.is_valid();

  const bool solved = result.status == SP::Error_code::OK || result.status == SP::Error_code::NOT_CONVERGED ||
                      result.status == SP::Error_code::NO_VALID_MAP || result.status == SP::Error_code::TIME_LIMIT ||
                      result.status == SP::Error_code::CANCELLED;
  if(solved) {  // the map was written: judge it independently of the solver
    const SP::Distortion_report report = SP::measure_distortion(mesh, sphere);
    record.valid = report.is_valid();
    record.flipped = report.flipped;
    record.degenerate = report.degenerate;
    record.degree = report.degree;
    record.max_norm_error = report.max_norm_error;
    record.qc_mean = report.quasi_conformal.mean;
    record.qc_p95 = report.quasi_conformal.percentile_95;
    record.log_area_mean = report.log_area_ratio.mean;
    record.min_area_ratio = report.min_area_ratio;
    record.l2_stretch = report.l2_stretch;
    record.angle_mean = report.angle_error.mean;
    if(record.valid) {
      const SP::Resampling_error resampled = SP::resampling_error(mesh, sphere, 6);
      record.resampling_mean = resampled.mean;
      record.resampling_max = resampled.max;
    }
  }
  mesh.remove_property_map(sphere);
  return record;
}

// Turns the mesh by a rotation fixed by `seed`. The energies, the map's validity and its
// distortion do not change under a rotation, but the rounding does, and on meshes with
// protrusions the solver's path follows the rounding: changing only the order of a small
// matrix product in the solver can nearly double the iteration count. Repeats of one
// input would time one path several times; the benchmark times a repeat on each of several
// turned inputs, and their median is a typical path.
void turn(Mesh& mesh, int seed)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  const Eigen::Quaterniond rotation =
    Eigen::Quaterniond(normal(random), normal(random), normal(random), normal(random)).normalized();
  for(vertex_descriptor v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    const Eigen::Vector3d turned = rotation * Eigen::Vector3d(p.x(), p.y(), p.z());
    mesh.point(v) = Point(turned.x(), turned.y(), turned.z());
  }
}

// Runs `task` in a forked child, which sends its result (plain data) back through a pipe.
// Empty if the child crashed or was killed (e.g. out of memory); `failure` then says how.
// Everything that may start threads (CHOLMOD's OpenMP, TBB) runs in children only: a
// process that forks after its OpenMP runtime has started threads can deadlock in the child.
template <class T, class Task>
std::optional<T> in_child(const Task& task, std::string& failure)
{
  int fds[2];
  if(pipe(fds) != 0) {
    failure = std::string("pipe: ") + std::strerror(errno);
    return std::nullopt;
  }
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = fork();
  if(pid < 0) {
    failure = std::string("fork: ") + std::strerror(errno);
    close(fds[0]);
    close(fds[1]);
    return std::nullopt;
  }
  if(pid == 0) {
    close(fds[0]);
    const T result = task();
    const char* bytes = reinterpret_cast<const char*>(&result);
    std::size_t written = 0;
    while(written < sizeof(T)) {
      const ssize_t n = write(fds[1], bytes + written, sizeof(T) - written);
      if(n <= 0)
        _exit(2);
      written += std::size_t(n);
    }
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  T result;
  char* bytes = reinterpret_cast<char*>(&result);
  std::size_t received = 0;
  while(received < sizeof(T)) {
    const ssize_t n = read(fds[0], bytes + received, sizeof(T) - received);
    if(n <= 0)
      break;
    received += std::size_t(n);
  }
  close(fds[0]);
  int wstatus = 0;
  waitpid(pid, &wstatus, 0);
  if(received == sizeof(T) && WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0)
    return result;
  failure = WIFSIGNALED(wstatus) ? "child process killed by signal " + std::to_string(WTERMSIG(wstatus))
                                 : "child process exited with " + std::to_string(WEXITSTATUS(wstatus));
  return std::nullopt;
}

Run_record run_forked(Mesh& mesh, const SP::Energy_mix& energy, SP::Pipeline pipeline, double max_seconds)
{
  std::string failure;
  const std::optional<Run_record> record =
    in_child<Run_record>([&] { return run_once(mesh, energy, pipeline, max_seconds); }, failure);
  if(record)
    return *record;
  Run_record crashed;
  copy_string(crashed.detail, sizeof(crashed.detail), failure);
  return crashed;
}

// ---------------------------------------------------------------------------------------
// Yardstick: one sparse Cholesky factorization + solve of the Laplacian

using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The cotangent Laplacian (uniform graph Laplacian if some cotangent is not finite) plus
// 1e-8 * mean diagonal on the diagonal, so that it is positive definite.
Sparse laplacian(const Mesh& mesh, std::string& kind)
{
  const int n = int(mesh.number_of_vertices());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(12 * mesh.number_of_faces() + n);
  bool finite = true;
  for(int attempt = 0; attempt < 2; ++attempt) {
    const bool cotangent = attempt == 0;
    entries.clear();
    std::vector<double> diagonal(n, 0.0);
    for(auto f : mesh.faces()) {
      int id[3], k = 0;
      Eigen::Vector3d p[3];
      for(vertex_descriptor v : vertices_around_face(mesh.halfedge(f), mesh)) {
        if(k == 3)
          break;
        const Point& q = mesh.point(v);
        id[k] = int(v.idx());
        p[k] = Eigen::Vector3d(q.x(), q.y(), q.z());
        ++k;
      }
      for(int i = 0; i < 3; ++i) {  // the corner i weighs the opposite edge (j, l)
        const int j = (i + 1) % 3, l = (i + 2) % 3;
        double w = 0.5;
        if(cotangent) {
          const Eigen::Vector3d a = p[j] - p[i], b = p[l] - p[i];
          w = 0.5 * a.dot(b) / a.cross(b).norm();
          if(!std::isfinite(w))
            finite = false;
        }
        entries.emplace_back(id[j], id[l], -w);
        entries.emplace_back(id[l], id[j], -w);
        diagonal[id[j]] += w;
        diagonal[id[l]] += w;
      }
    }
    if(cotangent && !finite)
      continue;
    double mean = 0;
    for(double d : diagonal)
      mean += d;
    mean /= std::max(1, n);
    for(int i = 0; i < n; ++i)
      entries.emplace_back(i, i, diagonal[i] + 1e-8 * mean);
    kind = cotangent ? "cotan" : "uniform";
    break;
  }
  Sparse matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD
// The fastest of CHOLMOD's factorizations: supernodal wins on large meshes, simplicial on
// small and thin ones, as for the Newton matrices (see Cholmod_traits); huge pages help the
// supernodal one at some sizes only (see solve_time()).
const char* const yardstick_solver_name = "CHOLMOD LLT (the fastest of supernodal, supernodal on huge pages, and simplicial)";
#else
const char* const yardstick_solver_name = "Eigen SimplicialLLT";
#endif

double median(std::vector<double> values)
{
  if(values.empty())
    return 0;
  std::sort(values.begin(), values.end());
  const std::size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

struct Yardstick
{
  double seconds = -1;  // median of 3; negative if the factorization failed
  bool cotangent = true;  // false: the uniform graph Laplacian was used
};

// Median of 3 times of (symbolic analysis + numeric factorization + one solve) with
// `Solver`; negative if it failed. CHOLMOD's OpenMP regions run as in the package's runs
// (inline, by the process tuning of main()): the yardstick is not to carry an overhead that
// the package's runs avoid. Its supernodes are CHOLMOD's own, as in the package's
// factorizations (Cholmod_traits). OpenBLAS has its own thread count, and with `huge_pages`
// CHOLMOD's large blocks are on transparent huge pages, which make some factorizations
// faster and others slower (tools/process_tuning.h).
template <class Solver>
double solve_time(const Sparse& matrix, const Eigen::VectorXd& rhs, bool huge_pages = false)
{
  const process_tuning::Yardstick_settings settings(huge_pages);
  std::vector<double> times;
  for(int r = 0; r < 3; ++r) {
    const Clock::time_point start = Clock::now();
    Solver solver;
    solver.compute(matrix);
    if(solver.info() != Eigen::Success)
      return -1;
    const Eigen::VectorXd x = solver.solve(rhs);
    times.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    if(!x.allFinite())
      return -1;
  }
  return median(times);
}

// The fastest of the successful times; negative if none succeeded.
double fastest(std::initializer_list<double> times)
{
  double best = -1;
  for(double t : times)
    if(t >= 0 && (best < 0 || t < best))
      best = t;
  return best;
}

// Assembling the matrix is not timed.
Yardstick measure_yardstick(const Mesh& mesh)
{
  Yardstick out;
  std::string kind;
  const Sparse matrix = laplacian(mesh, kind);
  out.cotangent = kind == "cotan";
  Eigen::VectorXd rhs(matrix.rows());
  for(Eigen::Index i = 0; i < rhs.size(); ++i)
    rhs[i] = std::sin(double(i));  // anything not in the near-kernel
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD
  using Supernodal = Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower>;
  out.seconds = fastest({solve_time<Supernodal>(matrix, rhs), solve_time<Supernodal>(matrix, rhs, true),
                         solve_time<Eigen::CholmodSimplicialLLT<Sparse, Eigen::Lower>>(matrix, rhs)});
#else
  out.seconds = solve_time<Eigen::SimplicialLLT<Sparse, Eigen::Lower>>(matrix, rhs);
#endif
  return out;
}

// ---------------------------------------------------------------------------------------
// Meshes

struct Mesh_input
{
  std::string path;  // as given, possibly with suffixes
  std::string file;  // without them
  std::string name;  // file stem, with the suffixes
  int loops = 0;     // @loopN: Loop subdivisions
  int decimate = 0;  // @decimateN: edges collapsed until N% are left, after subdividing
  int slivers = 0;   // @sliversN: faces split at 1e-6 above an edge's midpoint, after subdividing
  int needles = 0;   // @needlesN: faces split at 1e-6 of an edge from a corner, 1e-7 off it
};

/// A MESH starting with one of these is built in code (synthetic_shapes.h): `tube:capsule150`,
/// `tube:helix4`, `tube:cylinder2000`, `iso:metaballs130`, `iso:starfish100`, `iso:lattice150`,
/// `shape:spikes150`, `shape:white7` (`shape:` takes any of its names).
const std::array<std::string, 3> synthetic_prefixes{"tube:", "iso:", "shape:"};

/// The length of `file`'s prefix of a shape built in code, 0 if it is a file.
std::size_t synthetic_prefix(const std::string& file)
{
  for(const std::string& prefix : synthetic_prefixes)
    if(file.compare(0, prefix.size(), prefix) == 0)
      return prefix.size();
  return 0;
}

/// `MESH[@loopN][@decimateN][@sliversN][@needlesN]`; nothing on an unknown suffix.
std::optional<Mesh_input> parse_mesh_argument(const std::string& argument)
{
  Mesh_input in;
  in.path = argument;
  const std::size_t slash = argument.find_last_of('/');
  const std::size_t at = argument.find('@', slash == std::string::npos ? 0 : slash + 1);
  in.file = argument.substr(0, at);
  if(at != std::string::npos)
    for(const std::string& suffix : split(argument.substr(at + 1), '@')) {
      const std::size_t digits = suffix.find_first_of("0123456789");
      const std::string kind = suffix.substr(0, digits);
      const int count = digits == std::string::npos ? 0 : std::atoi(suffix.c_str() + digits);
      int* field = kind == "loop"      ? &in.loops
                   : kind == "decimate" ? &in.decimate
                   : kind == "slivers"  ? &in.slivers
                   : kind == "needles"  ? &in.needles
                                        : nullptr;
      if(!field || count <= 0 || (field == &in.decimate && count > 100))
        return std::nullopt;
      *field = count;
    }
  std::string stem = in.file.substr(slash == std::string::npos ? 0 : slash + 1);
  const std::size_t dot = stem.rfind('.');
  if(synthetic_prefix(in.file) > 0)
    stem = in.file.substr(synthetic_prefix(in.file));
  else if(dot != std::string::npos && dot > 0)
    stem = stem.substr(0, dot);
  in.name = stem + (at == std::string::npos ? "" : argument.substr(at));
  return in;
}

/// Builds a `tube:`, `iso:` or `shape:` mesh, reads any other; false if that gave no mesh.
bool load_mesh(const std::string& file, Mesh& mesh)
{
  if(synthetic_prefix(file) == 0)
    return CGAL::IO::read_polygon_mesh(file, mesh) && !mesh.is_empty();
  std::optional<Mesh> shape = synthetic_shapes::by_name<Point>(file.substr(synthetic_prefix(file)));
  if(shape)
    mesh = std::move(*shape);
  return shape && !mesh.is_empty();
}

// ---------------------------------------------------------------------------------------
// Output

struct Row
{
  std::string mesh, path, energy, pipeline;
  std::size_t vertices = 0, faces = 0;
  int repeats = 0;
  std::vector<double> times;
  double time = 0, yardstick = 0;
  std::string yardstick_kind;
  Run_record run;  // the run of median time (all runs compute the same map)
  long peak_rss_kb = 0, peak_delta_kb = 0;  // max over the runs
  std::string status;
};

const char* status_name(int status, bool ran)
{
  if(!ran)
    return "CRASHED";
  switch(SP::Error_code(status)) {
  case SP::Error_code::OK: return "OK";
  case SP::Error_code::EMPTY_MESH: return "EMPTY_MESH";
  case SP::Error_code::INVALID_MESH: return "INVALID_MESH";
  case SP::Error_code::NOT_TRIANGLE_MESH: return "NOT_TRIANGLE_MESH";
  case SP::Error_code::NOT_CLOSED: return "NOT_CLOSED";
  case SP::Error_code::NON_MANIFOLD: return "NON_MANIFOLD";
  case SP::Error_code::ISOLATED_VERTICES: return "ISOLATED_VERTICES";
  case SP::Error_code::NOT_CONNECTED: return "NOT_CONNECTED";
  case SP::Error_code::NOT_GENUS_ZERO: return "NOT_GENUS_ZERO";
  case SP::Error_code::NON_FINITE_INPUT: return "NON_FINITE_INPUT";
  case SP::Error_code::DEGENERATE_INPUT: return "DEGENERATE_INPUT";
  case SP::Error_code::INVALID_PARAMETER: return "INVALID_PARAMETER";
  case SP::Error_code::INVALID_INITIALIZATION: return "INVALID_INITIALIZATION";
  case SP::Error_code::NO_VALID_MAP: return "NO_VALID_MAP";
  case SP::Error_code::NOT_CONVERGED: return "NOT_CONVERGED";
  case SP::Error_code::CANCELLED: return "CANCELLED";
  case SP::Error_code::TIME_LIMIT: return "TIME_LIMIT";
  }
  return "UNKNOWN";
}

// The energy column fits the longest energy of the run ("symmetric_dirichlet:0.7:0.3").
void print_header(int energy_width)
{
  std::printf("%-18s %8s %-*s %9s %9s %8s %5s %11s %-5s %5s %5s %7s %8s %8s %8s %9s %8s %7s %7s %8s %8s  %s\n",
              "mesh", "faces", energy_width, "energy", "time_s", "chol_s", "ratio", "iters", "energy_val", "valid", "flip", "degen",
              "degree", "qc_mean", "qc_p95", "logA", "minA", "L2str", "rsMean%", "rsMax%", "peak_MB", "dpeakMB",
              "status / stages");
}

void print_row(const Row& r, int energy_width)
{
  const Run_record& x = r.run;
  std::printf("%-18s %8zu %-*s %9.3f %9.4f %8.1f %5zu %11.5g %-5s %5zu %5zu %7.4f %8.3f %8.3f %8.3f %9.2e %8.2f "
              "%7.3f %7.2f %8.1f %8.1f  %s %s\n",
              r.mesh.c_str(), r.faces, energy_width, r.energy.c_str(), r.time, r.yardstick,
              r.yardstick > 0 ? r.time / r.yardstick : 0.0, x.iterations, x.energy, x.valid ? "yes" : "NO",
              x.flipped, x.degenerate, x.degree, x.qc_mean, x.qc_p95, x.log_area_mean, x.min_area_ratio,
              x.l2_stretch, 100 * x.resampling_mean, 100 * x.resampling_max, r.peak_rss_kb / 1024.0,
              r.peak_delta_kb / 1024.0, r.status.c_str(), x.stages);
  std::fflush(stdout);
}

std::string csv_field(const std::string& s)
{
  if(s.find_first_of(",\"\n") == std::string::npos)
    return s;
  std::string out = "\"";
  for(char c : s) {
    if(c == '"')
      out += '"';
    out += c;
  }
  return out + "\"";
}

std::string json_string(const std::string& s)
{
  std::string out = "\"";
  for(char c : s) {
    if(c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if(static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A number for JSON: non-finite values become null.
std::string json_number(double v)
{
  if(!std::isfinite(v))
    return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", v);
  return buffer;
}

bool write_csv(const std::string& file, const std::vector<Row>& rows)
{
  std::ofstream out(file);
  if(!out)
    return false;
  out << "mesh,path,vertices,faces,energy,pipeline,repeats,status,valid,solver_valid,time_s,time_min_s,time_max_s,"
         "yardstick_s,yardstick_kind,ratio,iterations,final_energy,stages,peak_rss_mb,peak_delta_mb,flipped,"
         "degenerate,degree,max_norm_error,qc_mean,qc_p95,log_area_mean,min_area_ratio,l2_stretch,angle_error_mean,"
         "resampling_mean,resampling_max,detail\n";
  out.precision(9);
  for(const Row& r : rows) {
    const Run_record& x = r.run;
    const double lo = r.times.empty() ? 0 : *std::min_element(r.times.begin(), r.times.end());
    const double hi = r.times.empty() ? 0 : *std::max_element(r.times.begin(), r.times.end());
    out << csv_field(r.mesh) << ',' << csv_field(r.path) << ',' << r.vertices << ',' << r.faces << ','
        << r.energy << ',' << r.pipeline << ',' << r.repeats << ',' << r.status << ',' << (x.valid ? 1 : 0)
        << ',' << (x.solver_valid ? 1 : 0) << ',' << r.time << ',' << lo << ',' << hi << ',' << r.yardstick
        << ',' << r.yardstick_kind << ',' << (r.yardstick > 0 ? r.time / r.yardstick : 0.0) << ','
        << x.iterations << ',' << x.energy << ',' << csv_field(x.stages) << ',' << r.peak_rss_kb / 1024.0 << ','
        << r.peak_delta_kb / 1024.0 << ',' << x.flipped << ',' << x.degenerate << ',' << x.degree << ','
        << x.max_norm_error << ',' << x.qc_mean << ',' << x.qc_p95 << ',' << x.log_area_mean << ','
        << x.min_area_ratio << ',' << x.l2_stretch << ',' << x.angle_mean << ',' << x.resampling_mean << ','
        << x.resampling_max << ',' << csv_field(x.detail) << '\n';
  }
  return bool(out);
}

bool write_json(const std::string& file, const std::vector<Row>& rows, bool forked)
{
  std::ofstream out(file);
  if(!out)
    return false;
  out << "{\n  \"yardstick_solver\": " << json_string(yardstick_solver_name)
      << ",\n  \"memory\": " << json_string(forked ? "fork per run" : "in process") << ",\n  \"runs\": [";
  for(std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const Run_record& x = r.run;
    out << (i ? "," : "") << "\n    {";
    out << "\"mesh\": " << json_string(r.mesh) << ", \"path\": " << json_string(r.path)
        << ", \"vertices\": " << r.vertices << ", \"faces\": " << r.faces
        << ", \"energy\": " << json_string(r.energy) << ", \"pipeline\": " << json_string(r.pipeline)
        << ", \"repeats\": " << r.repeats << ", \"status\": " << json_string(r.status)
        << ", \"detail\": " << json_string(x.detail) << ", \"valid\": " << (x.valid ? "true" : "false")
        << ", \"solver_valid\": " << (x.solver_valid ? "true" : "false") << ", \"time_s\": " << json_number(r.time)
        << ", \"times_s\": [";
    for(std::size_t k = 0; k < r.times.size(); ++k)
      out << (k ? ", " : "") << json_number(r.times[k]);
    out << "], \"yardstick_s\": " << json_number(r.yardstick)
        << ", \"yardstick_kind\": " << json_string(r.yardstick_kind)
        << ", \"ratio\": " << json_number(r.yardstick > 0 ? r.time / r.yardstick : 0.0)
        << ", \"iterations\": " << x.iterations << ", \"final_energy\": " << json_number(x.energy)
        << ", \"stages\": " << json_string(x.stages) << ", \"peak_rss_mb\": " << json_number(r.peak_rss_kb / 1024.0)
        << ", \"peak_delta_mb\": " << json_number(r.peak_delta_kb / 1024.0) << ", \"flipped\": " << x.flipped
        << ", \"degenerate\": " << x.degenerate << ", \"degree\": " << json_number(x.degree)
        << ", \"max_norm_error\": " << json_number(x.max_norm_error) << ", \"qc_mean\": " << json_number(x.qc_mean)
        << ", \"qc_p95\": " << json_number(x.qc_p95) << ", \"log_area_mean\": " << json_number(x.log_area_mean)
        << ", \"min_area_ratio\": " << json_number(x.min_area_ratio)
        << ", \"l2_stretch\": " << json_number(x.l2_stretch)
        << ", \"angle_error_mean\": " << json_number(x.angle_mean)
        << ", \"resampling_mean\": " << json_number(x.resampling_mean)
        << ", \"resampling_max\": " << json_number(x.resampling_max) << "}";
  }
  out << "\n  ]\n}\n";
  return bool(out);
}

// ---------------------------------------------------------------------------------------
// Runs

// The mesh that `in` names, with its Loop subdivisions and defects; false, with a message,
// if there is none.
bool prepare_mesh(const Mesh_input& in, Mesh& mesh)
{
  if(!load_mesh(in.file, mesh)) {
    std::cerr << (synthetic_prefix(in.file) > 0 ? "no such shape: " : "cannot read ") << in.file << '\n';
    return false;
  }
  if(in.loops > 0)
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(in.loops));
  if(in.decimate > 0) {
    // CGAL's default cost and placement (Lindstrom and Turk): what a user's decimated scan
    // looks like, obtuse and long faces where the surface is flat.
    namespace SMS = CGAL::Surface_mesh_simplification;
    SMS::edge_collapse(mesh, SMS::Count_ratio_stop_predicate<Mesh>(in.decimate / 100.0));
  }
  std::mt19937 random(1);  // the same faces in every run
  mesh_defects::add_slivers(mesh, in.slivers, 1e-6, random);
  mesh_defects::add_needles(mesh, in.needles, 1e-6, 1e-7, random);
  mesh.collect_garbage();  // contiguous vertex indices for the Laplacian
  return true;
}

// `row.repeats` runs of `energy` on `mesh`, each after the first on a turned copy if the
// options say so (`input`: the points as read, put back after each); their times and peak
// memory go into `row`. A run that did not run ends the repeats and is then the only one
// returned.
std::vector<Run_record> run_repeats(Mesh& mesh, const std::vector<Point>& input, const SP::Energy_mix& energy,
                                    SP::Pipeline pipeline, const Options& options, Row& row)
{
  std::vector<Run_record> runs;
  for(int r = 0; r < row.repeats; ++r) {
    const bool turned = r > 0 && options.turn_repeats;
    if(turned)
      turn(mesh, r);
    Run_record run = options.fork_runs ? run_forked(mesh, energy, pipeline, options.max_seconds)
                                       : run_once(mesh, energy, pipeline, options.max_seconds);
    if(turned)
      for(vertex_descriptor v : mesh.vertices())
        mesh.point(v) = input[std::size_t(v)];
    if(!run.ran) {
      runs.assign(1, run);
      break;
    }
    const long delta = options.fork_runs ? run.peak_rss_kb - run.rss_before_kb : run.rss_after_kb - run.rss_before_kb;
    row.peak_rss_kb = std::max(row.peak_rss_kb, run.peak_rss_kb);
    row.peak_delta_kb = std::max(row.peak_delta_kb, delta);
    row.times.push_back(run.seconds);
    runs.push_back(run);
  }
  return runs;
}

// The run a row reports: the one of median time (the lower middle one for an even count),
// or the first that gave an invalid map: the turned inputs take different paths.
Run_record reported_run(const std::vector<Run_record>& runs)
{
  for(const Run_record& run : runs)
    if(run.ran && !run.valid)
      return run;
  std::vector<std::size_t> order(runs.size());
  for(std::size_t k = 0; k < order.size(); ++k)
    order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return runs[a].seconds < runs[b].seconds; });
  return runs[order[(order.size() - 1) / 2]];
}

} // namespace

int main(int argc, char** argv)
{
  // This program owns its process, and tunes it for CHOLMOD (tools/process_tuning.h): its
  // OpenMP regions inline, OpenBLAS one thread short of the cores.
  const std::string tuning = process_tuning::enable();
  Options options;
  if(!parse_options(argc, argv, options)) {
    usage(argv[0]);
    return 1;
  }
  const SP::Pipeline pipeline = options.pipeline == "paper" ? SP::Pipeline::PAPER : SP::Pipeline::ROBUST;
  std::cout << "# yardstick: " << yardstick_solver_name << " of the cotangent Laplacian; memory: "
            << (options.fork_runs ? "one forked process per run (peak = its ru_maxrss)"
                                  : "in process (ru_maxrss is process-wide; dpeak = statm after - before)")
            << "; pipeline: " << options.pipeline << '\n';
  std::cout << "# process tuning: " << tuning << '\n';
  int energy_width = 9;
  for(const std::string& e : options.energies)
    energy_width = std::max(energy_width, int(e.size()));
  print_header(energy_width);

  std::vector<Row> rows;
  bool failures = false;
  for(const std::string& argument : options.meshes) {
    const std::optional<Mesh_input> parsed = parse_mesh_argument(argument);
    if(!parsed) {
      std::cerr << "unknown suffix in " << argument << " (@loopN, @decimateN, @sliversN, @needlesN)\n";
      failures = true;
      continue;
    }
    const Mesh_input& in = *parsed;
    Mesh mesh;
    if(!prepare_mesh(in, mesh)) {
      failures = true;
      continue;
    }

    std::string failure;
    const std::optional<Yardstick> measured =
      options.fork_runs ? in_child<Yardstick>([&] { return measure_yardstick(mesh); }, failure)
                        : std::optional<Yardstick>(measure_yardstick(mesh));
    if(!measured)
      std::cerr << in.name << ": yardstick: " << failure << '\n';
    const double yardstick = measured ? measured->seconds : -1;
    const std::string kind = measured ? (measured->cotangent ? "cotan" : "uniform") : "none";
    if(measured && measured->seconds < 0)
      std::cerr << in.name << ": the yardstick factorization failed\n";
    const int repeats = options.repeats ? *options.repeats : (mesh.number_of_faces() > 200000 ? 1 : 3);
    std::vector<Point> input;  // the points as read, put back after each turned repeat
    for(vertex_descriptor v : mesh.vertices())
      input.push_back(mesh.point(v));

    for(const std::string& energy_name : options.energies) {
      const SP::Energy_mix energy = *energy_from_spec(energy_name);
      Row row;
      row.mesh = in.name;
      row.path = in.path;
      row.energy = energy_name;
      row.pipeline = options.pipeline;
      row.vertices = mesh.number_of_vertices();
      row.faces = mesh.number_of_faces();
      row.repeats = repeats;
      row.yardstick = yardstick;
      row.yardstick_kind = kind;
      const std::vector<Run_record> runs = run_repeats(mesh, input, energy, pipeline, options, row);
      if(!runs.back().ran) {
        std::cerr << row.mesh << " / " << energy_name << ": " << runs.back().detail << '\n';
        failures = true;
      }
      row.run = reported_run(runs);
      row.time = median(row.times);
      row.status = status_name(row.run.status, row.run.ran);
      if(row.run.ran && row.run.valid != row.run.solver_valid)
        std::cerr << row.mesh << " / " << energy_name << ": the solver says the map is "
                  << (row.run.solver_valid ? "valid" : "invalid") << ", measure_distortion says "
                  << (row.run.valid ? "valid" : "invalid") << '\n';
      print_row(row, energy_width);
      rows.push_back(row);
    }
  }

  if(!options.csv.empty() && !write_csv(options.csv, rows)) {
    std::cerr << "cannot write " << options.csv << '\n';
    failures = true;
  }
  if(!options.json.empty() && !write_json(options.json, rows, options.fork_runs)) {
    std::cerr << "cannot write " << options.json << '\n';
    failures = true;
  }
  return failures ? 2 : 0;
}
