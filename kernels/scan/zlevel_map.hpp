#pragma once
// Internals of the z-level contour kernel (kernels/scan/zlevel.hpp, step 8): the planar map of
// the pieces between splits, its faces, and which parts of it the faces decide. Used by
// zlevel_loops.cpp only.
//
// Why the contours it gives are closed. The pieces are the edges of a planar map (ends within
// tol::kZLevelLink are one vertex; the pieces around a vertex in the counter-clockwise order of
// where they cross a small circle about it). Every face is decided once, inside or outside U,
// and a piece is a contour piece when its two faces differ, run with the inside on its left.
// Around any vertex the faces' status changes at each contour piece, so the contour pieces
// alternate between arriving and leaving; the contour arriving by a piece leaves by the next
// contour piece counter-clockwise, a pairing that is one-to-one at every vertex. The contour
// pieces therefore form closed loops, whatever the faces' status: a wrong decision (a face
// thinner than the rounding, decided by its neighbours' votes) moves a contour by the width of
// that face, it does not open it. The argument needs the map to be planar and the contour to
// run on edges of it: a connected part of the map that is not (vertices - edges + faces != 2:
// two pieces cross where no split was recorded) or in which a piece the classification keeps
// has one face on both sides (the contour runs past a gap in the map) is left to the
// classification's own linking (zlevel_loops.cpp link_kept).
#include <array>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "kernels/scan/zlevel_detail.hpp"

namespace ncpath::zlevel_detail {

struct Dsu {
  std::vector<std::uint32_t> p;
  explicit Dsu(std::size_t n) : p(n) { std::iota(p.begin(), p.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) p[std::max(a, b)] = std::min(a, b);
  }
};

// The planar map of the pieces. Piece k has two ends, 2k at its start and 2k + 1 at its end,
// and two half-edges: 2k runs along it (its region on the left), 2k + 1 against it. Pieces
// the classification puts strictly inside another region (kInterior) are left out: they are
// not on the contour and both their sides lie in U.
class PieceMap {
 public:
  // rotations: false for a map only asked about its vertices (degrees).
  PieceMap(const std::vector<Curve>& curves, const std::vector<Piece>& pieces,
           const std::vector<std::uint8_t>& keep, bool rotations = true);

  std::size_t half_edges() const { return 2 * pieces_.size(); }
  // A piece left out: interior, a sliver (both ends one vertex) or a duplicate.
  bool dead(std::uint32_t piece) const { return dead_[piece] != 0; }
  std::uint32_t vertex_count() const { return vertices_; }
  std::uint32_t vertex_of(std::uint32_t end) const { return vertex_[end]; }
  std::uint32_t start_vertex(std::uint32_t piece) const { return vertex_[2 * piece]; }
  std::uint32_t end_vertex(std::uint32_t piece) const { return vertex_[2 * piece + 1]; }
  // Live pieces ending at each vertex.
  std::vector<std::uint32_t> degrees() const;
  // All ends at vertex v (left-out pieces' too).
  std::span<const std::uint32_t> ends_at(std::uint32_t v) const {
    return {all_.data() + all_start_[v], all_start_[v + 1] - all_start_[v]};
  }
  // The live end `step` places counter-clockwise from live end e around its vertex (-1:
  // clockwise).
  std::uint32_t turn_from(std::uint32_t e, int step) const;
  // The next half-edge of the face on h's left: at h's head, the end clockwise next to the
  // one h arrives by (end 2k + 1 for h = 2k, 2k for h = 2k + 1), leaving along it (the face
  // turns as far left as it can; leaving by end e is half-edge e).
  std::uint32_t next(std::uint32_t h) const { return turn_from(h ^ 1, -1); }

 private:
  void cluster_ends();
  void drop_duplicates(const std::vector<std::uint8_t>& keep);
  bool beside(std::uint32_t q, std::uint32_t r) const;
  Vec2 midpoint(std::uint32_t k) const;
  Vec2 end_point(std::uint32_t e) const { return (e & 1) ? pieces_[e / 2].b : pieces_[e / 2].a; }
  void sort_rotations();
  void place_ends(std::span<const std::uint32_t> ends, std::vector<double>& angle,
                  std::vector<double>& turn) const;

  const std::vector<Curve>& curves_;
  const std::vector<Piece>& pieces_;
  std::vector<std::uint32_t> vertex_;  // per end
  std::vector<std::uint8_t> dead_;     // per piece
  std::uint32_t vertices_ = 0;
  std::vector<std::uint32_t> rot_start_, rot_, pos_;  // live ends per vertex, ccw; pos in it
  std::vector<std::uint32_t> all_start_, all_;        // all ends per vertex
};

// The faces of the map (cycles of PieceMap::next) and whether each lies in U, by the vote of
// its pieces weighted by their lengths: a piece the face lies on the region side of (a
// half-edge along it) votes inside; one the face lies beside (a half-edge against it) votes
// outside when the classification keeps it (its other side is outside U), else inside.
// Pieces with the face on both sides (dangling in it) do not vote. face[h] is h's face;
// inside[f] its status.
struct Faces {
  std::vector<std::uint32_t> face;
  std::vector<std::uint8_t> inside;
};
Faces decide_faces(const PieceMap& map, const std::vector<Piece>& pieces,
                   const std::vector<std::uint8_t>& keep);

// Per piece: 1 when the faces decide it (see the top of this header), else the classification.
std::vector<std::uint8_t> sound_pieces(const PieceMap& map, const Faces& faces,
                                       const std::vector<Piece>& pieces,
                                       const std::vector<std::uint8_t>& keep);

// A curve that ends where no other piece does (a joint whose target curve was not found, a
// curve running on nearly along another one) ends, in exact arithmetic, on another region's
// boundary: the nearest live piece passing within tol::kZLevelLink of the end is split there,
// at the end's own coordinates, so that the map has the vertex. The halves keep the piece's
// classification.
void attach_loose_ends(const std::vector<Curve>& curves, std::vector<Piece>& pieces,
                       std::vector<std::uint8_t>& keep);

}  // namespace ncpath::zlevel_detail
