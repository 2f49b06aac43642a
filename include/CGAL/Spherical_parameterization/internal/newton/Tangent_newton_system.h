// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_TANGENT_NEWTON_SYSTEM_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_TANGENT_NEWTON_SYSTEM_H

#include <CGAL/Spherical_parameterization/Triangle_jet.h>
#include <CGAL/Spherical_parameterization/internal/backends/parallel_for.h>
#include <CGAL/Spherical_parameterization/internal/input/Triangle_soup.h>
#include <CGAL/Spherical_parameterization/internal/newton/project_psd.h>
#include <CGAL/Spherical_parameterization/internal/newton/tangent_basis.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// The Newton system of a map in the tangent charts of its points: two variables per free
/// vertex, the gradient and the lower triangle of the Hessian (2x2 blocks on the diagonal
/// and at every edge between free vertices). The sparsity pattern depends on the mesh only,
/// so the solver's symbolic analysis of `matrix()` is done once. Each face's Hessian is kept
/// (its lower triangle), so that the exact assembly can be projected to PSD afterwards
/// without evaluating the faces again.
template <class ConcurrencyTag>
class Tangent_newton_system
{
public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  using Vector = Eigen::VectorXd;
  using Basis = Eigen::Matrix<double, 3, 2>;
  using Face_hessian = Eigen::Matrix<double, 6, 6>;
  static constexpr int lower_entries = 21;  // of a symmetric 6x6 matrix

  /// The system of the first `free_vertices` of the `number_of_vertices` points of `faces`.
  Tangent_newton_system(const Faces& faces, std::size_t number_of_vertices, std::size_t free_vertices)
    : faces_(&faces), n_(number_of_vertices), free_(free_vertices)
  {
    build_pattern();
  }

  Matrix& matrix() { return matrix_; }
  const Vector& gradient() const { return gradient_; }

  /// The tangent basis of each vertex at the last `update_bases()`.
  const std::vector<Basis>& bases() const { return bases_; }

  void update_bases(const Points& x)
  {
    bases_.resize(n_);
    for(std::size_t v = 0; v < n_; ++v)
      bases_[v] = tangent_basis(x[v]);
  }

  /// Fills the gradient and the matrix (without shift) at `x`, in the charts of
  /// `update_bases(x)`. `face_jet(f, held)` returns face `f`'s energy jet, `held` true if
  /// the fold barrier holds the face: such a face gets its Hessian made PSD with absolute
  /// eigenvalues (the barrier is not convex in the points, `det` being trilinear), the others
  /// keep their exact Hessian unless `projected` (`project_free_face()`).
  template <class FaceJet>
  void assemble(const Points& x, const FaceJet& face_jet, bool projected, bool drop_rotation_curvature)
  {
    const std::size_t nf = faces_->size();
    face_gradient_.resize(nf);
    face_hessian_.resize(nf * lower_entries);
    held_.resize(nf);
    parallel_for<ConcurrencyTag>(nf, [&](std::size_t f) {
      bool held = false;
      const Triangle_jet jet = face_jet(f, held);
      held_[f] = held;
      face_gradient_[f] = jet.gradient;
      Face_hessian h = tangent_hessian(f, jet.hessian);
      if(held)
        project_held_face(h);
      else if(projected)
        project_free_face(h, f, x, drop_rotation_curvature);
      store_lower(h, f);
    });
    sum_face_terms(x);
  }

  /// After an exact `assemble()` at `x`: the same face terms with every face's Hessian
  /// projected, as a projected assembly gives them, from the face Hessians kept.
  void project_assembled_faces(const Points& x, bool drop_rotation_curvature)
  {
    parallel_for<ConcurrencyTag>(faces_->size(), [&](std::size_t f) {
      if(held_[f])
        return;  // projected already
      Face_hessian h;
      const double* in = &face_hessian_[f * lower_entries];
      for(int i = 0; i < 6; ++i)
        for(int j = 0; j <= i; ++j)
          h(i, j) = h(j, i) = *in++;
      project_free_face(h, f, x, drop_rotation_curvature);
      store_lower(h, f);
    });
    sum_face_terms(x);
  }

