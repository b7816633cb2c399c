#include "candidates.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace glint::cut {

namespace {
constexpr std::uint32_t kLeafSize = 4;
}

TriangleBvh::TriangleBvh(std::span<const dvec3> lo, std::span<const dvec3> hi, std::span<const std::uint8_t> include)
    : m_lo(lo.begin(), lo.end()), m_hi(hi.begin(), hi.end()) {
  for (std::uint32_t i = 0; i < lo.size(); ++i)
    if (include[i]) m_order.push_back(i);
  if (m_order.empty()) return;
  std::vector<dvec3> centres(lo.size());
  for (std::size_t i = 0; i < lo.size(); ++i) centres[i] = 0.5 * (lo[i] + hi[i]);
  m_nodes.reserve(2 * m_order.size() / kLeafSize + 2);
  m_nodes.emplace_back();
  build(0, std::uint32_t(m_order.size()), lo, hi, centres);
}

std::uint32_t TriangleBvh::build(std::uint32_t begin, std::uint32_t end, std::span<const dvec3> lo,
                                 std::span<const dvec3> hi, std::vector<dvec3>& centres) {
  // Iterative over an explicit stack: deep scenes would otherwise recurse ~40 levels,
  // which is fine, but the node index bookkeeping is simpler this way.
  struct Task {
    std::uint32_t node, begin, end;
  };
  std::vector<Task> stack{{0, begin, end}};
  while (!stack.empty()) {
    const Task t = stack.back();
    stack.pop_back();
    Node node;
    node.lo = dvec3(std::numeric_limits<double>::infinity());
    node.hi = -node.lo;
    dvec3 clo = node.lo, chi = node.hi;
    for (std::uint32_t i = t.begin; i < t.end; ++i) {
      const std::uint32_t tri = m_order[i];
      node.lo = glm::min(node.lo, lo[tri]);
      node.hi = glm::max(node.hi, hi[tri]);
      clo = glm::min(clo, centres[tri]);
      chi = glm::max(chi, centres[tri]);
    }
    if (t.end - t.begin <= kLeafSize) {
      node.first = t.begin;
      node.count = t.end - t.begin;
      m_nodes[t.node] = node;
      continue;
    }
    const dvec3 extent = chi - clo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t mid = (t.begin + t.end) / 2;
    // Ties broken by index: the tree (and so the candidate order) never depends on how
    // nth_element happens to permute equal keys.
    std::nth_element(m_order.begin() + t.begin, m_order.begin() + mid, m_order.begin() + t.end,
                     [&](std::uint32_t a, std::uint32_t b) {
                       return centres[a][axis] < centres[b][axis] || (centres[a][axis] == centres[b][axis] && a < b);
                     });
    node.first = std::uint32_t(m_nodes.size());
    node.count = 0;
    m_nodes[t.node] = node;
    m_nodes.emplace_back();
    m_nodes.emplace_back();
    stack.push_back({node.first + 1, mid, t.end});
    stack.push_back({node.first, t.begin, mid});
  }
  return 0;
}

void TriangleBvh::query(const dvec3& lo, const dvec3& hi, std::span<const dvec4> planes,
                        std::vector<std::uint32_t>& out) const {
  if (m_nodes.empty()) return;
  const std::size_t first = out.size();
  const auto outside = [&](const dvec3& blo, const dvec3& bhi) {
    if (blo.x > hi.x || blo.y > hi.y || blo.z > hi.z || bhi.x < lo.x || bhi.y < lo.y || bhi.z < lo.z) return true;
    for (const dvec4& p : planes) {
      // The box corner with the smallest plane value: outside when even it is outside.
      const double v = p.w + p.x * (p.x > 0 ? blo.x : bhi.x) + p.y * (p.y > 0 ? blo.y : bhi.y) +
                       p.z * (p.z > 0 ? blo.z : bhi.z);
      if (v > 0.0) return true;
    }
    return false;
  };
  // Median splits halve the count: depth ≤ log2(triangles) + 1, far below 128.
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = m_nodes[stack[--top]];
    if (outside(n.lo, n.hi)) continue;
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const std::uint32_t tri = m_order[i];
        if (!outside(m_lo[tri], m_hi[tri])) out.push_back(tri);
      }
    } else {
      stack[top++] = n.first + 1;
      stack[top++] = n.first;
    }
  }
  std::sort(out.begin() + std::ptrdiff_t(first), out.end());
}

std::size_t TriangleBvh::memoryBytes() const {
  return m_nodes.capacity() * sizeof(Node) + m_order.capacity() * 4 + (m_lo.capacity() + m_hi.capacity()) * sizeof(dvec3);
}

}  // namespace glint::cut
