// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_THREADS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_THREADS_H

#include <CGAL/Spherical_parameterization/internal/inline_openmp_regions.h>

#if defined(__unix__)
#include <dlfcn.h>
#endif

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// An integer setting of a library of the process (a thread count, a nesting level), as
/// its getter and setter, found at run time by name (`dlsym`): nothing is linked, and a
/// library the process does not have leaves both null.
struct Library_setting
{
  int (*get)() = nullptr;
  void (*set)(int) = nullptr;

  Library_setting() = default;
  Library_setting(const char* getter, const char* setter)
  {
#if defined(__unix__)
    get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, getter));
    set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, setter));
#else
    (void)getter;
    (void)setter;
#endif
  }
};

/// While alive, `setting` holds `change(its value)`; the value is restored after.
class Scoped_setting
{
public:
  Scoped_setting(const Library_setting& setting, int (*change)(int)) : setting_(setting)
  {
    if(setting_.get && setting_.set) {
      saved_ = setting_.get();
      changed_ = change(saved_) != saved_;
      if(changed_)
        setting_.set(change(saved_));
    }
  }
  ~Scoped_setting()
  {
    if(changed_)
      setting_.set(saved_);
  }
  Scoped_setting(const Scoped_setting&) = delete;
  Scoped_setting& operator=(const Scoped_setting&) = delete;

private:
  const Library_setting& setting_;
  int saved_ = 0;
  bool changed_ = false;
};

/// While alive, OpenBLAS (when it is the BLAS of the process) runs on one thread less than
/// it is set to (one thread on two cores), leaving a core of slack. Any other BLAS is left
/// alone. Define `CGAL_SPHERICAL_PARAMETERIZATION_KEEP_BLAS_THREADS` to turn this off.
/// The setting is the process's: two of these alive on two threads at once could restore
/// each other's values, so the package calls CHOLMOD's BLAS from one thread at a time (what
/// runs on another thread, the input's symbolic analysis and `Cholmod_traits::allocate_factor()`,
/// needs no BLAS and holds none of these).
///
/// Why: OpenBLAS's threads spin while they wait. When another process holds a core, a
/// CHOLMOD factorization with two BLAS threads on two cores slows down badly: bunny00 after
/// one subdivision (302k faces), Combined (1, 1), took 18.5 s against 12.0 s with one BLAS
/// thread while one core was busy, and once 443 s against 14 s while a build ran. On an idle
/// machine one thread cost 13 to 22% in session 10 (10.2 -> 11.5 s; bunny00 1.62 -> 1.98 s),
/// nothing measurable since the vertex ordering (doc/NOTES.md, round ten). On more cores the
/// factorization keeps most of its parallel speed-up.
class Blas_thread_slack : Scoped_setting
{
public:
  Blas_thread_slack() : Scoped_setting(openblas_threads(), [](int n) { return n > 1 ? n - 1 : n; }) {}

private:
  // Looked up once: a factorization and its solves each construct one of these.
  static const Library_setting& openblas_threads()
  {
#if defined(CGAL_SPHERICAL_PARAMETERIZATION_KEEP_BLAS_THREADS)
    static const Library_setting threads;
#else
    static const Library_setting threads("openblas_get_num_threads", "openblas_set_num_threads");
#endif
    return threads;
  }
};

/// While alive, the OpenMP parallel regions that the calling thread starts run on that
/// thread alone (its `max-active-levels` is 0; the setting is per thread). Without an
/// OpenMP runtime in the process it does nothing.
///
/// Why: Debian's CHOLMOD (3.0) opens OpenMP regions of a fixed 4 threads in its supernodal
/// factorization, for loops as short as clearing a supernode, whatever the cores. On two
/// cores the threads wait on each other at every region's barrier. With one thread
/// (`OMP_THREAD_LIMIT=1`, measured side by side, 3 runs each): bunny00 Dirichlet 3.85 to
/// 4.24 s -> 3.27 to 3.36 s, Combined 2.23 to 2.48 s -> 1.83 to 1.91 s.
/// Where `inline_openmp_regions.h` can, CHOLMOD's regions then run as plain calls, without
/// libgomp's team of one.
class Openmp_serial : Scoped_setting
{
public:
  Openmp_serial() : Scoped_setting(openmp_levels(), [](int) { return 0; })
  {
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_INLINE_OPENMP_REGIONS
    was_inline_ = inline_openmp_regions;
    inline_openmp_regions = true;
#endif
  }
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_INLINE_OPENMP_REGIONS
  ~Openmp_serial() { inline_openmp_regions = was_inline_; }
#endif

private:
  static const Library_setting& openmp_levels()
  {
    static const Library_setting levels("omp_get_max_active_levels", "omp_set_max_active_levels");
    return levels;
  }
#ifdef CGAL_SPHERICAL_PARAMETERIZATION_INLINE_OPENMP_REGIONS
  bool was_inline_ = false;
#endif
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_THREADS_H
