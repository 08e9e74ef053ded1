#include "trace/surface_tracer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "core/check.h"

namespace oceanref {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A piece [s0, s0 + width] × [t0, t0 + height] of a cell's bilinear parameter square, with x0 and
// p at its corners in the order (s0, t0), (s1, t0), (s0, t1), (s1, t1).
struct Patch {
  double s0 = 0.0, t0 = 0.0, width = 1.0, height = 1.0;
  std::array<glm::dvec2, 4> x0{};
  std::array<glm::dvec3, 4> p{};
};

// The cell's corners in x0, in the Patch order.
struct CellCorners {
  std::array<glm::dvec2, 4> base{};
};

CellCorners cell_corners(const TracedSurface& s, std::int64_t cell) {
  const std::int64_t i = cell % (s.columns - 1), j = cell / (s.columns - 1);
  const auto at = [&](std::int64_t a, std::int64_t b) {
    return (*s.base)[static_cast<std::size_t>(b * s.columns + a)];
  };
  return {{at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)}};
}

// x0 at (s, t) of the cell's bilinear map.
glm::dvec2 cell_point(const CellCorners& c, double s, double t) {
  return (1.0 - t) * ((1.0 - s) * c.base[0] + s * c.base[1]) +
         t * ((1.0 - s) * c.base[2] + s * c.base[3]);
}

// The box of p = (x0, 0, z0) + q over a quad of x0 from p at its corners: every point of the
// quad is within ρ of a corner, ρ ≤ (its longest side or diagonal)/√3 (the largest distance from
// a triangle's points to its nearest vertex), so q_j is within L_j·ρ of the corners' range of
// q_j, and |q_j| ≤ offset_j over the whole plane; x0 is within the quad's box.
BoundsTree::Node patch_box(const TracedSurface& s, const std::array<glm::dvec2, 4>& x0,
                           const std::array<glm::dvec3, 4>& p) {
  glm::dvec3 q_lower(kInfinity), q_upper(-kInfinity), x0_lower(kInfinity), x0_upper(-kInfinity);
  double longest = 0.0;
  for (std::size_t a = 0; a < 4; ++a) {
    const glm::dvec3 base(x0[a].x, 0.0, x0[a].y);
    q_lower = glm::min(q_lower, p[a] - base);
    q_upper = glm::max(q_upper, p[a] - base);
    x0_lower = glm::min(x0_lower, base);
    x0_upper = glm::max(x0_upper, base);
    for (std::size_t b = a + 1; b < 4; ++b) longest = std::max(longest, glm::length(x0[a] - x0[b]));
  }
  const double rho = longest * (0.5773502691896258 * (1.0 + 1e-12));  // 1/√3, rounded up
  const glm::dvec3 widening = s.lipschitz * rho;
  BoundsTree::Node node;
  node.lower = x0_lower + glm::max(q_lower - widening, -s.offset);
  node.upper = x0_upper + glm::min(q_upper + widening, s.offset);
  pad_box(node);
  return node;
}

int build(const TracedSurface& s, BoundsTree& tree, int i0, int i1, int j0, int j1) {
  const int index = static_cast<int>(tree.nodes.size());
  tree.nodes.emplace_back();
  BoundsTree::Node node;
  if (i1 - i0 == 1 && j1 - j0 == 1) {
    const std::int64_t cell = static_cast<std::int64_t>(j0) * (s.columns - 1) + i0;
    const CellCorners c = cell_corners(s, cell);
    std::array<glm::dvec3, 4> p{};
    const std::array<std::size_t, 4> vertex{static_cast<std::size_t>(j0 * s.columns + i0),
                                            static_cast<std::size_t>(j0 * s.columns + i1),
                                            static_cast<std::size_t>(j1 * s.columns + i0),
                                            static_cast<std::size_t>(j1 * s.columns + i1)};
    for (std::size_t a = 0; a < 4; ++a) p[a] = (*s.corners)[vertex[a]];
    node = patch_box(s, c.base, p);
    node.first = static_cast<int>(cell);
    node.count = 1;
  } else {
    if (i1 - i0 >= j1 - j0) {
      const int middle = (i0 + i1) / 2;
      node.children = {build(s, tree, i0, middle, j0, j1), build(s, tree, middle, i1, j0, j1)};
    } else {
      const int middle = (j0 + j1) / 2;
      node.children = {build(s, tree, i0, i1, j0, middle), build(s, tree, i0, i1, middle, j1)};
    }
    const BoundsTree::Node& a = tree.nodes[static_cast<std::size_t>(node.children[0])];
    const BoundsTree::Node& b = tree.nodes[static_cast<std::size_t>(node.children[1])];
    node.lower = glm::min(a.lower, b.lower);
    node.upper = glm::max(a.upper, b.upper);
  }
  tree.nodes[static_cast<std::size_t>(index)] = node;
  return index;
}

