// The GPU's hierarchy (raytrace/bvh.h): Embree's builder into glint's flat layout, and the
// traversal's arithmetic on the CPU (what shaders/bake/trace.comp does, for the tests).
#include "glint/raytrace/bvh.h"

#include "embree.h"
#include "glint/core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace glint::raytrace {

namespace {

// The builder's tree, in its thread-local memory until flattened.
struct BuildNode {
  bool leaf = false;
  BuildNode* children[2] = {nullptr, nullptr};
  RTCBounds bounds[2] = {};
  std::uint32_t count = 0;      ///< leaf: primitives
  std::uint32_t primitives[1];  ///< leaf: `count` primitive ids follow (allocated with room for them)
};

void* createNode(RTCThreadLocalAllocator allocator, unsigned int children, void*) {
  if (children != 2) return nullptr;  // (maxBranchingFactor is 2)
  auto* node = static_cast<BuildNode*>(rtcThreadLocalAlloc(allocator, sizeof(BuildNode), 16));
  *node = BuildNode{};
  return node;
}

void setNodeChildren(void* node, void** children, unsigned int count, void*) {
  for (unsigned int k = 0; k < count && k < 2; ++k) static_cast<BuildNode*>(node)->children[k] = static_cast<BuildNode*>(children[k]);
}

void setNodeBounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
  for (unsigned int k = 0; k < count && k < 2; ++k) static_cast<BuildNode*>(node)->bounds[k] = *bounds[k];
}

void* createLeaf(RTCThreadLocalAllocator allocator, const RTCBuildPrimitive* primitives, std::size_t count, void*) {
  const std::size_t bytes = sizeof(BuildNode) + (count > 0 ? count - 1 : 0) * sizeof(std::uint32_t);
  auto* node = static_cast<BuildNode*>(rtcThreadLocalAlloc(allocator, bytes, 16));
  *node = BuildNode{};
  node->leaf = true;
  node->count = std::uint32_t(count);
  for (std::size_t k = 0; k < count; ++k) node->primitives[k] = primitives[k].primID;
  return node;
}

RTCBounds unite(const RTCBounds& a, const RTCBounds& b) {
  RTCBounds r{};
  r.lower_x = std::min(a.lower_x, b.lower_x);
  r.lower_y = std::min(a.lower_y, b.lower_y);
  r.lower_z = std::min(a.lower_z, b.lower_z);
  r.upper_x = std::max(a.upper_x, b.upper_x);
  r.upper_y = std::max(a.upper_y, b.upper_y);
  r.upper_z = std::max(a.upper_z, b.upper_z);
  return r;
}

/// The primitives the builder gets: every triangle that can be hit (finite, not degenerate).
std::vector<RTCBuildPrimitive> primitivesOf(const Mesh& mesh) {
  std::vector<RTCBuildPrimitive> out;
  out.reserve(mesh.triangleCount());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
               c = mesh.positions[mesh.indices[3 * t + 2]];
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
      finite &= std::isfinite(a[k]) && std::isfinite(b[k]) && std::isfinite(c[k]);
      if (std::abs(a[k]) > kMaxCoordinate || std::abs(b[k]) > kMaxCoordinate || std::abs(c[k]) > kMaxCoordinate)
        fail(ErrorKind::Input, "triangle {} has a vertex beyond ±{:g}, the ray tracer's range", t, kMaxCoordinate);
    }
    if (!finite || glm::length(glm::cross(b - a, c - a)) == 0.0f) continue;
    const vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    out.push_back({.lower_x = lo.x, .lower_y = lo.y, .lower_z = lo.z, .geomID = 0,
                   .upper_x = hi.x, .upper_y = hi.y, .upper_z = hi.z, .primID = std::uint32_t(t)});
  }
  return out;
}

