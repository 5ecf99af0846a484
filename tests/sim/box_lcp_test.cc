#include "sim/core/box_lcp.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace ahhs::sim;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A contact-like boxed LCP: `contacts` normal rows (0 to infinity), two friction rows each
// (+-0.8 of their normal's force), `motors` rows bounded by +-1, on a symmetric positive
// definite S = A A^T + eps I whose A has fewer columns than S has rows (redundant rows, as a
// module lying flat has), and a right-hand side that presses the contacts.
struct Problem {
  int n = 0;
  std::vector<double> s, r, lo, hi;
  std::vector<int> findex;

  Problem(int contacts, int motors, int rank, double eps, std::uint64_t seed) {
    n = 3 * contacts + motors;
    std::mt19937_64 gen(seed);
    std::normal_distribution<double> g(0, 1);
    std::vector<double> a(static_cast<std::size_t>(n * rank));
    for (double& v : a) v = g(gen);
    s.assign(static_cast<std::size_t>(n * n), 0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        double v = i == j ? eps : 0;
        for (int k = 0; k < rank; ++k) v += a[i * rank + k] * a[j * rank + k];
        s[i * n + j] = v;
      }
    for (int i = 0; i < n; ++i) {
      r.push_back(g(gen));
      if (i < contacts) {
        r.back() = std::fabs(r.back()) + 0.5;  // pressed into the ground
        lo.push_back(0);
        hi.push_back(kInf);
        findex.push_back(-1);
      } else if (i < 3 * contacts) {
        lo.push_back(-0.8);
        hi.push_back(0.8);
        findex.push_back((i - contacts) / 2);
      } else {
        lo.push_back(-1);
        hi.push_back(1);
        findex.push_back(-1);
      }
    }
  }
  // The next step's problem: S and r moved a little.
  void Perturb(double size, std::uint64_t seed) {
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<double> u(-size, size);
    for (int i = 0; i < n; ++i) {
      r[i] *= 1 + u(gen);
      for (int j = 0; j <= i; ++j) {
        const double f = 1 + u(gen) * 0.1;
        s[i * n + j] *= f;
        if (i != j) s[j * n + i] = s[i * n + j];
      }
    }
  }
  double Solve(BoxLcp& lcp, std::vector<double>* x, BoxLcpStart* start) const {
    x->assign(static_cast<std::size_t>(n), 0);
    REQUIRE(
        lcp.Solve(n, s.data(), r.data(), lo.data(), hi.data(), findex.data(), x->data(), start));
    return 0;
  }
  // The largest violation of complementarity, relative to the problem's scale. The friction
  // bounds are those of the normal forces without friction (the first pass's solution, here
  // from a problem whose friction rows are held at 0).
  double Violation(const std::vector<double>& x) const {
    Problem first = *this;
    for (int i = 0; i < n; ++i)
      if (findex[i] >= 0) first.lo[i] = first.hi[i] = 0;
    std::vector<double> normals(static_cast<std::size_t>(n));
    BoxLcp lcp;
    REQUIRE(lcp.Solve(n, first.s.data(), first.r.data(), first.lo.data(), first.hi.data(), nullptr,
                      normals.data()));
    double scale = 0, worst = 0;
    for (int i = 0; i < n; ++i) scale = std::max(scale, std::fabs(r[i]));
    for (int i = 0; i < n; ++i) {
      double l = lo[i], h = hi[i];
      if (findex[i] >= 0) {
        h = std::fabs(hi[i] * normals[findex[i]]);
        l = -h;
      }
      double w = -r[i];
      for (int j = 0; j < n; ++j) w += s[i * n + j] * x[j];
      double v = std::max(l - x[i], x[i] - h);  // out of bounds
      if (l == h) {  // held at its only value (friction without a normal force)
        worst = std::max(worst, v);
        continue;
      }
      // At a bound to rounding: the bounds here and in the solve come from normal forces
      // computed in other rounding.
      const double tol = 1e-12 * (1 + std::fabs(h == kInf ? l : h));
      const bool at_lo = x[i] <= l + tol, at_hi = x[i] >= h - tol;
      if (!at_lo && !at_hi) v = std::max(v, std::fabs(w));
      if (at_lo) v = std::max(v, -w);
      if (at_hi) v = std::max(v, w);
      worst = std::max(worst, v);
    }
    return worst / scale;
  }
};

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0, scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, std::fabs(a[i] - b[i]));
    scale = std::max(scale, std::fabs(a[i]));
  }
  return d / scale;
}

}  // namespace

TEST_CASE("a boxed LCP started from the last step's states has the cold solve's solution",
          "[box_lcp]") {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Problem p(8, 5, 40, 1e-3, seed);
    BoxLcp cold, warm;
    BoxLcpStart start;
    std::vector<double> x0, x1, x2;
    p.Solve(warm, &x0, &start);  // no states yet: a cold solve that leaves them
    p.Perturb(0.01, seed + 100);
    p.Solve(cold, &x1, nullptr);
    p.Solve(warm, &x2, &start);
    INFO("seed " << seed);
    CHECK(p.Violation(x1) < 1e-12);
    CHECK(p.Violation(x2) < 1e-12);
    CHECK(MaxDifference(x1, x2) < 1e-10);
  }
}

TEST_CASE(
    "a boxed LCP started from its own solution's states takes all its rows in one block "
    "per pass",
    "[box_lcp]") {
  Problem p(10, 5, 40, 1e-3, 7);
  BoxLcp lcp;
  BoxLcpStart start;
  std::vector<double> x0, x1;
  p.Solve(lcp, &x0, &start);
  CHECK(lcp.last_pivots() > p.n);  // cold: a pivot or more per row
  p.Solve(lcp, &x1, &start);
  CHECK(lcp.last_pivots() == 2);  // one block per pass, no single pivots
  CHECK(MaxDifference(x0, x1) < 1e-12);
}

TEST_CASE("a boxed LCP started from wrong states still finds the solution", "[box_lcp]") {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Problem p(8, 5, 40, 1e-3, seed);
    std::mt19937_64 gen(seed);
    std::uniform_int_distribution<int> state(0, 3);
    BoxLcpStart start;
    for (int i = 0; i < p.n; ++i) {
      start.pass1.push_back(state(gen));
      start.pass2.push_back(state(gen));
    }
    BoxLcp cold, warm;
    std::vector<double> x1, x2;
    p.Solve(cold, &x1, nullptr);
    p.Solve(warm, &x2, &start);
    INFO("seed " << seed);
    CHECK(p.Violation(x2) < 1e-12);
    CHECK(MaxDifference(x1, x2) < 1e-10);
  }
}

TEST_CASE("a boxed LCP ignores a start made for another number of rows", "[box_lcp]") {
  Problem p(6, 3, 20, 1e-3, 3);
  BoxLcpStart start{std::vector<int>(5, 1), std::vector<int>(5, 1)};
  BoxLcp cold, warm;
  std::vector<double> x1, x2;
  p.Solve(cold, &x1, nullptr);
  p.Solve(warm, &x2, &start);
  CHECK(x1 == x2);  // the same pivots, the same bits
  CHECK(warm.last_block_rows() == 0);
  CHECK(start.pass2.size() == static_cast<std::size_t>(p.n));
}