// The patch's two halves, split across its longer side in x0 (so a long thin patch, as the
// projected grid's cells near the horizon are, is split along its length), p evaluated at the
// two new corners.
std::array<Patch, 2> halves(const TracedSurface& s, const CellCorners& c, const Patch& q) {
  const double along_s = std::max(glm::length(q.x0[1] - q.x0[0]), glm::length(q.x0[3] - q.x0[2]));
  const double along_t = std::max(glm::length(q.x0[2] - q.x0[0]), glm::length(q.x0[3] - q.x0[1]));
  std::array<Patch, 2> out{q, q};
  // The corners (first, second) of each edge that is cut: the new point between them.
  const auto cut = [&](std::size_t first, std::size_t second, double s_mid, double t_mid) {
    const glm::dvec2 x0 = cell_point(c, s_mid, t_mid);
    const glm::dvec3 p = s.point(x0);
    out[0].x0[second] = out[1].x0[first] = x0;
    out[0].p[second] = out[1].p[first] = p;
  };
  if (along_s >= along_t) {
    const double w = 0.5 * q.width;
    cut(0, 1, q.s0 + w, q.t0);
    cut(2, 3, q.s0 + w, q.t0 + q.height);
    out[0].width = out[1].width = w;
    out[1].s0 = q.s0 + w;
  } else {
    const double h = 0.5 * q.height;
    cut(0, 2, q.s0, q.t0 + h);
    cut(1, 3, q.s0 + q.width, q.t0 + h);
    out[0].height = out[1].height = h;
    out[1].t0 = q.t0 + h;
  }
  return out;
}

// The determinant of the columns a, b, c.
double determinant(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::dot(a, glm::cross(b, c));
}

// A hit candidate on a cell: parameters (s, t) and the ray's λ.
struct CellHit {
  double s = 0.0, t = 0.0, lambda = 0.0;
  bool refined = false;
};

// Newton's method on F(s, t, λ) = p(x0(s, t)) − origin − λ·direction from the triangle's hit;
// the root if it converges (steps ≤ 1e-12 in s, t and 1e-12·max(1, λ) in λ) inside the cell and
// near the patch (within one patch size), else the start.
CellHit refine(const TracedSurface& s, const CellCorners& c, const Patch& q, const CellHit& start,
               const glm::dvec3& origin, const glm::dvec3& direction) {
  constexpr int kIterations = 16;
  constexpr double kStep = 1e-12;
  CellHit x = start;
  for (int n = 0; n < kIterations; ++n) {
    const SurfacePoint p = s.point_derivatives(cell_point(c, x.s, x.t));
    const glm::dvec2 x0_s = (1.0 - x.t) * (c.base[1] - c.base[0]) + x.t * (c.base[3] - c.base[2]);
    const glm::dvec2 x0_t = (1.0 - x.s) * (c.base[2] - c.base[0]) + x.s * (c.base[3] - c.base[1]);
    const glm::dvec3 j_s = x0_s.x * p.d_dx0 + x0_s.y * p.d_dz0;
    const glm::dvec3 j_t = x0_t.x * p.d_dx0 + x0_t.y * p.d_dz0;
    const glm::dvec3 j_lambda = -direction;
    const glm::dvec3 minus_f = origin + x.lambda * direction - p.position;
    const double det = determinant(j_s, j_t, j_lambda);
    if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) return start;
    const double ds = determinant(minus_f, j_t, j_lambda) / det;
    const double dt = determinant(j_s, minus_f, j_lambda) / det;
    const double dl = determinant(j_s, j_t, minus_f) / det;
    x.s += ds;
    x.t += dt;
    x.lambda += dl;
    if (!std::isfinite(x.s + x.t + x.lambda)) return start;
    if (std::fabs(ds) <= kStep && std::fabs(dt) <= kStep &&
        std::fabs(dl) <= kStep * std::max(1.0, std::fabs(x.lambda))) {
      constexpr double kSlack = 1e-9;
      const bool in_cell =
          x.s >= -kSlack && x.s <= 1.0 + kSlack && x.t >= -kSlack && x.t <= 1.0 + kSlack;
      const bool near_patch = std::fabs(x.s - start.s) <= std::max(q.width, q.height) &&
                              std::fabs(x.t - start.t) <= std::max(q.width, q.height);
      if (!in_cell || !near_patch || !(x.lambda > 0.0)) return start;
      x.s = std::clamp(x.s, 0.0, 1.0);
      x.t = std::clamp(x.t, 0.0, 1.0);
      x.refined = true;
      return x;
    }
  }
  return start;
}

