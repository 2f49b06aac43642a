// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INLINE_OPENMP_REGIONS_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INLINE_OPENMP_REGIONS_H

// CHOLMOD's OpenMP regions, run as plain calls where the package's solver asked for them
// to run on the calling thread alone (`Openmp_serial`).
//
// Why: Debian's CHOLMOD opens two or three OpenMP regions per supernode of every
// supernodal factorization (`#pragma omp parallel for ... if(...)`, mostly to clear or
// fill a supernode). Even run on one thread, each goes through GNU libgomp's team start
// and end, and the end of a team's barrier is a `futex` system call whatever the team's
// size: 120k of them in one solve of bunny00 (75k faces). Where system calls are dear (the
// virtual machines we measure on), those regions took 8 to 25% of the solve: bunny00
// Combined 1.47 to 1.54 s -> 1.26 to 1.27 s, diplodocus Tutte 9.1 to 10.4 s -> 7.7 to 7.9
// s, bunny00 after one subdivision 7.7 to 8.5 s -> 7.1 to 7.8 s, the same maps bit for
// bit (doc/NOTES.md, session 48).
//
// How: this header defines `GOMP_parallel`, libgomp's entry point of a parallel region,
// in the program (as an inline function, emitted once). The dynamic linker then binds
// CHOLMOD's calls to it instead of libgomp's (symbol interposition). It calls the
// region's body directly only if all of these hold:
// - the calling thread is inside an `Openmp_serial` scope (the package's CHOLMOD calls);
// - the call comes from CHOLMOD's own code (not from a BLAS that uses OpenMP, whose
//   threads are left to `Blas_thread_slack`);
// - the thread is in no OpenMP region (in one, the body would see the enclosing team's
//   size and thread number; CHOLMOD's bodies split their loops by them).
// Run so, CHOLMOD's bodies see one thread, number 0, as in a region of one thread: they
// call nothing else of libgomp (`omp_get_num_threads`, `omp_get_thread_num`). Every other
// call goes on to libgomp's `GOMP_parallel` unchanged, so the program's own OpenMP
// regions run as before.
// Define `CGAL_SPHERICAL_PARAMETERIZATION_NO_INLINE_OPENMP_REGIONS` to leave libgomp alone.

#if defined(CGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD) && defined(__linux__) && defined(__GNUC__) && \
  !defined(CGAL_SPHERICAL_PARAMETERIZATION_NO_INLINE_OPENMP_REGIONS)
#define CGAL_SPHERICAL_PARAMETERIZATION_INLINE_OPENMP_REGIONS 1

#include <dlfcn.h>
#include <link.h>

#include <cstdint>
#include <cstring>

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// Whether the OpenMP regions that CHOLMOD opens on this thread run as plain calls
/// (set by `Openmp_serial`).
inline thread_local bool inline_openmp_regions = false;
/// How many regions ran so, on this thread: the tests check that the interposition works.
inline thread_local unsigned long inlined_openmp_regions = 0;

/// The executable code of CHOLMOD's shared library in this process (empty if CHOLMOD is
/// linked statically or not loaded).
struct Code_range
{
  std::uintptr_t begin = 0, end = 0;
  bool contains(const void* address) const
  {
    const std::uintptr_t a = reinterpret_cast<std::uintptr_t>(address);
    return begin <= a && a < end;
  }
};

inline const Code_range& cholmod_code()
{
  static const Code_range range = [] {
    Code_range found;
    dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* out) {
        if(!info->dlpi_name || !std::strstr(info->dlpi_name, "libcholmod"))
          return 0;
        Code_range& r = *static_cast<Code_range*>(out);
        for(int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& segment = info->dlpi_phdr[i];
          if(segment.p_type != PT_LOAD || !(segment.p_flags & PF_X))
            continue;
          r.begin = info->dlpi_addr + segment.p_vaddr;
          r.end = r.begin + segment.p_memsz;
          return 1;
        }
        return 0;
      },
      &found);
    return found;
  }();
  return range;
}

using Parallel_region = void (*)(void (*)(void*), void*, unsigned, unsigned);

/// libgomp's own `GOMP_parallel` (the next definition after this program's), or null.
inline Parallel_region next_parallel_region()
{
  static const Parallel_region next = reinterpret_cast<Parallel_region>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  return next;
}

/// The OpenMP nesting level of the calling thread (0 outside every region).
inline int openmp_level()
{
  using Level = int (*)();
  static const Level level = reinterpret_cast<Level>(dlsym(RTLD_DEFAULT, "omp_get_level"));
  return level ? level() : 0;
}

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

extern "C" __attribute__((used, noinline)) inline void GOMP_parallel(void (*body)(void*), void* data, unsigned threads,
                                                                     unsigned flags)
{
  namespace internal = CGAL::Spherical_parameterization::internal;
  const bool run_inline = internal::inline_openmp_regions &&
                          internal::cholmod_code().contains(__builtin_return_address(0)) &&
                          internal::openmp_level() == 0;
  const internal::Parallel_region next = run_inline ? nullptr : internal::next_parallel_region();
  if(!next) {
    ++internal::inlined_openmp_regions;
    body(data);
    return;
  }
  next(body, data, threads, flags);
}

#endif

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_INLINE_OPENMP_REGIONS_H
