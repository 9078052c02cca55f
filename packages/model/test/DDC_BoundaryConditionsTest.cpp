// Boundary conditions in 2-D and 3-D (packages/model/src/DDC_BoundaryConditions.hpp):
// the prescribed field u(X, λ) = λ(v + H(X − c)) + (R(λθ, a) − I)(X − c),
// component selection and the dimension checks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "DDC_BoundaryConditions.hpp"
#include "DDC_Mesh.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

using ddc::BoundaryConditions;
using ddc::CellType;
using ::testing::HasSubstr;
using PL = Teuchos::ParameterList;

namespace {

using ddc::test::inputErrorOf;
using ddc::test::kRoundoff;

/// One element of `type` on its reference cell, node set "Body/all".
ddc::Mesh oneCell(CellType type) {
  ddc::Mesh m;
  const int b = m.beginBody("Body", type);
  std::vector<int> nodes;
  for (const auto& x : ddc::referenceCell(type).nodes) nodes.push_back(m.addNode(x[0], x[1], x[2]));
  m.addElement(nodes.data());
  m.addNodeSet(b, "all", nodes);
  return m;
}

/// oneCell() with its first face as the side set "Body/all" too (what a
/// traction acts on).
ddc::Mesh oneCellWithFace(CellType type) {
  ddc::Mesh m = oneCell(type);
  m.addSideSet(0, "all", {m.makeSegment(0, 0)});
  return m;
}

BoundaryConditions parse(const ddc::Mesh& m, PL condition) {
  PL list("Boundary Conditions");
  condition.set("Set", "Body/all");
  list.set("C", condition);
  return BoundaryConditions::fromParameters(list, m, "Boundary Conditions");
}

std::string errorOf(const ddc::Mesh& m, const PL& condition) {
  return inputErrorOf([&] { parse(m, condition); });
}

TEST(BoundaryConditions, ComponentsAllMeansEveryComponentOfTheModel) {
  const auto bc2 = parse(oneCell(CellType::Quad4), PL()).displacements.at(0);
  EXPECT_TRUE(bc2.fix[0] && bc2.fix[1] && !bc2.fix[2]);
  const auto bc3 = parse(oneCell(CellType::Hex8), PL()).displacements.at(0);
  EXPECT_TRUE(bc3.fix[0] && bc3.fix[1] && bc3.fix[2]);
  PL xz;
  xz.set("Components", "XZ");
  const auto bc = parse(oneCell(CellType::Tet4), xz).displacements.at(0);
  EXPECT_TRUE(bc.fix[0] && !bc.fix[1] && bc.fix[2]);
}

// A rotation about an arbitrary axis through an arbitrary centre plus an
// affine field: the prescribed displacement is the closed form (Eigen's
// AngleAxis for R).
TEST(BoundaryConditions, RotationAboutAnArbitraryAxisIn3D) {
  PL p;
  p.set("Rotation Angle", 90.0);
  p.set("Rotation Axis X", 1.0);
  p.set("Rotation Axis Y", 2.0);
  p.set("Rotation Axis Z", -0.5);
  p.set("Center X", 0.3);
  p.set("Center Y", -0.2);
  p.set("Center Z", 0.7);
  p.set("Value Z", 0.05);
  p.set("Gradient ZX", 0.01);
  p.set("Gradient XZ", -0.02);
  const auto bc = parse(oneCell(CellType::Hex8), p).displacements.at(0);
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -0.5).normalized(), c(0.3, -0.2, 0.7);
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  H(2, 0) = 0.01;
  H(0, 2) = -0.02;
  for (double lambda : {0.25, 1.0}) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(lambda * M_PI / 2, axis).toRotationMatrix();
    for (const std::array<double, 3>& X : {std::array<double, 3>{1.0, -1.0, 0.5}, std::array<double, 3>{-0.4, 2.0, 3.0}}) {
      const Eigen::Vector3d d = Eigen::Vector3d(X[0], X[1], X[2]) - c;
      const Eigen::Vector3d expected = lambda * (Eigen::Vector3d(0, 0, 0.05) + H * d) + (R - Eigen::Matrix3d::Identity()) * d;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(bc.prescribed(k, X, lambda), expected[k], kRoundoff) << "component " << k;
    }
  }
}

