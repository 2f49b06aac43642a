// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_THREADS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_THREADS_H

#if defined(__unix__)
#include <dlfcn.h>
#endif

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// While alive, OpenBLAS (when it is the BLAS of the process) runs on one thread less than
/// it is set to (one thread on two cores), leaving a core of slack; the previous count is
/// restored after. Found at run time (`dlsym`), so nothing is linked and
/// any other BLAS is left alone. Define `CGAL_SPHERICAL_PARAMETERIZATION_KEEP_BLAS_THREADS`
/// to turn this off.
///
/// Why: OpenBLAS's threads spin while they wait. When another process holds a core, a
/// CHOLMOD factorization with two BLAS threads on two cores slows down badly: bunny00 after
/// one subdivision (302k faces), Combined (1, 1), took 18.5 s against 12.0 s with one BLAS
/// thread while one core was busy, and once 443 s against 14 s while a build ran. On an idle
/// machine one thread costs 13 to 22% (10.2 -> 11.5 s; bunny00 1.62 -> 1.98 s), 13% in the
/// median of the benchmark. On more cores the factorization keeps most of its parallel speed-up.
class Blas_thread_slack
{
public:
  Blas_thread_slack()
  {
    const Openblas& blas = openblas();
    if(blas.get && blas.set) {
      saved_ = blas.get();
      if(saved_ > 1)
        blas.set(saved_ - 1);
    }
  }
  ~Blas_thread_slack()
  {
    if(saved_ > 1)
      openblas().set(saved_);
  }
  Blas_thread_slack(const Blas_thread_slack&) = delete;
  Blas_thread_slack& operator=(const Blas_thread_slack&) = delete;

private:
  struct Openblas
  {
    int (*get)() = nullptr;
    void (*set)(int) = nullptr;
  };

  // Looked up once: a factorization and its solves each construct one of these.
  static const Openblas& openblas()
  {
    static const Openblas functions = [] {
      Openblas f;
#if defined(__unix__) && !defined(CGAL_SPHERICAL_PARAMETERIZATION_KEEP_BLAS_THREADS)
      f.get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
      f.set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
#endif
      return f;
    }();
    return functions;
  }

  int saved_ = 0;
};

/// While alive, the OpenMP parallel regions that the calling thread starts run on that
/// thread alone (its `max-active-levels` is 0; restored after). Found at run time (`dlsym`):
/// nothing is linked, and without an OpenMP runtime in the process it does nothing.
///
/// Why: Debian's CHOLMOD (3.0) opens OpenMP regions of a fixed 4 threads in its supernodal
/// factorization, for loops as short as clearing a supernode, whatever the cores. On two
/// cores the threads wait on each other at every region's barrier. With one thread
/// (`OMP_THREAD_LIMIT=1`, measured side by side, 3 runs each): bunny00 Dirichlet 3.85 to
/// 4.24 s -> 3.27 to 3.36 s, Combined 2.23 to 2.48 s -> 1.83 to 1.91 s.
class Openmp_serial
{
public:
  Openmp_serial()
  {
    const Openmp& omp = openmp();
    if(omp.get && omp.set) {
      saved_ = omp.get();
      omp.set(0);
    }
  }
  ~Openmp_serial()
  {
    if(saved_ >= 0)
      openmp().set(saved_);
  }
  Openmp_serial(const Openmp_serial&) = delete;
  Openmp_serial& operator=(const Openmp_serial&) = delete;

private:
  struct Openmp
  {
    int (*get)() = nullptr;
    void (*set)(int) = nullptr;
  };

  static const Openmp& openmp()
  {
    static const Openmp functions = [] {
      Openmp f;
#if defined(__unix__)
      f.get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
      f.set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
#endif
      return f;
    }();
    return functions;
  }

  int saved_ = -1;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_SOLVER_THREADS_H
