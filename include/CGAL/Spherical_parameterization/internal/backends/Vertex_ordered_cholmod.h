// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BACKENDS_VERTEX_ORDERED_CHOLMOD_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BACKENDS_VERTEX_ORDERED_CHOLMOD_H

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

#include <algorithm>
#include <tuple>
#include <utility>
#include <vector>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// CHOLMOD's Cholesky factorization whose fill-reducing ordering can be computed
/// on the vertex graph of a Newton matrix made of 2x2 blocks (unknowns `2v` and `2v + 1` of
/// vertex `v`), by METIS nested dissection, and expanded to the blocks.
///
/// Why (the pattern of the 2n x 2n Newton matrix; figures in doc/DESIGN.md):
/// - on the largest meshes CHOLMOD's own analysis tries AMD, finds it poor and runs METIS on
///   the 2n x 2n matrix; METIS on the vertex graph, half the size, takes about half the time
///   for the same flops and factorization time;
/// - on meshes a few times smaller CHOLMOD keeps AMD; METIS on the vertex graph costs more
///   analysis but cuts the flops and the factorization time, which the few factorizations
///   of a level repay;
/// - on smaller meshes it is a wash, hence `Cholmod_traits` asks for it from 50000 vertices on.
/// Eigen's supernodal class gives the interface; `Cholmod_traits` lets CHOLMOD choose the
/// simplicial factorization for the matrices with few flops per entry of the factor.
///
/// A supernodal factor can also be given the matrix already in its order (`order_ahead()`,
/// then `factorize_in_order()` and `solve_in_order()`): CHOLMOD otherwise permutes the lower
/// triangle it is given with two transpositions, into fresh memory, at every factorization.
template <class Matrix>
class Vertex_ordered_cholmod : public Eigen::CholmodSupernodalLLT<Matrix, Eigen::Lower>
{
  using Base = Eigen::CholmodSupernodalLLT<Matrix, Eigen::Lower>;
  using Vector = Eigen::VectorXd;

public:
  /// Symbolic analysis of `m` (of even size) with the METIS ordering of its vertex graph;
  /// false, with nothing analysed, if CHOLMOD could not provide it (built without METIS).
  bool analyze_pattern_by_vertices(const Matrix& m)
  {
    std::vector<int> permutation;
    if(m.rows() % 2 != 0 || !vertex_graph_ordering(m, permutation))
      return false;
    if(this->m_cholmodFactor)
      cholmod_free_factor(&this->m_cholmodFactor, &this->cholmod());
    cholmod_sparse a = Eigen::viewAsCholmod(m.template selfadjointView<Eigen::Lower>());
    const Methods saved(this->cholmod());
    this->cholmod().nmethods = 1;
    this->cholmod().method[0].ordering = CHOLMOD_GIVEN;
    this->m_cholmodFactor = cholmod_analyze_p(&a, permutation.data(), nullptr, 0, &this->cholmod());
    saved.restore(this->cholmod());
    if(!this->m_cholmodFactor)
      return false;
    this->m_isInitialized = true;
    this->m_info = Eigen::Success;
    this->m_analysisIsOk = true;
    this->m_factorizationIsOk = false;
    return true;
  }

  bool is_supernodal() const { return this->m_cholmodFactor && this->m_cholmodFactor->is_super; }

