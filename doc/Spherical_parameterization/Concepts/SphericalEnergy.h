/*!
\ingroup PkgSphericalParameterizationConcepts
\cgalConcept

A planar energy of one triangle, the `E_flat` of Friedel et al.: the energy of the flat
<em>chord triangle</em> spanned by the three sphere points of a face, measured against the input
triangle of that face. The package multiplies it by \f$ d_{\min}^{-2} \f$ (see
`CGAL::Spherical_parameterization::inverse_squared_d_min()`) and sums over the faces; the
energy itself never sees the sphere.

What depends on the input triangle only (weights, areas) is computed once per face by
`face_data()` and stored as a `Face_data`; `flat_energy()` is then called at every iteration
of the solver. It is written once, on a generic number type: with `Number = double` it gives
the value, with `Number = CGAL::Spherical_parameterization::Triangle_jet` the value with its
exact gradient and Hessian in the nine coordinates of the chord triangle. Build it from the
primitives of `CGAL::Spherical_parameterization::Chord_triangle` and the operations on
`Triangle_jet`, and write `using std::sqrt;` (or `log`) in the function so that both number
types find their overload.

Requirements on the values:
- `flat_energy()` is finite and non-negative on non-degenerate chord triangles; it may be
  `+infinity` where the energy has a barrier (the solver rejects such steps);
- the input has been scaled to total area \f$ 4\pi \f$, the area of the unit sphere, before
  `face_data()` is called, so that lengths and areas compare with those of the chord
  triangles whatever the size of the model;
- `flat_energy()` is `const` and may be called from several threads at once (the faces are
  evaluated in parallel with `CGAL::Parallel_tag`, the default when TBB is linked): it must
  not modify shared state.

A model is copied by `CGAL::Spherical_parameterization::Spherical_parameterizer_3` and by
`CGAL::spherical_parameterize()`. It must be default constructible if the parameterizer is
constructed without an energy (except for `Balanced_energy`, `Combined_energy` and
`Energy_mix`, whose defaults are `balanced_energy()`, `combined_energy(1, 1)` and the same
balanced energy).

\cgalRefines `CopyConstructible`

\cgalHasModel `CGAL::Spherical_parameterization::Tutte_energy`
\cgalHasModel `CGAL::Spherical_parameterization::Dirichlet_energy`
\cgalHasModel `CGAL::Spherical_parameterization::Area_energy`
\cgalHasModel `CGAL::Spherical_parameterization::Stretch_energy`
\cgalHasModel `CGAL::Spherical_parameterization::MIPS_energy`
\cgalHasModel `CGAL::Spherical_parameterization::Area_distortion_energy`
\cgalHasModel `CGAL::Spherical_parameterization::Inverse_dirichlet_energy`
\cgalHasModel `CGAL::Spherical_parameterization::Weighted_sum`

\sa \ref SPCustomEnergy in the User Manual, and the example \ref custom_energy.cpp.
*/
class SphericalEnergy
{
public:
  /// \name Types
  /// @{

  /*!
  The per-face constants, computed once from the input triangle: for instance the half
  cotangent weights of its edges, or its area. Copyable; may be an empty `struct`.
  `CGAL::Spherical_parameterization::Jacobian_face_data` holds what the energies of the
  Jacobian need.
  */
  typedef unspecified_type Face_data;

  /// @}

  /// \name Operations
  /// @{

  /*!
  The constants of the face whose input triangle, scaled with the whole mesh to area
  \f$ 4\pi \f$, is `r`.
  */
  Face_data face_data(const CGAL::Spherical_parameterization::Reference_triangle& r) const;

  /*!
  The energy of the chord triangle `t` against the input triangle described by `d`.
  Instantiated with `Number = double` and
  `Number = CGAL::Spherical_parameterization::Triangle_jet`.
  */
  template <class Number>
  Number flat_energy(const CGAL::Spherical_parameterization::Chord_triangle<Number>& t,
                     const Face_data& d) const;

  /*!
  Optional: `true` if the energy grows without bound as a face's signed area goes to zero, as
  `Area_distortion_energy` does. The solver then lengthens the full steps of its positive
  definite Hessian model while the energy keeps falling, since such an energy's Hessian
  stays indefinite in the compressed faces up to its minimum. `Weighted_sum` forwards it from
  its terms of non-zero weight. An energy without this member is taken not to have one.
  */
  bool has_area_barrier() const;

  /// @}
};
