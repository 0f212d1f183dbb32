#pragma once
// The part under a preview's paths (preview.hpp): read again from the job's input as the job
// used it, and turned into what the picture draws.
#include <cstdint>
#include <string>
#include <vector>

#include "batch/jobs/job_spec.hpp"
#include "batch/preview/preview.hpp"
#include "kernels/mesh/triangle_mesh.hpp"

namespace ncpath::preview {

// A mesh job's mesh (transformed as the job did) or a profile job's loops (each closed,
// sampled: lines by their ends, arcs and NURBS curves finely), with their xy box. `problem`
// says why there is no part ("" when there is one, or the job has no input to draw).
struct Part {
  TriangleMesh mesh;
  std::vector<std::vector<Vec2>> loops;  // boundaries and islands, each closed
  double x_lo = 0, y_lo = 0, x_hi = 0, y_hi = 0;
  bool empty = true;
  std::string problem;
};
Part load_part(const jobs::JobSpec& job);

// A top view of the mesh, one value per pixel of a w x h picture (row-major, row 0 at the
// top): the lit colour of the highest facet over the pixel's centre, or the background.
std::vector<Rgb> height_map(const TriangleMesh& mesh, const Frame& frame, int w, int h);

}  // namespace ncpath::preview
