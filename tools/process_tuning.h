// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tuning of a whole process for CHOLMOD's factorizations, for the programs that own their
// process and opt in: the benchmark and the command line tool. The package's headers do none
// of it, since a library leaves the thread counts, allocators and symbols of its user's
// process alone. A program that includes this header and calls
// `process_tuning::enable()` at the start of main(), before it starts threads, gets:
//
// 1. CHOLMOD's OpenMP regions run as plain calls on the calling thread.
//    Why: Debian's CHOLMOD (3.0) opens two or three OpenMP regions of 4 threads per
//    supernode of a supernodal factorization, for loops as short as clearing a supernode,
//    whatever the cores. On two cores those threads wait on each other at every region's
//    barrier, and even a region of one thread goes through libgomp's team start and end,
//    whose barrier ends with a `futex` system call, so many of them per solve, dear in a
//    virtual machine.
//    How: this header defines `GOMP_parallel`, libgomp's entry point of a parallel region, in
//    the program; the dynamic linker then binds CHOLMOD's calls to it instead of libgomp's
//    (symbol interposition). Once enabled, it calls a region's body directly if the call
//    comes from CHOLMOD's own code and the thread is in no OpenMP region. The body then sees
//    one thread, number 0, as in a region of one thread; CHOLMOD's bodies split their loops
//    by those two numbers and call nothing else of libgomp. Every other region goes on to
//    libgomp unchanged, so the program's own OpenMP regions run as before.
// 2. OpenBLAS, when it is the BLAS of the process, runs one thread short of its count (one
//    thread on two cores), unless `OPENBLAS_NUM_THREADS` sets the count.
//    Why: OpenBLAS's threads spin while they wait. When another process holds a core, a
//    factorization with two BLAS threads on two cores slows down badly, and many times over
//    while a parallel build runs.
// 3. For the benchmark's yardstick, `Yardstick_settings`: OpenBLAS back at the count the
//    process started with while it lives, and CHOLMOD's large blocks on transparent huge
//    pages if asked, which make some plain factorizations a little faster.
//
// `SPHERICAL_PARAMETERIZATION_NO_PROCESS_TUNING=1` in the environment leaves `enable()` without
// effect (the interposed `GOMP_parallel` then passes every region on), to measure what the
// tuning gives.

#ifndef SPHERICAL_PARAMETERIZATION_TOOLS_PROCESS_TUNING_H
#define SPHERICAL_PARAMETERIZATION_TOOLS_PROCESS_TUNING_H

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <optional>
#include <string>

#if defined(__unix__)
#include <dlfcn.h>
#endif

#if defined(CGAL_SPHERICAL_PARAMETERIZATION_USE_CHOLMOD) && defined(__linux__) && defined(__GNUC__)
#define SPHERICAL_PARAMETERIZATION_TUNE_CHOLMOD 1
#include <SuiteSparse_config.h>
#include <link.h>
#include <sys/mman.h>
#endif

namespace process_tuning {

// A function or variable of a library of the process, found by name: nothing more is
// linked, and a library the process does not have gives null.
template <class T>
T* find_symbol(const char* name)
{
#if defined(__unix__)
  return reinterpret_cast<T*>(dlsym(RTLD_DEFAULT, name));
#else
  (void)name;
  return nullptr;
#endif
}

// OpenBLAS's thread count as the process started, or -1 if OpenBLAS is not its BLAS.
inline int& initial_blas_threads()
{
  static int threads = -1;
  return threads;
}

inline void set_blas_threads(int threads)
{
  if(auto* set = find_symbol<void(int)>("openblas_set_num_threads"))
    set(threads);
}

#ifdef SPHERICAL_PARAMETERIZATION_TUNE_CHOLMOD
// Set once by enable(), before the program starts threads; read by every region after.
inline std::atomic<bool> inline_cholmod_regions{false};
// The regions run as plain calls so far, in this process (a check that the interposition works).
inline std::atomic<unsigned long> inlined_cholmod_regions{0};

// The executable code of CHOLMOD's shared library in this process (empty if CHOLMOD is
// linked statically).
struct Code_range
{
  std::uintptr_t begin = 0, end = 0;
  bool contains(const void* address) const
  {
    const auto a = reinterpret_cast<std::uintptr_t>(address);
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
        for(int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& segment = info->dlpi_phdr[i];
          if(segment.p_type == PT_LOAD && (segment.p_flags & PF_X)) {
            auto& r = *static_cast<Code_range*>(out);
            r.begin = info->dlpi_addr + segment.p_vaddr;
            r.end = r.begin + segment.p_memsz;
            return 1;
          }
        }
        return 0;
      },
      &found);
    return found;
  }();
  return range;
}

using Parallel_region = void(void (*)(void*), void*, unsigned, unsigned);

// libgomp's own `GOMP_parallel`: the next definition after the program's.
inline Parallel_region* libgomp_parallel_region()
{
  static Parallel_region* const next = reinterpret_cast<Parallel_region*>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  return next;
}

// The OpenMP nesting level of the calling thread (0 outside every region).
inline int openmp_level()
{
  static int (*const level)() = find_symbol<int()>("omp_get_level");
  return level ? level() : 0;
}
#endif

