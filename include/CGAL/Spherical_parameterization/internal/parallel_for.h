// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PARALLEL_FOR_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PARALLEL_FOR_H

#include <CGAL/tags.h>

#include <cstddef>
#include <functional>
#include <future>
#include <system_error>
#include <type_traits>
#include <utility>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// Calls `fn(i)` for `i` in `[0, n)`, on all cores with `CGAL::Parallel_tag` and TBB.
/// `fn` must only write to data of its own index, which keeps results deterministic.
template <class ConcurrencyTag, class Fn>
void parallel_for(std::size_t n, const Fn& fn)
{
#ifdef CGAL_LINKED_WITH_TBB
  if constexpr(std::is_same<ConcurrencyTag, CGAL::Parallel_tag>::value) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
      for(std::size_t i = r.begin(); i != r.end(); ++i)
        fn(i);
    });
    return;
  }
#else
  static_assert(!std::is_same<ConcurrencyTag, CGAL::Parallel_tag>::value,
                "CGAL::Parallel_tag needs TBB (CGAL_LINKED_WITH_TBB)");
#endif
  for(std::size_t i = 0; i < n; ++i)
    fn(i);
}

/// Runs a task from construction to `wait()` on a thread of its own with `CGAL::Parallel_tag`
/// (a dedicated thread rather than a TBB task, which TBB could run on the waiting thread
/// inside an unrelated `parallel_for`); with `CGAL::Sequential_tag`, or if no thread could
/// be started, in `wait()`. The destructor waits for a started task, and runs none.
template <class ConcurrencyTag>
class Background_task
{
public:
  explicit Background_task(std::function<void()> task)
  {
    if constexpr(std::is_same<ConcurrencyTag, CGAL::Parallel_tag>::value) {
      try {
        done_ = std::async(std::launch::async, task);
        return;
      } catch(const std::system_error&) {
      }
    }
    task_ = std::move(task);
  }
  ~Background_task()
  {
    if(done_.valid())
      done_.wait();
  }
  Background_task(const Background_task&) = delete;
  Background_task& operator=(const Background_task&) = delete;

  void wait()
  {
    if(done_.valid())
      done_.get();
    if(task_)
      std::exchange(task_, nullptr)();
  }

private:
  std::future<void> done_;
  std::function<void()> task_;
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_PARALLEL_FOR_H
