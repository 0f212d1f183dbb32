#pragma once
// The checks of the exact curve kernels on any mesh (issue 34), in process: a scan, z-level or
// pencil run, its paths checked by the verifier (engine/verify_mesh.hpp, the oracle of
// record: the deepest cut into the mesh), and the kernel's own invariant against the point
// drop-cutter (engine/drop_index.hpp, exact, a second method):
//   scan    every exact segment equals the drop-cutter along its plane (samples inside it);
//   z-level the area each level's contours enclose equals the drop-cutter's: the share of grid
//           points where the tool at the level would touch the part (optional, grid step h),
//           within the grid's resolution (the contours' length times h);
//   pencil  no invariant of its own here (its tests compare representations); its paths pass
//           the chord guard first, as in the pencil job;
//   raster  the drop-cutter itself (engine/raster.hpp), its chords through the chord guard as
//           in the raster job, then the verifier.
// Used by tests/engine/robustness_test.cpp (corpus and generated parts) and the soak command
// bench/corpus_soak.cpp.
#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/chord_guard.hpp"
#include "engine/drop_index.hpp"
#include "engine/pencil.hpp"
#include "engine/raster.hpp"
#include "engine/scan.hpp"
#include "engine/verify_mesh.hpp"
#include "engine/zlevel.hpp"
#include "kernels/cutters/cutter.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::test {

struct KernelRun {
  std::string error;                // what the run threw, if anything
  double max_gouge = 0;             // mm, the verifier's deepest cut (0: none above 1e-6)
  std::uint64_t open_chains = 0;    // z-level (and the pencil's z-level) chains left open
  double scan_deviation = 0;        // mm, largest |segment - drop-cutter| across the segment
  std::uint64_t scan_samples = 0;
  std::map<double, double> level_area;  // z-level: tip z -> signed area of its contours, mm^2
  double area_deviation = 0;        // mm^2, largest |contours - drop-cutter grid| over levels
  double area_resolution = 0;       // mm^2, that level's allowance (contour length * h)
  std::uint64_t paths = 0;          // pencil
  double length = 0;                // mm, pencil traced length
  bool ok() const { return error.empty() && max_gouge == 0 && open_chains == 0; }
};

// mm: scan segments narrower than this along their line are not compared with the
// drop-cutter (see run_scan_checked).
inline constexpr double kScanSteepWidth = 1e-6;

namespace robustness_detail {

// Tip z of an exact scan segment at u along its line (docs/hdf5-schema.md, scan/).
inline double segment_z(const ScanSegmentRecord& s, double u) {
  const auto& g = s.geometry;
  switch (s.kind) {
    case 0:
    case 3:
    case 5:
      return g[0] * u + g[1];
    case 1: {
      const double du = u - g[0];
      return g[1] + std::sqrt(std::max(0.0, g[2] * g[2] - du * du));
    }
    default: {  // upper root of the ellipse's equation in dz
      const double du = u - g[0], M = g[2], m = g[3], c = std::cos(g[4]), s2 = std::sin(g[4]);
      const double A = s2 * s2 / (M * M) + c * c / (m * m);
      const double B = 2 * du * c * s2 * (1 / (M * M) - 1 / (m * m));
      const double C = du * du * (c * c / (M * M) + s2 * s2 / (m * m)) - 1;
      return g[1] + (-B + std::sqrt(std::max(0.0, B * B - 4 * A * C))) / (2 * A);
    }
  }
}

inline void verify(const MeshVerifier& verifier, const Cutter& cutter, const ClChunk& cl,
                   KernelRun& out) {
  const MeshVerifyReport r = verify_moves(verifier, cutter, cl, MeshVerifyParams{});
  out.max_gouge = std::max(out.max_gouge, r.max_gouge);
  if (!r.error.empty()) out.error = r.error;
}

inline void verify(const TriangleMesh& mesh, const Cutter& cutter, const ClChunk& cl,
                   KernelRun& out) {
  verify(MeshVerifier(mesh), cutter, cl, out);
}

// As the raster and pencil jobs do (batch/jobs/): chords that would cut in lifted by the chord
// guard, then the verifier; one index for both.
inline void verify_guarded(const TriangleMesh& mesh, const Cutter& cutter, const ClChunk& cl,
                           KernelRun& out) {
  const auto verifier = std::make_shared<const MeshVerifier>(mesh);
  ChordGuard guard(verifier, cutter);
  verify(*verifier, cutter, guard.apply(cl), out);
}

inline double polygon_area(const std::vector<double>& xyz, std::size_t first, std::size_t n) {
  double a = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double* p = &xyz[3 * (first + i)];
    const double* q = &xyz[3 * (first + i + 1)];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return 0.5 * a;
}

}  // namespace robustness_detail