// Opts the process in (see the top of this file); returns what it changed, for a log line.
inline std::string enable()
{
  initial_blas_threads() = -1;
  if(auto* get = find_symbol<int()>("openblas_get_num_threads"))
    initial_blas_threads() = get();
  const char* off = std::getenv("SPHERICAL_PARAMETERIZATION_NO_PROCESS_TUNING");
  if(off && *off && std::strcmp(off, "0") != 0)
    return "off (SPHERICAL_PARAMETERIZATION_NO_PROCESS_TUNING)";
  std::string done;
#ifdef SPHERICAL_PARAMETERIZATION_TUNE_CHOLMOD
  inline_cholmod_regions = true;
  done = "CHOLMOD's OpenMP regions inline";
#else
  done = "CHOLMOD's OpenMP regions left to the runtime";
#endif
  const int threads = initial_blas_threads();
  if(threads > 1 && !std::getenv("OPENBLAS_NUM_THREADS")) {
    set_blas_threads(threads - 1);
    done += ", OpenBLAS threads " + std::to_string(threads) + " -> " + std::to_string(threads - 1);
  } else if(threads > 0) {
    done += ", OpenBLAS threads " + std::to_string(threads) + " (kept)";
  }
  return done;
}

// `std::malloc`, except that a block of 4 MB or more is aligned to 2 MB and on transparent
// huge pages (`madvise(MADV_HUGEPAGE)`) where Linux has them; released by `std::free`.
inline void* huge_page_malloc(std::size_t size)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::size_t page = std::size_t(1) << 21;
  if(size >= 2 * page) {
    void* block = nullptr;
    if(posix_memalign(&block, page, size) != 0)
      return nullptr;
    madvise(block, size & ~(page - 1), MADV_HUGEPAGE);  // advice: a refusal is harmless
    return block;
  }
#endif
  return std::malloc(size);
}

// `std::calloc` on `huge_page_malloc`.
inline void* huge_page_calloc(std::size_t count, std::size_t size)
{
  if(size != 0 && count > std::size_t(-1) / size)
    return nullptr;
  void* block = huge_page_malloc(count * size);
  if(block)
    std::memset(block, 0, count * size);
  return block;
}

// While alive, CHOLMOD allocates with `huge_page_malloc`. SuiteSparse before version 7 keeps
// CHOLMOD's allocator in a global, `SuiteSparse_config`, which this swaps and restores: for
// one thread at a time, and only if the allocator is the default one. Elsewhere it does
// nothing.
class Cholmod_huge_pages
{
public:
  Cholmod_huge_pages()
  {
#if defined(SPHERICAL_PARAMETERIZATION_TUNE_CHOLMOD) && defined(MADV_HUGEPAGE) && SUITESPARSE_MAIN_VERSION < 7
    auto* config = find_symbol<SuiteSparse_config_struct>("SuiteSparse_config");
    if(config && config->malloc_func == &std::malloc && config->calloc_func == &std::calloc) {
      config->malloc_func = &huge_page_malloc;
      config->calloc_func = &huge_page_calloc;
      restore_ = [config] {
        config->malloc_func = &std::malloc;
        config->calloc_func = &std::calloc;
      };
    }
#endif
  }
  ~Cholmod_huge_pages()
  {
    if(restore_)
      restore_();
  }
  Cholmod_huge_pages(const Cholmod_huge_pages&) = delete;
  Cholmod_huge_pages& operator=(const Cholmod_huge_pages&) = delete;

  // True if CHOLMOD allocates with `huge_page_malloc` while this lives.
  bool active() const { return bool(restore_); }

private:
  std::function<void()> restore_;
};

// While alive, the conditions the benchmark's yardstick is measured in: OpenBLAS at the
// count the process started with (its own default: all cores), and CHOLMOD's large blocks
// on huge pages if `huge_pages`.
class Yardstick_settings
{
public:
  explicit Yardstick_settings(bool huge_pages)
  {
    if(auto* get = find_symbol<int()>("openblas_get_num_threads")) {
      tuned_threads_ = get();
      if(initial_blas_threads() > 0 && tuned_threads_ != initial_blas_threads())
        set_blas_threads(initial_blas_threads());
    }
    if(huge_pages)
      huge_pages_.emplace();
  }
  ~Yardstick_settings()
  {
    huge_pages_.reset();
    if(tuned_threads_ > 0 && tuned_threads_ != initial_blas_threads())
      set_blas_threads(tuned_threads_);
  }
  Yardstick_settings(const Yardstick_settings&) = delete;
  Yardstick_settings& operator=(const Yardstick_settings&) = delete;

private:
  int tuned_threads_ = -1;
  std::optional<Cholmod_huge_pages> huge_pages_;
};

} // namespace process_tuning

#ifdef SPHERICAL_PARAMETERIZATION_TUNE_CHOLMOD
// The interposed entry point of OpenMP's parallel regions (see the top of this file). Inline,
// so that it is defined once whatever includes it; `used` keeps it when nothing of the
// program calls it, so that the linker exports it for CHOLMOD's calls.
extern "C" __attribute__((used, noinline)) inline void GOMP_parallel(void (*body)(void*), void* data, unsigned threads,
                                                                     unsigned flags)
{
  namespace pt = process_tuning;
  if(pt::inline_cholmod_regions.load(std::memory_order_relaxed) &&
     pt::cholmod_code().contains(__builtin_return_address(0)) && pt::openmp_level() == 0) {
    pt::inlined_cholmod_regions.fetch_add(1, std::memory_order_relaxed);
    body(data);
    return;
  }
  if(pt::Parallel_region* next = pt::libgomp_parallel_region())
    next(body, data, threads, flags);
  else
    body(data);  // no libgomp in the process: a region of one thread
}
#endif

#endif // SPHERICAL_PARAMETERIZATION_TOOLS_PROCESS_TUNING_H
