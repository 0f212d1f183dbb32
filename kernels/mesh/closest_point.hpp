#pragma once
// Closest points of one segment or triangle, and the first contact of a moving ball with a
// triangle: exact, double precision. The engine's mesh distance index runs them in its
// Embree callbacks (engine/mesh_distance.hpp), the pencil-cut in its crease refinement.
#include "kernels/geom/vec.hpp"

namespace ncpath {

// Distance from x to the segment pq; writes the closest point to out. Clamped ends return
// the vertex itself, so facets sharing a vertex give bitwise equal answers there. A
// degenerate segment is its point p.
double point_segment_closest(const Vec3& x, const Vec3& p, const Vec3& q, Vec3& out);

// Distance from x to triangle abc (n = (b - a) x (c - a) non-zero); writes the closest point
// to q.
double point_triangle_closest(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, Vec3& q);

// First t in [0, t_max] at which the ball of radius r centred at x + t * d (d unit) touches
// triangle abc; 0 when it touches at t = 0; +inf when not by t_max.
double sweep_ball_triangle(const Vec3& x, const Vec3& d, double r, double t_max, const Vec3& a,
                           const Vec3& b, const Vec3& c);

}  // namespace ncpath
