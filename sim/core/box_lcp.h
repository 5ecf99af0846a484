// A small dense boxed LCP, solved exactly by Dantzig's principal pivoting (one index at a
// time, as ODE's dSolveLCP does, but on a matrix of a few dozen rows).
//
// Finds x and w = S x - r with, for every i, one of
//   x_i = lo_i and w_i >= 0,   x_i = hi_i and w_i <= 0,   lo_i < x_i < hi_i and w_i = 0,
// for a symmetric positive definite S (n x n, row-major) and lo_i <= 0 <= hi_i. A row with
// findex[i] >= 0 is a friction row: friction rows are taken up after all others, and their
// bounds are then set, all at once, to +-|hi_i * x[findex[i]]| (as ODE does: later changes of
// the normal forces do not move them).
//
// With a BoxLcpStart from the previous step (the same rows in the same order), each pass first
// takes a block of rows at once: the rows at a bound and the free rows that the last solve ended
// with, one Cholesky factor and one solve; rows that do not strictly agree with it (a free row
// not strictly inside its bounds, a row at a bound not strictly pushed onto it) are left out and
// taken afterwards one at a time as above. The solution is the same (the LCP has one, S being
// positive definite), in other rounding; the pivots are a few instead of one or more per row.
#pragma once

#include <vector>

namespace ahhs::sim {

// Where the rows of a solve ended, per pass (1 free, 2 at lo, 3 at hi): a warm start for the next.
struct BoxLcpStart {
  std::vector<int> pass1, pass2;
};

class BoxLcp {
 public:
  // Returns false if the pivoting did not finish (a degenerate cycle); x then holds the last
  // iterate, which satisfies the rows taken up so far. With `start`, starts from it when it has
  // n rows and leaves this solve's states in it.
  bool Solve(int n, const double* s, const double* r, const double* lo, const double* hi,
             const int* findex, double* x, BoxLcpStart* start = nullptr);
  // Single pivots, plus one per block.
  int last_pivots() const { return pivots_; }
  // Rows the last solve took in blocks.
  int last_block_rows() const { return block_rows_; }

 private:
  // Takes row i (not yet taken) by pivoting until it is complementary; false if it cycles.
  bool Take(int n, const double* s, const double* r, int i, double* x);
  // Takes the rows with candidate[i] at the states `guess` as one block (see the class comment).
  void TakeBlock(int n, const double* s, const double* r, const char* candidate, const int* guess,
                 double* x);
  // The Cholesky factor of S_CC for the whole free set, column by column (the same bits as
  // FactorFrom(n, s, 0)); false if S_CC is not positive definite.
  bool FactorAll(int n, const double* s);
  // rhs_ (the free rows, in the factor's order) becomes S_CC^-1 rhs_, by the factor.
  void SolveFree();
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
  std::vector<int> guess_;
  std::vector<char> candidate_;
  std::vector<double> column_;
  int cap_ = 0;
  int pivots_ = 0, block_rows_ = 0;
};

}  // namespace ahhs::sim
