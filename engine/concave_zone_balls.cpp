// The centre balls of a mesh's elements (engine/concave_zone.hpp explains what they hold).
#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "engine/concave_zone_detail.hpp"
#include "engine/parallel.hpp"
#include "kernels/geom/tolerance.hpp"

namespace ncpath::concave_zone_detail {

namespace {

struct FacetGeometry {
  std::vector<Vec3> normal;  // unit, as wound; zero when degenerate
  std::vector<std::uint8_t> degenerate;
};

FacetGeometry facet_geometry(const TriangleMesh& mesh) {
  FacetGeometry g;
  const std::size_t nf = mesh.facets.size();
  g.normal.assign(nf, Vec3::Zero());
  g.degenerate.assign(nf, 0);
  par::for_each(nf, 4096, [&](std::size_t f) {
    const auto& t = mesh.facets[f];
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    if (len >= tol::kDegenerateArea2)
      g.normal[f] = n / len;
    else
      g.degenerate[f] = 1;
  });
  return g;
}

// 1 where the vertex's star is not a disk wound consistently: some edge at it is not used by
// exactly two facets in opposite directions (or a facet there is degenerate).
std::vector<std::uint8_t> irregular_vertices(const TriangleMesh& mesh, const FacetsAround& stars,
                                             const FacetGeometry& g) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::uint8_t> bad(nv, 0);
  par::for_ranges(nv, 4096, [&](std::size_t b, std::size_t e) {
    std::vector<std::uint32_t> out, in;
    for (std::size_t v = b; v < e; ++v) {
      out.clear();
      in.clear();
      for (std::uint32_t k = stars.start[v]; k < stars.start[v + 1]; ++k) {
        const std::uint32_t f = stars.ids[k];
        const auto& t = mesh.facets[f];
        const int c = t[0] == v ? 0 : t[1] == v ? 1 : 2;
        if (g.degenerate[f] || t[(c + 1) % 3] == v || t[(c + 2) % 3] == v) bad[v] = 1;
        out.push_back(t[(c + 1) % 3]);  // edge v -> next
        in.push_back(t[(c + 2) % 3]);   // edge prev -> v
      }
      std::sort(out.begin(), out.end());
      std::sort(in.begin(), in.end());
      if (out != in || std::adjacent_find(out.begin(), out.end()) != out.end()) bad[v] = 1;
    }
  });
  return bad;
}

// Which side a ball touches each facet from: +1 along its normal as wound, -1 against it, 0
// either. A closed component (every vertex regular) is touched from outside only: a ball on
// the drop-cutter surface is clear of the mesh and joined to z = +inf by free space, so it is
// outside every closed component; outside is where the normals point when the component's
// signed volume is positive. (An inner shell's side may come out wrong; no ball from above
// reaches it.)
std::vector<std::int8_t> facet_sides(const TriangleMesh& mesh,
                                     const std::vector<std::uint8_t>& irregular) {
  const std::size_t nv = mesh.vertices.size(), nf = mesh.facets.size();
  std::vector<std::uint32_t> parent(nv);
  for (std::uint32_t v = 0; v < nv; ++v) parent[v] = v;
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : mesh.facets)
    for (int k = 1; k < 3; ++k) {
      const std::uint32_t a = find(t[0]), b = find(t[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<double> volume(nv, 0);
  std::vector<std::uint8_t> open(nv, 0);
  const Aabb3 box = bounding_box(mesh);
  const Vec3 o = 0.5 * (box.lo + box.hi);
  for (const auto& t : mesh.facets) {
    const std::uint32_t c = find(t[0]);
    const Vec3 a = mesh.vertices[t[0]] - o, b = mesh.vertices[t[1]] - o,
               d = mesh.vertices[t[2]] - o;
    volume[c] += a.dot(b.cross(d));
    for (std::uint32_t v : t) open[c] |= irregular[v];
  }
  std::vector<std::int8_t> side(nf, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t c = find(mesh.facets[f][0]);
    if (!open[c] && volume[c] != 0) side[f] = volume[c] > 0 ? 1 : -1;
  }
  return side;
}

struct MeshFacts {
  const TriangleMesh& mesh;
  const FacetsAround& stars;
  const FacetGeometry& g;
  const std::vector<std::uint8_t>& irregular;
  const std::vector<std::int8_t>& side;
};

// Collects an element's balls.
struct BallSink {
  std::vector<CentreBall>* out;
  double R = 0;
  void add(const CentreBall& b) { out->push_back(b); }
  void unbounded(const Vec3& centre, double size, std::array<std::uint32_t, 3> verts) {
    CentreBall b;
    b.at = centre;
    b.reach = size + R;
    b.verts = verts;
    add(b);
  }
  // A bounded cone: dropped when a ball from above cannot touch with a normal in it.
  void cone(const Vec3& centre, double size, const Vec3& axis, double half,
            std::array<std::uint32_t, 3> verts) {
    if (std::asin(std::clamp(-axis.z(), -1.0, 1.0)) >= half + tol::kConcaveZoneAngle) return;
    add({centre + R * axis, size + 2 * R * std::sin(0.5 * half), axis, half, verts});
  }
};

// The signs (as wound) of the sides a ball touches facet f from: its own side, or both.
int side_count(const MeshFacts& m, std::uint32_t f) { return m.side[f] != 0 ? 1 : 2; }
double side_sign(const MeshFacts& m, std::uint32_t f, int k) {
  return m.side[f] != 0 ? double(m.side[f]) : (k == 0 ? 1.0 : -1.0);
}

void facet_balls(const MeshFacts& m, std::uint32_t f, BallSink& sink) {
  if (m.g.degenerate[f]) return;  // its edges and vertices are irregular: unbounded balls
  const auto& t = m.mesh.facets[f];
  const Vec3 c = (m.mesh.vertices[t[0]] + m.mesh.vertices[t[1]] + m.mesh.vertices[t[2]]) / 3;
  double r = 0;
  for (std::uint32_t v : t) r = std::max(r, (m.mesh.vertices[v] - c).norm());
  for (int k = 0; k < side_count(m, f); ++k)
    sink.cone(c, r, side_sign(m, f, k) * m.g.normal[f], tol::kConcaveZoneAngle, {t[0], t[1], t[2]});
}

// The facet holding the half-edge b -> a, at the regular vertex a.
std::uint32_t opposite_facet(const MeshFacts& m, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t k = m.stars.start[a]; k < m.stars.start[a + 1]; ++k) {
    const auto& t = m.mesh.facets[m.stars.ids[k]];
    for (int c = 0; c < 3; ++c)
      if (t[c] == b && t[(c + 1) % 3] == a) return m.stars.ids[k];
  }
  return kNone;
}

std::uint32_t third_vertex(const std::array<std::uint32_t, 3>& t, std::uint32_t a,
                           std::uint32_t b) {
  for (std::uint32_t v : t)
    if (v != a && v != b) return v;
  return t[0];
}

// Edge t[k] -> t[k + 1] of facet f, given once (by the facet where it runs up in index) when
// both ends are regular, else by every facet as an unbounded ball.
void edge_balls(const MeshFacts& m, std::uint32_t f, int k, BallSink& sink) {
  const auto& t = m.mesh.facets[f];
  const std::uint32_t a = t[k], b = t[(k + 1) % 3];
  const Vec3 &pa = m.mesh.vertices[a], &pb = m.mesh.vertices[b];
  const Vec3 mid = 0.5 * (pa + pb);
  const double half_len = 0.5 * (pb - pa).norm();
  if (m.irregular[a] || m.irregular[b]) return sink.unbounded(mid, half_len, {a, b, kNone});
  if (a > b) return;
  const std::uint32_t g = opposite_facet(m, a, b);
  if (g == kNone || m.g.degenerate[g]) return sink.unbounded(mid, half_len, {a, b, kNone});
  const Vec3 wg = m.mesh.vertices[third_vertex(m.mesh.facets[g], a, b)] - pa;
  for (int s = 0; s < side_count(m, f); ++s) {
    const double sign = side_sign(m, f, s);
    const Vec3 nf = sign * m.g.normal[f], ng = sign * m.g.normal[g];
    // Concave seen from this side: g rises above f's plane; a ball there cuts one of them.
    if (nf.dot(wg) > tol::kConcaveZoneAngle * wg.norm()) continue;
    const Vec3 sum = nf + ng;
    if (!(sum.norm() > tol::kConcaveZoneMinCos)) {
      sink.unbounded(mid, half_len, {a, b, kNone});
      continue;
    }
    const double half = 0.5 * std::atan2(nf.cross(ng).norm(), nf.dot(ng)) + tol::kConcaveZoneAngle;
    sink.cone(mid, half_len, sum.normalized(), half, {a, b, kNone});
  }
}

void vertex_balls(const MeshFacts& m, std::uint32_t v, BallSink& sink) {
  const std::uint32_t k0 = m.stars.start[v], k1 = m.stars.start[v + 1];
  if (k0 == k1) return;  // unreferenced
  const Vec3& p = m.mesh.vertices[v];
  if (m.irregular[v]) return sink.unbounded(p, 0, {v, kNone, kNone});
  const std::uint32_t f0 = m.stars.ids[k0];
  for (int s = 0; s < side_count(m, f0); ++s) {
    auto normal = [&](std::uint32_t f) {
      return m.side[f] != 0 ? double(m.side[f]) * m.g.normal[f]
                            : side_sign(m, f0, s) * m.g.normal[f];
    };
    Vec3 sum = Vec3::Zero();
    for (std::uint32_t k = k0; k < k1; ++k) sum += normal(m.stars.ids[k]);
    if (!(sum.norm() > 0)) {
      sink.unbounded(p, 0, {v, kNone, kNone});
      continue;
    }
    const Vec3 axis = sum.normalized();
    double min_cos = 1;
    for (std::uint32_t k = k0; k < k1; ++k)
      min_cos = std::min(min_cos, normal(m.stars.ids[k]).dot(axis));
    if (!(min_cos > tol::kConcaveZoneMinCos)) {
      sink.unbounded(p, 0, {v, kNone, kNone});
      continue;
    }
    const double half = std::acos(min_cos) + tol::kConcaveZoneAngle;
    // Every edge rising above each tangent plane in the cone: no ball touches the vertex.
    bool rises = true;
    for (std::uint32_t k = k0; k < k1 && rises; ++k)
      for (std::uint32_t u : m.mesh.facets[m.stars.ids[k]])
        if (u != v &&
            axis.dot(m.mesh.vertices[u] - p) <= std::sin(half) * (m.mesh.vertices[u] - p).norm())
          rises = false;
    if (!rises) sink.cone(p, 0, axis, half, {v, kNone, kNone});
  }
}

// Every element's balls, in facet order (its interior, then its edges), then vertex order.
std::vector<CentreBall> element_balls(const MeshFacts& m, double R) {
  const std::size_t nf = m.mesh.facets.size(), nv = m.mesh.vertices.size();
  auto emit = [&](std::size_t i, BallSink& sink) {
    if (i < nf) {
      facet_balls(m, std::uint32_t(i), sink);
      for (int k = 0; k < 3; ++k) edge_balls(m, std::uint32_t(i), k, sink);
    } else {
      vertex_balls(m, std::uint32_t(i - nf), sink);
    }
  };
  // Blocks of elements, each filling its own vector, joined in block order.
  constexpr std::size_t kBlock = 4096;
  const std::size_t blocks = (nf + nv + kBlock - 1) / kBlock;
  std::vector<std::vector<CentreBall>> parts(blocks);
  par::for_each(blocks, 1, [&](std::size_t b) {
    BallSink sink{&parts[b], R};
    parts[b].reserve(2 * kBlock);
    for (std::size_t i = b * kBlock; i < std::min(nf + nv, (b + 1) * kBlock); ++i) emit(i, sink);
  });
  std::vector<CentreBall> balls;
  std::size_t total = 0;
  for (const auto& part : parts) total += part.size();
  balls.reserve(total);
  for (auto& part : parts) {
    balls.insert(balls.end(), part.begin(), part.end());
    std::vector<CentreBall>().swap(part);
  }
  return balls;
}

}  // namespace

std::vector<CentreBall> centre_balls(const TriangleMesh& mesh, double R) {
  const FacetGeometry g = facet_geometry(mesh);
  const FacetsAround stars = facets_around(mesh);
  const std::vector<std::uint8_t> irregular = irregular_vertices(mesh, stars, g);
  const std::vector<std::int8_t> side = facet_sides(mesh, irregular);
  return element_balls(MeshFacts{mesh, stars, g, irregular, side}, R);
}

}  // namespace ncpath::concave_zone_detail