  /// After the analysis of `m` chose a supernodal factor: analyses instead the lower triangle
  /// of `m` permuted by that factor's ordering, with the natural ordering. The factor is the
  /// same, and `factorize_in_order()` copies the values of `m` into that permuted matrix,
  /// one pass without allocation, where CHOLMOD would transpose twice. False, with the
  /// analysis left as it was, for a simplicial factor or if CHOLMOD refused.
  bool order_ahead(const Matrix& m)
  {
    if(!is_supernodal())
      return false;
    const int* perm = static_cast<const int*>(this->m_cholmodFactor->Perm);
    std::vector<int> permutation(perm, perm + m.rows());
    Matrix permuted;
    std::vector<int> source;
    permute_lower(m, permutation, permuted, source);
    const Matrix& pattern = permuted;
    cholmod_sparse a = Eigen::viewAsCholmod(pattern.template selfadjointView<Eigen::Lower>());
    const Methods saved(this->cholmod());
    this->cholmod().nmethods = 1;
    this->cholmod().method[0].ordering = CHOLMOD_NATURAL;
    this->cholmod().postorder = false;  // the order is already postordered
    cholmod_factor* natural = cholmod_analyze(&a, &this->cholmod());
    saved.restore(this->cholmod());
    if(!natural || natural->ordering != CHOLMOD_NATURAL) {
      if(natural)
        cholmod_free_factor(&natural, &this->cholmod());
      this->cholmod().status = CHOLMOD_OK;
      return false;
    }
    cholmod_free_factor(&this->m_cholmodFactor, &this->cholmod());
    this->m_cholmodFactor = natural;
    permutation_ = std::move(permutation);
    permuted_ = std::move(permuted);
    source_ = std::move(source);
    return true;
  }

  /// Factors `m`, through its permuted copy after `order_ahead()`.
  void factorize_in_order(const Matrix& m)
  {
    if(permutation_.empty())
      return Base::factorize(m);
    const double* values = m.valuePtr();
    double* copy = permuted_.valuePtr();
    for(std::size_t k = 0; k < source_.size(); ++k)
      copy[k] = values[source_[k]];
    Base::factorize(permuted_);
  }

  /// Solves with the last factor, in the order of the matrices given to `factorize_in_order()`.
  Vector solve_in_order(const Vector& b) const
  {
    if(permutation_.empty())
      return Base::solve(b);
    Vector permuted_b(b.size());
    for(Eigen::Index k = 0; k < b.size(); ++k)
      permuted_b[k] = b[permutation_[std::size_t(k)]];
    const Vector y = Base::solve(permuted_b);
    Vector x(b.size());
    for(Eigen::Index k = 0; k < b.size(); ++k)
      x[permutation_[std::size_t(k)]] = y[k];
    return x;
  }

  /// True once the factor has numbers (a factorization or `allocate_numeric_factor()`).
  bool has_numeric_factor() const { return this->m_cholmodFactor && this->m_cholmodFactor->xtype != CHOLMOD_PATTERN; }

  /// Allocates the numeric part of an analysed supernodal factor, as its first factorization
  /// would, and writes it once, so that this factorization does not meet fresh memory.
  void allocate_numeric_factor()
  {
    cholmod_factor* factor = this->m_cholmodFactor;
    if(!factor || !factor->is_super || factor->xtype != CHOLMOD_PATTERN)
      return;
    // The conversion `cholmod_super_numeric` makes of a symbolic factor.
    if(!cholmod_change_factor(CHOLMOD_REAL, true, true, true, true, factor, &this->cholmod())) {
      this->cholmod().status = CHOLMOD_OK;  // left symbolic: the factorization allocates it
      return;
    }
    std::fill_n(static_cast<double*>(factor->x), factor->xsize, 0.0);
  }

private:
  std::vector<int> permutation_;  // after `order_ahead()`: CHOLMOD's `Perm` of the first analysis
  Matrix permuted_;               // the lower triangle of the matrix in that order
  std::vector<int> source_;       // for each of its entries, the entry of the matrix given

  struct Methods
  {
    explicit Methods(const cholmod_common& c)
      : count(c.nmethods), first_ordering(c.method[0].ordering), postorder(c.postorder)
    {
    }
    void restore(cholmod_common& c) const
    {
      c.nmethods = count;
      c.method[0].ordering = first_ordering;
      c.postorder = postorder;
    }
    int count, first_ordering, postorder;
  };

