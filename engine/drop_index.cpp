#include "engine/drop_index.hpp"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>

#include "engine/embree_user_scene.hpp"

namespace ncpath {

namespace {

// The per-query state Embree hands back to the intersection callback.
struct QueryContext {
  RTCIntersectContext rtc;  // must be first: Embree sees a pointer to it
  const FacetTable* table;
  const Cutter* cutter;
  double x, y, z_top;
  CutterContact best;
};

}  // namespace

struct DropIndex::Impl {
  const FacetTable* table;
  Cutter cutter;
  double z_top;
  EmbreeUserScene embree;

  static void bounds(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const Impl*>(args->geometryUserPtr);
    const PreparedFacet& f = self->table->facets[args->primID];
    const double R = self->cutter.radius;
    RTCBounds* b = args->bounds_o;
    b->lower_x = pad_down(f.min_x - R);
    b->lower_y = pad_down(f.min_y - R);
    b->lower_z = pad_down(f.min_z - R);  // no tip from this facet is lower
    b->upper_x = pad_up(f.max_x + R);
    b->upper_y = pad_up(f.max_y + R);
    b->upper_z = pad_up(f.max_z);  // and none is higher than its top vertex
  }

  static void intersect(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    auto* q = reinterpret_cast<QueryContext*>(args->context);
    auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
    const PreparedFacet& f = q->table->facets[args->primID];
    if (drop_facet(*q->cutter, f, q->x, q->y, args->primID, q->best)) {
      // Shorten the ray to the new best tip, rounded so that boxes reaching exactly that
      // height are still visited (ties are decided in double, not by Embree).
      const float t = static_cast<float>(q->z_top - q->best.tip_z);
      rh->ray.tfar = std::nextafter(t, std::numeric_limits<float>::infinity());
      rh->hit.geomID = args->geomID;
      rh->hit.primID = args->primID;
    }
  }

  static void occluded(const RTCOccludedFunctionNArguments*) {}
};

DropIndex::DropIndex(const FacetTable& table, const Cutter& cutter)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.table = &table;
  m.cutter = cutter;
  m.z_top = table.box.empty() ? 1.0 : table.box.hi.z() + 1.0;
  m.embree = EmbreeUserScene(table.facets.size(), &m, &Impl::bounds, &Impl::intersect,
                             &Impl::occluded, RTC_SCENE_FLAG_ROBUST);
}

DropIndex::~DropIndex() = default;

CutterContact DropIndex::query(double x, double y) const {
  const Impl& m = *impl_;
  QueryContext q;
  rtcInitIntersectContext(&q.rtc);
  q.table = m.table;
  q.cutter = &m.cutter;
  q.x = x;
  q.y = y;
  q.z_top = m.z_top;
  if (m.table->facets.empty()) return q.best;
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(x);
  rh.ray.org_y = static_cast<float>(y);
  rh.ray.org_z = static_cast<float>(m.z_top);
  rh.ray.dir_x = 0;
  rh.ray.dir_y = 0;
  rh.ray.dir_z = -1;
  rh.ray.tnear = 0;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(m.embree.scene(), &q.rtc, &rh);
  return q.best;
}

CutterContact drop_brute_force(const FacetTable& table, const Cutter& cutter, double x, double y) {
  CutterContact best;
  for (std::size_t i = 0; i < table.facets.size(); ++i)
    drop_facet(cutter, table.facets[i], x, y, static_cast<std::uint32_t>(i), best);
  return best;
}

}  // namespace ncpath
