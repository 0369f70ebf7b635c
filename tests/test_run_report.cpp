// Progress line, the colour scale of result pictures, and the run report.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "solver/output/progress.h"
#include "solver/output/run_history.h"
#include "report/result_picture.h"
#include "report/run_report.h"

namespace nmm::report {
namespace {

namespace fs = std::filesystem;
using solve::ProgressLine;

std::string read_all(std::FILE* f) {
  std::rewind(f);
  std::string s;
  char buf[512];
  while (std::fgets(buf, sizeof buf, f)) s += buf;
  return s;
}

TEST(ProgressLine, ShowsPercentTimeAndTimeLeft) {
  ProgressLine p(ProgressLine::Mode::plain, 2.0, stderr);
  // Half the simulated time in 10 s of wall time: about 10 s left.
  const std::string line = p.line(500, 1.0, 10.0);
  EXPECT_NE(line.find(" 50.0%"), std::string::npos) << line;
  EXPECT_NE(line.find("t = 1 / 2 s"), std::string::npos) << line;
  EXPECT_NE(line.find("step 500"), std::string::npos) << line;
  EXPECT_NE(line.find("10 s spent, about 10 s left"), std::string::npos) << line;
  // A quarter in 3 min: 9 min left.
  EXPECT_NE(p.line(10, 0.5, 180).find("about 9 min 00 s left"), std::string::npos);
}

TEST(ProgressLine, PlainLinesAreRateLimitedAndQuietPrintsNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressLine p(ProgressLine::Mode::plain, 1.0, f, 0.5, 5.0);
    for (int i = 1; i <= 1000; ++i) p.update(i, i * 1e-3);  // far less than 5 s of wall time
  }
  EXPECT_EQ(read_all(f), "") << "no line before the first 5 s";
  {
    ProgressLine p(ProgressLine::Mode::plain, 1.0, f, 0.0, 0.0);  // period 0: every update
    p.update(1, 0.25);
    p.update(2, 0.5);
    p.finish(2, 0.5, false);  // the caller says why in its one line
    p.finish(4, 1.0, true);
  }
  const std::string out = read_all(f);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 3) << out;  // 2 updates, the final line
  EXPECT_NE(out.find(" 25.0%"), std::string::npos) << out;
  EXPECT_NE(out.find("100.0%"), std::string::npos) << out;
  EXPECT_EQ(out.find("interrupted"), std::string::npos) << out;
  std::fclose(f);
  std::FILE* g = std::tmpfile();
  ProgressLine quiet(ProgressLine::Mode::off, 1.0, g, 0, 0);
  quiet.update(1, 0.5);
  quiet.finish(1, 0.5, true);
  EXPECT_EQ(read_all(g), "");
  std::fclose(g);
}

// A warning (slow BLAS kernels) comes once, on its own line before the first progress line; a
// run that prints no progress line (a failure's one line, --quiet) does not show it.
TEST(ProgressLine, AWarningComesOnceBeforeTheFirstLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressLine p(ProgressLine::Mode::plain, 1.0, f, 0.0, 0.0);
    p.set_warning("slow kernels");
    p.update(1, 0.5);
    p.update(2, 1.0);
    p.finish(2, 1.0, true);
  }
  const std::string out = read_all(f);
  EXPECT_EQ(out.rfind("nmm-solve: warning: slow kernels\n", 0), 0u) << out;
  EXPECT_EQ(out.find("warning", out.find('\n')), std::string::npos) << out;  // once
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 4) << out;
  std::fclose(f);
  for (const ProgressLine::Mode mode : {ProgressLine::Mode::plain, ProgressLine::Mode::off}) {
    std::FILE* g = std::tmpfile();
    ProgressLine p(mode, 1.0, g, 5.0, 5.0);
    p.set_warning("slow kernels");
    p.update(1, 0.5);                                  // before its period: no line
    p.finish(1, 0.5, mode == ProgressLine::Mode::off);  // plain: a run that stopped
    EXPECT_EQ(read_all(g), "");
    std::fclose(g);
  }
}

TEST(ResultPicture, SliverStressStaysOutOfTheColourScale) {
  // The issue's slope: overburden about 1 MPa in 0.5 m² elements, one 0.0125 m² sliver at
  // 37.7 MPa. Area-weighted, the sliver is 0.0125 / 50 of the area: the 99th percentile stays 1.
  std::vector<double> value(100, 1.0), area(100, 0.5);
  value.push_back(37.7);
  area.push_back(0.0125);
  EXPECT_DOUBLE_EQ(weighted_quantile(value, area, 0.99), 1.0);
  EXPECT_DOUBLE_EQ(weighted_quantile(value, area, 1.0), 37.7);
  // Unweighted (equal areas) a 2 % share of large values would reach the 99th percentile.
  std::vector<double> v2(98, 1.0), a2(100, 1.0);
  v2.push_back(5);
  v2.push_back(6);
  EXPECT_DOUBLE_EQ(weighted_quantile(v2, a2, 0.99), 5.0);
}

TEST(ResultPicture, ContactStatesMarkTheEdgesAtTheVertexAndTheEdgeFaced) {
  // Element 0: loop vertices 0..3; element 1: 4..6. A sliding contact of vertex 5 against edge
  // 1 → 2 marks edges 4 → 5, 5 → 6 and 1 → 2 sliding; a sticking contact of vertex 4 marks the
  // closing edge 6 → 4 sticking, and leaves edge 4 → 5 sliding (sliding wins).
  Mesh m;
  m.element_loop_offset = {0, 4, 7};
  m.loop_xy.assign(14, 0.0);
  m.loop_edge_origin.assign(7, kEdgeBoundary);
  const std::vector<int> s =
      edge_contact_states(m, {{0, 0, 2, 5, 1}, {0, 0, 1, 4, -1}, {0, 0, 1, -1, -1}});
  EXPECT_EQ(s, (std::vector<int>{0, 2, 0, 0, 2, 2, 1}));
}

