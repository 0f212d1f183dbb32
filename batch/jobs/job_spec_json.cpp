// A job spec written back as JSON text, defaults included: the `params` and `tool`
// attributes of the job's group in the HDF5 output (batch/output/cl_writer.hpp).
#include "batch/jobs/job_spec.hpp"

#include <nlohmann/json.hpp>

#include "batch/jobs/mesh_op_params.hpp"

namespace ncpath::jobs {

std::string tool_json(const Cutter& c) {
  nlohmann::ordered_json j;
  j["type"] = cutter_type_name(c.type);
  j["diameter_mm"] = 2 * c.radius;
  j["corner_radius_mm"] = c.corner_radius;
  return j.dump();
}

std::string params_json(const JobSpec& job) {
  nlohmann::ordered_json j;
  j["operation"] = operation_name(job.operation);
  nlohmann::ordered_json t;
  t["scale"] = job.transform.scale;
  t["translate"] = {job.transform.translate.x(), job.transform.translate.y(),
                    job.transform.translate.z()};
  t["fit_xy"] = job.transform.fit_xy_mm ? nlohmann::ordered_json(*job.transform.fit_xy_mm)
                                        : nlohmann::ordered_json(nullptr);
  j["transform"] = t;
  if (job.operation == Operation::kRaster) {
    const RasterParams& p = job.raster;
    j["direction"] = p.direction == ScanDirection::kX ? "x" : "y";
    j["interval"] = p.interval;
    j["step"] = p.step;
    j["margin"] = p.margin;
    j["rect"] = p.rect ? nlohmann::ordered_json(*p.rect) : nlohmann::ordered_json(nullptr);
    j["adaptive_tolerance"] = p.adaptive_tolerance;
    j["min_step"] = p.min_step;
    j["floor_z"] = p.floor_z ? nlohmann::ordered_json(*p.floor_z) : nlohmann::ordered_json(nullptr);
    j["chunk_lines"] = p.chunk_lines;
    j["strip_height"] = p.strip_height;
    j["bin_width"] = p.bin_width;
  } else if (job.operation == Operation::kScan) {
    const ScanParams& p = job.scan;
    j["families"] = families_name(p.families);
    j["interval"] = p.interval;
    j["tolerance"] = p.tolerance;
    j["margin"] = p.margin;
    j["rect"] = p.rect ? nlohmann::ordered_json(*p.rect) : nlohmann::ordered_json(nullptr);
    j["floor_z"] = p.floor_z ? nlohmann::ordered_json(*p.floor_z) : nlohmann::ordered_json(nullptr);
    j["chunk_planes"] = p.chunk_planes;
  } else if (job.operation == Operation::kZLevel) {
    zlevel_params_json(job.zlevel, j);
  } else if (job.operation == Operation::kPencil) {
    pencil_params_json(job.pencil, j);
  } else if (job.operation == Operation::kFillet) {
    fillet_params_json(job.fillet, job.fillet_reference, j);
  } else if (job.operation == Operation::kOffset) {
    j["stepover"] = job.offset.stepover;
    j["stock"] = job.offset.stock;
    j["depth"] = job.offset.depth;
    j["tolerance"] = job.offset.tolerance;
    j["join_tolerance"] = job.offset.join_tolerance;
  } else if (job.operation == Operation::kPocket) {
    const PocketParams& p = job.pocket;
    j["stepover"] = p.stepover;
    j["stock"] = p.stock;
    j["depth"] = p.depth;
    j["stepdown"] = p.stepdown;
    j["tolerance"] = p.tolerance;
    j["join_tolerance"] = p.join_tolerance;
    j["order"] = order_name(p.order);
    j["milling"] = milling_name(p.milling);
    j["helix_radius"] = p.helix_radius;
    j["ramp_angle"] = p.ramp_angle;
    j["clearance"] = p.clearance;
    j["safe_z"] = job.gcode_safe_z.value_or(kDefaultSafeAboveTop);
  } else if (job.operation == Operation::kPocket3d) {
    const Pocket3dJobParams& p = job.pocket3d;
    j["surface"] = job.surface.string();
    j["scallop"] = p.scallop;
    j["eps"] = p.eps;
    j["delta"] = p.delta;
    j["stock"] = p.stock;
    j["tolerance"] = p.tolerance;
    j["join_tolerance"] = p.join_tolerance;
    j["order"] = order_name(p.order);
    j["milling"] = milling_name(p.milling);
    j["clearance"] = p.clearance;
    j["min_interval"] = p.min_interval;
    j["safe_z"] = job.gcode_safe_z.value_or(kDefaultSafeAboveTop);
  } else {
    j["points"] = job.points.string();
  }
  if (job.operation == Operation::kOffset || job.operation == Operation::kPocket ||
      job.operation == Operation::kPocket3d)
    j["units"] = job.units ? nlohmann::ordered_json(job.units->name) : nlohmann::ordered_json("drawing");
  return j.dump();
}

}  // namespace ncpath::jobs
