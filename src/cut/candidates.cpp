#include "candidates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace glint::cut {

namespace {
constexpr std::uint32_t kLeafSize = 4;
}

namespace {
float down(double x) {
  float f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float up(double x) {
  float f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

/// Binned surface area heuristic over the centres' `axis`: the scene mixes large floor
/// triangles and small pipe facets, where median splits make boxes that overlap a lot.
/// Partitions order[begin, end) (each side sorted by index) and returns where the right
/// side starts, or `mid` when no split has triangles on both sides.
std::uint32_t sahSplit(std::vector<std::uint32_t>& order, std::uint32_t begin, std::uint32_t end, int axis,
                       const dvec3& clo, const dvec3& extent, std::span<const dvec3> lo, std::span<const dvec3> hi,
                       const std::vector<dvec3>& centres, std::uint32_t mid) {
  constexpr int kBins = 16;
  struct Bin {
    dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    std::uint32_t count = 0;
  };
  Bin bins[kBins];
  const auto binOf = [&](std::uint32_t tri) {
    return std::min(kBins - 1, int(double(kBins) * (centres[tri][axis] - clo[axis]) / extent[axis]));
  };
  for (std::uint32_t i = begin; i < end; ++i) {
    Bin& b = bins[binOf(order[i])];
    b.lo = glm::min(b.lo, lo[order[i]]);
    b.hi = glm::max(b.hi, hi[order[i]]);
    ++b.count;
  }
  const auto area = [](const dvec3& l, const dvec3& h) {
    const dvec3 d = glm::max(h - l, dvec3(0.0));
    return d.x * d.y + d.y * d.z + d.z * d.x;
  };
  double rightArea[kBins];
  std::uint32_t rightCount[kBins];
  dvec3 rl(std::numeric_limits<double>::infinity()), rh(-rl);
  std::uint32_t rc = 0;
  for (int b = kBins - 1; b > 0; --b) {
    rl = glm::min(rl, bins[b].lo);
    rh = glm::max(rh, bins[b].hi);
    rc += bins[b].count;
    rightArea[b] = area(rl, rh);
    rightCount[b] = rc;
  }
  dvec3 ll(std::numeric_limits<double>::infinity()), lh(-ll);
  std::uint32_t lc = 0;
  double best = std::numeric_limits<double>::infinity();
  int split = -1;
  for (int b = 1; b < kBins; ++b) {
    ll = glm::min(ll, bins[b - 1].lo);
    lh = glm::max(lh, bins[b - 1].hi);
    lc += bins[b - 1].count;
    if (lc == 0 || rightCount[b] == 0) continue;
    const double cost = area(ll, lh) * double(lc) + rightArea[b] * double(rightCount[b]);
    if (cost < best) {
      best = cost;
      split = b;
    }
  }
  if (split > 0) {
    auto* m = std::partition(order.data() + begin, order.data() + end,
                             [&](std::uint32_t tri) { return binOf(tri) < split; });
    mid = std::uint32_t(m - order.data());
    // partition's order depends on nothing but the input order: deterministic; sort
    // each side by index so that it also does not depend on the library's partition.
    std::sort(order.begin() + begin, order.begin() + mid);
    std::sort(order.begin() + mid, order.begin() + end);
  }
  return mid;
}

}  // namespace

TriangleBvh::TriangleBvh(std::span<const dvec3> lo, std::span<const dvec3> hi, std::span<const std::uint8_t> include) {
  for (std::uint32_t i = 0; i < lo.size(); ++i)
    if (include[i]) m_order.push_back(i);
  if (m_order.empty()) return;
  std::vector<dvec3> centres(lo.size());
  for (std::size_t i = 0; i < lo.size(); ++i) centres[i] = 0.5 * (lo[i] + hi[i]);
  m_nodes.reserve(2 * m_order.size() / kLeafSize + 2);
  m_nodes.emplace_back();
  build(lo, hi, centres);
  m_boxes.resize(m_order.size());
  for (std::size_t i = 0; i < m_order.size(); ++i) {
    const dvec3 &l = lo[m_order[i]], &h = hi[m_order[i]];
    m_boxes[i] = {vec3(down(l.x), down(l.y), down(l.z)), vec3(up(h.x), up(h.y), up(h.z))};
  }
}

void TriangleBvh::build(std::span<const dvec3> lo, std::span<const dvec3> hi, std::vector<dvec3>& centres) {
  struct Task {
    std::uint32_t node, begin, end;
  };
  std::vector<Task> stack{{0, 0, std::uint32_t(m_order.size())}};
  while (!stack.empty()) {
    const Task t = stack.back();
    stack.pop_back();
    dvec3 nlo(std::numeric_limits<double>::infinity()), nhi(-nlo), clo(nlo), chi(nhi);
    for (std::uint32_t i = t.begin; i < t.end; ++i) {
      const std::uint32_t tri = m_order[i];
      nlo = glm::min(nlo, lo[tri]);
      nhi = glm::max(nhi, hi[tri]);
      clo = glm::min(clo, centres[tri]);
      chi = glm::max(chi, centres[tri]);
    }
    Node node;
    node.box = {vec3(down(nlo.x), down(nlo.y), down(nlo.z)), vec3(up(nhi.x), up(nhi.y), up(nhi.z))};
    if (t.end - t.begin <= kLeafSize) {
      node.first = t.begin;
      node.count = t.end - t.begin;
      m_nodes[t.node] = node;
      continue;
    }
    // Split by the surface area heuristic over the centres' longest axis (sahSplit), else
    // at the median. Ties broken by index, so the tree never depends on sort details.
    const dvec3 extent = chi - clo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    std::uint32_t mid = (t.begin + t.end) / 2;
    if (extent[axis] > 0.0) mid = sahSplit(m_order, t.begin, t.end, axis, clo, extent, lo, hi, centres, mid);
    if (mid == t.begin || mid == t.end) {
      mid = (t.begin + t.end) / 2;
      std::nth_element(m_order.begin() + t.begin, m_order.begin() + mid, m_order.begin() + t.end,
                       [&](std::uint32_t a, std::uint32_t b) {
                         return centres[a][axis] < centres[b][axis] || (centres[a][axis] == centres[b][axis] && a < b);
                       });
    }
    node.first = std::uint32_t(m_nodes.size());
    node.count = 0;
    m_nodes[t.node] = node;
    m_nodes.emplace_back();
    m_nodes.emplace_back();
    stack.push_back({node.first + 1, mid, t.end});
    stack.push_back({node.first, t.begin, mid});
  }
}

void TriangleBvh::query(const dvec3& lo, const dvec3& hi, std::span<const dvec4> planes,
                        std::vector<std::uint32_t>& out) const {
  if (m_nodes.empty()) return;
  const std::size_t first = out.size();
  const auto outside = [&](const Box& b) {
    if (double(b.lo.x) > hi.x || double(b.lo.y) > hi.y || double(b.lo.z) > hi.z || double(b.hi.x) < lo.x ||
        double(b.hi.y) < lo.y || double(b.hi.z) < lo.z)
      return true;
    for (const dvec4& p : planes) {
      // The box corner with the smallest plane value: outside when even it is outside.
      const double v = p.w + p.x * double(p.x > 0 ? b.lo.x : b.hi.x) + p.y * double(p.y > 0 ? b.lo.y : b.hi.y) +
                       p.z * double(p.z > 0 ? b.lo.z : b.hi.z);
      if (v > 0.0) return true;
    }
    return false;
  };
  // Depth-first: the stack holds at most one pending sibling per level.
  thread_local std::vector<std::uint32_t> stack;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const Node& n = m_nodes[stack.back()];
    stack.pop_back();
    if (outside(n.box)) continue;
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
        if (!outside(m_boxes[i])) out.push_back(m_order[i]);
    } else {
      stack.push_back(n.first + 1);
      stack.push_back(n.first);
    }
  }
  std::sort(out.begin() + std::ptrdiff_t(first), out.end());
}

std::size_t TriangleBvh::memoryBytes() const {
  return m_nodes.capacity() * sizeof(Node) + m_order.capacity() * 4 + m_boxes.capacity() * sizeof(Box);
}

}  // namespace glint::cut
