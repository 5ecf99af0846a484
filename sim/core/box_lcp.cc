#include "sim/core/box_lcp.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ahhs::sim {
namespace {
constexpr double kUnbounded = std::numeric_limits<double>::infinity();
constexpr int kFree = 1, kAtLo = 2, kAtHi = 3;
}  // namespace

double* BoxLcp::Row(int a) { return &chol_[static_cast<std::size_t>(a) * cap_]; }

bool BoxLcp::FactorFrom(int n, const double* s, int from) {
  // Rows from..nc-1 of the Cholesky factor of S_CC, the rows above kept.
  const int nc = static_cast<int>(free_.size());
  for (int a = from; a < nc; ++a) {
    const int ra = free_[static_cast<std::size_t>(a)];
    double* la = Row(a);
    for (int b = 0; b <= a; ++b) {
      double v = s[static_cast<std::size_t>(ra) * static_cast<std::size_t>(n) +
                   static_cast<std::size_t>(free_[static_cast<std::size_t>(b)])];
      const double* lb = Row(b);
      for (int k = 0; k < b; ++k) v -= la[k] * lb[k];
      if (a == b) {
        if (!(v > 0)) return false;
        la[a] = std::sqrt(v);
      } else {
        la[b] = v / lb[b];
      }
    }
  }
  return true;
}

void BoxLcp::SolveFree() {
  // L y = rhs, L^T z = y.
  const int nc = static_cast<int>(free_.size());
  for (int a = 0; a < nc; ++a) {
    const double* la = Row(a);
    double v = rhs_[static_cast<std::size_t>(a)];
    for (int k = 0; k < a; ++k) v -= la[k] * rhs_[static_cast<std::size_t>(k)];
    rhs_[static_cast<std::size_t>(a)] = v / la[a];
  }
  for (int a = nc - 1; a >= 0; --a) {
    double v = rhs_[static_cast<std::size_t>(a)];
    for (int k = a + 1; k < nc; ++k) v -= Row(k)[a] * rhs_[static_cast<std::size_t>(k)];
    rhs_[static_cast<std::size_t>(a)] = v / Row(a)[a];
  }
}

bool BoxLcp::FreeDirection(int n, const double* s, int i) {
  // dx_C = -S_CC^-1 S_C,i by the factor.
  const int nc = static_cast<int>(free_.size());
  rhs_.resize(static_cast<std::size_t>(nc));
  for (int a = 0; a < nc; ++a)
    rhs_[static_cast<std::size_t>(a)] =
        -s[static_cast<std::size_t>(free_[static_cast<std::size_t>(a)]) *
               static_cast<std::size_t>(n) +
           static_cast<std::size_t>(i)];
  SolveFree();
  for (int a = 0; a < nc; ++a)
    dx_[static_cast<std::size_t>(free_[static_cast<std::size_t>(a)])] =
        rhs_[static_cast<std::size_t>(a)];
  return true;
}

bool BoxLcp::FactorAll(int n, const double* s) {
  const int nc = static_cast<int>(free_.size());
  const auto un = static_cast<std::size_t>(n);
  for (int a = 0; a < nc; ++a) {
    const double* sa = s + static_cast<std::size_t>(free_[static_cast<std::size_t>(a)]) * un;
    double* la = Row(a);
    for (int b = 0; b <= a; ++b) la[b] = sa[free_[static_cast<std::size_t>(b)]];
  }
  column_.resize(static_cast<std::size_t>(nc));
  double* c = column_.data();
  for (int k = 0; k < nc; ++k) {
    double* lk = Row(k);
    if (!(lk[k] > 0)) return false;
    lk[k] = std::sqrt(lk[k]);
    for (int a = k + 1; a < nc; ++a) {
      double* la = Row(a);
      la[k] = la[k] / lk[k];
      c[a] = la[k];
    }
    // The rest of the factor loses column k, in the order FactorFrom subtracts it.
    for (int a = k + 1; a < nc; ++a) {
      double* la = Row(a);
      const double cak = c[a];
      for (int b = k + 1; b <= a; ++b) la[b] -= cak * c[b];
    }
  }
  return true;
}

