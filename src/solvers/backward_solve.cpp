// D L' x = y over the elimination tree's subtrees on threads (backward_solve.h).
#include "backward_solve.h"

#include <algorithm>
#include <queue>

#include "latfrac/base/threads.h"

namespace latfrac {

namespace {

// The length of the chain that CHOLMOD's simplicial kernels take at column j (scanning
// down from n - 1): j alone, or j and j-1, or j, j-1 and j-2 when their patterns nest
// (each column's pattern is the next one's plus that column). The same tests in the same
// order as CHOLMOD's t_cholmod_ltsolve.c, so the grouping, and with it every rounding, is
// CHOLMOD's. Its kernel for four right-hand sides takes pairs at most (longest = 2).
int chain_at(const SimplicialFactor& f, std::int64_t j, int longest) {
  const std::int64_t entries = f.count[j];
  if (j < 4 || entries != f.count[j - 1] - 1 || f.row[f.start[j - 1] + 1] != j) return 1;
  if (longest == 2 || entries != f.count[j - 2] - 2 || f.row[f.start[j - 2] + 2] != j) return 2;
  return 3;
}

// One chain of L' (highest column j, length s) for K right-hand sides in row form (x[i*K+c]).
template <int K>
inline void chain_solve(const SimplicialFactor& f, std::int64_t j, int s, double* x) {
  const std::int64_t* li = f.row;
  const double* lx = f.value;
  std::int64_t p = f.start[j];
  const std::int64_t end = p + f.count[j];
  if (s == 1) {
    const double d = lx[p];
    double y[K];
    for (int c = 0; c < K; ++c) y[c] = x[j * K + c] / d;
    for (++p; p < end; ++p) {
      const double* xi = x + li[p] * K;
      for (int c = 0; c < K; ++c) y[c] -= lx[p] * xi[c];
    }
    for (int c = 0; c < K; ++c) x[j * K + c] = y[c];
  } else if (s == 2) {
    std::int64_t q = f.start[j - 1];
    const double d0 = lx[p], d1 = lx[q], t = lx[q + 1];
    double y0[K], y1[K];
    for (int c = 0; c < K; ++c) {
      y0[c] = x[j * K + c] / d0;
      y1[c] = x[(j - 1) * K + c] / d1;
    }
    for (++p, q += 2; p < end; ++p, ++q) {
      const double* xi = x + li[p] * K;
      for (int c = 0; c < K; ++c) {
        y0[c] -= lx[p] * xi[c];
        y1[c] -= lx[q] * xi[c];
      }
    }
    for (int c = 0; c < K; ++c) {
      y1[c] -= t * y0[c];
      x[j * K + c] = y0[c];
      x[(j - 1) * K + c] = y1[c];
    }
  } else {
    std::int64_t q = f.start[j - 1], r = f.start[j - 2];
    const double d0 = lx[p], d1 = lx[q], d2 = lx[r];
    const double t0 = lx[q + 1], t1 = lx[r + 1], t2 = lx[r + 2];
    double y0[K], y1[K], y2[K];
    for (int c = 0; c < K; ++c) {
      y0[c] = x[j * K + c] / d0;
      y1[c] = x[(j - 1) * K + c] / d1;
      y2[c] = x[(j - 2) * K + c] / d2;
    }
    for (++p, q += 2, r += 3; p < end; ++p, ++q, ++r) {
      const double* xi = x + li[p] * K;
      for (int c = 0; c < K; ++c) {
        y0[c] -= lx[p] * xi[c];
        y1[c] -= lx[q] * xi[c];
        y2[c] -= lx[r] * xi[c];
      }
    }
    for (int c = 0; c < K; ++c) {
      y1[c] -= t0 * y0[c];
      y2[c] -= t2 * y0[c] + t1 * y1[c];
      x[j * K + c] = y0[c];
      x[(j - 1) * K + c] = y1[c];
      x[(j - 2) * K + c] = y2[c];
    }
  }
}

}  // namespace

bool BackwardSolve::build(const SimplicialFactor& f, int threads) {
  ready_ = false;
  tree_ready_ = false;
  pieces_.clear();
  const std::int64_t n = f.n;
  // The tree: each column's parent is its first row below the diagonal (the smallest).
  parent_.assign(n, -1);
  count_.assign(f.count, f.count + n);
  for (std::int64_t j = 0; j < n; ++j) {
    std::int64_t first = -1;
    for (std::int64_t p = f.start[j] + 1; p < f.start[j] + f.count[j]; ++p)
      if (first < 0 || f.row[p] < first) first = f.row[p];
    if (first >= 0 && first <= j) return false;
    parent_[j] = first;
  }
  // Each subtree's entries, its columns and its lowest column (children come before
  // their parent).
  std::vector<std::int64_t> work(n, 0), size(n, 1), lowest(n);
  std::int64_t entries = 0;
  for (std::int64_t j = 0; j < n; ++j) lowest[j] = j;
  for (std::int64_t j = 0; j < n; ++j) {
    entries += f.count[j];
    work[j] += f.count[j];
    if (parent_[j] >= 0) {
      work[parent_[j]] += work[j];
      size[parent_[j]] += size[j];
      lowest[parent_[j]] = std::min(lowest[parent_[j]], lowest[j]);
    }
  }
  // Postordered, every subtree is the column range lowest..root; then i > j is an
  // ancestor of j exactly when lowest[i] <= j. Each entry L(i, j) must be one.
  // (The threads' schedule below does not need it: it checks its own pieces.)
  tree_ready_ = true;
  for (std::int64_t j = 0; j < n && tree_ready_; ++j) {
    if (size[j] != j - lowest[j] + 1) tree_ready_ = false;
    for (std::int64_t p = f.start[j] + 1; p < f.start[j] + f.count[j]; ++p)
      if (lowest[f.row[p]] > j) tree_ready_ = false;
  }
  if (threads < 2 || entries < least_entries) return false;
  // The chains, as CHOLMOD finds them, for up to three right-hand sides (map 0) and for
  // four (map 1); each column's chain (its highest column) in either.
  std::vector<std::int64_t> chain_top[2];
  for (int map = 0; map < 2; ++map) {
    chains_[map].assign(n, 0);
    chain_top[map].assign(n, 0);
    for (std::int64_t j = n - 1; j >= 0;) {
      const int s = chain_at(f, j, map == 0 ? 3 : 2);
      chains_[map][j] = static_cast<std::uint8_t>(s);
      for (int m = 0; m < s; ++m) chain_top[map][j - m] = j;
      j -= s;
    }
  }
  std::vector<std::int64_t> child_start(n + 1, 0), children(n);
  for (std::int64_t j = 0; j < n; ++j)
    if (parent_[j] >= 0) ++child_start[parent_[j] + 1];
  for (std::int64_t j = 0; j < n; ++j) child_start[j + 1] += child_start[j];
  {
    std::vector<std::int64_t> next(child_start.begin(), child_start.end() - 1);
    for (std::int64_t j = 0; j < n; ++j)
      if (parent_[j] >= 0) children[next[parent_[j]]++] = j;
  }
  // Split from the roots down: the largest subtree's root goes to the top, with every
  // column that shares a chain with it in either map, and the children of what went to
  // the top become subtrees; until the largest subtree holds at most 1/(2 threads) of
  // what the subtrees hold (room for the threads to even out), or the top would hold a
  // quarter of the entries.
  std::vector<std::uint8_t> top(n, 0), open_root(n, 0);
  auto larger = [&](std::int64_t a, std::int64_t b) { return work[a] < work[b]; };
  std::priority_queue<std::int64_t, std::vector<std::int64_t>, decltype(larger)> open(larger);
  std::int64_t in_subtrees = 0, in_top = 0;
  auto add_open = [&](std::int64_t j) {
    open_root[j] = 1;
    open.push(j);
    in_subtrees += work[j];
  };
  for (std::int64_t j = 0; j < n; ++j)
    if (parent_[j] < 0) add_open(j);
  std::vector<std::int64_t> pending, added;
  while (!open.empty()) {
    const std::int64_t j = open.top();
    if (!open_root[j]) {  // taken into the top with a chain since
      open.pop();
      continue;
    }
    if (work[j] * 2 * threads <= in_subtrees) break;
    // The columns that go to the top with j (marked in `top` as they are found; unmarked
    // again if the top would grow too big).
    added.clear();
    pending.assign(1, j);
    while (!pending.empty()) {
      const std::int64_t c = pending.back();
      pending.pop_back();
      if (top[c]) continue;
      top[c] = 1;
      added.push_back(c);
      for (int map = 0; map < 2; ++map) {
        const std::int64_t t = chain_top[map][c];
        for (int m = 0; m < chains_[map][t]; ++m)
          if (!top[t - m]) pending.push_back(t - m);
      }
    }
    std::int64_t added_entries = 0;
    for (std::int64_t c : added) added_entries += f.count[c];
    if (4 * (in_top + added_entries) > entries) {
      for (std::int64_t c : added) top[c] = 0;
      break;
    }
    open.pop();
    in_top += added_entries;
    for (std::int64_t c : added) {
      if (open_root[c]) {
        open_root[c] = 0;
        in_subtrees -= work[c];
      }
    }
    for (std::int64_t c : added)
      for (std::int64_t k = child_start[c]; k < child_start[c + 1]; ++k)
        if (!top[children[k]] && !open_root[children[k]]) add_open(children[k]);
  }
  for (; !open.empty(); open.pop()) {
    const std::int64_t j = open.top();
    if (open_root[j]) pieces_.push_back({lowest[j], j, work[j]});
    open_root[j] = 0;
  }
  if (pieces_.size() < 2) return false;
  std::sort(pieces_.begin(), pieces_.end(),
            [](const Piece& a, const Piece& b) { return a.entries > b.entries; });
  // Checks that make the schedule safe whatever the pattern: the pieces and the top cover
  // every column once, each chain of either map lies in one piece or in the top, and a
  // column reads x only in its own piece or in the top (the top only in the top).
  std::vector<std::int64_t> piece_of(n, -2);
  for (std::int64_t j = 0; j < n; ++j)
    if (top[j]) piece_of[j] = -1;
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    for (std::int64_t j = pieces_[k].first; j <= pieces_[k].last; ++j) {
      if (piece_of[j] != -2) return false;
      piece_of[j] = static_cast<std::int64_t>(k);
    }
  }
  for (int map = 0; map < 2; ++map) {
    tops_[map].clear();
    for (std::int64_t j = n - 1; j >= 0; --j) {
      if (piece_of[j] == -2) return false;
      if (chains_[map][j] == 0) continue;
      for (int m = 1; m < chains_[map][j]; ++m)
        if (piece_of[j - m] != piece_of[j]) return false;
      if (top[j]) tops_[map].push_back(j);
    }
  }
  for (std::int64_t j = 0; j < n; ++j) {
    for (std::int64_t p = f.start[j] + 1; p < f.start[j] + f.count[j]; ++p) {
      const std::int64_t i = piece_of[f.row[p]];
      if (i != -1 && i != piece_of[j]) return false;
    }
  }
  ready_ = true;
  return true;
}