// Scan, both families; every exact segment sampled at 5 inner points against the drop-cutter.
inline KernelRun run_scan_checked(const TriangleMesh& mesh, double radius, double interval) {
  using namespace robustness_detail;
  KernelRun out;
  try {
    const Cutter ball = ball_cutter(2 * radius);
    ScanParams p;
    p.families = ScanFamilies::kBoth;
    p.interval = interval;
    ClChunk cl;
    std::vector<ScanSegmentRecord> segs;
    RunControl control;
    const ScanStats st = run_scan(
        mesh, ball, p,
        [&](const ScanChunk& c) {
          cl.append(c.cl);
          segs.insert(segs.end(), c.segments.begin(), c.segments.end());
        },
        control);
    verify(mesh, ball, cl, out);
    const DropIndex index(mesh, ball);
    for (const ScanSegmentRecord& s : segs) {
      const bool along_x = s.start[1] == s.end[1];
      // Vertical segments, and the near-vertical ones of a wall tilted by rounding (their z is
      // not a function of u at double precision), are checked by the verifier only.
      const double du = along_x ? s.end[0] - s.start[0] : s.end[1] - s.start[1];
      if (s.kind == kScanSegmentVertical || std::abs(du) < kScanSteepWidth) continue;
      // Deviations across the segment: on a steep one, a rounding of u moves z by its slope.
      const double across = 1 / std::hypot(1.0, (s.end[2] - s.start[2]) / du);
      for (double f : {0.02, 0.25, 0.5, 0.75, 0.98}) {
        const double x = s.start[0] + f * (s.end[0] - s.start[0]);
        const double y = s.start[1] + f * (s.end[1] - s.start[1]);
        const double drop = std::max(st.floor_z, index.query(x, y).tip_z);
        const double dev = std::abs(segment_z(s, along_x ? x : y) - drop) * across;
        out.scan_deviation = std::max(out.scan_deviation, dev);
        ++out.scan_samples;
      }
    }
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

// Z-levels by step_down from the top; grid > 0: the drop-cutter area oracle on that grid.
inline KernelRun run_zlevel_checked(const TriangleMesh& mesh, double radius, double step_down,
                                    double grid = 0) {
  using namespace robustness_detail;
  KernelRun out;
  try {
    const Cutter ball = ball_cutter(2 * radius);
    ZLevelOpParams p;
    p.step_down = step_down;
    ClChunk cl;
    std::map<double, double> length;
    RunControl control;
    const ZLevelOpStats st = run_zlevel(
        mesh, ball, p,
        [&](const ZLevelChunk& c) {
          std::size_t first = cl.path_sizes.size(), at = cl.xyz.size() / 3;
          cl.append(c.cl);
          std::size_t contour = 0;
          for (std::size_t k = first; k < cl.path_sizes.size(); ++k) {
            const std::size_t n = cl.path_sizes[k];
            if (cl.path_kinds[k] == std::uint8_t(PathKind::kCut)) {
              const double z = c.contour_level[contour++];
              out.level_area[z] += polygon_area(cl.xyz, at, n);
              for (std::size_t i = 0; i + 1 < n; ++i) {
                const double* a = &cl.xyz[3 * (at + i)];
                length[z] += std::hypot(a[3] - a[0], a[4] - a[1]);
              }
            }
            at += n;
          }
        },
        control);
    out.open_chains = st.open_chains;
    verify(mesh, ball, cl, out);
    if (grid > 0) {
      const DropIndex index(mesh, ball);
      const Aabb3 box = bounding_box(mesh);
      for (int k = 1; box.hi.z() - k * step_down > box.lo.z(); ++k) {
        const double z = box.hi.z() - k * step_down;  // as run_zlevel makes its levels
        if (!out.level_area.count(z) && !length.count(z)) out.level_area[z] = 0;
        double inside = 0;
        for (double x = box.lo.x() - radius; x <= box.hi.x() + radius; x += grid)
          for (double y = box.lo.y() - radius; y <= box.hi.y() + radius; y += grid)
            inside += index.query(x + 0.5 * grid, y + 0.5 * grid).tip_z >= z;
        const double dev = std::abs(out.level_area[z] - inside * grid * grid);
        const double allow = length[z] * grid + 4 * grid * grid;
        if (dev - allow > out.area_deviation - out.area_resolution) {
          out.area_deviation = dev;
          out.area_resolution = allow;
        }
      }
    }
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

inline KernelRun run_pencil_checked(const TriangleMesh& mesh, double radius, double interval,
                                    double step_down) {
  KernelRun out;
  try {
    const Cutter ball = ball_cutter(2 * radius);
    PencilParams p;
    p.interval = interval;
    p.step_down = step_down;
    RunControl control;
    const PencilResult r = run_pencil(mesh, ball, p, control);
    out.open_chains = r.stats.zlevel_open_chains;
    out.paths = r.stats.paths;
    out.length = r.stats.traced_length;
    robustness_detail::verify_guarded(mesh, ball, pencil_chunk(r), out);
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

// Raster along x (interval, step), chords guarded as the raster job does, then verified.
inline KernelRun run_raster_checked(const TriangleMesh& mesh, double radius, double interval,
                                    double step) {
  KernelRun out;
  try {
    const Cutter ball = ball_cutter(2 * radius);
    RasterParams p;
    p.interval = interval;
    p.step = step;
    ClChunk cl;
    RunControl control;
    run_raster(mesh, ball, p, [&](const ClChunk& c) { cl.append(c); }, control);
    robustness_detail::verify_guarded(mesh, ball, cl, out);
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace ncpath::test