  // The lower triangle of P m P^T, P the permutation whose k-th row is row
  // `permutation[k]` of `m` (CHOLMOD's `Perm`), with its row indices sorted in each column
  // as CHOLMOD's transposition gives them; `source[k]` is the entry of `m` that entry k copies.
  static void permute_lower(const Matrix& m, const std::vector<int>& permutation, Matrix& permuted,
                            std::vector<int>& source)
  {
    const Eigen::Index n = m.rows();
    std::vector<int> rank(std::size_t(n), 0);
    for(std::size_t k = 0; k < permutation.size(); ++k)
      rank[std::size_t(permutation[k])] = int(k);
    // fn(row, column, index in m) for each entry of m's lower triangle (CHOLMOD reads no
    // other), at its place in P m P^T's lower triangle
    const auto for_each_entry = [&](auto fn) {
      for(Eigen::Index j = 0; j < n; ++j)
        for(typename Matrix::InnerIterator it(m, j); it; ++it)
          if(it.row() >= j) {
            const int r = rank[std::size_t(it.row())], c = rank[std::size_t(j)];
            fn(std::max(r, c), std::min(r, c), int(&it.value() - m.valuePtr()));
          }
    };
    permuted.resize(n, n);  // outer indices all 0
    int* outer = permuted.outerIndexPtr();
    for_each_entry([&](int, int column, int) { ++outer[column + 1]; });
    for(Eigen::Index j = 0; j < n; ++j)
      outer[j + 1] += outer[j];
    permuted.resizeNonZeros(outer[n]);
    int* inner = permuted.innerIndexPtr();
    source.resize(std::size_t(outer[n]));
    std::vector<int> next(outer, outer + n);
    for_each_entry([&](int row, int column, int index) {
      const int k = next[std::size_t(column)]++;
      inner[k] = row;
      source[std::size_t(k)] = index;
    });
    std::vector<std::pair<int, int>> column;  // (row, source) of one column, to sort
    for(Eigen::Index j = 0; j < n; ++j) {
      column.clear();
      for(int k = outer[j]; k < outer[j + 1]; ++k)
        column.emplace_back(inner[k], source[std::size_t(k)]);
      std::sort(column.begin(), column.end());
      for(int k = outer[j]; k < outer[j + 1]; ++k)
        std::tie(inner[k], source[std::size_t(k)]) = column[std::size_t(k - outer[j])];
    }
    std::fill(permuted.valuePtr(), permuted.valuePtr() + permuted.nonZeros(), 0.0);
  }

  // METIS on the graph of the 2x2 blocks, each vertex then expanded to its two unknowns.
  // `cholmod_metis` gives the ordering alone; `cholmod_analyze` would add a symbolic
  // factorization of the vertex graph that nothing uses.
  bool vertex_graph_ordering(const Matrix& m, std::vector<int>& permutation)
  {
    const Matrix vertices = vertex_graph(m);
    cholmod_sparse a = Eigen::viewAsCholmod(vertices.template selfadjointView<Eigen::Lower>());
    std::vector<int> order(std::size_t(vertices.rows()));
    if(!cholmod_metis(&a, nullptr, 0, false, order.data(), &this->cholmod()) || this->cholmod().status != CHOLMOD_OK)
      return false;
    permutation.resize(2 * order.size());
    for(std::size_t k = 0; k < order.size(); ++k) {
      permutation[2 * k] = 2 * order[k];
      permutation[2 * k + 1] = 2 * order[k] + 1;
    }
    return true;
  }

  // The lower triangle of the n x n matrix with an entry `(u, v)` wherever the 2x2 block
  // `(u, v)`, `u >= v`, has its entry `(2u, 2v)`, as the Newton matrix's blocks all do. (A
  // block without it is left out of the graph: only the ordering's quality suffers.)
  static Matrix vertex_graph(const Matrix& m)
  {
    const Eigen::Index n = m.rows() / 2;
    Matrix graph(n, n);
    graph.resizeNonZeros(m.nonZeros() / 4 + n);
    int* outer = graph.outerIndexPtr();
    int* inner = graph.innerIndexPtr();
    int k = 0;
    for(Eigen::Index v = 0; v < n; ++v) {
      outer[v] = k;
      for(typename Matrix::InnerIterator it(m, 2 * v); it; ++it)
        if(it.row() % 2 == 0)
          inner[k++] = int(it.row() / 2);
    }
    outer[n] = k;
    graph.resizeNonZeros(k);
    std::fill(graph.valuePtr(), graph.valuePtr() + k, 1.0);
    return graph;
  }
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BACKENDS_VERTEX_ORDERED_CHOLMOD_H
