#pragma once
// A dual row's value as the partial sums of the subdomains it joins, added in subdomain
// order, so that it is the same number on any count of processes (docs/DISTRIBUTED.md).
// FetiSystem's B products and the Dirichlet and lumped preconditioners' rows sum this way.

#include <Eigen/Core>

namespace fetic::solver {

// One term of a row's sum: values(y) * value; `new_subdomain` starts the next subdomain's
// partial sum.
struct RowTerm {
  int y = 0;
  double value = 0.0;
  bool new_subdomain = false;
};

// The sum over [first, end) of term.value * value_of(term), partial sum by partial sum.
template <class ValueOf>
double sum_row_terms_of(const RowTerm* first, const RowTerm* end, ValueOf value_of) {
  double total = 0.0, partial = 0.0;
  for (const RowTerm* term = first; term != end; ++term) {
    if (term->new_subdomain) {
      total += partial;
      partial = 0.0;
    }
    partial += term->value * value_of(term);
  }
  return total + partial;
}

// The sum over [first, end) of term.value * values(term.y).
inline double sum_row_terms(const RowTerm* first, const RowTerm* end,
                            const Eigen::VectorXd& values) {
  return sum_row_terms_of(first, end, [&](const RowTerm* term) { return values(term->y); });
}

// The same with each term's value at the term's own place: values[k] for first[k].
inline double sum_row_terms_in_order(const RowTerm* first, const RowTerm* end,
                                     const double* values) {
  return sum_row_terms_of(first, end, [&](const RowTerm* term) { return values[term - first]; });
}

}  // namespace fetic::solver
