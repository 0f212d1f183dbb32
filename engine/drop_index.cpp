#include "engine/drop_index.hpp"

#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <limits>

#include "engine/embree_user_scene.hpp"
#include "engine/parallel.hpp"

namespace ncpath {

namespace {

// Recently prepared facets of on-demand indexes, per thread: direct-mapped by primitive.
struct FacetCache {
  static constexpr std::size_t kSlots = 4096;
  struct Slot {
    std::uint64_t owner = 0;  // the index's id; 0: empty
    std::uint32_t prim = 0;
    PreparedFacet facet;
  };
  std::vector<Slot> slots = std::vector<Slot>(kSlots);
};

std::uint64_t next_id() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

}  // namespace

struct DropIndex::Impl {
  // The per-query state Embree hands back to the intersection callback.
  struct QueryContext {
    RTCIntersectContext rtc;  // must be first: Embree sees a pointer to it
    const Impl* index;
    double x, y;
    CutterContact best;
  };

  const TriangleMesh* mesh;
  Cutter cutter;
  std::vector<std::uint32_t> kept;      // usable facets: primitive i is mesh.facets[kept[i]]
  std::vector<PreparedFacet> prepared;  // kPrepared: primitive i prepared; else empty
  double z_top = 1;
  EmbreeUserScene embree;

  std::uint64_t id = next_id();  // tells this index's entries in a thread's cache apart

  // Primitive i prepared: from the table, else from the calling thread's cache of recently
  // prepared facets (consecutive queries meet mostly the same facets; valid until this
  // thread's next call).
  const PreparedFacet& facet(std::uint32_t i) const {
    if (!prepared.empty()) return prepared[i];
    thread_local FacetCache cache;
    FacetCache::Slot& slot = cache.slots[i % FacetCache::kSlots];
    if (slot.owner != id || slot.prim != i) {
      prepare(kept[i], slot.facet);
      slot.owner = id;
      slot.prim = i;
    }
    return slot.facet;
  }
  bool prepare(std::size_t source, PreparedFacet& f) const {
    const auto& v = mesh->facets[source];
    return prepare_facet(mesh->vertices[v[0]], mesh->vertices[v[1]], mesh->vertices[v[2]], f);
  }

  static void bounds(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const Impl*>(args->geometryUserPtr);
    const PreparedFacet& f = self->facet(args->primID);
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
    const Impl& m = *q->index;
    const PreparedFacet& f = m.facet(args->primID);
    if (drop_facet(m.cutter, f, q->x, q->y, m.kept[args->primID], q->best)) {
      // Shorten the ray to the new best tip, rounded so that boxes reaching exactly that
      // height are still visited (ties are decided in double, not by Embree).
      const float t = static_cast<float>(m.z_top - q->best.tip_z);
      rh->ray.tfar = std::nextafter(t, std::numeric_limits<float>::infinity());
      rh->hit.geomID = args->geomID;
      rh->hit.primID = args->primID;
    }
  }

  static void occluded(const RTCOccludedFunctionNArguments*) {}
};

DropIndex::DropIndex(const TriangleMesh& mesh, const Cutter& cutter, Facets facets)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.mesh = &mesh;
  m.cutter = cutter;
  const std::size_t n = mesh.facets.size();
  std::vector<std::uint8_t> usable(n, 0);
  par::for_each(n, 4096, [&](std::size_t i) {
    PreparedFacet f;
    usable[i] = m.prepare(i, f);
  });
  Aabb3 box;
  for (std::size_t i = 0; i < n; ++i) {
    if (!usable[i]) continue;
    m.kept.push_back(static_cast<std::uint32_t>(i));
    for (int k = 0; k < 3; ++k) box.add(mesh.vertices[mesh.facets[i][k]]);
  }
  m.z_top = box.empty() ? 1.0 : box.hi.z() + 1.0;
  const bool small = m.kept.size() * sizeof(PreparedFacet) <= kPreparedTableBytes;
  if (facets == Facets::kPrepared || (facets == Facets::kAuto && small)) {
    m.prepared.resize(m.kept.size());
    par::for_each(m.kept.size(), 4096,
                  [&](std::size_t i) { m.prepare(m.kept[i], m.prepared[i]); });
  }
  m.embree = EmbreeUserScene(m.kept.size(), &m, &Impl::bounds, &Impl::intersect,
                             &Impl::occluded, RTC_SCENE_FLAG_ROBUST);
}

DropIndex::~DropIndex() = default;

std::uint64_t DropIndex::facet_count() const { return impl_->kept.size(); }
std::uint64_t DropIndex::degenerate() const {
  return impl_->mesh->facets.size() - impl_->kept.size();
}

CutterContact DropIndex::query(double x, double y) const {
  const Impl& m = *impl_;
  Impl::QueryContext q;
  rtcInitIntersectContext(&q.rtc);
  q.index = &m;
  q.x = x;
  q.y = y;
  if (m.kept.empty()) return q.best;
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
