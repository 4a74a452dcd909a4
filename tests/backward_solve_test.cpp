// The backward solve over the elimination tree's subtrees on threads (src/solvers/
// backward_solve.h): after factor updates, solve_sparse on two threads must give CHOLMOD's
// own simplicial solve (what it gives on one thread) bit for bit, for one to six
// right-hand sides (CHOLMOD groups chains of columns differently for four), and the
// answer must solve the updated system: K' x = b with K' = K + c c'.
// Also: the tree gives the forward solve's reach, the set of columns a few-entry right-hand
// side changes.
#include <catch2/catch.hpp>
#include <cmath>

#include "latfrac/base/threads.h"
#include "latfrac/mechanics/stiffness.h"
#include "latfrac/scene/model_builder.h"
#include "backward_solve.h"
#include "latfrac/solvers/cholesky.h"
#include "scenes.h"

using namespace latfrac;

namespace {

// K x for the upper triangle of a symmetric matrix in compressed columns (with
// absolute = true, |K| |x|).
Vector product(StiffnessMatrix& k, const Vector& x, bool absolute = false) {
  Vector y = Vector::Zero(x.size());
  for (std::int64_t j = 0; j < k.size(); ++j) {
    for (std::int64_t p = k.column_start()[j]; p < k.column_start()[j + 1]; ++p) {
      const std::int64_t i = k.row_index()[p];
      const double v = absolute ? std::abs(k.values()[p]) : k.values()[p];
      y[i] += v * (absolute ? std::abs(x[j]) : x[j]);
      if (i != j) y[j] += v * (absolute ? std::abs(x[i]) : x[i]);
    }
  }
  return y;
}

struct ThreadCount {
  explicit ThreadCount(int n) { threads::set_count(n); }
  ~ThreadCount() { threads::set_count(0); }
};

}  // namespace

TEST_CASE("The threaded backward solve gives CHOLMOD's answer bit for bit", "[solver]") {
  // A 2-D section of about 3200 nodes: a factor of well over least_entries entries.
  Scene scene = testing::box_scene(2, 500.0, {40e3, 20e3, 20e3}, false);
  Model model = build_model(scene);
  StiffnessMatrix k(model);
  k.assemble(model, Vector::Zero(model.dofs().dof_count()));
  const std::int64_t n = k.size();
  // Two updates, each with a few-entry column (a bond's pattern, made up): the factor
  // becomes the simplicial LDL' that solve_sparse needs.
  const std::vector<LinearBackend::Column> update1 = {{{10, 3e9}, {11, -1e9}, {400, 2e9}}};
  const std::vector<LinearBackend::Column> update2 = {{{n / 2, 5e9}, {n / 2 + 1, 4e9}}};
  const int columns = GENERATE(1, 2, 3, 4, 6);
  std::vector<LinearBackend::Column> b;
  for (int c = 0; c < columns; ++c)
    b.push_back({{(c * 997 + 5) % n, 1.0e6 * (c + 1)}, {(c * 331 + n / 3) % n, -2.5e6}});
  std::vector<double> x[2];
  for (int t = 1; t <= 2; ++t) {
    const ThreadCount count(t);
    CholeskyFactor factor;
    factor.factorize(k);
    factor.update(update1, false);
    factor.update(update2, false);
    x[t - 1].assign(static_cast<std::size_t>(n * columns), 0.0);
    REQUIRE(factor.solve_sparse(b, x[t - 1].data()));
    CHECK(factor.backward_on_threads() == (t == 2));
  }
  CHECK(x[0] == x[1]);
  // The answer solves (K + c1 c1' + c2 c2') x = b: a small residual against the size of
  // the products that make it, |K| |x| (CHOLMOD's own answer reaches 3e-9 of it here; a
  // column solved out of order would be off by its whole size).
  for (int c = 0; c < columns; ++c) {
    const Vector xc = Eigen::Map<const Vector>(x[1].data() + c * n, n);
    Vector r = product(k, xc);
    for (const auto& u : {update1[0], update2[0]}) {
      double dot = 0;
      for (const auto& [row, value] : u) dot += value * xc[row];
      for (const auto& [row, value] : u) r[row] += value * dot;
    }
    for (const auto& [row, value] : b[static_cast<std::size_t>(c)]) r[row] -= value;
    CHECK(r.cwiseAbs().maxCoeff() <= 1e-7 * product(k, xc, true).maxCoeff());
  }
}

TEST_CASE("The elimination tree gives a forward solve's reach", "[solver]") {
  // A made-up factor pattern of 7 columns (the diagonal first in each): the tree
  // 0 -> 2, 1 -> 2, 2 -> 6, 3 -> 5, 4 -> 5, 5 -> 6, postordered, and each column's rows
  // on its path to the root, as a factor's pattern has them.
  std::vector<std::vector<std::int64_t>> pattern = {{0, 2, 6}, {1, 2}, {2, 6}, {3, 5},
                                                    {4, 5, 6}, {5, 6}, {6}};
  auto factor_of = [](const std::vector<std::vector<std::int64_t>>& columns,
                      std::vector<std::int64_t>& start, std::vector<std::int64_t>& count,
                      std::vector<std::int64_t>& row, std::vector<double>& value) {
    start.clear();
    count.clear();
    row.clear();
    for (const auto& c : columns) {
      start.push_back(static_cast<std::int64_t>(row.size()));
      count.push_back(static_cast<std::int64_t>(c.size()));
      row.insert(row.end(), c.begin(), c.end());
    }
    value.assign(row.size(), 1.0);
    return SimplicialFactor{static_cast<std::int64_t>(columns.size()), start.data(),
                            count.data(), row.data(), value.data()};
  };
  std::vector<std::int64_t> start, count, row;
  std::vector<double> value;
  const SimplicialFactor f = factor_of(pattern, start, count, row, value);
  BackwardSolve tree;
  CHECK_FALSE(tree.build(f, 2));  // far below least_entries: no threads' schedule
  REQUIRE(tree.tree_ready());
  // The reach by its definition: every column reachable from the rows along L's graph
  // (column j to the rows of its entries), found by growing the set until it stops.
  auto closure = [&](std::vector<std::int64_t> rows) {
    std::vector<char> in(7, 0);
    for (auto r : rows) in[r] = 1;
    for (bool grew = true; grew;) {
      grew = false;
      for (std::int64_t j = 0; j < 7; ++j)
        if (in[j])
          for (auto i : pattern[j])
            if (!in[i]) in[i] = grew = 1;
    }
    std::vector<std::int64_t> reached;
    for (std::int64_t j = 0; j < 7; ++j)
      if (in[j]) reached.push_back(j);
    return reached;
  };
  for (const std::vector<std::int64_t>& rows :
       {std::vector<std::int64_t>{1}, {3, 0}, {4}, {6}, {2, 2, 5}, {0, 1, 3, 4}}) {
    CHECK(tree.reach(rows) == closure(rows));
  }
  CHECK(tree.reach({1}) == std::vector<std::int64_t>{1, 2, 6});  // by hand
  // A pattern whose tree is not postordered (column 1's parent is 4, so 4's subtree
  // {1, 3, 4} is not a column range): the tree does not give the reach.
  pattern[1] = {1, 4};
  const SimplicialFactor g = factor_of(pattern, start, count, row, value);
  tree.build(g, 2);
  CHECK_FALSE(tree.tree_ready());
}
