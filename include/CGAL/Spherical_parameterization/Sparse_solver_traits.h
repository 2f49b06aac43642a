// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_SPARSE_SOLVER_TRAITS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_SPARSE_SOLVER_TRAITS_H

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD
#include <CGAL/Spherical_parameterization/internal/backends/Vertex_ordered_cholmod.h>
#include <Eigen/CholmodSupport>
#endif

namespace CGAL {
namespace Spherical_parameterization {

/// \ingroup PkgSphericalParameterizationRef
/// Sparse symmetric solver of the Newton systems with Eigen's `SimplicialLDLT`.
/// Only the lower triangle of the matrix is read. The pattern is analysed once.
/// \cgalModels `SphericalSparseSolverTraits`
class Eigen_sparse_LDLT_traits
{
public:
  /// \cond SKIP_IN_MANUAL
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  using Vector = Eigen::VectorXd;

  void analyze_pattern(const Matrix& m) { solver_.analyzePattern(m); }

  /// Factors `m`; true if and only if `m` is positive definite.
  bool factorize(const Matrix& m)
  {
    solver_.factorize(m);
    return solver_.info() == Eigen::Success && solver_.vectorD().minCoeff() > 0 && solver_.vectorD().allFinite();
  }

  Vector solve(const Vector& b) const { return solver_.solve(b); }
  /// \endcond

private:
  Eigen::SimplicialLDLT<Matrix, Eigen::Lower> solver_;
};

#ifdef CGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD
/// \ingroup PkgSphericalParameterizationRef
/// The same with CHOLMOD's Cholesky factorization (SuiteSparse), about twice as fast on
/// large meshes. Available when `CGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD` is defined.
/// CHOLMOD chooses per matrix between its supernodal factorization (dense BLAS blocks) and
/// its simplicial one, by the flops per entry of the factor: supernodal from 40 on
/// (CHOLMOD's default switch). The supernodes are CHOLMOD's own (`nrelax` 4, 16, 48): coarser
/// ones save BLAS calls but store more zeros, and on the 2x2 blocks of the Newton matrices
/// the smaller factor is the faster one when CHOLMOD's OpenMP regions run on the calling
/// thread (see below); when they go through OpenMP's thread team, the larger meshes still
/// gain and the smaller ones may lose (see doc/DESIGN.md).
/// From 50000 vertices on, the fill-reducing ordering is METIS's on the mesh's vertex graph,
/// expanded to the two unknowns of each vertex (a matrix of even size is taken to be made of
/// such 2x2 blocks; any other matrix is still factored correctly, perhaps with more fill):
/// on large meshes it is cheaper to compute than CHOLMOD's own ordering, or gives a factor of
/// fewer flops.
/// Every supernodal factor is given its matrix already in its order: the values are copied
/// into a permuted matrix kept for that, where CHOLMOD would transpose the lower triangle twice
/// into fresh memory at each factorization. The factor is the same, bit for bit; large
/// meshes solve a little faster, and the copy adds to the peak memory.
/// The solver changes nothing of the process beyond its own CHOLMOD objects: OpenBLAS's
/// thread count, CHOLMOD's OpenMP regions and SuiteSparse's allocator stay as the program set
/// them, and two solvers may run on two threads at once. What tunes those for a whole process
/// (the benchmark and the command line tool opt in) is in `tools/process_tuning.h`, outside
/// the package: Debian's CHOLMOD opens OpenMP regions of 4 threads for loops as short as
/// clearing a supernode, and OpenBLAS's threads spin while they wait, which on two cores
/// costs the factorizations much of their time.
/// \cgalModels `SphericalSparseSolverTraits`
class Cholmod_traits
{
public:
  /// \cond SKIP_IN_MANUAL
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  using Vector = Eigen::VectorXd;

  Cholmod_traits()
  {
    cholmod_common& c = solver_.cholmod();
    c.print = 0;  // an indefinite matrix is expected, not an error to print
    c.supernodal = CHOLMOD_AUTO;
    c.supernodal_switch = supernodal_from;
    // LL' for the simplicial factorization too: as LDL' (CHOLMOD's default) it factors an
    // indefinite matrix without failing (test_parameterizer), and the failure is how the
    // Newton solver learns that its shift is too small.
    c.final_ll = 1;
  }

  void analyze_pattern(const Matrix& m)
  {
    if(m.rows() < 2 * vertex_ordering_from || !solver_.analyze_pattern_by_vertices(m))
      solver_.analyzePattern(m);
    solver_.order_ahead(m);
  }
  bool factorize(const Matrix& m)
  {
    solver_.factorize_in_order(m);
    return solver_.info() == Eigen::Success;
  }
  Vector solve(const Vector& b) const
  {
    return solver_.solve_in_order(b);
  }

  /// Allocates the factor's numbers for the analysed pattern and writes them once, so that
  /// the first factorization does not meet fresh memory: the page faults of a large factor
  /// can make the first factorization much slower than the next ones, notably in a virtual
  /// machine. Another thread may do it while this object is otherwise unused. Supernodal
  /// factors only: the simplicial ones are small.
  void allocate_factor()
  {
    solver_.allocate_numeric_factor();
  }

  /// True if the last analysis chose the supernodal factorization.
  bool is_supernodal() const { return solver_.is_supernodal(); }
  /// \endcond

private:
  static constexpr Eigen::Index vertex_ordering_from = 50000;  // vertices
  static constexpr double supernodal_from = 40;                // flops per entry of the factor
  internal::Vertex_ordered_cholmod<Matrix> solver_;
};

/// The solver used when none is named: CHOLMOD when available, else Eigen.
using Default_sparse_solver_traits = Cholmod_traits;
#else
using Default_sparse_solver_traits = Eigen_sparse_LDLT_traits;
#endif

} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_SPARSE_SOLVER_TRAITS_H
