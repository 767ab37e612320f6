#pragma once
// Per-point buffers that a parallel loop fills whole: std::vector zero-fills what resize() adds, serially, and on a
// fresh block that fill is also where every page faults in, on one core (the 1M draw's two 64 MB neighbour lists:
// 5% of its CPU time). A Buffer's resize() leaves trivial elements uninitialised, so that the pages fault in where
// the filling loop first writes them, on every core.

#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace pcsketch {

/// std::allocator whose value-initialisation (resize(n), vector(n)) is default-initialisation.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A std::vector whose resize() does not zero what it adds: every element must be written before it is read.
template <class T>
using Buffer = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace pcsketch
