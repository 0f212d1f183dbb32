#include "batch/preview/report.hpp"

#include <openssl/evp.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "batch/output/cl_reader.hpp"

namespace ncpath::preview {

namespace {

std::string html_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string data_uri(const std::string& png) {
  std::string b64(4 * ((png.size() + 2) / 3) + 1, '\0');
  const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(b64.data()),
                                reinterpret_cast<const unsigned char*>(png.data()),
                                static_cast<int>(png.size()));
  b64.resize(static_cast<std::size_t>(n));
  return "data:image/png;base64," + b64;
}

std::string number(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// "ball 5 mm", "bull 10 mm r2"; the JSON as written when it is not a tool.
std::string tool_text(const std::string& json) {
  try {
    const nlohmann::json j = nlohmann::json::parse(json);
    std::string s = j.at("type").get<std::string>() + " " +
                    number(j.at("diameter_mm").get<double>(), "%g") + " mm";
    const double r = j.value("corner_radius_mm", 0.0);
    if (j.at("type") != "ball" && r > 0) s += " r" + number(r, "%g");
    return s;
  } catch (const std::exception&) {
    return json;
  }
}

std::string stat(const std::vector<out::StatValue>& stats, const char* name, const char* format) {
  for (const out::StatValue& s : stats) {
    if (s.name != name) continue;
    if (const auto* d = std::get_if<double>(&s.value)) return number(*d, format);
    if (const auto* i = std::get_if<std::int64_t>(&s.value)) return number(double(*i), format);
    if (const auto* t = std::get_if<std::string>(&s.value)) return *t;
  }
  return "";
}

const char* kStyle = R"(
body { font-family: sans-serif; margin: 1.5em; color: #222; }
h1 { font-size: 1.5em; margin-bottom: 0.2em; }
p.summary { color: #555; margin-top: 0; }
table { border-collapse: collapse; width: 100%; }
th, td { border-bottom: 1px solid #ddd; padding: 6px 8px; text-align: left; vertical-align: top; }
th { background: #f2f2f2; position: sticky; top: 0; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
img.thumb { width: 160px; height: 120px; border: 1px solid #ccc; }
.status-ok { color: #19692c; font-weight: bold; }
.status-failed { color: #b3261e; font-weight: bold; }
tr.failed { background: #fdf0ef; }
.msg { color: #b3261e; font-size: 0.9em; max-width: 40em; }
section.full { margin: 2em 0; }
section.full img { max-width: 100%; border: 1px solid #ccc; }
)";

struct Row {
  out::StoredJob job;
  std::vector<out::StatValue> stats;
  Picture full, thumb;
  std::size_t index = 0;
};

void write_row(std::ostream& o, const Row& r) {
  const bool ok = r.job.status == "ok";
  const std::string id = std::to_string(r.index);
  o << "<tr class=\"" << (ok ? "ok" : "failed") << "\" id=\"job-" << id << "\">"
    << "<td><a href=\"#full-" << id << "\"><img class=\"thumb\" alt=\"" << html_escape(r.job.name)
    << "\" src=\"" << data_uri(r.thumb.png) << "\"></a></td>"
    << "<td>" << html_escape(r.job.name) << "</td><td><span class=\"status-"
    << (ok ? "ok" : "failed") << "\">" << html_escape(r.job.status) << "</span>";
  if (!r.job.message.empty()) o << "<div class=\"msg\">" << html_escape(r.job.message) << "</div>";
  o << "</td><td>" << html_escape(r.job.operation) << "</td><td>"
    << html_escape(std::filesystem::path(r.job.input_path).filename().string()) << "</td><td>"
    << html_escape(tool_text(r.job.tool_json)) << "</td><td class=\"num\">" << r.full.points
    << "</td><td class=\"num\">" << number(r.full.cut_mm, "%.0f") << " / "
    << number(r.full.link_mm, "%.0f") << " / " << number(r.full.rapid_mm, "%.0f")
    << "</td><td class=\"num\">" << stat(r.stats, "total_s", "%.2f") << "</td><td>";
  const std::string mode = stat(r.stats, "verify_mode", "");
  if (mode.empty())
    o << "not verified";
  else
    o << html_escape(mode) << ": deepest gouge " << stat(r.stats, "verify_max_gouge", "%.3g")
      << " mm, " << stat(r.stats, "verify_moves", "%.0f") << " moves";
  o << "</td></tr>\n";
}

}  // namespace

std::size_t write_report(const std::filesystem::path& cl_file, const std::filesystem::path& html,
                         const ReportOptions& options) {
  std::vector<Row> rows;
  for (out::StoredJob& j : out::read_jobs(cl_file)) {
    Row r;
    r.index = rows.size();
    r.job = std::move(j);
    r.stats = out::read_stats(cl_file, r.job.name);
    r.full = preview_png(cl_file, r.job.name, options.full);
    r.thumb = preview_png(cl_file, r.job.name, options.thumb);
    rows.push_back(std::move(r));
  }
  std::stable_partition(rows.begin(), rows.end(),
                        [](const Row& r) { return r.job.status != "ok"; });
  const auto failed = static_cast<std::size_t>(
      std::count_if(rows.begin(), rows.end(), [](const Row& r) { return r.job.status != "ok"; }));
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
    << "<title>ncpath report: " << html_escape(cl_file.filename().string()) << "</title><style>"
    << kStyle << "</style></head><body>\n<h1>ncpath batch report</h1>\n<p class=\"summary\">"
    << html_escape(cl_file.string()) << " &middot; " << rows.size() << " jobs &middot; "
    << rows.size() - failed << " ok &middot; " << failed << " failed</p>\n"
    << "<table id=\"jobs\"><thead><tr><th>picture</th><th>job</th><th>status</th>"
    << "<th>operation</th><th>input</th><th>tool</th><th>points</th>"
    << "<th>cut / link / rapid (mm)</th><th>time (s)</th><th>verification</th></tr></thead>"
    << "<tbody>\n";
  for (const Row& r : rows) write_row(o, r);
  o << "</tbody></table>\n<h2>Pictures</h2>\n";
  for (const Row& r : rows)
    o << "<section class=\"full\" id=\"full-" << r.index << "\"><h3>" << html_escape(r.job.name)
      << "</h3><img alt=\"" << html_escape(r.job.name) << "\" src=\"" << data_uri(r.full.png)
      << "\"></section>\n";
  o << "</body></html>\n";
  std::ofstream f(html, std::ios::binary | std::ios::trunc);
  f << o.str();
  f.close();
  if (!f) throw std::runtime_error(html.string() + ": cannot write the report");
  return rows.size();
}

}  // namespace ncpath::preview