/// The builder's tree into the flat arrays: children adjacent, leaves' triangles in order.
void flatten(const BuildNode* root, const RTCBounds& rootBounds, const Mesh& mesh, Bvh& out) {
  struct Item {
    const BuildNode* node;
    RTCBounds bounds;
    std::uint32_t index;
    int depth;
  };
  out.nodes.push_back({});
  std::vector<Item> stack{{root, rootBounds, 0, 1}};
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    out.depth = std::max(out.depth, item.depth);
    BvhNode& n = out.nodes[item.index];
    n.lower = {item.bounds.lower_x, item.bounds.lower_y, item.bounds.lower_z};
    n.upper = {item.bounds.upper_x, item.bounds.upper_y, item.bounds.upper_z};
    if (item.node->leaf) {
      n.first = std::uint32_t(out.triangles.size());
      n.count = item.node->count;
      for (std::uint32_t k = 0; k < item.node->count; ++k) {
        const std::uint32_t t = item.node->primitives[k];
        const auto corner = [&](int c) { return vec4(mesh.positions[mesh.indices[3 * std::size_t(t) + std::size_t(c)]], 0.0f); };
        out.triangles.push_back({corner(0), corner(1), corner(2)});
        out.ids.push_back(t);
      }
      continue;
    }
    const std::uint32_t first = std::uint32_t(out.nodes.size());
    n.first = first;
    n.count = 0;
    out.nodes.push_back({});
    out.nodes.push_back({});
    for (int k = 1; k >= 0; --k) stack.push_back({item.node->children[k], item.node->bounds[k], first + std::uint32_t(k), item.depth + 1});
  }
}

// ---- the traversal's arithmetic (shaders/bake/trace.comp does the same) ----------------

/// The slab test on [tnear, tfar] with the reciprocal direction; the far side widened by
/// 2γ(3) so that a box around a triangle a watertight test hits is never missed.
bool hitsBox(const BvhNode& n, const vec3& origin, const vec3& inverse, float tnear, float tfar, float& entry) {
  const vec3 t0 = (n.lower - origin) * inverse, t1 = (n.upper - origin) * inverse;
  const vec3 lo = glm::min(t0, t1), hi = glm::max(t0, t1);
  // NaN (0 · ∞ on a slab's plane) must not decide: max/min below ignore it on the tnear/tfar side.
  const float enter = std::max({tnear, lo.x == lo.x ? lo.x : tnear, lo.y == lo.y ? lo.y : tnear, lo.z == lo.z ? lo.z : tnear});
  const float leave = std::min({tfar, hi.x == hi.x ? hi.x : tfar, hi.y == hi.y ? hi.y : tfar, hi.z == hi.z ? hi.z : tfar}) *
                      (1.0f + 2.0f * 3.0f * 0.5f * std::numeric_limits<float>::epsilon() / (1.0f - 3.0f * 0.5f * std::numeric_limits<float>::epsilon()));
  entry = enter;
  return enter <= leave;
}

/// The watertight test: the hit's t and the weights of corners 1 and 2.
struct Shear {
  int kx, ky, kz;
  float sx, sy, sz;
};

Shear shearOf(const vec3& d) {
  const vec3 a = glm::abs(d);
  const int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (d[kz] < 0.0f) std::swap(kx, ky);
  return {kx, ky, kz, d[kx] / d[kz], d[ky] / d[kz], 1.0f / d[kz]};
}

bool hitsTriangle(const BvhTriangle& tri, const vec3& origin, const Shear& s, float tnear, float tfar, float& t, float& u,
                  float& v) {
  const vec3 A = vec3(tri.a) - origin, B = vec3(tri.b) - origin, C = vec3(tri.c) - origin;
  const float ax = A[s.kx] - s.sx * A[s.kz], ay = A[s.ky] - s.sy * A[s.kz];
  const float bx = B[s.kx] - s.sx * B[s.kz], by = B[s.ky] - s.sy * B[s.kz];
  const float cx = C[s.kx] - s.sx * C[s.kz], cy = C[s.ky] - s.sy * C[s.kz];
  float U = cx * by - cy * bx, V = ax * cy - ay * cx, W = bx * ay - by * ax;
  if (U == 0.0f || V == 0.0f || W == 0.0f) {  // on an edge in float: decided in double
    U = float(double(cx) * double(by) - double(cy) * double(bx));
    V = float(double(ax) * double(cy) - double(ay) * double(cx));
    W = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return false;
  const float det = U + V + W;
  if (det == 0.0f) return false;
  const float T = U * (s.sz * A[s.kz]) + V * (s.sz * B[s.kz]) + W * (s.sz * C[s.kz]);
  const float inv = 1.0f / det;
  t = T * inv;
  if (!(t >= tnear && t <= tfar)) return false;
  u = V * inv;
  v = W * inv;
  return true;
}

}  // namespace

