#include "kernels/mesh/subdivide.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <limits>
#include <utility>
#include <vector>

namespace ncpath {

namespace {

constexpr std::size_t kMaxIndex = std::numeric_limits<std::uint32_t>::max();

// Facet-edge slot s = 3 * facet + k is the edge from corner k to corner (k + 1) % 3.
std::pair<std::uint32_t, std::uint32_t> slot_edge(const TriangleMesh& mesh, std::size_t s) {
  const auto& f = mesh.facets[s / 3];
  const std::uint32_t u = f[s % 3];
  const std::uint32_t v = f[(s % 3 + 1) % 3];
  return {std::min(u, v), std::max(u, v)};
}

}  // namespace

bool subdivide_midpoint_fits(std::size_t num_vertices, std::size_t num_facets) {
  return num_facets <= kMaxIndex / 4 && num_vertices <= kMaxIndex - 3 * num_facets;
}

namespace {

// The facet-edge slots sorted by undirected edge (edge key = lo << 32 | hi, then slot), and
// the midpoint subdivision's topology: mid[s] is the new vertex of slot s's edge.
struct Split {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  std::vector<std::uint32_t> mid;
  TriangleMesh mesh;  // vertices: the input's, then one midpoint per edge
};

Split split(const TriangleMesh& mesh) {
  const std::size_t nv = mesh.vertices.size();
  const std::size_t nf = mesh.facets.size();
  const std::size_t ns = 3 * nf;
  assert(subdivide_midpoint_fits(nv, nf));
  Split sp;

  // Group the facet-edge slots by undirected edge: sort (edge key, slot). Within a group
  // the first entry is the edge's first appearance in facet order, its representative.
  sp.keyed.resize(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    const auto [lo, hi] = slot_edge(mesh, s);
    assert(hi < nv);
    sp.keyed[s] = {(std::uint64_t{lo} << 32) | hi, static_cast<std::uint32_t>(s)};
  }
  std::sort(sp.keyed.begin(), sp.keyed.end());

  // mid[s] first holds the representative slot of s's edge, then the midpoint's vertex
  // index. Representatives come before the slots they stand for, so one pass in slot order
  // numbers the midpoints by first appearance, independent of the sort.
  std::vector<std::uint32_t>& mid = sp.mid;
  mid.resize(ns);
  std::size_t num_edges = 0;
  std::uint32_t rep = 0;
  for (std::size_t i = 0; i < ns; ++i) {
    if (i == 0 || sp.keyed[i].first != sp.keyed[i - 1].first) {
      rep = sp.keyed[i].second;
      ++num_edges;
    }
    mid[sp.keyed[i].second] = rep;
  }

  TriangleMesh& out = sp.mesh;
  out.vertices.reserve(nv + num_edges);
  out.vertices.assign(mesh.vertices.begin(), mesh.vertices.end());
  for (std::size_t s = 0; s < ns; ++s) {
    if (mid[s] == s) {
      const auto [lo, hi] = slot_edge(mesh, s);
      mid[s] = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(0.5 * (mesh.vertices[lo] + mesh.vertices[hi]));
    } else {
      mid[s] = mid[mid[s]];
    }
  }
  assert(out.vertices.size() == nv + num_edges);

  out.facets.resize(4 * nf);
  for (std::size_t i = 0; i < nf; ++i) {
    const auto& f = mesh.facets[i];
    const std::uint32_t ab = mid[3 * i], bc = mid[3 * i + 1], ca = mid[3 * i + 2];
    out.facets[4 * i + 0] = {f[0], ab, ca};
    out.facets[4 * i + 1] = {ab, f[1], bc};
    out.facets[4 * i + 2] = {ca, bc, f[2]};
    out.facets[4 * i + 3] = {ab, bc, ca};
  }
  return sp;
}

// Per input vertex, what Loop's vertex rule needs: its edges and their far ends, summed in
// edge-key order; the edges on one facet only (boundary) or on three or more (non-manifold)
// are creases.
struct Star {
  std::uint32_t edges = 0, creases = 0;
  Vec3 ring = Vec3::Zero(), crease_ring = Vec3::Zero();
};

// Loop's weight of each ring neighbour of an interior vertex of valence n.
double loop_beta(std::uint32_t n) {
  const double c = 0.375 + 0.25 * std::cos(2 * std::numbers::pi / n);
  return (0.625 - c * c) / n;
}

}  // namespace

TriangleMesh subdivide_midpoint(const TriangleMesh& mesh) { return split(mesh).mesh; }

TriangleMesh subdivide_loop(const TriangleMesh& mesh) {
  Split sp = split(mesh);
  const std::vector<Vec3>& p = mesh.vertices;
  std::vector<Star> star(p.size());
  for (std::size_t i = 0; i < sp.keyed.size();) {
    std::size_t j = i;
    while (j < sp.keyed.size() && sp.keyed[j].first == sp.keyed[i].first) ++j;
    const std::uint32_t s = sp.keyed[i].second;
    const auto [lo, hi] = slot_edge(mesh, s);
    const bool crease = j - i != 2;
    Vec3& e = sp.mesh.vertices[sp.mid[s]];
    if (crease) {
      e = 0.5 * (p[lo] + p[hi]);
    } else {  // the two facets' corners opposite the edge
      const auto& f0 = mesh.facets[s / 3];
      const auto& f1 = mesh.facets[sp.keyed[i + 1].second / 3];
      const std::uint32_t o0 = f0[(s % 3 + 2) % 3], o1 = f1[(sp.keyed[i + 1].second % 3 + 2) % 3];
      e = 0.375 * (p[lo] + p[hi]) + 0.125 * (p[o0] + p[o1]);
    }
    for (const auto& [v, w] : {std::pair{lo, hi}, std::pair{hi, lo}}) {
      ++star[v].edges;
      star[v].ring += p[w];
      if (crease) {
        ++star[v].creases;
        star[v].crease_ring += p[w];
      }
    }
    i = j;
  }
  for (std::size_t v = 0; v < p.size(); ++v) {
    const Star& st = star[v];
    if (st.creases == 0 && st.edges >= 3) {
      const double b = loop_beta(st.edges);
      sp.mesh.vertices[v] = (1 - st.edges * b) * p[v] + b * st.ring;
    } else if (st.creases == 2) {
      sp.mesh.vertices[v] = 0.75 * p[v] + 0.125 * st.crease_ring;
    }  // else: a corner, a non-manifold or an unused vertex stays where it is
  }
  return sp.mesh;
}

}  // namespace ncpath
