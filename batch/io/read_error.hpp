#pragma once
// The one exception of the readers: a malformed or unreadable input file. what() reads
//   "<file>: <location>: <what is wrong>"
// e.g. "bunny.stl: byte 684 (facet 13): truncated file: expected 50 bytes for facet 13,
// 12 left". The location is "line N", "byte N (facet K)", ... and is left out (with its
// colon) when there is none, e.g. for a file that cannot be opened.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

namespace ncpath::io {

class ReadError : public std::runtime_error {
 public:
  ReadError(std::filesystem::path file, std::string location, std::string problem)
      : std::runtime_error(compose(file, location, problem)),
        file_(std::move(file)),
        location_(std::move(location)),
        problem_(std::move(problem)) {}

  const std::filesystem::path& file() const { return file_; }
  const std::string& location() const { return location_; }  // may be empty
  const std::string& problem() const { return problem_; }

 private:
  static std::string compose(const std::filesystem::path& file, const std::string& location,
                             const std::string& problem) {
    std::string s = file.string();
    if (!location.empty()) s += ": " + location;
    return s + ": " + problem;
  }

  std::filesystem::path file_;
  std::string location_;
  std::string problem_;
};

}  // namespace ncpath::io