// In 2-D the rotation is about z and equals the plane rotation written out,
// bit for bit (2-D results must not change).
TEST(BoundaryConditions, PlaneRotationIsUnchanged) {
  PL p;
  p.set("Rotation Angle", 37.0);
  p.set("Center X", 0.25);
  p.set("Center Y", -1.5);
  const auto bc = parse(oneCell(CellType::Quad9), p).displacements.at(0);
  const std::array<double, 3> X{0.7, 0.4, 0.0};
  const double a = 0.6 * 37.0 * M_PI / 180.0, dx = X[0] - 0.25, dy = X[1] + 1.5;
  EXPECT_EQ(bc.prescribed(0, X, 0.6), (std::cos(a) * dx - std::sin(a) * dy) - dx);
  EXPECT_EQ(bc.prescribed(1, X, 0.6), (std::sin(a) * dx + std::cos(a) * dy) - dy);
}

TEST(BoundaryConditions, ZOnA2DModelIsAnError) {
  const auto m = oneCell(CellType::Quad4);
  for (const char* key : {"Value Z", "Center Z", "Gradient ZX", "Gradient XZ", "Rotation Axis X"}) {
    PL p;
    p.set(key, 1.0);
    EXPECT_THAT(errorOf(m, p), HasSubstr("parameter 'Boundary Conditions/C/" + std::string(key) +
                                         "' is set but the model is 2-D; Z applies to 3-D models only"));
  }
  PL comps;
  comps.set("Components", "YZ");
  EXPECT_THAT(errorOf(m, comps), HasSubstr("'Boundary Conditions/C/Components' = YZ prescribes Z but the model is 2-D"));
  PL traction;
  traction.set("Type", "Traction");
  traction.set("Traction Z", 2.0);
  ddc::Mesh sides = oneCell(CellType::Quad4);
  sides.addSideSet(0, "all", {sides.makeSegment(0, 0)});
  EXPECT_THAT(errorOf(sides, traction), HasSubstr("'Boundary Conditions/C/Traction Z' is set but the model is 2-D"));
}

TEST(BoundaryConditions, RotationNeedsEveryComponentAndAnAxis) {
  const auto m = oneCell(CellType::Hex20);
  PL p;
  p.set("Rotation Angle", 10.0);
  p.set("Components", "XY");
  EXPECT_THAT(errorOf(m, p), HasSubstr("a Rotation Angle needs every component prescribed (Components = All)"));
  PL q;
  q.set("Rotation Angle", 10.0);
  q.set("Rotation Axis Z", 0.0);
  EXPECT_THAT(errorOf(m, q), HasSubstr("the rotation axis (Rotation Axis X/Y/Z) must have a finite length > 0"));
  PL r;
  r.set("Components", "XY");
  r.set("Value Z", 1.0);
  EXPECT_THAT(errorOf(m, r), HasSubstr("'Boundary Conditions/C/Value Z' is set but Components = XY does not prescribe Z"));
}

