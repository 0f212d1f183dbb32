#pragma once
// Curve-based drive-plane scanning of a mesh with a ball-end mill (issue 5).
//
// The mesh is offset locally by the ball radius (kernels/mesh/offset_elements.hpp, built
// once per family in parallel); every drive plane slices the offset elements exactly
// (kernels/scan/plane_slice.hpp) and its CL curve is the upper envelope of the pieces
// (kernels/scan/envelope.hpp), raised to the floor where the tool touches nothing higher:
// typed segments (lines, circular and elliptic arcs, vertical wall segments), junctions with
// their kind and bi-contact vectors, and a polyline within `tolerance` that never lies below
// the exact curve (each chord lifted by its largest gap to the arc).
//
// Families: kX lines run along x (planes y = const), kY lines along y (planes x = const);
// kBoth runs the x family, then the y family. Planes sit at v0 + i * interval across the
// rectangle (the part's xy box grown by margin, or rect), like the raster operation. Lines
// zig-zag; consecutive lines are joined along the rectangle's side by a link at depth that
// is the exact CL curve of the side plane (the other family's scan of that plane), so links
// are as gouge-free as the cut.
//
// Element lookup per plane: elements sorted by the low end of their extent across the
// planes; a plane takes the run whose low end is within the longest short extent below it
// (binary search), filtered by the high end; the few elements longer than that (big facets)
// are checked for every plane.
//
// Parallel over planes (TBB), chunks of planes handed to the sink in order: identical output
// for any thread count.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/cl_chunk.hpp"
#include "engine/offset_elements_build.hpp"
#include "engine/run_control.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath {

enum class ScanFamilies : std::uint8_t { kX = 0, kY = 1, kBoth = 2 };

struct ScanParams {
  ScanFamilies families = ScanFamilies::kX;
  double interval = 0.5;                      // mm between drive planes
  double tolerance = 0.001;                   // mm: chordal tolerance of the polylines
  double margin = 0.0;                        // mm added on every side of the part's xy box
  std::optional<std::array<double, 4>> rect;  // x_min, y_min, x_max, y_max (mm); overrides
  std::optional<double> floor_z;              // mm; default: the part's lowest z
  std::uint32_t chunk_planes = 32;            // planes per streamed chunk
};

// Empty when usable; else a message naming the bad key.
std::string validate(const ScanParams& params);

// Segment kinds stored per exact segment: the PieceKind values (plane_slice.hpp) and:
inline constexpr std::uint8_t kScanSegmentVertical = 6;

// Element of the mesh a segment or junction belongs to (engine/offset_elements_build.hpp).
using ScanElementRef = ElementRef;

// Exact data of one chunk of cut paths. Segments and junctions are in cutting order;
// `path` is the cut path's index within the job (0, 1, ... over all cut paths).
struct ScanSegmentRecord {
  std::int64_t path = 0;
  std::uint8_t kind = 0;
  ScanElementRef element;
  std::array<double, 3> start{}, end{};  // tool tip, mm, in cutting order
  // Geometry in the plane's (u, tip z) coordinates, u along the line (x for x lines):
  //   lines (facet, cylinder line, floor): slope, intercept;
  //   sphere arc: centre u, centre z, radius;
  //   cylinder ellipse/circle: centre u, centre z, semi-major, semi-minor, angle of the
  //   major axis from +u (rad);  vertical: u.
  std::array<double, 5> geometry{};
};

struct ScanJunctionRecord {
  std::int64_t path = 0;
  std::uint8_t kind = 0;  // JunctionKind
  std::array<double, 3> position{};  // tool tip, mm
  std::array<double, 3> b1{}, b2{};  // unit, world frame, in cutting order
  ScanElementRef element1, element2;
  double angle = 0;  // between b1 and b2, rad
};

struct ScanChunk {
  ClChunk cl;
  std::vector<ScanSegmentRecord> segments;
  std::vector<ScanJunctionRecord> junctions;
};

struct ScanStats {
  std::uint64_t planes = 0, planes_x = 0, planes_y = 0;
  std::uint64_t pieces = 0;              // slice pieces over all planes (incl. floor)
  std::uint64_t segments = 0;            // exact CL segments of the cut paths
  std::uint64_t junctions = 0, sharp_concave = 0, convex = 0, tangent = 0;
  std::uint64_t cut_points = 0, link_points = 0;
  std::uint64_t decisions = 0, crossings = 0;  // envelope work
  std::uint64_t hidden = 0;       // curved pieces under the facet lines (dropped early)
  std::uint64_t linear_pieces = 0;  // facet lines, cylinder lines, the floor
  std::uint64_t facets = 0, edges = 0, vertices = 0;  // offset elements (one family)
  std::uint64_t facets_degenerate = 0;
  double floor_z = 0;
  std::array<double, 4> rect{};
  double elements_s = 0;  // offset elements + plane index, both families
  double compute_s = 0;   // planes (wall time of the chunk computations)
  double sink_s = 0;
};

// Offset elements of both plane families (family 1: x and y exchanged) with their plane
// indices: built once per mesh and ball radius, then shared read-only.
struct ScanElements {
  std::array<OffsetElements, 2> el;
  std::array<PlaneIndex, 2> index;
  std::array<std::vector<double>, 2> only_at;  // per family: the planes its index answers (all: empty)
  Aabb3 box;                    // the mesh's
  std::size_t mesh_facets = 0;  // facets in the mesh (including degenerate ones)
  double build_s = 0;
};
// Throws std::invalid_argument when the mesh has no usable facet. only_at[f] non-empty: family
// f's index answers queries at those planes only (build_plane_index), e.g. the side planes
// of a scan of the other family alone.
ScanElements build_scan_elements(const TriangleMesh& mesh, double radius,
                                 const std::array<std::vector<double>, 2>& only_at = {});

// The cutter must be a ball. Throws Cancelled, std::invalid_argument for bad params.
ScanStats run_scan(const TriangleMesh& mesh, const Cutter& cutter, const ScanParams& params,
                   const std::function<void(const ScanChunk&)>& sink, RunControl& control);
// The same over prebuilt elements (their radius must be the cutter's).
ScanStats run_scan(const ScanElements& elements, const Cutter& cutter, const ScanParams& params,
                   const std::function<void(const ScanChunk&)>& sink, RunControl& control);

// Junctions of one plane's exact CL curve (family 0: plane y = v, u along x; family 1: plane
// x = v, u along y) over u in [u0, u1] above floor_z, in the world frame: position (tool
// tip), unit b1, b2 in the direction of increasing u, kind (JunctionKind).
struct PlaneJunction {
  Vec3 position = Vec3::Zero(), b1 = Vec3::Zero(), b2 = Vec3::Zero();
  std::uint8_t kind = 0;
  bool on_floor = false;  // one side is the floor, not the part
  ElementRef element1, element2;  // the elements b1 and b2 touch
};
std::vector<PlaneJunction> plane_junctions(const ScanElements& elements, int family, double v,
                                           double u0, double u1, double floor_z);

}  // namespace ncpath
