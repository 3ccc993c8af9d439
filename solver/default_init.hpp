#pragma once
// A std::vector that leaves its new elements default-initialized (for a trivial type:
// not written at all) when it is sized, for arrays filled in parallel right after: a
// value-initializing resize() zeroes them first, a serial first touch of every page.

#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace fetic::solver {

template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  using value_type = T;
  DefaultInitAllocator() noexcept = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}  // NOLINT: implicit
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  template <class U>
  void construct(U* at) noexcept {
    ::new (static_cast<void*>(at)) U;
  }
  template <class U, class... Args>
  void construct(U* at, Args&&... args) {
    ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using DefaultInitVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace fetic::solver
