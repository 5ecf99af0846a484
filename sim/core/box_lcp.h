// A small dense boxed LCP, solved exactly by Dantzig's principal pivoting (one index at a
// time, as ODE's dSolveLCP does, but on a matrix of a few dozen rows).
//
// Finds x and w = S x - r with, for every i, one of
//   x_i = lo_i and w_i >= 0,   x_i = hi_i and w_i <= 0,   lo_i < x_i < hi_i and w_i = 0,
// for a symmetric positive definite S (n x n, row-major) and lo_i <= 0 <= hi_i. A row with
// findex[i] >= 0 is a friction row: friction rows are taken up after all others, and their
// bounds are then set, all at once, to +-|hi_i * x[findex[i]]| (as ODE does: later changes of
// the normal forces do not move them).
#pragma once

#include <vector>

namespace ahhs::sim {

class BoxLcp {
 public:
  // Returns false if the pivoting did not finish (a degenerate cycle); x then holds the last
  // iterate, which satisfies the rows taken up so far.
  bool Solve(int n, const double* s, const double* r, const double* lo, const double* hi,
             const int* findex, double* x);
  int last_pivots() const { return pivots_; }

 private:
  // dx_C = -S_CC^-1 S_C,i (the change of the free rows that keeps their w at 0).
  bool FreeDirection(int n, const double* s, int i);
  // Refactors the Cholesky factor of S_CC from free row `from` on (the free set grew or lost
  // a row there); false if S_CC is not positive definite.
  bool FactorFrom(int n, const double* s, int from);
  double* Row(int a);

  std::vector<int> state_;  // 0 not yet taken, 1 free (w = 0), 2 at lo, 3 at hi
  std::vector<int> free_;   // rows with w = 0, in the order of the factor
  std::vector<int> bound_;  // rows at a bound that may leave it (lo < hi)
  std::vector<double> lo_, hi_, w_, dx_, dw_, chol_, rhs_;  // chol_: rows of cap_
  int cap_ = 0;
  int pivots_ = 0;
};

}  // namespace ahhs::sim
