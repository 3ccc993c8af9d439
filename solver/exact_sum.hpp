#pragma once
// An exact sum of doubles (a long accumulator in the manner of Kulisch): every addend is
// added without rounding into integer limbs that cover the whole range of double, so the
// sum does not depend on the order of the additions - and a scalar product summed by
// one process or by any number of them, each adding its own rows, is the same number to
// the last bit. FETI-C decides its working set from signs and sizes of such numbers; with
// exact sums, a solve on 1, 2, 3 or 4 processes takes the same decisions as the serial
// one and converges in the same iterations (tests/mpi).
//
// Only the final conversion to double rounds (from the top 96 bits, a deterministic
// function of the exact sum). Infinite and NaN addends are counted and give +-inf or NaN.

#include <array>
#include <cstdint>

namespace fetic::solver {

class ExactSum {
 public:
  // Limb k holds the bits of weight 2^(32 k + kBase), kBase below the smallest double's
  // lowest bit (2^-1074 as a 53-bit mantissa times 2^-1126); the top limbs leave room for
  // sums far beyond the largest double.
  static constexpr int kLimbs = 72;
  static constexpr int kBase = -1152;
  // Words exchanged between processes: the limbs and three counters.
  static constexpr int kWords = kLimbs + 3;

  void add(double x);
  // this += other (exact).
  void merge(const ExactSum& other);
  double value() const;

  // Carries so that every limb but the top lies in [0, 2^32); then the words for a sum
  // over processes (integer addition: exact in any order).
  void to_words(std::int64_t* words) const;
  void from_words(const std::int64_t* words);

 private:
  void normalize() const;

  mutable std::array<std::int64_t, kLimbs> limbs_{};
  mutable int pending_ = 0;  // additions since the last normalize()
  std::int64_t nans_ = 0, positive_infinities_ = 0, negative_infinities_ = 0;
};

// sum over i of a[i] * b[i] for i in [0, n), exactly summed (each product rounded once).
ExactSum exact_dot(const double* a, const double* b, long n);
// The same over the indices with mask[i] != 0.
ExactSum exact_dot(const double* a, const double* b, long n, const char* mask);

}  // namespace fetic::solver
