#include "kernels/mesh/subdivide.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>
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

TriangleMesh subdivide_midpoint(const TriangleMesh& mesh) {
  const std::size_t nv = mesh.vertices.size();
  const std::size_t nf = mesh.facets.size();
  const std::size_t ns = 3 * nf;
  assert(subdivide_midpoint_fits(nv, nf));

  // Group the facet-edge slots by undirected edge: sort (edge key, slot). Within a group
  // the first entry is the edge's first appearance in facet order, its representative.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    const auto [lo, hi] = slot_edge(mesh, s);
    assert(hi < nv);
    keyed[s] = {(std::uint64_t{lo} << 32) | hi, static_cast<std::uint32_t>(s)};
  }
  std::sort(keyed.begin(), keyed.end());

  // mid[s] first holds the representative slot of s's edge, then the midpoint's vertex
  // index. Representatives come before the slots they stand for, so one pass in slot order
  // numbers the midpoints by first appearance, independent of the sort.
  std::vector<std::uint32_t> mid(ns);
  std::size_t num_edges = 0;
  std::uint32_t rep = 0;
  for (std::size_t i = 0; i < ns; ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) {
      rep = keyed[i].second;
      ++num_edges;
    }
    mid[keyed[i].second] = rep;
  }

  TriangleMesh out;
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
  return out;
}

}  // namespace ncpath