  /// The diagonal of the matrix without shift.
  std::vector<double> diagonal() const
  {
    std::vector<double> diagonal(2 * free_);
    for(std::size_t i = 0; i < 2 * free_; ++i)
      diagonal[i] = matrix_.valuePtr()[diagonal_index_[i]];
    return diagonal;
  }

  /// The mean absolute value of the diagonal, the scale of the shifts.
  double mean_abs_diagonal() const
  {
    double sum = 0;
    for(std::size_t i = 0; i < 2 * free_; ++i)
      sum += std::abs(matrix_.valuePtr()[diagonal_index_[i]]);
    return sum / double(2 * free_);
  }

  /// Writes `diagonal + mu` on the matrix's diagonal.
  void set_shifted_diagonal(const std::vector<double>& diagonal, double mu)
  {
    for(std::size_t i = 0; i < 2 * free_; ++i)
      matrix_.valuePtr()[diagonal_index_[i]] = diagonal[i] + mu;
  }

  /// `r - H s` for the assembled matrix H.
  Vector residual(const Vector& r, const Vector& s) const
  {
    Vector out = r;
    out.noalias() -= matrix_.template selfadjointView<Eigen::Lower>() * s;
    return out;
  }

  /// d = J^-1 r for the block diagonal J of the assembled Hessian, each vertex's 2x2 block
  /// with its eigenvalues replaced by their absolute values, at least this share of the
  /// largest (a near-singular block, such as a vertex whose faces are all flat along one
  /// direction, must not blow up).
  static constexpr double block_jacobi_floor = 1e-6;
  void block_jacobi(const Vector& r, Vector& d) const
  {
    d.resize(2 * free_);
    for(std::size_t v = 0; v < free_; ++v) {
      const int k = diagonal_index_[2 * v];  // (2v, 2v), then (2v + 1, 2v) below it in the column
      Eigen::Matrix2d block;
      block << matrix_.valuePtr()[k], matrix_.valuePtr()[k + 1], matrix_.valuePtr()[k + 1],
               matrix_.valuePtr()[diagonal_index_[2 * v + 1]];
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(block);
      const double floor =
        block_jacobi_floor * eigen.eigenvalues().cwiseAbs().maxCoeff() + std::numeric_limits<double>::min();
      const Eigen::Vector2d inverse = eigen.eigenvalues().cwiseAbs().cwiseMax(floor).cwiseInverse();
      d.template segment<2>(2 * v) =
        (eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose()) * r.template segment<2>(2 * v);
    }
  }

  /// The tangent vector `d` as one ambient vector per vertex (zero at the fixed vertices).
  std::vector<Eigen::Vector3d> ambient(const Vector& d) const
  {
    std::vector<Eigen::Vector3d> v(n_, Eigen::Vector3d::Zero());
    for(std::size_t i = 0; i < free_; ++i)
      v[i] = bases_[i] * d.template segment<2>(2 * i);
    return v;
  }

  /// The ambient vectors `v` (one per vertex) in the tangent charts of the free vertices.
  Vector tangent(const std::vector<Eigen::Vector3d>& v) const
  {
    Vector d(2 * free_);
    for(std::size_t i = 0; i < free_; ++i)
      d.template segment<2>(2 * i) = bases_[i].transpose() * v[i];
    return d;
  }

  /// The points `x` moved by `alpha d` in their tangent charts; the fixed vertices stay.
  void step_to(const Points& x, const Vector& d, double alpha, Points& out) const
  {
    for(std::size_t v = 0; v < n_; ++v)
      out[v] = v < free_ ? retract(x[v], bases_[v], alpha * d.template segment<2>(2 * v)) : x[v];
  }

  /// Allocates and writes the buffers of the first assembly (see `Newton_solver::prepare_memory()`).
  void prepare_memory()
  {
    const std::size_t nf = faces_->size();
    face_gradient_.assign(nf, Triangle_jet::Gradient::Zero());
    face_hessian_.assign(nf * lower_entries, 0.0);
    ambient_gradient_.assign(n_, Eigen::Vector3d::Zero());
    bases_.assign(n_, Basis::Zero());
  }

