// batch/output/gcode_writer: the produced program is read back by a small independent
// interpreter (G0/G1/G2/G3 with I J, absolute, arcs sampled with the controller's spiral rule)
// and compared with the CL points both ways; preamble/postamble words, number format, safe-Z
// travel, retractions, the Grbl word set and the error paths.
#include "batch/output/gcode_writer.hpp"

#include <gtest/gtest.h>

#include "tests/support/oracle.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace ncpath::out {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kChord = 1e-5;  // mm, chordal error of the interpreter's arc sampling

std::filesystem::path out_path(const std::string& name) {
  return std::filesystem::path(NCPATH_BINARY_DIR) / ("gcode_test_" + name);
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// ---- a tiny RS274 interpreter -------------------------------------------------------------

struct Motion {
  bool rapid;
  Vec3 a, b;
};

struct Program {
  std::vector<Motion> moves;       // arcs sampled into short chords
  std::vector<std::string> codes;  // non-comment text of each non-empty line
  std::set<std::string> words;     // every G and M word, e.g. "G21", "M3"
  std::set<char> letters;          // every word letter used
  std::vector<double> feeds;       // F values in order
  double spindle = 0;
  bool exponent = false;
  bool negative_zero = false;
  double radius_mismatch = 0;  // largest |end radius - start radius| of an arc, mm
  int arcs = 0;
  std::string error;  // first problem the interpreter met
};

Program interpret(const std::string& text) {
  Program pr;
  std::istringstream in(text);
  std::string raw;
  int motion = -1;
  Vec3 pos(NAN, NAN, NAN);
  const std::regex exp_re("[0-9.][eE][-+]?[0-9]");
  const std::regex neg_zero_re("^-0*\\.?0*$");
  while (std::getline(in, raw)) {
    std::string code;
    bool in_comment = false;
    for (const char ch : raw) {
      if (ch == '(') {
        if (in_comment) pr.error = "nested comment";
        in_comment = true;
      } else if (ch == ')') {
        in_comment = false;
      } else if (ch == ';' && !in_comment) {
        break;
      } else if (!in_comment) {
        code += ch;
      }
    }
    if (in_comment) pr.error = "unclosed comment";
    if (code.find_first_not_of(' ') == std::string::npos) continue;
    pr.codes.push_back(code);
    if (std::regex_search(code, exp_re)) pr.exponent = true;
    std::map<char, double> w;
    std::size_t i = 0;
    while (i < code.size()) {
      if (code[i] == ' ') {
        ++i;
        continue;
      }
      const char letter = code[i++];
      if (letter < 'A' || letter > 'Z') {
        pr.error = "bad character in: " + code;
        break;
      }
      std::size_t j = i;
      while (j < code.size() && (std::isdigit(code[j]) || code[j] == '.' || code[j] == '-')) ++j;
      const std::string num = code.substr(i, j - i);
      i = j;
      if (num.empty()) {
        pr.error = "word without number in: " + code;
        break;
      }
      if (std::regex_match(num, neg_zero_re)) pr.negative_zero = true;
      const double v = std::stod(num);
      pr.letters.insert(letter);
      if (letter == 'G' || letter == 'M') {
        pr.words.insert(std::string(1, letter) + num);
        if (letter == 'G' && (num == "0" || num == "1" || num == "2" || num == "3")) {
          motion = std::stoi(num);
        }
      } else {
        w[letter] = v;
      }
    }
    if (w.count('F')) pr.feeds.push_back(w['F']);
    if (w.count('S')) pr.spindle = w['S'];
    if (!w.count('X') && !w.count('Y') && !w.count('Z')) continue;
    const Vec3 end(w.count('X') ? w['X'] : pos.x(), w.count('Y') ? w['Y'] : pos.y(),
                   w.count('Z') ? w['Z'] : pos.z());
    if (motion == 0 || motion == 1) {
      if (!std::isnan(pos.x()) && !std::isnan(pos.z())) pr.moves.push_back({motion == 0, pos, end});
      pos = end;
    } else if (motion == 2 || motion == 3) {
      ++pr.arcs;
      if (!w.count('I') || !w.count('J') || std::isnan(pos.x())) {
        pr.error = "arc without I J or start: " + code;
        continue;
      }
      const Vec2 c = pos.head<2>() + Vec2(w['I'], w['J']);
      const double r0 = (pos.head<2>() - c).norm();
      const double r1 = (end.head<2>() - c).norm();
      pr.radius_mismatch = std::max(pr.radius_mismatch, std::abs(r1 - r0));
      const double a0 = std::atan2(pos.y() - c.y(), pos.x() - c.x());
      double d = std::atan2(end.y() - c.y(), end.x() - c.x()) - a0;
      if (motion == 3) {
        while (d <= 0) d += 2 * kPi;  // equal ends: a full circle
      } else {
        while (d >= 0) d -= 2 * kPi;
      }
      const double r = std::max(r0, r1);
      const double dmax = 2 * std::acos(1 - kChord / std::max(r, kChord));
      const int n = std::max(1, static_cast<int>(std::ceil(std::abs(d) / dmax)));
      Vec3 prev = pos;
      for (int k = 1; k <= n; ++k) {
        const double u = static_cast<double>(k) / n;
        const double rr = r0 + u * (r1 - r0);  // spiral between the two radii, as LinuxCNC
        const Vec3 q =
            k == n ? end
                   : Vec3(c.x() + rr * std::cos(a0 + u * d), c.y() + rr * std::sin(a0 + u * d),
                          pos.z() + u * (end.z() - pos.z()));
        pr.moves.push_back({false, prev, q});
        prev = q;
      }
      pos = end;
    } else {
      pr.error = "coordinates without motion mode: " + code;
    }
  }
  return pr;
}

double seg_dist(const Vec3& a, const Vec3& b, const Vec3& p) {
  return ncpath::test::point_segment_distance(a, b, p);
}

double dist_to_feed_moves(const Program& pr, const Vec3& p) {
  double best = INFINITY;
  for (const Motion& m : pr.moves) {
    if (!m.rapid) best = std::fmin(best, seg_dist(m.a, m.b, p));
  }
  return best;
}

// ---- the job ------------------------------------------------------------------------------

void add_path(ClChunk& ch, const std::vector<Vec3>& pts, PathKind kind) {
  for (const Vec3& p : pts) {
    ch.xyz.insert(ch.xyz.end(), {p.x(), p.y(), p.z()});
    ch.contact.push_back(0);
  }
  ch.path_sizes.push_back(static_cast<std::uint32_t>(pts.size()));
  ch.path_kinds.push_back(static_cast<std::uint8_t>(kind));
}

// The CL paths of the job, by kind: cut/link polylines (in order) and the rapid.
struct Job {
  std::vector<std::vector<Vec3>> cut_paths;  // cut and link paths, in order
  ClChunk first, second;                     // the job as two appends
};

Job make_job() {
  Job j;
  std::vector<Vec3> circle;  // cut: closed clockwise circle, 200 points
  for (int i = 0; i < 200; ++i) {
    const double a = -2 * kPi * i / 199.0;
    circle.emplace_back(20 + 15 * std::cos(a), 10 + 15 * std::sin(a), -1);
  }
  std::vector<Vec3> link;  // link at depth from the circle's end
  for (int i = 0; i <= 4; ++i) link.emplace_back(35, 10 + 5.0 * i, -1);
  const std::vector<Vec3> rapid = {Vec3(35, 30, -1), Vec3(70, 0, -2)};
  std::vector<Vec3> helix;  // cut: half a ccw helix from the rapid's end
  for (int i = 0; i < 50; ++i) {
    const double u = i / 49.0;
    helix.emplace_back(60 + 10 * std::cos(u * kPi), 10 * std::sin(u * kPi), -2 - u);
  }
  std::vector<Vec3> wiggle;  // cut: starts away from the helix's end -> retract
  for (int i = 0; i <= 100; ++i) {
    const double x = 0.3 * i;
    wiggle.emplace_back(i == 0 ? -0.00001 : x, -20 + 0.5 * std::sin(x / 3), -0.5);
  }
  add_path(j.first, circle, PathKind::kCut);
  add_path(j.first, link, PathKind::kLinkAtDepth);
  add_path(j.second, rapid, PathKind::kRapid);
  add_path(j.second, helix, PathKind::kCut);
  add_path(j.second, wiggle, PathKind::kCut);
  j.cut_paths = {circle, link, helix, wiggle};
  return j;
}

GcodeParams params_for(GcodeDialect d) {
  GcodeParams p;
  p.dialect = d;
  p.job_name = "pocket (test)";
  return p;
}

std::string write_job(const std::string& name, const GcodeParams& prm, GcodeStats* stats) {
  const Job job = make_job();
  const std::filesystem::path path = out_path(name);
  GcodeWriter w(path, prm);
  w.append(job.first);
  w.append(job.second);
  w.finish();
  if (stats) *stats = w.stats();
  return slurp(path);
}

void expect_same_path_as_cl(const Program& pr, const Job& job, double tol) {
  ASSERT_TRUE(pr.error.empty()) << pr.error;
  // Every CL point of the cut and link paths lies on the interpreted cutting moves.
  for (const auto& path : job.cut_paths) {
    for (std::size_t i = 0; i < path.size(); ++i) {
      ASSERT_LE(dist_to_feed_moves(pr, path[i]), tol + kChord) << i;
    }
  }
  // Every cutting move is either a vertical plunge or lies on the CL polylines.
  for (const Motion& m : pr.moves) {
    if (m.rapid || (m.a.head<2>() - m.b.head<2>()).norm() < 1e-12) continue;
    for (const double u : {0.0, 0.5, 1.0}) {
      const Vec3 q = m.a + u * (m.b - m.a);
      double best = INFINITY;
      for (const auto& path : job.cut_paths) {
        for (std::size_t i = 0; i + 1 < path.size(); ++i) {
          best = std::fmin(best, seg_dist(path[i], path[i + 1], q));
        }
      }
      ASSERT_LE(best, tol + kChord) << "cutting move off the CL path at " << q.transpose();
    }
  }
}

TEST(GcodeWriter, LinuxCncProgramIsTheClPath) {
  GcodeStats st;
  const GcodeParams prm = params_for(GcodeDialect::kLinuxCnc);
  const std::string text = write_job("linuxcnc.ngc", prm, &st);
  const Program pr = interpret(text);
  expect_same_path_as_cl(pr, make_job(), prm.arc_tolerance);

  for (const char* word : {"G21", "G90", "G17", "G40", "G49", "G80", "G94", "M3", "M5", "M2"}) {
    EXPECT_TRUE(pr.words.count(word)) << word;
  }
  EXPECT_TRUE(pr.words.count("G2") || pr.words.count("G3"));
  EXPECT_TRUE(pr.words.count("G2"));  // the clockwise circle
  EXPECT_TRUE(pr.words.count("G3"));  // the counter-clockwise helix
  EXPECT_GT(pr.arcs, 0);
  EXPECT_LT(pr.arcs + static_cast<int>(st.lines), 200);  // far fewer moves than points
  EXPECT_EQ(pr.spindle, 12000);
  std::set<double> feeds;
  for (const double f : pr.feeds) feeds.insert(f);
  EXPECT_EQ(feeds, (std::set<double>{800, 200}));
  EXPECT_FALSE(pr.exponent);
  EXPECT_FALSE(pr.negative_zero);
  EXPECT_NE(text.find("X0.0000 Y-20.0000"), std::string::npos);  // -0.00001 printed as 0
  EXPECT_LT(pr.radius_mismatch, 0.005);                          // Grbl's arc definition limit
  EXPECT_NE(text.find("(job: pocket _test_)"), std::string::npos);
  // Modal set-up before the first motion; program end last.
  EXPECT_EQ(pr.codes[0], "G21 G90 G17");
  EXPECT_EQ(pr.codes[pr.codes.size() - 2], "M5");
  EXPECT_EQ(pr.codes.back(), "M2");
  EXPECT_EQ(st.arcs, pr.arcs);
}

TEST(GcodeWriter, RapidsAtSafeZAndRetractsBetweenDisconnectedPaths) {
  GcodeStats st;
  const GcodeParams prm = params_for(GcodeDialect::kLinuxCnc);
  const Program pr = interpret(write_job("travel.ngc", prm, &st));
  ASSERT_TRUE(pr.error.empty()) << pr.error;
  // No horizontal G0 below safe Z, and no G0 ever goes down below safe Z.
  int climbs = 0;
  for (const Motion& m : pr.moves) {
    if (!m.rapid) continue;
    if ((m.a.head<2>() - m.b.head<2>()).norm() > 0) {
      EXPECT_GE(m.a.z(), prm.safe_z - 1e-9);
      EXPECT_GE(m.b.z(), prm.safe_z - 1e-9);
    }
    EXPECT_GE(m.b.z(), std::min(m.a.z(), prm.safe_z) - 1e-9);
    climbs += m.a.z() < prm.safe_z && m.b.z() >= prm.safe_z;
  }
  // Rapid path and the disconnected wiggle: 2 retractions, plus the postamble's.
  EXPECT_EQ(st.retractions, 2);
  EXPECT_EQ(climbs, 3);
  EXPECT_EQ(st.plunges, 3);  // first path, end of the rapid, the wiggle
  // The retraction before the wiggle: between the helix's end and the wiggle's start the
  // tool is at safe Z.
  const Vec3 helix_end(50, 0, -3);
  const Vec3 wiggle_start(0, -20, -0.5);
  std::size_t i_end = 0, i_start = 0;
  for (std::size_t i = 0; i < pr.moves.size(); ++i) {
    if ((pr.moves[i].b - helix_end).norm() < 1e-3) i_end = i;
    if ((pr.moves[i].b - wiggle_start).norm() < 1e-3 && i_start == 0) i_start = i;
  }
  ASSERT_LT(i_end, i_start);
  double top = -INFINITY;
  for (std::size_t i = i_end; i <= i_start; ++i) top = std::max(top, pr.moves[i].b.z());
  EXPECT_GE(top, prm.safe_z);
}

TEST(GcodeWriter, GrblOmitsWhatGrblRejects) {
  const GcodeParams prm = params_for(GcodeDialect::kGrbl);
  const std::string text = write_job("grbl.nc", prm, nullptr);
  const Program pr = interpret(text);
  expect_same_path_as_cl(pr, make_job(), prm.arc_tolerance);
  // Words every Grbl (0.8 .. 1.1) accepts.
  const std::set<std::string> allowed = {"G0",  "G1",  "G2", "G3", "G17", "G21",
                                         "G90", "G94", "M2", "M3", "M5"};
  for (const std::string& w : pr.words) EXPECT_TRUE(allowed.count(w)) << w;
  for (const char l : pr.letters) {
    EXPECT_NE(std::string("GMXYZIJFS").find(l), std::string::npos) << l;
  }
  for (const char* w : {"G21", "G90", "G17", "M3", "M5", "M2"}) EXPECT_TRUE(pr.words.count(w));
  EXPECT_FALSE(pr.words.count("G40"));
  EXPECT_FALSE(pr.words.count("G49"));
  EXPECT_FALSE(pr.words.count("G80"));
  EXPECT_TRUE(pr.words.count("G2") || pr.words.count("G3"));
  EXPECT_LT(pr.radius_mismatch, 0.005);
  EXPECT_FALSE(pr.exponent);
  // Grbl's line buffer holds 80 characters (comments are dropped as they are read).
  for (const std::string& c : pr.codes) EXPECT_LE(c.size(), 80u) << c;
}

TEST(GcodeWriter, SameOutputForAnySplitIntoChunks) {
  const GcodeParams prm = params_for(GcodeDialect::kLinuxCnc);
  const std::string two = write_job("split2.ngc", prm, nullptr);
  Job job = make_job();
  job.first.append(job.second);
  const std::filesystem::path path = out_path("split1.ngc");
  {
    GcodeWriter w(path, prm);
    w.append(job.first);
    w.finish();
  }
  EXPECT_EQ(slurp(path), two);
}

TEST(GcodeWriter, PointsWithoutZSplitAPath) {
  ClChunk ch;
  std::vector<Vec3> pts;
  for (int i = 0; i <= 20; ++i) pts.emplace_back(i, 0, (i >= 8 && i <= 11) ? NAN : -1.0);
  add_path(ch, pts, PathKind::kCut);
  const std::filesystem::path path = out_path("nan.ngc");
  GcodeWriter w(path, params_for(GcodeDialect::kLinuxCnc));
  w.append(ch);
  w.finish();
  EXPECT_EQ(w.stats().retractions, 1);
  const Program pr = interpret(slurp(path));
  ASSERT_TRUE(pr.error.empty()) << pr.error;
  for (const Motion& m : pr.moves) {
    if (m.rapid) continue;
    for (const double u : {0.0, 0.5, 1.0}) {
      const double x = m.a.x() + u * (m.b.x() - m.a.x());
      EXPECT_FALSE(x > 7 + 1e-9 && x < 12 - 1e-9) << "cutting over the gap at x = " << x;
    }
  }
  for (int i : {0, 7, 12, 20}) EXPECT_LE(dist_to_feed_moves(pr, Vec3(i, 0, -1)), 1e-9);
}

TEST(GcodeWriter, UnwritablePathNamesThePath) {
  const std::filesystem::path bad = "/nonexistent-ncpath-dir/sub/out.ngc";
  try {
    GcodeWriter w(bad, params_for(GcodeDialect::kLinuxCnc));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

TEST(GcodeWriter, BadParamsAndChunksAreRejected) {
  GcodeParams p = params_for(GcodeDialect::kLinuxCnc);
  p.decimals = 2;
  EXPECT_THROW(GcodeWriter(out_path("bad.ngc"), p), std::invalid_argument);
  p = params_for(GcodeDialect::kLinuxCnc);
  p.arc_tolerance = 0.0001;  // below the rounding budget at 4 decimals
  EXPECT_THROW(GcodeWriter(out_path("bad.ngc"), p), std::invalid_argument);
  p = params_for(GcodeDialect::kLinuxCnc);
  p.feed = 0;
  EXPECT_THROW(GcodeWriter(out_path("bad.ngc"), p), std::invalid_argument);

  GcodeWriter w(out_path("bad_chunk.ngc"), params_for(GcodeDialect::kLinuxCnc));
  ClChunk ch;
  add_path(ch, {Vec3(0, 0, 0), Vec3(1, 0, 0)}, PathKind::kCut);
  ch.path_sizes[0] = 3;
  EXPECT_THROW(w.append(ch), std::invalid_argument);
  ch.path_sizes[0] = 2;
  ch.path_kinds[0] = 7;
  EXPECT_THROW(w.append(ch), std::invalid_argument);
  ch.path_kinds[0] = 0;
  ch.xyz[0] = NAN;  // x must be finite
  EXPECT_THROW(w.append(ch), std::invalid_argument);
  w.finish();
  EXPECT_THROW(w.append(ch), std::logic_error);
  EXPECT_THROW(w.finish(), std::logic_error);
}

TEST(GcodeWriter, UnfinishedProgramIsMarkedAndHasNoEnd) {
  const std::filesystem::path path = out_path("unfinished.ngc");
  {
    GcodeWriter w(path, params_for(GcodeDialect::kLinuxCnc));
    w.append(make_job().first);
  }
  const std::string text = slurp(path);
  EXPECT_NE(text.find("(incomplete"), std::string::npos);
  EXPECT_FALSE(interpret(text).words.count("M2"));
}

}  // namespace
}  // namespace ncpath::out