void BackwardSolve::check_paths(const SimplicialFactor& f, const std::vector<std::int64_t>& rows) {
  if (!tree_ready_ && !ready_) return;
  for (std::int64_t j : rows) {
    for (; j >= 0; j = parent_[j]) {
      if (f.count[j] != count_[j]) {
        ready_ = tree_ready_ = false;
        return;
      }
    }
  }
}

std::vector<std::int64_t> BackwardSolve::reach(const std::vector<std::int64_t>& rows) const {
  std::vector<char> reached(parent_.size(), 0);
  std::vector<std::int64_t> columns;
  for (std::int64_t j : rows)
    for (; j >= 0 && !reached[j]; j = parent_[j]) {
      reached[j] = 1;
      columns.push_back(j);
    }
  std::sort(columns.begin(), columns.end());
  return columns;
}

template <int K>
void BackwardSolve::solve_rows(const SimplicialFactor& f, double* x) const {
  const std::vector<std::uint8_t>& chain = chains_[K == 4 ? 1 : 0];
  for (const std::int64_t j : tops_[K == 4 ? 1 : 0]) chain_solve<K>(f, j, chain[j], x);
  threads::for_blocks(static_cast<std::int64_t>(pieces_.size()), 1,
                      [&](std::int64_t first, std::int64_t last) {
                        for (std::int64_t k = first; k < last; ++k) {
                          const Piece& piece = pieces_[static_cast<std::size_t>(k)];
                          for (std::int64_t j = piece.last; j >= piece.first; j -= chain[j])
                            chain_solve<K>(f, j, chain[j], x);
                        }
                      });
}

void BackwardSolve::solve(const SimplicialFactor& f, double* y, std::int64_t columns) const {
  const std::int64_t n = f.n;
  std::vector<double> rows;
  // Up to four right-hand sides at a time in row form, as CHOLMOD takes them.
  for (std::int64_t first = 0; first < columns; first += 4) {
    const int k = static_cast<int>(std::min<std::int64_t>(4, columns - first));
    rows.resize(static_cast<std::size_t>(n * k));
    for (int c = 0; c < k; ++c)
      for (std::int64_t i = 0; i < n; ++i) rows[i * k + c] = y[(first + c) * n + i];
    switch (k) {
      case 1:
        solve_rows<1>(f, rows.data());
        break;
      case 2:
        solve_rows<2>(f, rows.data());
        break;
      case 3:
        solve_rows<3>(f, rows.data());
        break;
      default:
        solve_rows<4>(f, rows.data());
        break;
    }
    for (int c = 0; c < k; ++c)
      for (std::int64_t i = 0; i < n; ++i) y[(first + c) * n + i] = rows[i * k + c];
  }
}

}  // namespace latfrac
