// Inertia in the model (the assembly a dynamic analysis' time integrator
// will drive): Model::kineticEnergy, applyMass and the Inertia term of
// Model::assemble, on a 2-D two-body mesh and a 3-D block, on 1 and 2 ranks.
//  - ½ vᵀ M v of a rigid translation is ½ m |c|² with m = ρ V of the mesh,
//    consistent and HRZ-lumped;
//  - assembling with Inertia{a, c, w} adds w M a to the residual (free DOFs
//    only, fint unchanged) and c M to the tangent: (K_c − K_0) v = c M v;
//  - a model whose body has no density refuses, on every rank;
//  - a tangent not made by Model::createMatrix() is refused.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "DDC_ElementFactory.hpp"
#include "DDC_MeshGenerators.hpp"
#include "DDC_Model.hpp"
#include "DDC_Partition.hpp"

namespace {

using PL = Teuchos::ParameterList;

/// Mass density of the test bodies.
constexpr double kRho = 2.5;
/// Round-off of global sums of O(100) element contributions.
constexpr double kRoundoff = 1e-12;

Teuchos::RCP<const Teuchos::Comm<int>> comm() { return Tpetra::getDefaultComm(); }

/// Two stacked 2-D blocks (Quad4 and Quad9) or one Hex8 block; every body
/// with density `rho`. Returns the model and the mesh volume (area in 2-D).
std::unique_ptr<ddc::Model> makeModel(int dim, double rho, double& volume,
                                      ddc::BoundaryConditions bcs = ddc::BoundaryConditions{}) {
  auto mesh = std::make_shared<ddc::Mesh>();
  std::vector<std::shared_ptr<const ddc::Element>> elements;
  auto element = [&](const char* type) {
    PL el("Element");
    el.set("Type", std::string(type));
    el.sublist("Material").set("Type", std::string("Neo-Hookean"));
    el.sublist("Material").set("Density", rho);
    elements.push_back(ddc::ElementFactory::withBuiltins().create(el, "Element"));
  };
  if (dim == 2) {
    for (const auto& [name, y0, nx, type] :
         {std::tuple<const char*, double, int, ddc::CellType>{"Lower", 0.0, 5, ddc::CellType::Quad4},
          {"Upper", 0.5, 3, ddc::CellType::Quad9}}) {
      PL rect("Rectangle");
      rect.set("Origin Y", y0);
      rect.set("Length X", 2.0);
      rect.set("Length Y", 0.5);
      rect.set("Elements X", nx);
      rect.set("Elements Y", 2);
      ddc::generateRectangle(*mesh, name, type, rect, "Rectangle");
    }
    element("Quad4");
    element("Quad9");
    volume = 2.0;
  } else {
    PL box("Box");
    box.set("Length X", 2.0);
    box.set("Length Y", 1.0);
    box.set("Length Z", 0.5);
    box.set("Elements X", 4);
    box.set("Elements Y", 2);
    box.set("Elements Z", 2);
    ddc::generateBox(*mesh, "Block", ddc::CellType::Hex8, box, "Box");
    element("Hex8");
    volume = 1.0;
  }
  return std::make_unique<ddc::Model>(comm(), mesh, elements, ddc::partitionMetis(*mesh, comm()->getSize()),
                                      std::move(bcs));
}

/// A uniform velocity c on every node of the model.
Teuchos::RCP<ddc::Vector> uniform(const ddc::Model& m, const Eigen::Vector3d& c) {
  auto v = m.createVector();
  for (int n = 0; n < m.mesh().numNodes(); ++n)
    for (int k = 0; k < m.dim(); ++k) {
      const ddc::GO g = m.dof(n, k);
      if (v->getMap()->isNodeGlobalElement(g)) v->replaceGlobalValue(g, c[k]);
    }
  return v;
}

class Inertia : public testing::TestWithParam<int> {};

TEST_P(Inertia, RigidTranslationKineticEnergyIsHalfTheMassTimesTheSpeedSquared) {
  double V = 0.0;
  auto m = makeModel(GetParam(), kRho, V);
  EXPECT_TRUE(m->bodiesWithoutMass().empty());
  const Eigen::Vector3d c(0.3, -0.4, GetParam() == 3 ? 1.2 : 0.0);
  const auto v = uniform(*m, c);
  for (ddc::MassLumping l : {ddc::MassLumping::Consistent, ddc::MassLumping::HRZ, ddc::MassLumping::RowSum}) {
    m->setMassLumping(l);
    EXPECT_NEAR(m->kineticEnergy(*v) / (0.5 * kRho * V * c.squaredNorm()), 1.0, kRoundoff) << int(l);
  }
}

TEST_P(Inertia, AssemblyAddsMassTimesAccelerationAndTheMassToTheTangent) {
  double V = 0.0;
  auto m = makeModel(GetParam(), kRho, V);
  const int d = GetParam();
  auto u = m->createVector();
  u->randomize(-0.01, 0.01);  // a small deformation
  const Eigen::Vector3d c(1.5, -0.5, 0.25);
  const auto a = uniform(*m, c);
  auto r0 = m->createVector(), r1 = m->createVector(), f0 = m->createVector(), f1 = m->createVector();
  auto K0 = m->createMatrix(), K1 = m->createMatrix();
  const double factor = 7.0, weight = 0.75;
  ddc::Inertia inertia;
  inertia.acceleration = a.get();
  inertia.tangentFactor = factor;
  inertia.residualFactor = weight;
  ddc::AssemblyRequest plain;
  plain.fint = f0.get();
  plain.residual = r0.get();
  plain.tangent = K0.get();
  m->assemble(*u, 0.0, plain);
  ddc::AssemblyRequest withInertia;
  withInertia.fint = f1.get();
  withInertia.residual = r1.get();
  withInertia.tangent = K1.get();
  withInertia.inertia = &inertia;
  m->assemble(*u, 0.0, withInertia);
  // fint unchanged; the residual grows by w M a, whose components sum to w m c.
  f1->update(-1.0, *f0, 1.0);
  EXPECT_EQ(f1->normInf(), 0.0) << "fint holds the internal force only";
  r1->update(-1.0, *r0, 1.0);
  auto Ma = m->createVector();
  m->applyMass(*a, *Ma);
  auto diff = m->createVector();
  diff->update(1.0, *r1, -weight, *Ma, 0.0);
  EXPECT_LT(diff->normInf(), kRoundoff * Ma->normInf());
  std::vector<double> sums(3, 0.0), total(3, 0.0);
  {
    auto rd = r1->getData();
    for (int n = 0; n < m->mesh().numNodes(); ++n)
      for (int k = 0; k < d; ++k) {
        const ddc::LO l = r1->getMap()->getLocalElement(m->dof(n, k));
        if (l != Teuchos::OrdinalTraits<ddc::LO>::invalid()) sums[k] += rd[l];
      }
  }
  Teuchos::reduceAll(*comm(), Teuchos::REDUCE_SUM, 3, sums.data(), total.data());
  for (int k = 0; k < d; ++k) EXPECT_NEAR(total[k], weight * kRho * V * c[k], kRoundoff * kRho * V) << k;
  // (K_c − K_0) v = c M v for any v.
  auto v = m->createVector();
  v->randomize();
  auto Kv0 = m->createVector(), Kv1 = m->createVector(), Mv = m->createVector();
  K0->apply(*v, *Kv0);
  K1->apply(*v, *Kv1);
  m->applyMass(*v, *Mv);
  const double scale = Kv1->normInf();  // the difference cancels entries of this size
  Kv1->update(-1.0, *Kv0, -factor, *Mv, 1.0);
  EXPECT_LT(Kv1->normInf(), kRoundoff * scale);
}

TEST_P(Inertia, ABodyWithoutDensityIsRefusedOnEveryRank) {
  double V = 0.0;
  auto m = makeModel(GetParam(), 0.0, V);
  ASSERT_FALSE(m->bodiesWithoutMass().empty());
  auto v = m->createVector();
  EXPECT_THROW(m->kineticEnergy(*v), std::logic_error);
}

// The owned rows of the tangent are summed in place by the local indices of
// the model's own pattern, so a matrix of another pattern would be filled
// wrongly: it is refused (on every rank, before any communication).
TEST_P(Inertia, ATangentOfAnotherPatternIsRefused) {
  double V = 0.0;
  auto m = makeModel(GetParam(), kRho, V);
  auto diagonal = Teuchos::rcp(new ddc::CrsGraph(m->ownedMap(), 1));
  for (size_t l = 0; l < m->ownedMap()->getNodeNumElements(); ++l) {
    const ddc::GO g = m->ownedMap()->getGlobalElement(ddc::LO(l));
    diagonal->insertGlobalIndices(g, Teuchos::tuple<ddc::GO>(g));
  }
  diagonal->fillComplete();
  ddc::CrsMatrix K(diagonal);
  K.fillComplete();
  auto u = m->createVector();
  ddc::AssemblyRequest request;
  request.tangent = &K;
  EXPECT_THROW(m->assemble(*u, 0.0, request), std::logic_error);
  const auto own = m->createMatrix();
  request.tangent = own.get();
  EXPECT_NO_THROW(m->assemble(*u, 0.0, request));
}

INSTANTIATE_TEST_SUITE_P(Dimensions, Inertia, testing::Values(2, 3),
                         [](const testing::TestParamInfo<int>& i) { return std::to_string(i.param) + "D"; });

}  // namespace