// A load curve scales values, gradient and angle by s(λ), piecewise linear
// through its points and constant beyond them: a press then a slide.
TEST(BoundaryConditions, LoadCurveScalesTheWholeField) {
  const auto m = oneCell(CellType::Hex8);
  PL press;
  press.set("Components", "Y");
  press.set("Value Y", -1.4);
  press.set("Load Curve", "0 0, 0.25 1, 1 1");
  const auto p = parse(m, press).displacements.at(0);
  const std::array<double, 3> X{0.5, 0.5, 0.5};
  EXPECT_NEAR(p.prescribed(1, X, 0.125), -0.7, kRoundoff);
  EXPECT_NEAR(p.prescribed(1, X, 0.25), -1.4, kRoundoff);
  EXPECT_NEAR(p.prescribed(1, X, 0.6), -1.4, kRoundoff);
  EXPECT_NEAR(p.prescribed(1, X, 2.0), -1.4, kRoundoff);  // constant beyond the last point
  PL slide;
  slide.set("Components", "X");
  slide.set("Value X", 4.0);
  slide.set("Gradient XY", 2.0);
  slide.set("Load Curve", "0 0,0.25 0,  1 1");
  const auto s = parse(m, slide).displacements.at(0);
  EXPECT_EQ(s.prescribed(0, X, 0.2), 0.0);
  EXPECT_NEAR(s.prescribed(0, X, 0.625), 0.5 * (4.0 + 2.0 * 0.5), kRoundoff);
  // No curve: s = λ, as before.
  PL plain;
  plain.set("Value X", 3.0);
  EXPECT_NEAR(parse(m, plain).displacements.at(0).prescribed(0, X, 0.3), 0.9, kRoundoff);
  // The angle too: a quarter turn by λ = 0.5, held.
  PL turn;
  turn.set("Rotation Angle", 90.0);
  turn.set("Load Curve", "0 0, 0.5 1");
  const auto t = parse(m, turn).displacements.at(0);
  const std::array<double, 3> e1{1.0, 0.0, 0.0};
  EXPECT_NEAR(t.prescribed(0, e1, 0.8), -1.0, kRoundoff);
  EXPECT_NEAR(t.prescribed(1, e1, 0.8), 1.0, kRoundoff);
}

TEST(BoundaryConditions, LoadCurveErrorsNameThePath) {
  const auto m = oneCell(CellType::Hex8);
  auto curve = [&](const std::string& text) {
    PL p;
    p.set("Load Curve", text);
    return errorOf(m, p);
  };
  EXPECT_THAT(curve("0 0, 0.5"), HasSubstr("parameter 'Boundary Conditions/C/Load Curve' = '0 0, 0.5': cannot read ' 0.5'"));
  EXPECT_THAT(curve("0 0, 0.5 1 2"), HasSubstr("cannot read ' 0.5 1 2'"));
  EXPECT_THAT(curve("0 0, x 1"), HasSubstr("cannot read ' x 1'"));
  EXPECT_THAT(curve("0 0, 0.5 1, 0.5 2"), HasSubstr("the load factors must increase strictly (0.5 follows 0.5)"));
  EXPECT_THAT(curve("0 1"), HasSubstr("a load curve needs at least two points"));
  EXPECT_THAT(curve("0 0, inf 1"), HasSubstr("cannot read ' inf 1'"));
  // A traction's curve is read alike: the same errors, naming the path.
  const auto face = oneCellWithFace(CellType::Hex8);
  PL t;
  t.set("Type", "Traction");
  t.set("Load Curve", "0 0, 0.5 1, 0.5 2");
  EXPECT_THAT(errorOf(face, t), HasSubstr("parameter 'Boundary Conditions/C/Load Curve' = '0 0, 0.5 1, 0.5 2': the load "
                                       "factors must increase strictly (0.5 follows 0.5)"));
}

// A traction's load curve scales it as a displacement's: '0 0, 0.5 0, 1 1'
// (a push after a press) is nothing up to load factor 0.5, then grows to
// the whole traction at 1; without a curve s = λ.
TEST(BoundaryConditions, LoadCurveScalesATraction) {
  const auto m = oneCellWithFace(CellType::Hex8);
  PL push;
  push.set("Type", "Traction");
  push.set("Traction X", 2.0);
  push.set("Load Curve", "0 0, 0.5 0, 1 1");
  const auto t = parse(m, push).tractions.at(0);
  EXPECT_EQ(t.traction[0], 2.0);
  EXPECT_EQ(t.scale(0.25), 0.0);
  EXPECT_EQ(t.scale(0.5), 0.0);
  EXPECT_NEAR(t.scale(0.75), 0.5, kRoundoff);
  EXPECT_EQ(t.scale(1.0), 1.0);
  PL plain;
  plain.set("Type", "Traction");
  EXPECT_EQ(parse(m, plain).tractions.at(0).scale(0.3), 0.3);
}

}  // namespace