  /// Frees everything but `bases()`.
  void keep_only_bases()
  {
    Matrix().swap(matrix_);
    std::vector<int>().swap(entry_index_);
    std::vector<int>().swap(diagonal_index_);
    std::vector<Triangle_jet::Gradient>().swap(face_gradient_);
    std::vector<double>().swap(face_hessian_);
    std::vector<char>().swap(held_);
    std::vector<Eigen::Vector3d>().swap(ambient_gradient_);
    Vector().swap(gradient_);
  }

private:
  void build_pattern()
  {
    // Lower triangle of the matrix of the free vertices: 2x2 blocks on the diagonal and at
    // every edge between two of them, written column by column from the vertex adjacency
    // (per-face triplets would cost nearly half the set-up).
    const std::vector<std::vector<int>> later = later_neighbours();
    const int size = int(2 * free_);
    std::size_t entries = 0;
    for(const std::vector<int>& n : later)
      entries += 4 * n.size() + 3;
    matrix_.resize(size, size);
    matrix_.resizeNonZeros(Eigen::Index(entries));
    int* outer = matrix_.outerIndexPtr();
    int* inner = matrix_.innerIndexPtr();
    int k = 0;
    for(int column = 0; column < size; ++column) {
      const int v = column / 2;
      outer[column] = k;
      for(int row = column; row < 2 * v + 2; ++row)  // the diagonal block
        inner[k++] = row;
      for(int u : later[v]) {
        inner[k++] = 2 * u;
        inner[k++] = 2 * u + 1;
      }
    }
    outer[size] = k;
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + k, 0.0);

