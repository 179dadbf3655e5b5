// CSG expressions as indicators: the two-valued evaluation against the
// built-in operations, and the three-valued one (value_over, which drives the
// early terminations) against brute-force enumeration of every completion:
// it must never claim a constant that some assignment breaks, and for
// expressions that use each operand once it must find every constant.
#include "ember/csg.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>
#include <vector>

#include "ember/error.hpp"

namespace ember {
namespace {

using Op = Operation;

/// Every vector in {-1, 0, 1, 2}^n (winding numbers, nested and inverted shells included).
void for_each_winding_vector(std::size_t n, const std::function<void(const std::vector<int>&)>& f) {
  std::vector<int> w(n, -1);
  for (;;) {
    f(w);
    std::size_t i = 0;
    while (i < n && w[i] == 2) w[i++] = -1;
    if (i == n) return;
    ++w[i];
  }
}

TEST(Csg, BuiltInOperationsAgreeWithTheirIndicators) {
  for (std::size_t n = 1; n <= 4; ++n)
    for (Op op : {Op::Union, Op::Intersection, Op::Difference, Op::Xor, Op::AtLeastK})
      for (int k = 1; k <= (op == Op::AtLeastK ? static_cast<int>(n) : 1); ++k) {
        const Csg e = Csg::of(op, n, k);
        const Indicator reference = indicator_for(op, n, k);
        EXPECT_EQ(e.operand_count(), n);
        for_each_winding_vector(n, [&](const std::vector<int>& w) {
          EXPECT_EQ(e.inside(w), reference(w)) << e.to_string() << " n=" << n << " k=" << k;
        });
      }
}

/// The exact value of `e` over `state` by enumerating the free operands.
int brute_value_over(const Csg& e, const std::vector<signed char>& state) {
  std::vector<std::size_t> free;
  for (std::size_t i = 0; i < state.size(); ++i)
    if (state[i] < 0) free.push_back(i);
  int seen = -2;
  std::vector<int> w(state.size());
  for (std::size_t mask = 0; mask < (std::size_t{1} << free.size()); ++mask) {
    for (std::size_t i = 0; i < state.size(); ++i) w[i] = state[i] > 0 ? 1 : 0;
    for (std::size_t j = 0; j < free.size(); ++j) w[free[j]] = (mask >> j) & 1;
    const int v = e.inside(w) ? 1 : 0;
    if (seen == -2) seen = v;
    if (seen != v) return -1;
  }
  return seen;
}

/// A random expression over the operands in `pool` (each used once when the
/// pool is a permutation of distinct indices).
Csg random_expression(std::mt19937& rng, std::vector<std::size_t> pool) {
  if (pool.size() == 1) return Csg::operand(pool[0]);
  const std::size_t split = 1 + rng() % (pool.size() - 1);
  const std::vector<std::size_t> left(pool.begin(), pool.begin() + split), right(pool.begin() + split, pool.end());
  const Csg a = random_expression(rng, left), b = random_expression(rng, right);
  switch (rng() % 5) {
    case 0: return a | b;
    case 1: return a & b;
    case 2: return a - b;
    case 3: return a ^ b;
    default: return Csg::at_least(1 + static_cast<int>(rng() % 3), {a, b, a & b});
  }
}

void check_every_state(const Csg& e, std::size_t n, bool read_once) {
  std::vector<signed char> state(n, -1);
  for (;;) {
    const int claimed = e.value_over(state), truth = brute_value_over(e, state);
    if (claimed >= 0) {
      ASSERT_EQ(claimed, truth) << e.to_string() << " claims a constant that an assignment breaks";
    } else if (read_once) {
      // at_least above repeats its terms, so read-once only without it.
      ASSERT_EQ(truth, -1) << e.to_string() << " missed a constant";
    }
    std::size_t i = 0;
    while (i < n && state[i] == 1) state[i++] = -1;
    if (i == n) return;
    ++state[i];
  }
}

TEST(Csg, ValueOverIsSoundAndCompleteForReadOnceExpressions) {
  std::mt19937 rng(11);
  for (int round = 0; round < 400; ++round) {
    const std::size_t n = 1 + rng() % 6;
    std::vector<std::size_t> pool(n);
    for (std::size_t i = 0; i < n; ++i) pool[i] = i;
    std::shuffle(pool.begin(), pool.end(), rng);
    const Csg e = random_expression(rng, pool);
    const bool read_once = e.to_string().find("at_least") == std::string::npos;
    check_every_state(e, n, read_once);
  }
}

TEST(Csg, ValueOverIsSoundWhenOperandsRepeat) {
  std::mt19937 rng(12);
  for (int round = 0; round < 400; ++round) {
    const std::size_t n = 1 + rng() % 4;
    std::vector<std::size_t> pool(2 + rng() % 5);
    for (std::size_t& p : pool) p = rng() % n;
    pool[0] = n - 1;  // operand_count() == n
    check_every_state(random_expression(rng, pool), n, false);
  }
  // Where the Kleene evaluation cannot see a cancellation it says "may change".
  const Csg a = Csg::operand(0);
  const std::vector<signed char> free{-1};
  EXPECT_EQ((a ^ a).value_over(free), -1);
  EXPECT_EQ((a - a).value_over(free), -1);
}

TEST(Csg, TextShowsTheTreeWithSameOperatorChainsFlattened) {
  const Csg a = Csg::operand(0), b = Csg::operand(1), c = Csg::operand(2);
  EXPECT_EQ(((a | b) - c).to_string(), "(#0 | #1) - #2");
  EXPECT_EQ(((a | b) | c).to_string(), "#0 | #1 | #2");
  EXPECT_EQ(((a - b) - c).to_string(), "#0 - #1 - #2");
  EXPECT_EQ((a - (b - c)).to_string(), "#0 - (#1 - #2)");
  EXPECT_EQ(Csg::at_least(2, {a, b | c, c}).to_string(), "at_least(2, #0, (#1 | #2), #2)");
  // A flattened chain is one node: a deep left-leaning chain stays shallow.
  Csg chain = a;
  for (int i = 0; i < 1000; ++i) chain = chain | Csg::operand(1 + i % 2);
  EXPECT_EQ(chain.nodes().size(), 1002u);
  EXPECT_TRUE(chain.inside(std::vector<int>{0, 0, 1}));
  EXPECT_FALSE(chain.inside(std::vector<int>{0, 0, 0}));
}

TEST(Csg, DeepExpressionsEvaluateBeyondTheSmallStack) {
  // Right-leaning differences nest: #0 - (#1 - (#2 - ...)), 100 levels deep.
  Csg e = Csg::operand(99);
  for (int i = 98; i >= 0; --i) e = Csg::operand(static_cast<std::size_t>(i)) - e;
  std::vector<int> w(100, 1);
  // All inside: a - (b - (c - ...)) alternates from the innermost operand out.
  bool expected = true;
  for (int i = 98; i >= 0; --i) expected = !expected;
  EXPECT_EQ(e.inside(w), expected);
  std::vector<signed char> state(100, 1);
  EXPECT_EQ(e.value_over(state), expected ? 1 : 0);
}

TEST(Csg, MisuseIsAnErrorThatSaysWhatToFix) {
  const Csg a = Csg::operand(0), b = Csg::operand(1);
  EXPECT_THROW(Csg::at_least(3, {a, b}), Error);
  EXPECT_THROW(Csg::at_least(0, {a, b}), Error);
  EXPECT_THROW(Csg::of(Op::AtLeastK, 2, 3), Error);
  EXPECT_THROW(a | Csg(), Error);
  try {
    (void)Csg::at_least(3, {a, b});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("between 1 and the number of terms (2)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ember
