// Copyright (c) 2026 The CGAL Spherical_parameterization authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BACKENDS_PARALLEL_FOR_H
#define CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BACKENDS_PARALLEL_FOR_H

#include <CGAL/tags.h>

#include <cstddef>
#include <functional>
#include <type_traits>
#include <utility>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>
#endif

namespace CGAL {
namespace Spherical_parameterization {
namespace internal {

/// True for `CGAL::Parallel_tag` and the tags derived from it (as CGAL tests its tags).
/// Without TBB, asking for it is an error at compile time, as in CGAL's packages, rather
/// than a sequential run the caller did not ask for.
template <class ConcurrencyTag>
constexpr bool is_parallel = std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value;

/// Calls `fn(i)` for `i` in `[0, n)`, on TBB's threads with `CGAL::Parallel_tag`.
/// `fn` must only write to data of its own index, which keeps results deterministic.
template <class ConcurrencyTag, class Fn>
void parallel_for(std::size_t n, const Fn& fn)
{
#ifdef CGAL_LINKED_WITH_TBB
  if constexpr(is_parallel<ConcurrencyTag>) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
      for(std::size_t i = r.begin(); i != r.end(); ++i)
        fn(i);
    });
    return;
  }
#else
  static_assert(!is_parallel<ConcurrencyTag>, "CGAL::Parallel_tag needs TBB (CGAL_LINKED_WITH_TBB)");
#endif
  for(std::size_t i = 0; i < n; ++i)
    fn(i);
}

/// Runs a task from construction to `wait()`: with `CGAL::Parallel_tag`, as a TBB task that
/// a free TBB thread takes up meanwhile (or the caller in `wait()`, if none did); with
/// `CGAL::Sequential_tag`, in `wait()`. An exception of the task is thrown by `wait()`. The
/// destructor waits for a started task, and runs none.
///
/// The task goes to an arena of its own, not to the caller's: a thread waiting in one of the
/// caller's parallel loops takes tasks of its arena only, so it never takes up this task
/// (seconds of work on a large mesh) while the loop's other threads are done and wait.
template <class ConcurrencyTag>
class Background_task
{
public:
  explicit Background_task(std::function<void()> task)
  {
#ifdef CGAL_LINKED_WITH_TBB
    if constexpr(is_parallel<ConcurrencyTag>) {
      arena_.enqueue(group_.defer(std::move(task)));
      started_ = true;
      return;
    }
#else
    static_assert(!is_parallel<ConcurrencyTag>, "CGAL::Parallel_tag needs TBB (CGAL_LINKED_WITH_TBB)");
#endif
    task_ = std::move(task);
  }
  ~Background_task()
  {
#ifdef CGAL_LINKED_WITH_TBB
    if(started_) {
      group_.cancel();  // a task not yet taken up is not run
      try {
        arena_.execute([this] { group_.wait(); });
      } catch(...) {
      }
    }
#endif
  }
  Background_task(const Background_task&) = delete;
  Background_task& operator=(const Background_task&) = delete;

  void wait()
  {
#ifdef CGAL_LINKED_WITH_TBB
    if(std::exchange(started_, false))
      arena_.execute([this] { group_.wait(); });
#endif
    if(task_)
      std::exchange(task_, nullptr)();
  }

private:
  std::function<void()> task_;  // a task to run in `wait()`
#ifdef CGAL_LINKED_WITH_TBB
  tbb::task_arena arena_;
  tbb::task_group group_;  // destroyed before the arena that runs its task
  bool started_ = false;   // enqueued and not yet waited for
#endif
};

} // namespace internal
} // namespace Spherical_parameterization
} // namespace CGAL

#endif // CGAL_SPHERICAL_PARAMETERIZATION_INTERNAL_BACKENDS_PARALLEL_FOR_H