    // Where the entry (row, col) of the lower triangle is: in column `col` of vertex v, the
    // diagonal block comes first, then the blocks of `later[v]` in their order.
    const auto position = [&](int row, int col) {
      const int v = col / 2, u = row / 2;
      if(u == v)
        return outer[col] + row - col;
      const std::vector<int>& n = later[v];
      const int rank = int(std::lower_bound(n.begin(), n.end(), u) - n.begin());
      return outer[col] + 2 - col % 2 + 2 * rank + row % 2;
    };
    entry_index_.resize(faces_->size() * lower_entries);
    for(std::size_t f = 0; f < faces_->size(); ++f)
      for_each_lower_entry((*faces_)[f], [&](int local, int row, int col) {
        entry_index_[f * lower_entries + local] = row < size ? position(row, col) : -1;
      });
    diagonal_index_.resize(size);
    for(int i = 0; i < size; ++i)
      diagonal_index_[i] = outer[i];
  }

  // For each free vertex, its free neighbours of larger index, sorted.
  std::vector<std::vector<int>> later_neighbours() const
  {
    std::vector<std::vector<int>> later(free_);
    for(const auto& t : *faces_)
      for(int i = 0; i < 3; ++i) {
        const int a = std::min(t[i], t[(i + 1) % 3]), b = std::max(t[i], t[(i + 1) % 3]);
        if(std::size_t(b) < free_)
          later[a].push_back(b);
      }
    for(std::vector<int>& n : later) {
      std::sort(n.begin(), n.end());
      n.erase(std::unique(n.begin(), n.end()), n.end());
    }
    return later;
  }

  // Calls fn(local, row, col) for the 21 lower entries (i >= j) of a face's 6x6 block,
  // with (row, col) the global entry, swapped into the lower triangle.
  template <class Fn>
  static void for_each_lower_entry(const std::array<int, 3>& t, Fn fn)
  {
    int local = 0;
    for(int i = 0; i < 6; ++i)
      for(int j = 0; j <= i; ++j) {
        int row = 2 * t[i / 2] + i % 2, col = 2 * t[j / 2] + j % 2;
        if(row < col) std::swap(row, col);
        fn(local++, row, col);
      }
  }

  // A face's 9x9 ambient Hessian pulled back to the tangent variables of its vertices.
  Face_hessian tangent_hessian(std::size_t f, const Triangle_jet::Hessian& ambient) const
  {
    const auto& t = (*faces_)[f];
    Face_hessian h;
    for(int i = 0; i < 3; ++i)
      for(int j = 0; j < 3; ++j)
        h.template block<2, 2>(2 * i, 2 * j) =
          bases_[t[i]].transpose() * ambient.template block<3, 3>(3 * i, 3 * j) * bases_[t[j]];
    return h;
  }

  // An orthonormal basis of the tangent directions that rotate the three points of face `f`
  // together about the centre (the face's energy is invariant along them). A face whose
  // points coincide has only two; a direction lost to rounding is left out (a zero column).
  Eigen::Matrix<double, 6, 3> face_rotations(std::size_t f, const Points& x) const
  {
    const auto& t = (*faces_)[f];
    Eigen::Matrix<double, 6, 3> r;
    for(int k = 0; k < 3; ++k) {
      for(int i = 0; i < 3; ++i)
        r.template block<2, 1>(2 * i, k) = bases_[t[i]].transpose() * Eigen::Vector3d::Unit(k).cross(x[t[i]]);
      const double length = r.col(k).norm();
      for(int j = 0; j < k; ++j)  // Gram-Schmidt
        r.col(k) -= r.col(j).dot(r.col(k)) * r.col(j);
      const double left = r.col(k).norm();
      if(left > 1e-8 * length)
        r.col(k) /= left;
      else
        r.col(k).setZero();
    }
    return r;
  }

  // A face's Hessian made PSD where the barrier does not hold it. With
  // `drop_rotation_curvature`, its negative curvature along the rotations of its three
  // points, which comes from the chart (the energy is invariant along them), is dropped
  // rather than made absolute: made absolute, it adds about the face's energy to the
  // stiffness of every smooth mode of the map, which is the order of those modes' own.
  void project_free_face(Face_hessian& h, std::size_t f, const Points& x, bool drop_rotation_curvature) const
  {
    if(drop_rotation_curvature)
      project_to_psd(h, face_rotations(f, x));
    else
      project_to_psd(h);
  }

  // A face the barrier holds keeps the absolute value of every negative eigenvalue: its
  // gradient is the barrier's, which makes the curvature along its rotations large, and
  // made absolute it damps the capped steps of the continuation and floor stages.
  static void project_held_face(Face_hessian& h) { project_to_psd(h); }

  void store_lower(const Face_hessian& h, std::size_t f)
  {
    double* out = &face_hessian_[f * lower_entries];
    for(int i = 0; i < 6; ++i)
      for(int j = 0; j <= i; ++j)
        *out++ = h(i, j);
  }

  // The matrix (without shift) and the gradients from the face terms, summed in face order
  // so that the result does not depend on the number of threads.
  void sum_face_terms(const Points& x)
  {
    std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0);
    ambient_gradient_.assign(n_, Eigen::Vector3d::Zero());
    for(std::size_t f = 0; f < faces_->size(); ++f) {
      const auto& t = (*faces_)[f];
      for(int i = 0; i < 3; ++i)
        ambient_gradient_[t[i]] += face_gradient_[f].template segment<3>(3 * i);
      const double* h = &face_hessian_[f * lower_entries];
      const int* index = &entry_index_[f * lower_entries];
      for(int k = 0; k < lower_entries; ++k)
        if(index[k] >= 0)
          matrix_.valuePtr()[index[k]] += h[k];
    }
    gradient_.resize(2 * free_);
    for(std::size_t v = 0; v < free_; ++v) {
      gradient_.template segment<2>(2 * v) = bases_[v].transpose() * ambient_gradient_[v];
      // Second-order term of the retraction x = (p + B u) / |p + B u|: -<g_v, x_v> I_2.
      const double curvature = -ambient_gradient_[v].dot(x[v]);
      matrix_.valuePtr()[diagonal_index_[2 * v]] += curvature;
      matrix_.valuePtr()[diagonal_index_[2 * v + 1]] += curvature;
    }
  }

  const Faces* faces_;
  std::size_t n_;
  std::size_t free_;  // the unknowns: vertices 0 to free_ - 1
  Matrix matrix_;
  std::vector<int> entry_index_;     // per face, where its 21 lower entries go in the matrix (-1: a fixed vertex)
  std::vector<int> diagonal_index_;  // where each diagonal entry is
  std::vector<Basis> bases_;
  std::vector<Triangle_jet::Gradient> face_gradient_;
  std::vector<double> face_hessian_;  // per face, the lower triangle of its tangent Hessian
  std::vector<char> held_;            // per face: held by the fold barrier at the last assembly
  std::vector<Eigen::Vector3d> ambient_gradient_;
  Vector gradient_;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_NEWTON_TANGENT_NEWTON_SYSTEM_H
