#include "solver/huge_pages.hpp"

#include <sys/mman.h>

#include <atomic>
#include <cstdint>
#include <mutex>

namespace fetic::solver::huge_pages {

namespace {

std::atomic<std::size_t> mapped{0};
std::atomic<bool> all_advised{true};

std::size_t round_up(std::size_t bytes, std::size_t to) {
  return (bytes + to - 1) / to * to;
}

// `bytes` (a multiple of kHugePage) of anonymous memory aligned to `alignment` (a power
// of two, at least kHugePage), advised for huge pages: the kernel then backs each aligned
// 2 MiB of it with one page at its first touch where it can.
char* map_aligned(std::size_t bytes, std::size_t alignment) {
  const std::size_t span = bytes + alignment;
  void* raw = mmap(nullptr, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto begin = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = round_up(begin, alignment);
  // The unaligned head and the tail beyond `bytes` go back at once.
  if (aligned > begin) munmap(raw, aligned - begin);
  const std::uintptr_t end = begin + span;
  if (end > aligned + bytes)
    munmap(reinterpret_cast<void*>(aligned + bytes), end - aligned - bytes);
  char* p = reinterpret_cast<char*>(aligned);
  // Refused where huge pages are not built in: ordinary pages then, only slower.
  if (madvise(p, bytes, MADV_HUGEPAGE) != 0) all_advised.store(false, std::memory_order_relaxed);
  mapped.fetch_add(bytes, std::memory_order_relaxed);
  return p;
}

void unmap(void* p, std::size_t bytes) noexcept {
  munmap(p, bytes);
  mapped.fetch_sub(bytes, std::memory_order_relaxed);
}

// A chunk's first cache line: how many allocations live in it.
struct Header {
  std::size_t live = 0;
};
static_assert(sizeof(Header) <= kAlignment);

Header* header_of(void* p) {
  return reinterpret_cast<Header*>(reinterpret_cast<std::uintptr_t>(p) & ~(kChunk - 1));
}

// The chunk being handed out and how much of it is. One for all threads, under a mutex:
// an allocation here is one per factor (about 20,000 at 1e7 unknowns), so the lock costs
// nothing measurable, and a chunk then never waits for a thread that may allocate from
// it again - it goes back as soon as its last allocation does.
std::mutex lock;
Header* current = nullptr;
std::size_t used = 0;

void* take(std::size_t bytes) {
  const std::lock_guard<std::mutex> guard(lock);
  if (!current || used + bytes > kChunk) {
    char* fresh = map_aligned(kChunk, kChunk);
    // The chunk left behind is unmapped by its last allocation's deallocate().
    current = new (fresh) Header{};
    used = kAlignment;
  }
  ++current->live;
  void* p = reinterpret_cast<char*>(current) + used;
  used += bytes;
  return p;
}

void release(Header* chunk) noexcept {
  const std::lock_guard<std::mutex> guard(lock);
  if (--chunk->live > 0) return;
  if (chunk == current) current = nullptr;
  unmap(chunk, kChunk);
}

}  // namespace

void* allocate(std::size_t bytes) {
  const std::size_t size = round_up(bytes == 0 ? 1 : bytes, kAlignment);
  if (size > kLarge) return map_aligned(round_up(size, kHugePage), kHugePage);
  return take(size);
}

void deallocate(void* p, std::size_t bytes) noexcept {
  if (!p) return;
  const std::size_t size = round_up(bytes == 0 ? 1 : bytes, kAlignment);
  if (size > kLarge)
    unmap(p, round_up(size, kHugePage));
  else
    release(header_of(p));
}

std::size_t mapped_bytes() {
  return mapped.load(std::memory_order_relaxed);
}

bool advised() {
  return all_advised.load(std::memory_order_relaxed);
}

}  // namespace fetic::solver::huge_pages
