// Tests of the mesh lattice and its range checks (common/lattice.h): the numbers derived from a
// scene's mesh size are bounded before they are used, and the cutter's lattice covers the bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/lattice.h"
#include "common/scene.h"

namespace nmm {
namespace {

std::vector<BodyDef> box_body(double x0, double y0, double x1, double y1) {
  BodyDef b;
  b.material = 0;
  b.outer = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  return {b};
}

TEST(Lattice, CoversTheBodiesWithOneRowAndColumnToSpare) {
  const auto bodies = box_body(-3.2, 1.1, 7.9, 4.4);
  const double h = 0.5;
  ASSERT_EQ(lattice_problem(bodies, h), "");
  const Lattice L = make_lattice(bodies, h);
  const double dy = h * std::sqrt(3.0) / 2.0;
  EXPECT_DOUBLE_EQ(L.dy, dy);
  // Every node row and column lies within the box widened by 1.5 h and 2 dy, and the box lies
  // strictly inside the lattice's first and last full rows and columns.
  const Vec2 lo = L.node(L.i0, L.j0), hi = L.node(L.i0 + L.ni - 1, L.j0 + L.nj - 1);
  EXPECT_LT(lo.x, -3.2 - 0.5 * h);
  EXPECT_LT(lo.y, 1.1);
  EXPECT_GT(hi.x, 7.9 + 0.5 * h);
  EXPECT_GT(hi.y, 4.4);
  EXPECT_GE(lo.x, -3.2 - 2 * h);
  EXPECT_LE(hi.y, 4.4 + 2 * dy);
  EXPECT_EQ(L.index(L.i0, L.j0), 0);
  EXPECT_EQ(L.index(L.i0 + L.ni - 1, L.j0 + L.nj - 1), L.nodes() - 1);
}

TEST(Lattice, HugeMeshSizesAreRefusedBeforeAnyProductOverflows) {
  const auto bodies = box_body(0, 0, 10, 5);
  for (double h : {1e308, std::numeric_limits<double>::max(), 1e200, 1e20, 1e8}) {
    const std::string problem = lattice_problem(bodies, h);
    EXPECT_NE(problem.find("is too large"), std::string::npos) << h << ": " << problem;
    EXPECT_THROW(make_lattice(bodies, h), std::logic_error);
  }
  // Up to the bodies' own reach the lattice is fine: nodes at most 2.5e7 m out.
  EXPECT_EQ(lattice_problem(bodies, 1e7), "");
  EXPECT_EQ(lattice_problem(box_body(-1e7, -1e7, 1e7, 1e7), 1e7), "");
}

TEST(Lattice, TinyMeshSizesAreRefusedByTheTriangleCount) {
  const auto bodies = box_body(0, 0, 10, 5);
  for (double h : {1e-3, 1e-100, 4.9e-324}) {
    const std::string problem = lattice_problem(bodies, h);
    EXPECT_NE(problem.find("triangles over the bodies' bounding box"), std::string::npos)
        << h << ": " << problem;
  }
  EXPECT_NE(lattice_problem(bodies, 1e-200).find("more than 1e+308"), std::string::npos);
}

TEST(Lattice, NonPositiveOrNonFiniteSizesAreNamed) {
  const auto bodies = box_body(0, 0, 1, 1);
  for (double h : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_NE(lattice_problem(bodies, h), "") << h;
}

TEST(Lattice, SceneWithMeshSize1e308ExitsAsBadInputNamingTheSize) {
  try {
    parse_scene(R"({ "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
      "bodies": [ { "material": "rock", "outer": [[0,0],[10,0],[10,5],[0,5]] } ],
      "mesh": { "size": 1e308 } })",
                "big.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/mesh/size");
    EXPECT_NE(e.message().find("mesh size 1e+308 m is too large"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nmm
