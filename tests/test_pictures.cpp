// The pictures a rock engineer reads before the numbers: result.svg's axes, scale bar and
// exaggeration, a failed run's reason under the picture, the shared colour map, sweep.svg's
// grid, and the engineering numbers of index.html.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "common/error.h"
#include "report/failure_cause.h"
#include "studies/mechanism_picture.h"
#include "common/number_format.h"
#include "report/result_picture.h"
#include "common/svg_plot.h"
#include "common/svg_writer.h"
#include "studies/sweep.h"
#include "studies/sweep_picture.h"

namespace nmm {
namespace {

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

// The texts of an SVG in document order.
std::vector<std::string> texts(const std::string& svg) {
  std::vector<std::string> out;
  const std::regex re("<text[^>]*>([^<]*)</text>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1]);
  return out;
}

bool has_text(const std::string& svg, const std::string& t) {
  for (const std::string& s : texts(svg))
    if (s == t) return true;
  return false;
}

// A 10 m × 4 m body as one square manifold element (loop vertices 0..3), meshed at `h`.
Mesh one_block(double h) {
  Mesh m;
  m.mesh_size = h;
  m.loop_xy = {0, 0, 10, 0, 10, 4, 0, 4};
  m.element_loop_offset = {0, 4};
  m.element_triangle = {0};
  m.element_block = {0};
  m.element_body = {0};
  m.loop_edge_origin.assign(4, kEdgeBoundary);
  return m;
}

SceneDef one_block_scene() {
  SceneDef s;
  s.name = "block";
  BodyDef b;
  b.outer = {{0, 0}, {10, 0}, {10, 4}, {0, 4}};
  s.bodies.push_back(b);
  s.mesh_size = 0.5;
  return s;
}

// The block moved by (ux, uy) at its top corners (the bottom ones held).
std::string draw(const Mesh& m, double ux, double uy, const std::string& status, double factor,
                 std::vector<double>* xy_out = nullptr, StopCode stop = StopCode::ok) {
  std::vector<double> xy = m.loop_xy, stress(3, 0.0);
  xy[4] += ux, xy[5] += uy, xy[6] += ux, xy[7] += uy;
  report::PictureState st;
  st.time = 0.5;
  st.status = status;
  st.stop = stop;
  st.loop_xy = &xy;
  st.stress = &stress;
  st.exaggeration = factor;
  if (xy_out) *xy_out = xy;
  return report::result_svg(m, one_block_scene(), st, report::PictureField::displacement);
}

TEST(Pictures, RoundTicksScaleBarsAndFactors) {
  EXPECT_EQ(nice_ticks(0, 10, 6), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(nice_ticks(-3, 33, 6), (std::vector<double>{0, 10, 20, 30}));  // step 36/6 → 10
  EXPECT_EQ(nice_ticks(-3, 33, 8), (std::vector<double>{0, 5, 10, 15, 20, 25, 30}));
  EXPECT_EQ(nice_ticks(1, 1, 6), std::vector<double>{});
  EXPECT_DOUBLE_EQ(round_down_125(3.7), 2.0);
  EXPECT_DOUBLE_EQ(round_down_125(0.07), 0.05);
  EXPECT_DOUBLE_EQ(round_down_125(1000), 1000.0);
  EXPECT_DOUBLE_EQ(round_down_125(19.99), 10.0);
  // Automatic exaggeration: the largest displacement drawn as about 5 % of the model.
  EXPECT_EQ(report::automatic_exaggeration(1e-4, 10), 5000);  // 0.05·10 / 1e-4 = 5000
  EXPECT_EQ(report::automatic_exaggeration(3e-4, 10), 1000);  // 1667 → 1000
  EXPECT_EQ(report::automatic_exaggeration(0.2, 10), 1);      // 2 % of the model: true scale
  EXPECT_EQ(report::automatic_exaggeration(0.1, 10), 1);      // exactly 1 %: true scale
  EXPECT_EQ(report::automatic_exaggeration(0, 10), 1);
  EXPECT_EQ(report::automatic_exaggeration(1e-12, 10), 1);    // round-off is not magnified
}

TEST(Pictures, ResultHasAxesInMetresAndAScaleBar) {
  const std::string svg = draw(one_block(0.5), 0.3, 0, "ok", 0);  // 3 % of 10 m: true scale
  for (const char* t : {"0", "2", "4", "6", "8", "10", "x (m)", "y (m)", "scale bar 2 m"})
    EXPECT_TRUE(has_text(svg, t)) << t << "\n" << svg;
  EXPECT_NE(svg.find("deformation true scale"), std::string::npos);
  // The colour bar's labels come first among the numbers (tests/cli/picture_facts.py reads
  // them so): 0 to 0.3 m = 150 mm mean over the element's four vertices.
  const std::vector<std::string> t = texts(svg);
  const auto first = std::find(t.begin(), t.end(), "0");
  ASSERT_NE(first, t.end());
  EXPECT_EQ(*(first + 4), "150");
}

TEST(Pictures, SmallDisplacementsAreExaggeratedInTheDrawingOnly) {
  const Mesh m = one_block(0.5);
  // 0.4 mm at the top: 4e-5 of the model. Factor 0.05 × 10 / 4e-4 = 1250 → 1000.
  std::vector<double> xy;
  const std::string automatic = draw(m, 4e-4, 0, "ok", 0, &xy);
  EXPECT_NE(automatic.find("displacement ×1000"), std::string::npos) << automatic;
  // The top corners drawn 0.4 m right of where they started; the colour bar in true mm.
  EXPECT_NE(automatic.find("10.4,-4 0.4,-4"), std::string::npos) << automatic;
  const std::string true_scale = draw(m, 4e-4, 0, "ok", 1);
  EXPECT_NE(true_scale.find("deformation true scale"), std::string::npos);
  EXPECT_NE(true_scale.find("10.0004,-4 0.0004,-4"), std::string::npos) << true_scale;
  auto bar = [](const std::string& svg) {
    std::vector<std::string> t = texts(svg);
    const auto first = std::find(t.begin(), t.end(), "0");
    return std::vector<std::string>(first, first + 5);
  };
  EXPECT_EQ(bar(automatic), bar(true_scale));
  EXPECT_EQ(bar(automatic).back(), "0.2");  // mm: mean of 0, 0, 0.4, 0.4
  // A factor asked for is drawn as asked, whatever the displacement.
  EXPECT_NE(draw(m, 4e-4, 0, "ok", 200).find("displacement ×200"), std::string::npos);
  EXPECT_NE(draw(m, 0.3, 0, "ok", 5).find("displacement ×5"), std::string::npos);
}

TEST(Pictures, AFailedRunsReasonIsWrappedUnderThePicture) {
  const std::string reason =
      "time step cut below its floor (1e-05 s) at t = 0.0123 s because one step moved a cover by "
      "0.0812 m, more than the 0.06 m a step may move (2 × max_displacement_ratio 0.01 × w0 3 m, "
      "w0 being half the model size as in DDA)";
  const Mesh coarse = one_block(10);  // the body is 10 m × 4 m
  const std::string svg = draw(coarse, 0.3, 0, reason, 0, nullptr, StopCode::step_displacement);
  EXPECT_NE(svg.find("block  t = 0.5 s  (stopped, reason below)"), std::string::npos);
  // The title is short: the reason is not in it.
  for (const std::string& t : texts(svg))
    if (t.find("(stopped, reason below)") != std::string::npos) {
      EXPECT_LT(t.size(), 90u) << t;
    }
  // Reason and cause, each wrapped into lines that together are the whole sentence.
  std::string joined;
  std::size_t reason_lines = 0, longest = 0;
  bool in_reason = false;
  for (const std::string& t : texts(svg)) {
    if (t.rfind("stopped: ", 0) == 0) in_reason = true;
    if (t.rfind("likely cause: ", 0) == 0) in_reason = false;
    if (in_reason) {
      joined += (joined.empty() ? "" : " ") + t;
      ++reason_lines;
      longest = std::max(longest, t.size());
    }
  }
  EXPECT_EQ(joined, "stopped: " + reason);
  EXPECT_GE(reason_lines, 2u);
  // No wider than the picture: the drawing keeps the width it has without the reason.
  auto width = [](const std::string& doc) {
    const std::regex vb("viewBox=\"([-0-9.e]+) ([-0-9.e]+) ([-0-9.e]+) ([-0-9.e]+)\"");
    std::smatch mm;
    return std::regex_search(doc, mm, vb) ? std::stod(mm[3]) : -1.0;
  };
  EXPECT_DOUBLE_EQ(width(svg), width(draw(coarse, 0.3, 0, "ok", 0)));
  const std::string cause = report::likely_failure_cause(coarse, one_block_scene(), StopCode::step_displacement);
  EXPECT_NE(cause.find("mesh size 10 m against body 0, 10 m wide and 4 m high: the mesh is "
                       "coarser than the body"),
            std::string::npos)
      << cause;
  EXPECT_NE(svg.find("likely cause: mesh size 10 m"), std::string::npos);
  // A mesh finer than the body: the cause follows the kind of failure.
  EXPECT_NE(report::likely_failure_cause(one_block(0.5), one_block_scene(), StopCode::step_displacement)
                .find("a block moved farther in one step than contacts can follow"),
            std::string::npos);
  EXPECT_EQ(report::likely_failure_cause(coarse, one_block_scene(), StopCode::ok), "");
  EXPECT_EQ(report::likely_failure_cause(coarse, one_block_scene(), StopCode::interrupted), "");
  EXPECT_NE(report::likely_failure_cause(one_block(0.5), one_block_scene(), StopCode::unconstrained)
                .find("a block is held by nothing"),
            std::string::npos);
  EXPECT_EQ(draw(coarse, 0.3, 0, "ok", 0).find("likely cause"), std::string::npos);
  EXPECT_EQ(draw(coarse, 0.3, 0, "step 30", 0).find("stopped"), std::string::npos);
}

// How a finished run ended, read back from its summary.json: by its stop_code; an older summary
// without one by its status (ok, interrupted, anything else a failure).
TEST(Pictures, RunOutcomeFromSummary) {
  using nlohmann::json;
  const Outcome stopped = report::run_outcome(
      json{{"status", "a contact penetrated 0.3 m"}, {"stop_code", "penetration"}, {"stop_time", 1.5}});
  EXPECT_EQ(stopped.code, StopCode::penetration);
  EXPECT_EQ(stopped.reason, "a contact penetrated 0.3 m");
  EXPECT_EQ(stopped.time, 1.5);
  EXPECT_TRUE(stopped.failed());
  EXPECT_TRUE(report::run_outcome(json{{"status", "ok"}, {"stop_code", "ok"}}).ok());
  EXPECT_EQ(report::run_outcome(json{{"status", "interrupted"}}).code, StopCode::interrupted);
  EXPECT_EQ(report::run_outcome(json{{"status", "not positive definite"}}).code, StopCode::failed);
  EXPECT_EQ(report::run_outcome(json{{"status", "okay"}}).code, StopCode::failed);  // only the exact word
  EXPECT_EQ(report::run_outcome(json::object()).code, StopCode::failed);
  // Every code's name reads back as the code.
  for (StopCode c : {StopCode::ok, StopCode::interrupted, StopCode::step_displacement, StopCode::penetration,
                     StopCode::contact_not_converged, StopCode::direction_not_finite, StopCode::bolts_not_settled,
                     StopCode::fracture_cascade, StopCode::flow_not_converged, StopCode::unconstrained,
                     StopCode::element_folded, StopCode::displacement_not_finite, StopCode::failed}) {
    StopCode back = StopCode::ok;
    EXPECT_TRUE(stop_code_from_name(stop_code_name(c), back)) << stop_code_name(c);
    EXPECT_EQ(back, c);
  }
}

TEST(Pictures, WordsWrapToTheWidth) {
  EXPECT_EQ(wrap_words("aa bb cc dd", 5), (std::vector<std::string>{"aa bb", "cc dd"}));
  EXPECT_EQ(wrap_words("aaaaaaa b", 5), (std::vector<std::string>{"aaaaaaa", "b"}));
  EXPECT_EQ(wrap_words("× × ×", 3), (std::vector<std::string>{"× ×", "×"}));  // code points
  EXPECT_EQ(wrap_words("", 5), std::vector<std::string>{});
}

TEST(Pictures, EngineeringNumbers) {
  EXPECT_EQ(format_engineering(5.576478281, "s"), "5.58 s");
  EXPECT_EQ(format_engineering(1.2e-4, "m"), "120 µm");
  EXPECT_EQ(format_engineering(0.2, "s"), "200 ms");
  EXPECT_EQ(format_engineering(1e10, "N/m"), "10 GN/m");
  EXPECT_EQ(format_engineering(999.7, "m"), "1 km");
  EXPECT_EQ(format_engineering(-18812.3, "J/m"), "-18.8 kJ/m");
  EXPECT_EQ(format_engineering(0, "s"), "0 s");
  EXPECT_EQ(format_engineering(12.345, ""), "12.3");
  EXPECT_EQ(format_engineering(1.5e9, ""), "1.50e+09");
}

TEST(Pictures, SweepGridHasAPanelPerParameterAndOutput) {
  studies::Sweep sweep;
  sweep.parameters = {"variant", "joint_sets.interface.friction_deg"};
  sweep.summary_outputs = {"status", "max_penetration"};
  sweep.history_outputs = {"ux"};
  const std::string csv =
      "run,name,variant,joint_sets.interface.friction_deg,exit,run_status,job_wall_seconds,"
      "summary.status,summary.max_penetration,history.ux.p0\n"
      "r0001,springs,springs,10,0,ok,1.0,ok,1e-4,0.30\n"
      "r0002,springs,springs,20,0,ok,1.0,ok,2e-4,0.15\n"
      "r0003,springs,springs,40,0,ok,1.0,ok,3e-4,0.001\n"
      "r0004,joint-laws,joint-laws,10,0,ok,1.0,ok,1e-4,0.31\n"
      "r0005,joint-laws,joint-laws,20,3,\"time step cut below its floor, at t = 0.1 s\",1.0,"
      "\"time step cut below its floor, at t = 0.1 s\",2e-4,0.2\n"
      "r0006,joint-laws,joint-laws,40,0,ok,1.0,ok,3e-4,0.002\n";
  EXPECT_EQ(studies::split_csv_line("a,\"b,\"\"c\"\"\",d"),
            (std::vector<std::string>{"a", "b,\"c\"", "d"}));
  std::size_t panels = 0;
  const std::string svg = studies::sweep_svg(sweep, csv, &panels);
  // 2 parameters × 2 numeric outputs (summary.status is text: no panel).
  EXPECT_EQ(panels, 4u);
  EXPECT_EQ(count(svg, "<svg "), 5u) << "the grid and its four panels";
  for (const char* p : {"max_penetration against variant", "max_penetration against friction_deg",
                        "ux of point 0 against variant", "ux of point 0 against friction_deg"})
    EXPECT_EQ(count(svg, std::string(">") + p + "<"), 1u) << p;
  EXPECT_EQ(svg.find("status against"), std::string::npos);
  // Axis labels with the full column names.
  EXPECT_EQ(count(svg, ">joint_sets.interface.friction_deg<"), 2u);
  EXPECT_EQ(count(svg, ">history.ux.p0<"), 2u);
  // Variant names are categories on the axis; a line per variant along the friction angle, a
  // line per friction angle across the variants; the run that stopped in a series of its own.
  EXPECT_EQ(count(svg, ">springs<"), 2u);
  EXPECT_EQ(count(svg, ">joint-laws<"), 2u);
  EXPECT_NE(svg.find(">variant springs<"), std::string::npos);
  EXPECT_NE(svg.find(">friction_deg 10<"), std::string::npos);
  EXPECT_NE(svg.find(">stopped runs<"), std::string::npos);
  // Two columns: the second panel starts at the first's width.
  EXPECT_NE(svg.find("<svg x=\"480\" y=\"0\""), std::string::npos);
  sweep.parameters.clear();
  EXPECT_EQ(studies::sweep_svg(sweep, csv), "");
}

TEST(Pictures, AMechanismThatCannotBeDrawnIsARunErrorAndNoFile) {
  // nmm-fos warns and goes on (its factor is the result); the trial folder is its own output.
  const std::string svg = (std::filesystem::temp_directory_path() / "nmm_no_mechanism.svg").string();
  std::filesystem::remove(svg);
  EXPECT_THROW(studies::write_mechanism_svg("/nonexistent/trial/out", "t", svg), RunError);
  EXPECT_FALSE(std::filesystem::exists(svg));
}

TEST(Pictures, ColourMapIsViridis) {
  EXPECT_STREQ(report::kColourMapName, "viridis");
  EXPECT_EQ(report::colour_map(0), "#440154");
  EXPECT_EQ(report::colour_map(0.5), "#21918c");
  EXPECT_EQ(report::colour_map(1), "#fde725");
  EXPECT_EQ(report::colour_map(NAN), "#440154");
}

}  // namespace
}  // namespace nmm