// The ray against a small patch's two triangles (p00, p10, p01) and (p10, p11, p01): the nearer
// hit's parameters, refined by Newton's method; λ < 0 if both miss.
CellHit hit_small_patch(const TracedSurface& s, const CellCorners& c, const Patch& q,
                        const glm::dvec3& origin, const glm::dvec3& direction) {
  CellHit best{0.0, 0.0, -1.0, false};
  double t = 0.0, u = 0.0, v = 0.0;
  if (intersect_triangle(origin, direction, q.p[0], q.p[1], q.p[2], t, u, v)) {
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0 - u);
    best = {q.s0 + u * q.width, q.t0 + v * q.height, t, false};
  }
  if (intersect_triangle(origin, direction, q.p[1], q.p[3], q.p[2], t, u, v) &&
      (best.lambda < 0.0 || t < best.lambda)) {
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0 - u);
    best = {q.s0 + (1.0 - v) * q.width, q.t0 + (u + v) * q.height, t, false};
  }
  if (best.lambda < 0.0) return best;
  return refine(s, c, q, best, origin, direction);
}

// The refinement of one cell (surface_tracer.h, 2.): updates `best` with the cell's nearest hit in
// front of the near plane, if nearer.
void trace_cell(const TracedSurface& s, const SurfaceTraceSettings& settings, std::int64_t cell,
                const glm::dvec3& origin, const glm::dvec3& direction, SurfaceHit& best) {
  constexpr int kMaximumDepth = 96;  // binary splits
  const CellCorners c = cell_corners(s, cell);
  const glm::dvec3 inverse = 1.0 / direction;
  Patch root;
  root.x0 = c.base;
  const std::int64_t i = cell % (s.columns - 1), j = cell / (s.columns - 1);
  const auto corner = [&](std::int64_t a, std::int64_t b) {
    return (*s.corners)[static_cast<std::size_t>((j + b) * s.columns + (i + a))];
  };
  root.p = {corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)};
  // A patch to test: where the ray enters its box, the box's largest extent.
  struct Entry {
    Patch patch;
    double near = 0.0, size = 0.0;
    int depth = 0;
  };
  const auto entry = [&](const Patch& q, int depth) {
    const BoundsTree::Node box = patch_box(s, q.x0, q.p);
    const auto [near, far] = box_interval(origin, inverse, box.lower, box.upper);
    const glm::dvec3 extent = box.upper - box.lower;
    return std::pair{Entry{q, near, std::max({extent.x, extent.y, extent.z}), depth}, near <= far};
  };
  const auto [first, enters] = entry(root, 0);
  if (!enters) return;
  std::vector<Entry> stack{first};
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    if (best.hit && e.near > best.t) continue;
    if (e.size <= std::max(settings.angular_tolerance * e.near, settings.absolute_tolerance) ||
        e.depth >= kMaximumDepth) {
      const CellHit h = hit_small_patch(s, c, e.patch, origin, direction);
      if (!(h.lambda > 0.0) || (best.hit && !(h.lambda < best.t))) continue;
      if (!(glm::dot(h.lambda * direction, settings.forward) > settings.near)) continue;
      best = {true, h.lambda, cell_point(c, h.s, h.t), cell, h.refined};
      continue;
    }
    const std::array<Patch, 2> children = halves(s, c, e.patch);
    const auto [a, a_enters] = entry(children[0], e.depth + 1);
    const auto [b, b_enters] = entry(children[1], e.depth + 1);
    // Pushed farther first, so the nearer is taken next (of equals, the first half).
    if (a_enters && b_enters && a.near <= b.near) {
      stack.push_back(b);
      stack.push_back(a);
    } else {
      if (a_enters) stack.push_back(a);
      if (b_enters) stack.push_back(b);
    }
  }
}
}  // namespace

BoundsTree build_surface_tree(const TracedSurface& surface) {
  BoundsTree tree;
  if (surface.columns < 2 || surface.rows < 2) return tree;
  OCEANREF_EXPECTS(surface.base != nullptr && surface.corners != nullptr &&
                       surface.base->size() == surface.corners->size() &&
                       surface.base->size() == static_cast<std::size_t>(surface.columns) *
                                                   static_cast<std::size_t>(surface.rows),
                   "a surface with x0 and p at each of its columns x rows vertices");
  tree.nodes.reserve(2 * static_cast<std::size_t>(surface.columns - 1) *
                     static_cast<std::size_t>(surface.rows - 1));
  build(surface, tree, 0, surface.columns - 1, 0, surface.rows - 1);
  return tree;
}

SurfaceHit trace_surface(const TracedSurface& surface, const BoundsTree& tree,
                         const SurfaceTraceSettings& settings, const glm::dvec3& origin,
                         const glm::dvec3& direction) {
  SurfaceHit best;
  const auto limit = [&] { return best.hit ? best.t : kInfinity; };
  visit_leaves_nearest_first(tree, origin, direction, limit, [&](const BoundsTree::Node& n) {
    trace_cell(surface, settings, n.first, origin, direction, best);
  });
  return best;
}

}  // namespace oceanref