Bvh buildBvh(const Mesh& mesh, const BvhOptions& options) {
  if (options.maxLeafSize < 1 || options.maxLeafSize > 32)
    fail(ErrorKind::Usage, "BVH leaf size must be 1..32, got {}", options.maxLeafSize);
  Bvh out;
  std::vector<RTCBuildPrimitive> primitives = primitivesOf(mesh);
  if (primitives.empty()) return out;
  RTCBounds rootBounds{primitives[0].lower_x, primitives[0].lower_y, primitives[0].lower_z, 0.0f,
                       primitives[0].upper_x, primitives[0].upper_y, primitives[0].upper_z, 0.0f};
  for (const RTCBuildPrimitive& p : primitives)
    rootBounds = unite(rootBounds, RTCBounds{p.lower_x, p.lower_y, p.lower_z, 0.0f, p.upper_x, p.upper_y, p.upper_z, 0.0f});
  const std::unique_ptr<RTCDeviceTy, void (*)(RTCDevice)> device(rtcNewDevice(nullptr), rtcReleaseDevice);
  if (!device) fail(ErrorKind::Internal, "Embree: no device ({})", int(rtcGetDeviceError(nullptr)));
  const std::unique_ptr<RTCBVHTy, void (*)(RTCBVH)> bvh(rtcNewBVH(device.get()), rtcReleaseBVH);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  args.maxBranchingFactor = 2;
  args.maxDepth = 48;  // the GPU traversal's stack holds 64
  args.sahBlockSize = 1;
  args.minLeafSize = 1;
  args.maxLeafSize = unsigned(options.maxLeafSize);
  args.traversalCost = 1.0f;
  args.intersectionCost = 1.0f;
  args.bvh = bvh.get();
  args.primitives = primitives.data();
  args.primitiveCount = primitives.size();
  args.primitiveArrayCapacity = primitives.capacity();
  args.createNode = createNode;
  args.setNodeChildren = setNodeChildren;
  args.setNodeBounds = setNodeBounds;
  args.createLeaf = createLeaf;
  const auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
  if (!root) fail(ErrorKind::Internal, "Embree's BVH builder failed ({})", int(rtcGetDeviceError(device.get())));
  flatten(root, rootBounds, mesh, out);
  return out;
}

std::optional<Hit> traverse(const Bvh& bvh, const Ray& ray, bool anyHit) {
  if (bvh.nodes.empty() || !(ray.tnear <= ray.tfar)) return std::nullopt;
  const vec3 inverse = 1.0f / ray.direction;
  const Shear shear = shearOf(ray.direction);
  if (!std::isfinite(shear.sz)) return std::nullopt;  // a zero direction never hits
  float best = ray.tfar;
  std::optional<Hit> hit;
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& n = bvh.nodes[stack[--top]];
    float entry = 0.0f;
    if (!hitsBox(n, ray.origin, inverse, ray.tnear, best, entry)) continue;
    if (n.count == 0) {
      // The nearer child last, so it is popped first.
      float e0 = 0.0f, e1 = 0.0f;
      const bool h0 = hitsBox(bvh.nodes[n.first], ray.origin, inverse, ray.tnear, best, e0);
      const bool h1 = hitsBox(bvh.nodes[n.first + 1], ray.origin, inverse, ray.tnear, best, e1);
      if (h0 && h1) {
        stack[top++] = e0 <= e1 ? n.first + 1 : n.first;
        stack[top++] = e0 <= e1 ? n.first : n.first + 1;
      } else if (h0 || h1) {
        stack[top++] = h0 ? n.first : n.first + 1;
      }
      continue;
    }
    for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
      float t = 0.0f, u = 0.0f, v = 0.0f;
      if (!hitsTriangle(bvh.triangles[k], ray.origin, shear, ray.tnear, best, t, u, v)) continue;
      best = t;
      const BvhTriangle& tri = bvh.triangles[k];
      hit = Hit{.t = t, .mesh = 0, .triangle = bvh.ids[k], .u = u, .v = v,
                .geometricNormal = glm::normalize(glm::cross(vec3(tri.b) - vec3(tri.a), vec3(tri.c) - vec3(tri.a)))};
      if (anyHit) return hit;
    }
  }
  return hit;
}

}  // namespace glint::raytrace
