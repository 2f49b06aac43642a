/*!
\ingroup PkgSphericalParameterizationConcepts
\cgalConcept

The sparse symmetric solver of the Newton systems of
`CGAL::Spherical_parameterization::Spherical_parameterizer_3`. The matrices have the
size \f$ 2n \times 2n \f$ for \f$ n \f$ vertices (two tangent coordinates per vertex) and
one sparsity pattern per mesh: `analyze_pattern()` is called once per mesh (the input, each
level of the coarse-to-fine solve, and each patch of a map that a stage frees), then
`factorize()` and `solve()` at every iteration, `factorize()` possibly several times per
iteration while the solver searches for the shift that makes the matrix positive definite.

Only the lower triangle of the matrix is stored and must be read. `factorize()` is the test
of positive definiteness of the solver: it must return `false` for a matrix that is not
positive definite rather than a factorization of it, so a Cholesky or \f$ LDL^T \f$
factorization that checks its pivots is the natural model.

A model is default constructed by the solver. With `CGAL::spherical_parameterize()` it is
chosen through the named parameter \ref SP_np_sparse_linear_solver "sparse_linear_solver",
whose value is only used for its type.

\cgalRefines `DefaultConstructible`

\cgalHasModel `CGAL::Spherical_parameterization::Eigen_sparse_LDLT_traits`
\cgalHasModel `CGAL::Spherical_parameterization::Cholmod_traits`
*/
class SphericalSparseSolverTraits
{
public:
  /// \name Types
  /// @{

  /// The matrix type: `Eigen::SparseMatrix<double, Eigen::ColMajor, int>`.
  typedef unspecified_type Matrix;

  /// The vector type: `Eigen::VectorXd`.
  typedef unspecified_type Vector;

  /// @}

  /// \name Operations
  /// @{

  /// Symbolic analysis of the sparsity pattern of `m` (its lower triangle): the ordering
  /// and the structure of the factor, reused by every later `factorize()`.
  void analyze_pattern(const Matrix& m);

  /// Numeric factorization of `m`, whose pattern is the one analysed. Returns `true` if and
  /// only if `m` is positive definite and the factorization succeeded.
  bool factorize(const Matrix& m);

  /// The solution `x` of `m x = b` for the matrix `m` of the last successful `factorize()`.
  Vector solve(const Vector& b) const;

  /// Optional. Allocates the memory of the factor of the analysed pattern and writes it once,
  /// so that the first `factorize()` does not meet fresh memory. The solver calls it, if the
  /// model has it, on another thread while it works on the coarser levels, between
  /// `analyze_pattern()` and the first `factorize()`, when nothing else uses the object.
  void allocate_factor();

  /// @}
};
