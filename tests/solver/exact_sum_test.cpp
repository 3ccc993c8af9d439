// The exact accumulator behind every scalar product of the dual methods: order-free,
// exact to the last bit, the same split over any number of parts.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "solver/exact_sum.hpp"

using fetic::solver::ExactSum;

namespace {

double sum_of(const std::vector<double>& values) {
  ExactSum sum;
  for (double v : values)
    sum.add(v);
  return sum.value();
}

}  // namespace

TEST_CASE("exact sum: cancellation that rounding loses is kept") {
  CHECK(sum_of({1e100, 1.0, -1e100}) == 1.0);
  CHECK(sum_of({1.0, 1e-300, -1.0}) == 1e-300);
  // The doubles nearest 0.1, 0.2 and 0.3 sum to exactly 2^-55; rounding after each
  // addition gives 2^-54.
  CHECK(sum_of({0.1, 0.2, -0.3}) == std::ldexp(1.0, -55));
  CHECK((0.1 + 0.2) - 0.3 == std::ldexp(1.0, -54));
  CHECK(sum_of({}) == 0.0);
  CHECK(sum_of({-2.5}) == -2.5);
  const double tiny = std::numeric_limits<double>::denorm_min();
  CHECK(sum_of({tiny, tiny, tiny}) == 3 * tiny);
  const double big = std::numeric_limits<double>::max();
  CHECK(sum_of({big, big, -big}) == big);  // the intermediate overflow does not matter
  CHECK(std::isinf(sum_of({big, big})));
}

TEST_CASE("exact sum: infinities and NaN") {
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(sum_of({1.0, inf}) == inf);
  CHECK(sum_of({1.0, -inf}) == -inf);
  CHECK(std::isnan(sum_of({inf, -inf})));
  CHECK(std::isnan(sum_of({1.0, std::nan("")})));
}

TEST_CASE("exact sum: the same bits in any order and any split into parts") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-60, 60);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> values(1000);
    for (double& v : values)
      v = std::ldexp(mantissa(rng), exponent(rng));
    const double reference = sum_of(values);
    // Against a long double sum sorted by magnitude (11 more bits than double): the two
    // agree to far below the addends' size.
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end(),
              [](double a, double b) { return std::abs(a) < std::abs(b); });
    long double careful = 0.0L;
    for (double v : sorted)
      careful += v;
    CHECK(std::abs(reference - static_cast<double>(careful)) <= 1e-15 * std::abs(sorted.back()));
    std::shuffle(values.begin(), values.end(), rng);
    CHECK(sum_of(values) == reference);
    // Split into parts, summed apart, merged (as processes do through their words).
    ExactSum parts[3];
    for (size_t i = 0; i < values.size(); ++i)
      parts[i % 3].add(values[i]);
    std::int64_t words[ExactSum::kWords], total[ExactSum::kWords] = {};
    for (const ExactSum& part : parts) {
      part.to_words(words);
      for (int w = 0; w < ExactSum::kWords; ++w)
        total[w] += words[w];
    }
    ExactSum merged;
    merged.from_words(total);
    CHECK(merged.value() == reference);
    ExactSum sequential = parts[0];
    sequential.merge(parts[1]);
    sequential.merge(parts[2]);
    CHECK(sequential.value() == reference);
  }
}
