// The backward half of a solve with a simplicial LDL' factor, D L' x = y, on threads.
//
// In the elimination tree of L (the parent of column j is the first row below its
// diagonal) column j of the backward solve needs only x at j's ancestors. Disjoint
// subtrees are therefore independent once their common ancestors are done. A fill-reducing
// order by nested dissection puts each separator above the two halves it splits, and a
// postordered tree keeps each subtree's columns contiguous. So: the top separators (the
// "top") serially, then the subtrees below them, each a column range, on the sweeps'
// threads (base/threads.h).
//
// Each column, or each chain of two or three columns, is computed with CHOLMOD's own
// simplicial kernel's arithmetic (the same grouping of chains, the same order of every
// product and sum), so the result is CHOLMOD's bit for bit on any number of threads: a
// test checks it against cholmod_l_solve2(CHOLMOD_DLt).
//
// The tree also gives the forward half's reach (reach()), whatever the threads.
#pragma once

#include <cstdint>
#include <vector>

namespace latfrac {

// A simplicial LDL' factor in CHOLMOD's layout: column j starts at start[j] with D(j, j)
// and lists count[j] entries, the others L(row, j) with row > j.
struct SimplicialFactor {
  std::int64_t n = 0;
  const std::int64_t* start = nullptr;
  const std::int64_t* count = nullptr;
  const std::int64_t* row = nullptr;
  const double* value = nullptr;
};

class BackwardSolve {
 public:
  // Below this many factor entries CHOLMOD solves alone. Chosen, not measured: a solve
  // there takes well under a millisecond, against a few microseconds to start the
  // threads; the 2-D section at 500 m (838k entries) is far above.
  static constexpr std::int64_t least_entries = 50000;

  // Builds the tree of the factor's pattern (whatever the threads and the size), then the
  // schedule, split for `threads` threads. False (and no schedule) when one thread is
  // given, the factor is small, or the pattern does not split (the checks below fail):
  // the caller then solves with CHOLMOD.
  bool build(const SimplicialFactor& factor, int threads);
  bool ready() const { return ready_; }
  // Whether the tree gives a forward solve's reach (reach() below): every entry L(i, j)
  // has been checked to lie on j's path to the root, i an ancestor of j. Fails only for
  // a pattern that is not a factor's (or a tree that is not postordered).
  bool tree_ready() const { return tree_ready_; }
  // The columns a forward solve L y = b changes when b has entries in `rows` only: the
  // union of their tree paths up to the root (Gilbert's theorem: the reach along the
  // graph of L is that union), ascending. Needs tree_ready().
  std::vector<std::int64_t> reach(const std::vector<std::int64_t>& rows) const;
  // An update of the factor changes only the columns on the tree's paths from the rows
  // it touches up to the root. The tree and the schedule stay when none of them changed
  // its pattern.
  void check_paths(const SimplicialFactor& factor, const std::vector<std::int64_t>& rows);
  // D L' X = Y in place for `columns` right-hand sides stored column after column.
  void solve(const SimplicialFactor& factor, double* y, std::int64_t columns) const;

 private:
  struct Piece {
    std::int64_t first, last;  // the columns, a subtree: first..last, last its root
    std::int64_t entries;
  };
  template <int K>
  void solve_rows(const SimplicialFactor& factor, double* x) const;
  bool ready_ = false;
  bool tree_ready_ = false;
  // For up to three right-hand sides (0) and for four (1): at a chain's highest column
  // its length, 0 elsewhere; and the top's chains (their highest columns), descending.
  std::vector<std::uint8_t> chains_[2];
  std::vector<std::int64_t> tops_[2];
  std::vector<Piece> pieces_;            // by entries, descending
  std::vector<std::int64_t> parent_;     // of the tree, -1 at a root
  std::vector<std::int64_t> count_;      // each column's entry count when built
};

}  // namespace latfrac
