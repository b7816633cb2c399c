#pragma once
// glint/core/union_find.h — disjoint sets over the numbers 0..n-1 (union-find with path
// halving), for grouping by connection: a mesh's surfaces and holes, the cutter's coplanar
// patches and merged regions. The caller decides which root survives a union, so a grouping
// numbers its sets the same way on every run.
//
/// ```cpp
/// glint::UnionFind sets(4);
/// sets.unite(3, 1);                       // the smaller root, 1, stays the root
/// sets.unite(1, 0);                       // {0, 1, 3}, rooted at 0
/// const bool joined = sets.find(3) == sets.find(0);  // true; 2 is alone
/// ```

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace glint {

class UnionFind {
public:
  explicit UnionFind(std::size_t n) : m_parent(n) { std::iota(m_parent.begin(), m_parent.end(), std::uint32_t{0}); }

  std::size_t size() const { return m_parent.size(); }

  /// The root of x's set (shortening the path as it goes).
  std::uint32_t find(std::uint32_t x) {
    while (m_parent[x] != x) x = m_parent[x] = m_parent[m_parent[x]];
    return x;
  }

  /// Joins the sets of a and b; the smaller root stays the root. False when they were one set.
  bool unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (a > b) std::swap(a, b);
    m_parent[b] = a;
    return true;
  }

  /// Makes the root `child` a member of the set rooted at `root` (both roots): the caller
  /// picks the survivor, as a merge that keeps data at one root must.
  void attach(std::uint32_t child, std::uint32_t root) { m_parent[child] = root; }

private:
  std::vector<std::uint32_t> m_parent;
};

}  // namespace glint
