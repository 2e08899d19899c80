// The assembled matrices' sparsity pattern (models/core/sparsity_pattern.*,
// docs/design.md §3.3), built column by column from the elements touching each
// DoF, is exactly the straightforward one: the set of (row, column) pairs of
// DoFs sharing a stencil, the diagonal and the extra entries, stored
// compressed with rows ascending and zero values. The expected arrays are made
// here from an ordered set of pairs.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <stdexcept>
#include <utility>

#include "models/core/sparsity_pattern.h"
#include "models/core/term_model.h"
#include "models/model_factory.h"
#include "tests/support/test_models.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

// (column, row) pairs in column-major order.
std::set<std::pair<int, int>> pairs_of(int num_dofs, const std::vector<Term*>& terms,
                                       const std::vector<std::pair<int, int>>& extra) {
  std::set<std::pair<int, int>> out;
  for (int i = 0; i < num_dofs; ++i) out.insert({i, i});
  for (const auto& [r, c] : extra) out.insert({c, r});
  for (const Term* t : terms)
    for (int e = 0; e < t->num_elements(); ++e)
      for (int a : t->stencil(e))
        for (int b : t->stencil(e))
          if (is_dof(a) && is_dof(b)) out.insert({b, a});
  return out;
}

void expect_pattern(const SparseMatrix& pattern, int num_dofs, const std::set<std::pair<int, int>>& pairs) {
  ASSERT_EQ(pattern.rows(), num_dofs);
  ASSERT_EQ(pattern.cols(), num_dofs);
  ASSERT_TRUE(pattern.isCompressed());
  ASSERT_EQ(pattern.nonZeros(), static_cast<Eigen::Index>(pairs.size()));
  std::vector<int> outer(num_dofs + 1, 0), inner;
  for (const auto& [c, r] : pairs) {
    ++outer[c + 1];
    inner.push_back(r);
  }
  for (int c = 0; c < num_dofs; ++c) outer[c + 1] += outer[c];
  EXPECT_TRUE(std::equal(outer.begin(), outer.end(), pattern.outerIndexPtr()));
  EXPECT_TRUE(std::equal(inner.begin(), inner.end(), pattern.innerIndexPtr()));
  for (Eigen::Index k = 0; k < pattern.nonZeros(); ++k) ASSERT_EQ(pattern.valuePtr()[k], 0.0) << "entry " << k;
}

void expect_model_pattern(const Scene& scene, const std::string& model_name) {
  SCOPED_TRACE(model_name);
  auto model = make_model(scene, model_name);
  const auto* terms_model = dynamic_cast<const TermModel*>(model.get());
  ASSERT_NE(terms_model, nullptr);
  std::vector<Term*> terms;
  for (const auto& t : terms_model->terms()) terms.push_back(t.get());
  const int n = model->num_dofs();
  const auto pairs = pairs_of(n, terms, {});
  ASSERT_GT(pairs.size(), static_cast<size_t>(10 * n));  // far more than the diagonal
  expect_pattern(model->pattern(), n, pairs);
}

TEST(SparsityPattern, YarnAndFemClothsEqualTheSetOfStencilPairs) {
  const Scene scene = parse_scene(test::hanging_cloth_toml(7, 0.01), "pattern.toml");
  expect_model_pattern(scene, "yarn");
  expect_model_pattern(scene, "fem");
}

TEST(SparsityPattern, KnitEqualsTheSetOfStencilPairs) {
  expect_model_pattern(parse_scene(test::hanging_knit_toml(4, 4), "knit.toml"), "knit");
}

// Constants in stencils, a DoF repeated in one stencil, a DoF no term touches,
// extras (repeated, on the diagonal, inside a stencil block and outside any).
TEST(SparsityPattern, ConstantsRepeatsUntouchedDoFsAndExtras) {
  const int n = 7;
  auto springs = test::make_linear_spring_1d({{0, 1}, {1, encode_constant(0)}, {3, 3}, {4, 2}, {5, 1}}, 1.0, 0.0);
  std::vector<Term*> terms{springs.get()};
  const std::vector<std::pair<int, int>> extra{{6, 0}, {6, 0}, {2, 2}, {2, 4}, {0, 5}, {3, 6}};
  const auto pairs = pairs_of(n, terms, extra);
  ASSERT_GT(pairs.size(), static_cast<size_t>(n + extra.size()));
  expect_pattern(build_sparsity_pattern(n, terms, extra), n, pairs);
}

TEST(SparsityPattern, RefusesEntriesOutOfRange) {
  auto springs = test::make_linear_spring_1d({{0, 1}, {1, 3}}, 1.0, 0.0);
  std::vector<Term*> terms{springs.get()};
  EXPECT_NO_THROW(build_sparsity_pattern(4, terms, {{0, 3}}));
  EXPECT_THROW(build_sparsity_pattern(3, terms, {}), std::logic_error);  // DoF 3 of 3
  EXPECT_THROW(build_sparsity_pattern(4, terms, {{0, 4}}), std::logic_error);
  EXPECT_THROW(build_sparsity_pattern(4, terms, {{-1, 0}}), std::logic_error);
}

}  // namespace
}  // namespace wl
