#pragma once
// Test helpers: hand-written ASCII DXF files (R12-style and R2000-style entity sections).
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

namespace ncpath::test {

// Group code / value pairs, one per line each, as DXF stores them.
inline std::string pairs(std::initializer_list<std::string> items) {
  std::string s;
  for (const std::string& x : items) s += x + "\n";
  return s;
}

// A DXF with only an ENTITIES section holding `entities` (already in pair form).
inline std::string dxf_entities(const std::string& entities) {
  return pairs({"0", "SECTION", "2", "ENTITIES"}) + entities + pairs({"0", "ENDSEC", "0", "EOF"});
}

inline std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "ncpath_profile_tests";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace ncpath::test
