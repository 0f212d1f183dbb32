#include "batch/jobs/profile_input.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>

#include "batch/io/dxf_reader.hpp"
#include "batch/io/profile_toml.hpp"
#include "engine/run_control.hpp"
#include "kernels/pocket/chain.hpp"

namespace ncpath::jobs {

namespace {

std::int64_t i64(std::uint64_t v) { return static_cast<std::int64_t>(v); }

io::ProfileSoup read_soup(const std::filesystem::path& path,
                          const std::optional<io::LengthUnit>& units) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".dxf") return io::read_dxf(path, units);
  if (ext == ".toml") return io::read_profile_toml(path, units);
  throw io::ReadError(
      path, "",
      "unknown profile format '" + ext + "' (expected .dxf or .toml, see docs/profile-format.md)");
}

}  // namespace

ProfileInput read_profile_regions(const std::filesystem::path& path, double join_tolerance,
                                  const std::optional<io::LengthUnit>& units,
                                  std::vector<out::StatValue>& stats) {
  Stopwatch read_clock;
  io::ProfileSoup soup = read_soup(path, units);
  ChainResult chained = chain_and_nest(soup.curves, soup.nurbs, soup.sources, join_tolerance);
  if (!chained.error.empty()) throw io::ReadError(path, "", chained.error);
  stats.push_back({"units", soup.units.name, ""});
  stats.push_back({"units_from", soup.units_from, ""});
  stats.push_back({"mm_per_unit", soup.units.mm_per_unit, "mm"});
  if (!soup.units_warning.empty()) add_input_warning(stats, soup.units_warning);
  stats.push_back({"profile_curves", i64(soup.curves.size()), ""});
  stats.push_back({"zero_length_dropped", i64(soup.zero_length_dropped), ""});
  stats.push_back({"warnings", i64(soup.warnings.size()), ""});
  stats.push_back({"largest_gap_closed", chained.largest_gap_closed, "mm"});
  stats.push_back({"regions", i64(chained.regions.size()), ""});
  stats.push_back({"read_s", read_clock.seconds(), "s"});
  return {std::move(chained.regions), std::move(soup.sources)};
}

std::string region_label(const ProfileInput& in, std::size_t region) {
  const std::string names = boundary_entities(in, region);
  return "region " + std::to_string(region) + (names.empty() ? "" : " (boundary: " + names + ")");
}

std::string boundary_entities(const ProfileInput& in, std::size_t region) {
  if (region >= in.regions.size()) return "";
  // Distinct sources in the order the boundary meets them (a polyline gives many curves).
  std::vector<std::uint32_t> seen;
  for (const ProfileCurve& c : in.regions[region].boundary.curves)
    if (c.seg.source < in.sources.size() &&
        std::find(seen.begin(), seen.end(), c.seg.source) == seen.end())
      seen.push_back(c.seg.source);
  constexpr std::size_t kNamed = 3;
  std::string out;
  for (std::size_t i = 0; i < std::min(seen.size(), kNamed); ++i) {
    const SourceEntity& s = in.sources[seen[i]];
    if (!out.empty()) out += ", ";
    out += s.handle.empty() ? s.type : s.type + " " + s.handle;
  }
  if (seen.size() > kNamed) out += " and " + std::to_string(seen.size() - kNamed) + " more";
  return out;
}

}  // namespace ncpath::jobs