TEST(RunReport, PlotsHistoryAndWritesIndex) {
  const fs::path dir = fs::temp_directory_path() / ("nmm_report_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json") << R"({"status": "interrupted", "steps_completed": 2,
                                           "simulated_time": 0.002, "wall_seconds": 5.576478281,
                                           "contacts": {"pairs_tested": 3694546},
                                           "timings": {"solves": 0.000123},
                                           "max_penetration": 3.16e-6,
                                           "effects": ["elasticity", "gravity"],
                                           "equilibrium": {"verdict": "moving",
                                             "criterion": "max_velocity_m_s < 0.0001",
                                             "max_velocity_m_s": 0.0823,
                                             "max_unbalanced_ratio": 1.1}})";
  std::ofstream(dir / "history.csv") << "step,time,point,x,y,ux,uy\n0,0,0,1,1,0,0\n"
                                        "1,0.001,0,1,0.999,0,-0.001\n2,0.002,0,1,0.998,0,-0.002\n";
  nmm::solve::write_run_history(dir.string(), {{1, 0.001, 0.001, 5, 0, 3, 0.2, 0.01, 0.3},
                                   {2, 0.002, 0.001, 7, 1, 4, 3e-6, 1e-7, 2e-5}});
  std::ofstream(dir / "energy.csv") << "step,time,kinetic,strain,gravity,springs,load_work,friction,residual\n"
                                       "0,0,0,0,0,0,0,0,0\n2,0.002,5,1,-6,0,0,0,0\n";
  const ReportFiles files = make_run_report(dir.string());
  {
    // Three panels in one picture: solver effort, the equilibrium indicators, the energy terms.
    std::stringstream rh_svg;
    rh_svg << std::ifstream(dir / "run_history.svg").rdbuf();
    const std::string svg = rh_svg.str();
    EXPECT_LT(svg.find("solver effort per step"), svg.find("equilibrium: unbalanced force ratio")) << svg;
    EXPECT_LT(svg.find("equilibrium: unbalanced force ratio"), svg.find("energy (J per m of thickness)")) << svg;
    EXPECT_NE(svg.find("max unbalanced force ratio"), std::string::npos);
    EXPECT_NE(svg.find("gravity potential V"), std::string::npos);
    std::size_t nested = 0;
    for (std::size_t at = svg.find("<svg "); at != std::string::npos; at = svg.find("<svg ", at + 1))
      ++nested;
    EXPECT_EQ(nested, 4u) << "the outer document and its three panels";
  }
  EXPECT_TRUE(fs::exists(dir / "history.svg"));
  EXPECT_TRUE(fs::exists(dir / "run_history.svg"));
  std::stringstream html;
  html << std::ifstream(dir / "index.html").rdbuf();
  EXPECT_NE(html.str().find("interrupted"), std::string::npos);
  EXPECT_NE(html.str().find("history.svg"), std::string::npos);
  // Numbers rounded, with units (engineering notation); the summary a table, not JSON.
  EXPECT_NE(html.str().find("<tr><th>gravity</th><td class=\"n\">-6 J/m</td></tr>"), std::string::npos)
      << html.str();
  EXPECT_NE(html.str().find("simulated time 2 ms in 2 steps, wall 5.58 s"), std::string::npos);
  // The verdict beside the status, by the figure its criterion names (a dynamic run: velocity).
  EXPECT_NE(html.str().find("equilibrium: <span class=\"bad\">moving</span> (largest velocity 82.3 mm/s)"),
            std::string::npos)
      << html.str();
  EXPECT_NE(html.str().find("<th class=\"group\" colspan=\"2\">contacts</th>"), std::string::npos);
  EXPECT_NE(html.str().find("<th class=\"sub\">pairs tested</th><td class=\"n\">3\u202f694\u202f546</td>"),
            std::string::npos);
  EXPECT_NE(html.str().find("<th class=\"sub\">solves</th><td class=\"n\">123 µs</td>"), std::string::npos);
  EXPECT_NE(html.str().find("<th>max penetration</th><td class=\"n\">3.16 µm</td>"), std::string::npos);
  EXPECT_NE(html.str().find("<th>effects</th><td>elasticity, gravity</td>"), std::string::npos);
  EXPECT_EQ(html.str().find("5.576478281"), std::string::npos);
  EXPECT_EQ(html.str().find("{\""), std::string::npos) << "no raw JSON";
  EXPECT_NE(html.str().find("max-width:100%;height:auto"), std::string::npos);
  std::stringstream rh;
  rh << std::ifstream(dir / "run_history.csv").rdbuf();
  EXPECT_EQ(rh.str().substr(0, 108),
            "step,time,dt,iterations,cuts,closed_contacts,max_unbalanced_ratio,mean_unbalanced_ratio,"
            "max_velocity\n1,0.001");
  EXPECT_NE(rh.str().find(",3e-06,1e-07,2e-05\n"), std::string::npos) << rh.str();
  fs::remove(dir / "summary.json");
  EXPECT_THROW(make_run_report(dir.string()), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace nmm::report
