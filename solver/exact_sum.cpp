#include "solver/exact_sum.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <omp.h>

#include "solver/threads.hpp"

namespace fetic::solver {
namespace {

// Limbs take up to 2^31 additions of values below 2^32 before they could overflow.
constexpr int kAdditionsBeforeCarry = 1 << 30;

}  // namespace

void ExactSum::add(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  std::uint64_t mantissa = bits & ((std::uint64_t{1} << 52) - 1);
  if (biased == 0x7ff) {
    if (mantissa != 0)
      ++nans_;
    else if (bits >> 63)
      ++negative_infinities_;
    else
      ++positive_infinities_;
    return;
  }
  if (biased == 0 && mantissa == 0) return;  // +-0
  // x = mantissa * 2^exponent with an integer mantissa of at most 53 bits.
  int exponent;
  if (biased == 0) {
    exponent = -1074;  // subnormal
  } else {
    mantissa |= std::uint64_t{1} << 52;
    exponent = biased - 1075;
  }
  const int position = exponent - kBase;  // >= 78
  const int limb = position / 32;
  // The 32-bit words of mantissa * 2^shift (at most 85 bits).
  const int shift = position % 32;
  constexpr std::uint64_t kWord = 0xffffffffu;
  const std::int64_t parts[3] = {
      static_cast<std::int64_t>((mantissa << shift) & kWord),
      static_cast<std::int64_t>((shift == 0 ? mantissa >> 32 : mantissa >> (32 - shift)) & kWord),
      static_cast<std::int64_t>(shift == 0 ? 0 : mantissa >> (64 - shift))};
  if (bits >> 63) {
    limbs_[limb] -= parts[0];
    limbs_[limb + 1] -= parts[1];
    limbs_[limb + 2] -= parts[2];
  } else {
    limbs_[limb] += parts[0];
    limbs_[limb + 1] += parts[1];
    limbs_[limb + 2] += parts[2];
  }
  if (++pending_ >= kAdditionsBeforeCarry) normalize();
}

void ExactSum::normalize() const {
  for (int k = 0; k + 1 < kLimbs; ++k) {
    const std::int64_t carry = limbs_[k] >> 32;  // floor division by 2^32
    limbs_[k] -= carry * (std::int64_t{1} << 32);
    limbs_[k + 1] += carry;
  }
  pending_ = 0;
}

void ExactSum::merge(const ExactSum& other) {
  normalize();
  other.normalize();
  for (int k = 0; k < kLimbs; ++k)
    limbs_[k] += other.limbs_[k];
  normalize();
  nans_ += other.nans_;
  positive_infinities_ += other.positive_infinities_;
  negative_infinities_ += other.negative_infinities_;
}

void ExactSum::to_words(std::int64_t* words) const {
  normalize();
  for (int k = 0; k < kLimbs; ++k)
    words[k] = limbs_[k];
  words[kLimbs] = nans_;
  words[kLimbs + 1] = positive_infinities_;
  words[kLimbs + 2] = negative_infinities_;
}

void ExactSum::from_words(const std::int64_t* words) {
  for (int k = 0; k < kLimbs; ++k)
    limbs_[k] = words[k];
  nans_ = words[kLimbs];
  positive_infinities_ = words[kLimbs + 1];
  negative_infinities_ = words[kLimbs + 2];
  normalize();
}

double ExactSum::value() const {
  if (nans_ > 0 || (positive_infinities_ > 0 && negative_infinities_ > 0))
    return std::numeric_limits<double>::quiet_NaN();
  if (positive_infinities_ > 0) return std::numeric_limits<double>::infinity();
  if (negative_infinities_ > 0) return -std::numeric_limits<double>::infinity();
  normalize();
  // The sign is the top limb's; a negative sum is converted as minus its magnitude.
  std::array<std::int64_t, kLimbs> magnitude = limbs_;
  const bool negative = magnitude[kLimbs - 1] < 0;
  if (negative) {
    for (std::int64_t& limb : magnitude)
      limb = -limb;
    for (int k = 0; k + 1 < kLimbs; ++k) {
      const std::int64_t carry = magnitude[k] >> 32;
      magnitude[k] -= carry * (std::int64_t{1} << 32);
      magnitude[k + 1] += carry;
    }
  }
  int top = kLimbs - 1;
  while (top > 0 && magnitude[top] == 0)
    --top;
  // The top three limbs (at least 65 significant bits) decide the double, summed from the
  // least significant so that the result is a fixed function of the exact sum.
  double result = 0.0;
  for (int k = top >= 2 ? top - 2 : 0; k <= top; ++k)
    result += std::ldexp(static_cast<double>(magnitude[k]), 32 * k + kBase);
  return negative ? -result : result;
}

namespace {

// The exact sum of a[i] * b[i] over [0, n) (where mask[i] != 0, with a mask), each thread
// summing one contiguous part and the parts merged: exact, so the same bits for any
// number of threads (a dual vector at 1e7 unknowns has 870,000 rows, and an iteration
// takes several scalar products).
ExactSum dot_by_parts(const double* a, const double* b, long n, const char* mask) {
  const int threads = threads_for(n);
  if (threads == 1) {
    ExactSum sum;
    for (long i = 0; i < n; ++i)
      if (!mask || mask[i]) sum.add(a[i] * b[i]);
    return sum;
  }
  std::vector<ExactSum> parts(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const long count = omp_get_num_threads(), t = omp_get_thread_num();
    ExactSum sum;  // on the thread's own stack: no cache line shared while adding
    for (long i = n * t / count; i < n * (t + 1) / count; ++i)
      if (!mask || mask[i]) sum.add(a[i] * b[i]);
    parts[static_cast<std::size_t>(t)] = sum;
  }
  for (std::size_t t = 1; t < parts.size(); ++t)
    parts[0].merge(parts[t]);
  return parts[0];
}

}  // namespace

ExactSum exact_dot(const double* a, const double* b, long n) {
  return dot_by_parts(a, b, n, nullptr);
}

ExactSum exact_dot(const double* a, const double* b, long n, const char* mask) {
  return dot_by_parts(a, b, n, mask);
}

}  // namespace fetic::solver
