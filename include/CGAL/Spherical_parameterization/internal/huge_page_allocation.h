// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HUGE_PAGE_ALLOCATION_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HUGE_PAGE_ALLOCATION_H

#include <SuiteSparse_config.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#if defined(__linux__)
#include <dlfcn.h>
#include <sys/mman.h>
#endif

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

constexpr std::size_t huge_page = std::size_t(1) << 21;
constexpr std::size_t huge_page_block = 2 * huge_page;  // the smallest block put on huge pages

/// `std::malloc`, except that a block of 4 MB or more is aligned to 2 MB and asks the kernel
/// for transparent huge pages (`madvise(MADV_HUGEPAGE)`), where Linux has them. The block is
/// released with `std::free` either way.
inline void* huge_page_malloc(std::size_t size)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if(size >= huge_page_block) {
    void* block = nullptr;
    if(posix_memalign(&block, huge_page, size) != 0)
      return nullptr;
    madvise(block, size & ~(huge_page - 1), MADV_HUGEPAGE);  // advice: a refusal is harmless
    return block;
  }
#endif
  return std::malloc(size);
}

/// `std::calloc` on `huge_page_malloc` (`std::calloc` itself for a small block).
inline void* huge_page_calloc(std::size_t count, std::size_t size)
{
  if(size != 0 && count > std::size_t(-1) / size)
    return nullptr;
  if(count * size < huge_page_block)
    return std::calloc(count, size);
  void* block = huge_page_malloc(count * size);
  if(block)
    std::memset(block, 0, count * size);
  return block;
}

/// While alive, CHOLMOD allocates its large blocks (the factor, the permuted copies of the
/// matrix it makes at every factorization) with `huge_page_malloc`. Only CHOLMOD's default
/// allocator is replaced, and it is restored when the last guard of the process goes (a
/// count under a mutex, so that guards on several threads do not race each other); a
/// caller's own allocator is left alone. SuiteSparse before version 7 keeps its allocator in
/// a global, `SuiteSparse_config`, found by name (`dlsym`), so nothing more is linked; with
/// version 7 or later, or without `MADV_HUGEPAGE`, this does nothing.
///
/// The package's own factorizations no longer take it (`Cholmod_traits`, session 39): since
/// the input's factor is written ahead on another thread, huge pages only slowed down the
/// first factorization of the other levels. The benchmark's yardstick still tries it, as it
/// makes some factorizations faster (a Laplacian at 302k faces: 0.25 against 0.28 s). It was
/// added when a factorization of the 2n x 2n Newton matrix at 302k faces took 1.2 s, and 2.0
/// s the first time on a level; with huge pages 0.85 s and 1.25 s (doc/NOTES.md, round eleven).
class Cholmod_huge_pages
{
public:
  Cholmod_huge_pages()
  {
    Shared& shared = state();
    if(!shared.config)
      return;
    const std::lock_guard<std::mutex> lock(shared.mutex);
    if(shared.guards == 0) {
      Config& c = *shared.config;
      shared.replaced = c.malloc_func == &std::malloc && c.calloc_func == &std::calloc && c.free_func == &std::free;
      if(shared.replaced) {
        c.malloc_func = &huge_page_malloc;
        c.calloc_func = &huge_page_calloc;
      }
    }
    ++shared.guards;
    counted_ = true;
  }
  ~Cholmod_huge_pages()
  {
    if(!counted_)
      return;
    Shared& shared = state();
    const std::lock_guard<std::mutex> lock(shared.mutex);
    if(--shared.guards == 0 && shared.replaced) {
      shared.config->malloc_func = &std::malloc;
      shared.config->calloc_func = &std::calloc;
      shared.replaced = false;
    }
  }
  Cholmod_huge_pages(const Cholmod_huge_pages&) = delete;
  Cholmod_huge_pages& operator=(const Cholmod_huge_pages&) = delete;

  /// True if CHOLMOD allocates with `huge_page_malloc` while this guard lives.
  static bool active()
  {
    Shared& shared = state();
    if(!shared.config)
      return false;
    const std::lock_guard<std::mutex> lock(shared.mutex);
    return shared.replaced;
  }

private:
#if defined(__linux__) && defined(MADV_HUGEPAGE) && SUITESPARSE_MAIN_VERSION < 7
  using Config = SuiteSparse_config_struct;
  static Config* allocator_config() { return static_cast<Config*>(dlsym(RTLD_DEFAULT, "SuiteSparse_config")); }
#else
  struct Config
  {
    void* (*malloc_func)(std::size_t);
    void* (*calloc_func)(std::size_t, std::size_t);
    void (*free_func)(void*);
  };
  static Config* allocator_config() { return nullptr; }
#endif

  struct Shared
  {
    Config* const config = allocator_config();
    std::mutex mutex;
    int guards = 0;         // guards alive in the process
    bool replaced = false;  // CHOLMOD's allocator is ours, until the last guard goes
  };
  static Shared& state()
  {
    static Shared shared;
    return shared;
  }

  bool counted_ = false;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_HUGE_PAGE_ALLOCATION_H
