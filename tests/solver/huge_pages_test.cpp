// The huge-page arena of the kept factors (solver/huge_pages.hpp): alignment, allocations
// laid out in order within a chunk, chunks unmapped when their last allocation is freed
// (from any thread), and - where the kernel offers transparent huge pages on request -
// memory that /proc/self/smaps shows backed by them.

#include <catch2/catch.hpp>

#include <sys/mman.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "solver/huge_pages.hpp"
#include "tests/support/skip.hpp"

using namespace fetic::solver;

namespace {

std::uintptr_t address(const void* p) {
  return reinterpret_cast<std::uintptr_t>(p);
}

// The selected word of /sys/kernel/mm/transparent_hugepage/enabled ("always", "madvise",
// "never"), or "" where the file is missing.
std::string thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string word;
  while (in >> word)
    if (word.size() > 2 && word.front() == '[') return word.substr(1, word.size() - 2);
  return "";
}

// What /proc/self/smaps says of the mapping that holds p: its AnonHugePages (kB, -1 if not
// found) and whether its VmFlags carry "hg" (madvise(MADV_HUGEPAGE) was applied to it).
struct MappingFacts {
  long anon_huge_kb = -1;
  bool advised = false;
};

MappingFacts mapping_facts(const void* p) {
  std::ifstream in("/proc/self/smaps");
  std::string line;
  bool inside = false;
  MappingFacts facts;
  while (std::getline(in, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= address(p) && address(p) < end;
      continue;
    }
    if (!inside) continue;
    if (line.rfind("AnonHugePages:", 0) == 0) facts.anon_huge_kb = std::stol(line.substr(14));
    if (line.rfind("VmFlags:", 0) == 0)
      facts.advised = (line + " ").find(" hg ") != std::string::npos;
  }
  return facts;
}

// /proc/vmstat's thp_fault_fallback: page faults in huge-page regions the kernel served
// with small pages because it had no huge page at hand.
long thp_fault_fallbacks() {
  std::ifstream in("/proc/vmstat");
  std::string name;
  long value = 0;
  while (in >> name >> value)
    if (name == "thp_fault_fallback") return value;
  return 0;
}

}  // namespace

TEST_CASE("The huge-page arena aligns every allocation and lays them out in order") {
  const std::size_t before = huge_pages::mapped_bytes();
  std::vector<std::pair<void*, std::size_t>> taken;
  for (std::size_t bytes : {0, 1, 63, 64, 65, 1000, 4096, 100000}) {
    void* p = huge_pages::allocate(bytes);
    taken.emplace_back(p, bytes);
    CHECK(address(p) % huge_pages::kAlignment == 0);
    std::memset(p, 0xab, bytes);
  }
  // One after the other in one chunk (the first may have opened a new one).
  for (std::size_t k = 1; k + 1 < taken.size(); ++k) {
    const std::size_t rounded =
        (std::max<std::size_t>(taken[k].second, 1) + huge_pages::kAlignment - 1) /
        huge_pages::kAlignment * huge_pages::kAlignment;
    CHECK(address(taken[k + 1].first) == address(taken[k].first) + rounded);
  }
  void* large = huge_pages::allocate(huge_pages::kLarge + 1);
  CHECK(address(large) % huge_pages::kHugePage == 0);
  CHECK(huge_pages::mapped_bytes() >= before + huge_pages::kLarge);
  huge_pages::deallocate(large, huge_pages::kLarge + 1);
  for (const auto& [p, bytes] : taken)
    huge_pages::deallocate(p, bytes);
  CHECK(huge_pages::mapped_bytes() == before);
}

TEST_CASE("A huge-page chunk is unmapped when its last allocation is freed, from any thread") {
  // Nothing else lives in the arena: the first allocation opens a chunk.
  REQUIRE(huge_pages::mapped_bytes() == 0);
  const std::size_t before = 0;
  const std::size_t piece = huge_pages::kLarge;  // the largest a chunk takes
  std::vector<void*> first_chunk;
  for (int k = 0; k < 7; ++k)
    first_chunk.push_back(huge_pages::allocate(piece));
  const auto chunk_of = [](const void* p) { return address(p) & ~(huge_pages::kChunk - 1); };
  void* next = huge_pages::allocate(piece);  // the eighth with the header: a new chunk
  CHECK(chunk_of(next) != chunk_of(first_chunk.front()));
  for (void* p : first_chunk)
    CHECK(chunk_of(p) == chunk_of(first_chunk.front()));
  CHECK(huge_pages::mapped_bytes() == before + 2 * huge_pages::kChunk);
  // All but one freed here, the last from another thread: the chunk goes then.
  for (std::size_t k = 0; k + 1 < first_chunk.size(); ++k)
    huge_pages::deallocate(first_chunk[k], piece);
  CHECK(huge_pages::mapped_bytes() == before + 2 * huge_pages::kChunk);
  std::thread([&] { huge_pages::deallocate(first_chunk.back(), piece); }).join();
  CHECK(huge_pages::mapped_bytes() == before + huge_pages::kChunk);
  huge_pages::deallocate(next, piece);
  CHECK(huge_pages::mapped_bytes() == before);
}

TEST_CASE("A vector in the huge-page arena keeps its values and frees its chunk") {
  const std::size_t before = huge_pages::mapped_bytes();
  {
    huge_pages::Vector<double> values(300000, 0.5);
    huge_pages::Vector<float> small(7, 2.0f);
    values.back() = 3.0;
    huge_pages::Vector<double> moved = std::move(values);
    CHECK(moved.size() == 300000);
    CHECK(moved.front() == 0.5);
    CHECK(moved.back() == 3.0);
    CHECK(small[6] == 2.0f);
    if (huge_pages::kUsedByAllocator) CHECK(huge_pages::mapped_bytes() > before);
  }
  CHECK(huge_pages::mapped_bytes() == before);
}

TEST_CASE("The huge-page arena's memory is backed by huge pages where the kernel offers them") {
  const std::string mode = thp_mode();
  if (mode != "always" && mode != "madvise")
    FETIC_SKIP("transparent huge pages are '" << mode << "' here (not always/madvise)");
  // 6 MiB inside one chunk, touched: at least one whole aligned 2 MiB page lies in it.
  const std::size_t bytes = 6 * (std::size_t{1} << 20);
  void* p = huge_pages::allocate(bytes);
  const long fallbacks_before = thp_fault_fallbacks();
  std::memset(p, 1, bytes);
  const long fallbacks = thp_fault_fallbacks() - fallbacks_before;
  CHECK(huge_pages::advised());
  const MappingFacts facts = mapping_facts(p);
  INFO("AnonHugePages " << facts.anon_huge_kb << " kB in the mapping, " << fallbacks
                        << " huge-page faults served with small pages meanwhile");
  // The advice is ours and always visible; whether the kernel then had a free huge page
  // is not: a machine short of contiguous memory falls back (counted in /proc/vmstat),
  // which is slower but correct - only then is no huge page no failure.
  CHECK(facts.advised);
  // ...and the flag is read from the right mapping: memory mapped without the advice lacks it.
  const std::size_t plain_bytes = std::size_t{1} << 22;
  void* plain =
      mmap(nullptr, plain_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  REQUIRE(plain != MAP_FAILED);
  std::memset(plain, 1, plain_bytes);
  CHECK_FALSE(mapping_facts(plain).advised);
  munmap(plain, plain_bytes);
  if (fallbacks == 0)
    CHECK(facts.anon_huge_kb >= 2048);
  else
    WARN("the kernel had no free huge page (thp_fault_fallback rose): backing not checked");
  huge_pages::deallocate(p, bytes);
}
