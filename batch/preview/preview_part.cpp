#include "batch/preview/preview_part.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include <Eigen/Geometry>

#include "batch/io/mesh_reader.hpp"
#include "batch/jobs/profile_input.hpp"
#include "kernels/curves/nurbs.hpp"
#include "kernels/curves/segment.hpp"
#include "kernels/geom/tolerance.hpp"
#include "kernels/mesh/mesh_transform.hpp"

namespace ncpath::preview {

namespace {

constexpr int kNurbsSamples = 64;     // points per NURBS curve of a profile
constexpr double kArcStepRad = 0.05;  // angle between the points of a drawn arc

bool profile_job(const jobs::JobSpec& job) {
  return job.operation == jobs::Operation::kOffset || job.operation == jobs::Operation::kPocket ||
         job.operation == jobs::Operation::kPocket3d;
}

double join_tolerance(const jobs::JobSpec& job) {
  if (job.operation == jobs::Operation::kOffset) return job.offset.join_tolerance;
  if (job.operation == jobs::Operation::kPocket) return job.pocket.join_tolerance;
  return job.pocket3d.join_tolerance;
}

// The profile as one closed polyline (its last point is not repeated).
std::vector<Vec2> sample(const Profile& profile) {
  std::vector<Vec2> out;
  for (const ProfileCurve& c : profile.curves) {
    if (c.nurbs >= 0) {
      const Nurbs2& n = profile.nurbs[static_cast<std::size_t>(c.nurbs)];
      const double t0 = nurbs_t0(n), t1 = nurbs_t1(n);
      for (int k = 0; k < kNurbsSamples; ++k)
        out.push_back(nurbs_point(n, t0 + (t1 - t0) * k / kNurbsSamples));
      continue;
    }
    const int steps =
        c.seg.is_arc()
            ? std::max(2, static_cast<int>(std::ceil(std::abs(sweep(c.seg)) / kArcStepRad)))
            : 1;
    for (int k = 0; k < steps; ++k) out.push_back(point_at(c.seg, static_cast<double>(k) / steps));
  }
  return out;
}

void add_box(Part& p, double x, double y) {
  if (p.empty) {
    p.x_lo = p.x_hi = x;
    p.y_lo = p.y_hi = y;
    p.empty = false;
  }
  p.x_lo = std::min(p.x_lo, x);
  p.x_hi = std::max(p.x_hi, x);
  p.y_lo = std::min(p.y_lo, y);
  p.y_hi = std::max(p.y_hi, y);
}

}  // namespace

Part load_part(const jobs::JobSpec& job) {
  Part p;
  if (job.input.empty()) return p;
  try {
    if (profile_job(job)) {
      std::vector<out::StatValue> ignored;
      const jobs::ProfileInput in =
          jobs::read_profile_regions(job.input, join_tolerance(job), job.units, ignored);
      for (const Region& r : in.regions) {
        p.loops.push_back(sample(r.boundary));
        for (const Profile& island : r.islands) p.loops.push_back(sample(island));
      }
      for (const auto& loop : p.loops)
        for (const Vec2& q : loop) add_box(p, q.x(), q.y());
    } else {
      io::MeshReadResult in = io::read_mesh(job.input);
      const TransformOutcome tr = apply_transform(job.transform, in.mesh);
      if (!tr.ok()) throw std::invalid_argument("transform." + tr.error);
      p.mesh = std::move(in.mesh);
      for (const Vec3& v : p.mesh.vertices) add_box(p, v.x(), v.y());
    }
  } catch (const std::exception& e) {
    p = Part{};
    p.problem = job.input.string() + ": " + e.what();
  }
  return p;
}

namespace {

// Lit colour of a facet of normal n at height t in [0, 1] of the part's range: a grey-blue
// tint from low to high, Lambert light from the upper left plus ambient.
Rgb shade(const Vec3& n, double t) {
  static const Vec3 light = Vec3(-0.5, 0.5, 1.0).normalized();
  const double lambert = std::max(0.0, n.dot(light));
  const double k = 0.35 + 0.65 * lambert;
  return {k * (0.55 + 0.25 * t), k * (0.60 + 0.25 * t), k * (0.68 + 0.22 * t)};
}

}  // namespace

std::vector<Rgb> height_map(const TriangleMesh& mesh, const Frame& frame, int w, int h) {
  std::vector<double> top(static_cast<std::size_t>(w) * h,
                          -std::numeric_limits<double>::infinity());
  std::vector<Rgb> out(top.size(), kBackground);
  const Aabb3 box = bounding_box(mesh);
  const double z_span = std::max(tol::kPreviewMinZSpan, box.hi.z() - box.lo.z());
  for (const auto& f : mesh.facets) {
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    Vec3 n = (b - a).cross(c - a);
    if (!(n.norm() > 0)) continue;
    n = (n.z() < 0 ? -n : n).normalized();
    const Vec2 pa = frame.pixel(a.x(), a.y()), pb = frame.pixel(b.x(), b.y()),
               pc = frame.pixel(c.x(), c.y());
    const double det = (pb - pa).x() * (pc - pa).y() - (pb - pa).y() * (pc - pa).x();
    if (det == 0) continue;  // seen edge-on from above
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({pa.x(), pb.x(), pc.x()}))));
    const int x1 = std::min(w - 1, static_cast<int>(std::ceil(std::max({pa.x(), pb.x(), pc.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({pa.y(), pb.y(), pc.y()}))));
    const int y1 = std::min(h - 1, static_cast<int>(std::ceil(std::max({pa.y(), pb.y(), pc.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Vec2 q(x + 0.5, y + 0.5);
        const double u = ((q - pa).x() * (pc - pa).y() - (q - pa).y() * (pc - pa).x()) / det;
        const double v = ((pb - pa).x() * (q - pa).y() - (pb - pa).y() * (q - pa).x()) / det;
        if (u < 0 || v < 0 || u + v > 1) continue;
        const double z = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        if (z <= top[i]) continue;
        top[i] = z;
        out[i] = shade(n, (z - box.lo.z()) / z_span);
      }
  }
  return out;
}

}  // namespace ncpath::preview
