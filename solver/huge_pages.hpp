#pragma once
// Memory for the big arrays a solve keeps until its method is destroyed (the subdomain
// factors' entries: about two thirds of the resident bytes at 1e7 unknowns), taken in
// transparent huge pages. On this kind of machine (a microVM) every first touch of a
// 4 KiB page costs about 10 us - 2.7 s per GiB, a third of the FETI set-up at 1e7 - while
// a 2 MiB page taken after madvise(MADV_HUGEPAGE) costs about 0.25 us per 4 KiB
// (docs/BENCHMARKS.md, "Page faults"). glibc's malloc advises huge pages only when a
// tunable is set in the environment (glibc.malloc.hugetlb=1), so the kept arrays come
// from here instead.
//
// Allocations are handed out in order from one chunk at a time (kChunk bytes, aligned
// to kChunk, advised); a chunk counts the allocations living in it and is unmapped when
// the last of them is freed, from whichever thread - so the memory goes back with the
// method that holds the arrays. Space freed inside a chunk is not reused until the
// whole chunk is free: this is for arrays allocated once at their final size (a growing
// vector would leave its old copies behind). Requests above kLarge get their own advised
// mapping.
//
// Where huge pages are off ("never") or unknown to the kernel the memory is ordinary
// anonymous memory: madvise's refusal is not an error. Under AddressSanitizer the
// Allocator uses operator new instead, so that the sanitizer still checks every access
// to the factors (allocate() itself stays testable there).

#include <cstddef>
#include <new>
#include <vector>

namespace fetic::solver::huge_pages {

constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kChunk = std::size_t{64} << 20;
constexpr std::size_t kLarge = kChunk / 8;
constexpr std::size_t kAlignment = 64;  // a cache line; and every scalar type's alignment

// `bytes` (0 allowed) aligned to kAlignment; std::bad_alloc when the kernel refuses.
void* allocate(std::size_t bytes);
// `bytes` as given to allocate(); any thread.
void deallocate(void* p, std::size_t bytes) noexcept;
// Bytes mapped now: chunks (whole) and own mappings.
std::size_t mapped_bytes();
// Whether the kernel accepted madvise(MADV_HUGEPAGE) on every mapping so far.
bool advised();

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kUsedByAllocator = false;
#else
constexpr bool kUsedByAllocator = true;
#endif

template <class T>
struct Allocator {
  using value_type = T;
  Allocator() = default;
  template <class U>
  Allocator(const Allocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor)
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_alloc();
    if (!kUsedByAllocator) return static_cast<T*>(::operator new(n * sizeof(T)));
    return static_cast<T*>(huge_pages::allocate(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (!kUsedByAllocator) return ::operator delete(p);
    huge_pages::deallocate(p, n * sizeof(T));
  }
  template <class U>
  bool operator==(const Allocator<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const Allocator<U>&) const noexcept {
    return false;
  }
};

template <class T>
using Vector = std::vector<T, Allocator<T>>;

}  // namespace fetic::solver::huge_pages