bool BoxLcp::Take(int n, const double* s, const double* r, int i, double* x) {
  const auto un = static_cast<std::size_t>(n);
  const auto ui = static_cast<std::size_t>(i);
  if (lo_[ui] == hi_[ui]) {  // nothing to choose: fixed at its only value
    x[i] = lo_[ui];
    state_[ui] = kAtLo;
    return true;
  }
  {
    double v = -r[i];
    const double* si = s + ui * un;
    for (int k = 0; k < n; ++k) v += si[k] * x[k];
    w_[ui] = v;
  }
  for (int guard = 0; guard < 10 * n + 10; ++guard) {
    const double wi = w_[ui];
    if (wi == 0) {
      state_[ui] = kFree;
      free_.push_back(i);
      return FactorFrom(n, s, static_cast<int>(free_.size()) - 1);
    }
    if (x[i] == lo_[ui] && wi > 0) {
      state_[ui] = kAtLo;
      bound_.push_back(i);
      return true;
    }
    if (x[i] == hi_[ui] && wi < 0) {
      state_[ui] = kAtHi;
      bound_.push_back(i);
      return true;
    }
    const double dir = wi < 0 ? 1.0 : -1.0;
    if (!FreeDirection(n, s, i)) return false;
    ++pivots_;
    // Changes of w per unit step, for the rows at a bound and for i.
    auto change_of = [&](int j) {
      const double* sj = s + static_cast<std::size_t>(j) * un;
      double v = sj[i];
      for (int c : free_) v += sj[c] * dx_[static_cast<std::size_t>(c)];
      dw_[static_cast<std::size_t>(j)] = dir * v;
    };
    for (int j : bound_) change_of(j);
    change_of(i);
    // The longest step before something changes state.
    double t = -wi / dw_[ui];  // w_i reaches 0
    int event = 0, who = i;
    const double to_bound = dir > 0 ? hi_[ui] - x[i] : x[i] - lo_[ui];
    if (to_bound <= t) {
      t = to_bound;
      event = 1;
    }
    for (int c : free_) {
      const auto uc = static_cast<std::size_t>(c);
      const double d = dir * dx_[uc];
      double tc = kUnbounded;
      if (d > 0 && hi_[uc] < kUnbounded) tc = (hi_[uc] - x[c]) / d;
      if (d < 0 && lo_[uc] > -kUnbounded) tc = (lo_[uc] - x[c]) / d;
      if (tc < t) {
        t = tc;
        event = 2;
        who = c;
      }
    }
    for (int j : bound_) {
      const auto uj = static_cast<std::size_t>(j);
      double tj = kUnbounded;
      if (state_[uj] == kAtLo && dw_[uj] < 0) tj = -w_[uj] / dw_[uj];
      if (state_[uj] == kAtHi && dw_[uj] > 0) tj = -w_[uj] / dw_[uj];
      if (tj < t) {
        t = tj;
        event = 3;
        who = j;
      }
    }
    if (t < 0) t = 0;
    x[i] += dir * t;
    for (int c : free_) x[c] += dir * t * dx_[static_cast<std::size_t>(c)];
    for (int j : bound_) w_[static_cast<std::size_t>(j)] += t * dw_[static_cast<std::size_t>(j)];
    w_[ui] += t * dw_[ui];
    const auto uw = static_cast<std::size_t>(who);
    if (event == 1) x[i] = dir > 0 ? hi_[ui] : lo_[ui];
    if (event == 2) {  // a free row reached a bound
      const double d = dir * dx_[uw];
      x[who] = d > 0 ? hi_[uw] : lo_[uw];
      state_[uw] = d > 0 ? kAtHi : kAtLo;
      bound_.push_back(who);
      w_[uw] = 0;
      for (std::size_t k = 0; k < free_.size(); ++k)
        if (free_[k] == who) {
          free_.erase(free_.begin() + static_cast<std::ptrdiff_t>(k));
          if (!FactorFrom(n, s, static_cast<int>(k))) return false;
          break;
        }
    }
    if (event == 3) {  // a row at a bound is freed
      state_[uw] = kFree;
      bound_.erase(std::find(bound_.begin(), bound_.end(), who));
      w_[uw] = 0;
      free_.push_back(who);
      if (!FactorFrom(n, s, static_cast<int>(free_.size()) - 1)) return false;
    }
    if (event == 0) w_[ui] = 0;
    if (event == 1) {
      state_[ui] = dir > 0 ? kAtHi : kAtLo;
      bound_.push_back(i);
      return true;
    }
  }
  return false;
}

