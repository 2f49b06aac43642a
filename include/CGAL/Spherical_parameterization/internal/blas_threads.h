// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BLAS_THREADS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BLAS_THREADS_H

#if defined(__unix__) && !defined(CGAL_SPHERICAL_PARAMETERIZATION_KEEP_BLAS_THREADS)
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
/// machine one thread costs 8 to 15% (9.3 -> 10.7 s; bunny00 1.7 -> 1.85 s). On more cores
/// the factorization keeps most of its parallel speed-up.
class Blas_thread_slack
{
public:
  Blas_thread_slack()
  {
#if defined(__unix__) && !defined(CGAL_SPHERICAL_PARAMETERIZATION_KEEP_BLAS_THREADS)
    const auto get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    set_ = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    if(get && set_) {
      saved_ = get();
      if(saved_ > 1)
        set_(saved_ - 1);
    }
#endif
  }
  ~Blas_thread_slack()
  {
    if(set_ && saved_ > 1)
      set_(saved_);
  }
  Blas_thread_slack(const Blas_thread_slack&) = delete;
  Blas_thread_slack& operator=(const Blas_thread_slack&) = delete;

private:
  void (*set_)(int) = nullptr;
  int saved_ = 0;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BLAS_THREADS_H