void BoxLcp::TakeBlock(int n, const double* s, const double* r, const char* candidate,
                       const int* guess, double* x) {
  const auto un = static_cast<std::size_t>(n);
  guess_.assign(guess, guess + n);
  for (int attempt = 0; attempt < 3; ++attempt) {
    // Nothing taken; the block at its guessed states, the rows left out at 0.
    std::fill(state_.begin(), state_.end(), 0);
    free_.clear();
    bound_.clear();
    for (int i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      x[i] = 0;
      if (!candidate[i]) continue;
      int& g = guess_[ui];
      if (lo_[ui] == hi_[ui]) {
        x[i] = lo_[ui];
        state_[ui] = kAtLo;
        g = 0;
        continue;
      }
      if ((g == kAtLo && lo_[ui] == -kUnbounded) || (g == kAtHi && hi_[ui] == kUnbounded)) g = 0;
      if (g == kFree) free_.push_back(i);
      if (g == kAtLo) x[i] = lo_[ui];
      if (g == kAtHi) x[i] = hi_[ui];
    }
    ++pivots_;
    const int nc = static_cast<int>(free_.size());
    if (!FactorAll(n, s)) break;
    // x_C = S_CC^-1 (r_C - S_C,rest x_rest).
    rhs_.resize(static_cast<std::size_t>(nc));
    for (int a = 0; a < nc; ++a) {
      const double* sa = s + static_cast<std::size_t>(free_[static_cast<std::size_t>(a)]) * un;
      double v = r[free_[static_cast<std::size_t>(a)]];
      for (int j = 0; j < n; ++j) v -= sa[j] * x[j];
      rhs_[static_cast<std::size_t>(a)] = v;
    }
    SolveFree();
    for (int a = 0; a < nc; ++a)
      x[free_[static_cast<std::size_t>(a)]] = rhs_[static_cast<std::size_t>(a)];
    // Rows that contradict the block leave it.
    bool consistent = true;
    for (int i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      int& g = guess_[ui];
      if (!candidate[i] || lo_[ui] == hi_[ui] || g == 0) continue;
      if (g == kFree) {  // strictly inside its bounds
        if (!(x[i] > lo_[ui] && x[i] < hi_[ui])) {
          g = 0;
          consistent = false;
        }
        continue;
      }
      const double* si = s + ui * un;
      double w = -r[i];
      for (int j = 0; j < n; ++j) w += si[j] * x[j];
      w_[ui] = w;
      if (!(g == kAtLo ? w > 0 : w < 0)) {  // pushed strictly onto its bound
        g = 0;
        consistent = false;
      }
    }
    if (!consistent) continue;
    for (int i = 0; i < n; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      const int g = guess_[ui];
      if (!candidate[i] || lo_[ui] == hi_[ui] || g == 0) continue;
      state_[ui] = g;
      if (g == kFree) {
        w_[ui] = 0;
      } else {
        bound_.push_back(i);
        ++block_rows_;
      }
    }
    block_rows_ += nc;
    return;
  }
  // No consistent block: nothing taken.
  std::fill(state_.begin(), state_.end(), 0);
  free_.clear();
  bound_.clear();
  for (int i = 0; i < n; ++i) x[i] = 0;
}

bool BoxLcp::Solve(int n, const double* s, const double* r, const double* lo, const double* hi,
                   const int* findex, double* x, BoxLcpStart* start) {
  const auto un = static_cast<std::size_t>(n);
  state_.assign(un, 0);
  free_.clear();
  bound_.clear();
  lo_.assign(lo, lo + n);
  hi_.assign(hi, hi + n);
  w_.assign(un, 0);
  dw_.assign(un, 0);
  dx_.assign(un, 0);
  cap_ = n;
  chol_.resize(un * un);
  pivots_ = 0;
  block_rows_ = 0;
  for (int i = 0; i < n; ++i) x[i] = 0;
  const bool warm = start && start->pass1.size() == un && start->pass2.size() == un;
  if (warm) candidate_.assign(un, 0);
  bool ok = true;
  std::vector<int> pass1;
  for (int pass = 0; pass < 2; ++pass) {  // rows without findex first, then friction rows
    if (pass == 1 && findex) {
      // All friction bounds from the normal forces as they are now (0 for no normal force).
      for (int i = 0; i < n; ++i) {
        if (findex[i] < 0) continue;
        const auto ui = static_cast<std::size_t>(i);
        const double normal = x[findex[i]];
        hi_[ui] = normal == 0 ? 0 : std::fabs(hi[i] * normal);
        lo_[ui] = -hi_[ui];
      }
    }
    if (warm) {  // the first pass's rows, then all of them again
      for (int i = 0; i < n; ++i)
        candidate_[static_cast<std::size_t>(i)] = pass == 1 || !(findex && findex[i] >= 0);
      TakeBlock(n, s, r, candidate_.data(), pass == 0 ? start->pass1.data() : start->pass2.data(),
                x);
    }
    for (int i = 0; i < n; ++i)
      if (state_[static_cast<std::size_t>(i)] == 0 && (pass == 1 || !(findex && findex[i] >= 0)))
        ok = Take(n, s, r, i, x) && ok;
    if (pass == 0 && start) start->pass1 = state_;
  }
  if (start) start->pass2 = state_;
  return ok;
}

}  // namespace ahhs::sim
