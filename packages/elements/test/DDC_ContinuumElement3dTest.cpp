// 3-D continuum elements (Hex8, Hex20, Hex27, Tet4, Tet10) with each
// material: derivative checks against central finite differences,
// symmetry, self-equilibrated forces, homogeneous deformations against the
// closed-form laws on distorted (curved) elements, 90-degree rigid rotation,
// a neo-Hookean cube in homogeneous stretch, patch tests on distorted
// multi-element meshes, plane-strain consistency with Quad4/Quad9, inverted
// and degenerate elements.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include "DDC_ContinuumElement.hpp"
#include "DDC_ElementTestSupport.hpp"
#include "DDC_ShapeFunctions.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::CellType;
using ddc::test::centralDifferences;
using ddc::test::flatten;
using ddc::test::homogeneousDisplacement;
using ddc::test::kDisplacementScale;
using ddc::test::kFdStep;
using ddc::test::kFiniteDifference;
using ddc::test::kRoundoff;
using ddc::test::kTestE;
using ddc::test::kTestNu;
using ddc::test::makeTestElement;
using ddc::test::randomNodal;
using ddc::test::relDiff;
using ddc::test::scientific;
using ddc::test::unflatten;

const std::vector<std::string> k3dElements = {"Hex8", "Hex20", "Hex27", "Tet4", "Tet10"};
const std::vector<std::string> kMaterials = {"Neo-Hookean", "St. Venant-Kirchhoff", "Linear Elastic"};

CellType cellOf(const std::string& name) {
  for (CellType t : ddc::elementCellTypes())
    if (name == ddc::cellTypeName(t)) return t;
  throw std::invalid_argument("no cell type " + name);
}

/// Linear part of the reference-to-physical maps below: a general
/// (non-orthogonal, unequal) stretch and shear of the reference cell.
Eigen::Matrix3d geometryMap() {
  Eigen::Matrix3d A;
  A << 1.1, 0.15, -0.1,  //
      0.05, 0.95, 0.12,  //
      -0.08, 0.1, 1.05;
  return A;
}

/// Reference volume of a cell: 8 for [-1,1]^3, 1/6 for the unit tetrahedron.
double referenceVolume(CellType t) { return ddc::referenceCell(t).simplex ? 1.0 / 6.0 : 8.0; }

/// Nodes of an affine image of the reference cell (a parallelepiped or a
/// general tetrahedron, straight edges, mid-nodes at the edge middles);
/// its volume is det(A) times the reference volume.
Eigen::MatrixXd affineNodes(CellType t) {
  const auto& c = ddc::referenceCell(t);
  const double s = c.simplex ? 2.0 : 1.0;  // both about 2 across
  Eigen::MatrixXd X(c.numNodes, 3);
  for (int a = 0; a < c.numNodes; ++a)
    X.row(a) = (s * geometryMap() * Eigen::Vector3d(c.nodes[a][0], c.nodes[a][1], c.nodes[a][2])).transpose() +
               Eigen::RowVector3d(0.3, -0.2, 0.1);
  return X;
}

/// A distorted element: the affine nodes moved by a smooth non-affine map
/// (twisted hexahedron faces) and, for the non-corner nodes, by a
/// deterministic perturbation that curves the edges and faces.
Eigen::MatrixXd distortedNodes(CellType t) {
  const auto& c = ddc::referenceCell(t);
  Eigen::MatrixXd X = affineNodes(t);
  for (int a = 0; a < c.numNodes; ++a) {
    const auto& x = c.nodes[a];
    X.row(a) += 0.08 * Eigen::RowVector3d(x[1] * x[2], x[2] * x[0], x[0] * x[1]);
    if (a >= c.numCorners)
      X.row(a) += 0.04 * Eigen::RowVector3d(std::sin(3.0 * a + 1), std::cos(2.0 * a + 0.5), std::sin(1.7 * a + 0.3));
  }
  return X;
}

std::string cleanName(std::string s) {
  std::string clean;
  for (char ch : s)
    if (std::isalnum(static_cast<unsigned char>(ch))) clean += ch;
  return clean;
}

/// Closed-form 3-D laws at a homogeneous F, written independently of
/// DDC_Material.cpp: W and the Cauchy stress.
struct ClosedForm {
  double W;
  Eigen::Matrix3d sigma;
};

ClosedForm closedForm(const std::string& mat, const Eigen::Matrix3d& F) {
  const double mu = kTestE / (2 * (1 + kTestNu)), la = kTestE * kTestNu / ((1 + kTestNu) * (1 - 2 * kTestNu));
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const double J = F.determinant();
  if (mat == "Neo-Hookean") {
    // Spatial form (Bonet & Wood eq. 5.29): sigma = mu/J (b - I) + lambda ln J / J I.
    const Eigen::Matrix3d b = F * F.transpose();
    return {0.5 * mu * (b.trace() - 3) - mu * std::log(J) + 0.5 * la * std::log(J) * std::log(J),
            mu / J * (b - I) + la * std::log(J) / J * I};
  }
  if (mat == "St. Venant-Kirchhoff") {
    const Eigen::Matrix3d E = 0.5 * (F.transpose() * F - I);
    const Eigen::Matrix3d S = la * E.trace() * I + 2 * mu * E;
    return {0.5 * la * E.trace() * E.trace() + mu * (E.array() * E.array()).sum(), F * S * F.transpose() / J};
  }
  const Eigen::Matrix3d eps = 0.5 * (F + F.transpose()) - I;
  return {0.5 * la * eps.trace() * eps.trace() + mu * (eps.array() * eps.array()).sum(),
          la * eps.trace() * I + 2 * mu * eps};
}

/// The Cauchy stress tensor of an ElementPostResult (Voigt xx yy zz yz xz xy).
Eigen::Matrix3d cauchyTensor(const ddc::ElementPostResult& p) {
  const double* c = p.cauchy;
  Eigen::Matrix3d s;
  s << c[0], c[5], c[4],  //
      c[5], c[1], c[3],   //
      c[4], c[3], c[2];
  return s;
}

/// A general homogeneous deformation: stretch, shear, rotation, det F ~ 1.1.
Eigen::Matrix3d generalF() {
  Eigen::Matrix3d F;
  F << 1.2, 0.15, -0.05,  //
      -0.1, 0.9, 0.12,    //
      0.08, -0.07, 1.05;
  return F;
}

/// Rotation by `angle` about `axis` (Rodrigues).
Eigen::Matrix3d rotation(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// --------------------------------------------------- element x material grid

class Element3d : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {
 protected:
  std::string elem() const { return std::get<0>(GetParam()); }
  std::string mat() const { return std::get<1>(GetParam()); }
  CellType cell() const { return cellOf(elem()); }
};

TEST_P(Element3d, ReferenceGeometryIsValid) {
  auto el = makeTestElement(elem(), mat());
  EXPECT_EQ(el->dim(), 3);
  EXPECT_EQ(el->numNodes(), ddc::numCellNodes(cell()));
  EXPECT_GT(el->minReferenceJacobian(distortedNodes(cell())), 0.0);
  // An affine element's det(dX/dxi) is det A everywhere (A scaled for tets).
  const double detA = geometryMap().determinant() * (ddc::referenceCell(cell()).simplex ? 8.0 : 1.0);
  EXPECT_LT(relDiff(el->minReferenceJacobian(affineNodes(cell())), detA), kRoundoff);
}

TEST_P(Element3d, ResidualMatchesEnergyFiniteDifferences) {
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixXd X = distortedNodes(cell());
  const Eigen::MatrixXd u = randomNodal(el->numNodes(), 3, kDisplacementScale, 17);
  ddc::ElementPostResult post;
  el->postprocess(X, u, post);
  ASSERT_GT(post.minDetJ, 0.5) << "test state should be a moderate deformation";

  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  const Eigen::MatrixXd fd = centralDifferences(
      [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
        ddc::ElementResult e;
        el->compute(X, unflatten(v, 3), ddc::kEnergy, e);
        return Eigen::VectorXd::Constant(1, e.energy);
      },
      flatten(u), kFdStep);
  ASSERT_EQ(r.residual.size(), 3 * el->numNodes());
  EXPECT_GT(r.residual.norm(), 1.0) << "a non-trivial state is needed for a meaningful check";
  const double err = (r.residual - fd.row(0).transpose()).norm() / r.residual.norm();
  RecordProperty("fd_residual_rel_error", scientific(err));
  EXPECT_LT(err, kFiniteDifference);
}

TEST_P(Element3d, TangentMatchesResidualFiniteDifferencesAndIsSymmetric) {
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixXd X = distortedNodes(cell());
  const Eigen::MatrixXd u = randomNodal(el->numNodes(), 3, kDisplacementScale, 23);
  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  const Eigen::MatrixXd fd = centralDifferences(
      [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
        ddc::ElementResult e;
        el->compute(X, unflatten(v, 3), ddc::kResidual, e);
        return e.residual;
      },
      flatten(u), kFdStep);
  ASSERT_EQ(r.tangent.rows(), 3 * el->numNodes());
  ASSERT_EQ(r.tangent.cols(), 3 * el->numNodes());
  const double err = (r.tangent - fd).norm() / r.tangent.norm();
  RecordProperty("fd_tangent_rel_error", scientific(err));
  EXPECT_LT(err, kFiniteDifference);
  // Hyperelastic: K is a Hessian, symmetric up to round-off.
  EXPECT_LT((r.tangent - r.tangent.transpose()).norm(), kRoundoff * r.tangent.norm());
}

TEST_P(Element3d, NodeForcesAreSelfEquilibrated) {
  // Translation invariance: the nodal forces sum to zero. Rotation
  // invariance (finite-strain laws): zero net moment sum_a x_a x f_a.
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixXd X = distortedNodes(cell());
  const Eigen::MatrixXd u = randomNodal(el->numNodes(), 3, kDisplacementScale, 5);
  ddc::ElementResult r;
  el->compute(X, u, ddc::kResidual, r);
  const Eigen::MatrixXd f = unflatten(r.residual, 3);
  EXPECT_LT(f.colwise().sum().norm(), kRoundoff * f.norm());
  if (mat() != "Linear Elastic") {
    const Eigen::MatrixXd x = X + u;
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    for (int a = 0; a < x.rows(); ++a)
      m += Eigen::Vector3d(x.row(a).transpose()).cross(Eigen::Vector3d(f.row(a).transpose()));
    EXPECT_LT(m.norm(), kRoundoff * f.norm() * x.norm());
  }
}

TEST_P(Element3d, HomogeneousDeformationGivesClosedFormStress) {
  // An isoparametric element reproduces x = F X exactly, curved or not:
  // F, W and sigma are the same at every quadrature point.
  auto el = makeTestElement(elem(), mat());
  const Eigen::Matrix3d F = generalF();
  const ClosedForm exact = closedForm(mat(), F);
  const double scale = exact.sigma.norm();
  double worst = 0;
  for (const Eigen::MatrixXd& X : {affineNodes(cell()), distortedNodes(cell())}) {
    const Eigen::MatrixXd u = homogeneousDisplacement(X, F);
    ddc::ElementPostResult post;
    el->postprocess(X, u, post);
    EXPECT_LT(relDiff(post.energyDensity, exact.W), kRoundoff);
    worst = std::max(worst, (cauchyTensor(post) - exact.sigma).norm() / scale);
    EXPECT_LT(relDiff(post.minDetJ, F.determinant()), kRoundoff);
  }
  RecordProperty("homogeneous_stress_rel_error", scientific(worst));
  EXPECT_LT(worst, kRoundoff);
  // Energy U_e = W V_e on the affine element, V_e = det A V_ref.
  const Eigen::MatrixXd X = affineNodes(cell());
  const double volume =
      geometryMap().determinant() * (ddc::referenceCell(cell()).simplex ? 8.0 : 1.0) * referenceVolume(cell());
  ddc::ElementResult r;
  el->compute(X, homogeneousDisplacement(X, F), ddc::kEnergy, r);
  EXPECT_LT(relDiff(r.energy, exact.W * volume), kRoundoff);
}

// ------------------------------------------------------------ small strain

class SmallStrain3d : public ::testing::TestWithParam<std::string> {};

TEST_P(SmallStrain3d, EnergyIsQuadraticAndInfinitesimalRotationIsFree) {
  auto el = makeTestElement(GetParam(), "Linear Elastic");
  const Eigen::MatrixXd X = distortedNodes(cellOf(GetParam()));
  const Eigen::MatrixXd u = randomNodal(el->numNodes(), 3, kDisplacementScale, 99);
  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  const Eigen::VectorXd v = flatten(u);
  // Geometrically linear: f = K u and U = u.K.u / 2 exactly.
  EXPECT_LT((r.residual - r.tangent * v).norm(), kRoundoff * r.residual.norm());
  EXPECT_LT(relDiff(r.energy, 0.5 * v.dot(r.tangent * v)), kRoundoff);
  // An infinitesimal rotation u = w x X has eps = 0.
  const Eigen::Vector3d w(0.1, -0.2, 0.3);
  Eigen::MatrixXd rot(X.rows(), 3);
  for (int a = 0; a < X.rows(); ++a) rot.row(a) = w.cross(Eigen::Vector3d(X.row(a).transpose())).transpose();
  el->compute(X, rot, ddc::kAll, r);
  EXPECT_LT(std::abs(r.energy), kRoundoff * kTestE);
  EXPECT_LT(r.residual.norm(), kRoundoff * kTestE);
}

INSTANTIATE_TEST_SUITE_P(Every3dElement, SmallStrain3d, ::testing::ValuesIn(k3dElements));

INSTANTIATE_TEST_SUITE_P(AllElementsAndMaterials, Element3d,
                         ::testing::Combine(::testing::ValuesIn(k3dElements), ::testing::ValuesIn(kMaterials)),
                         [](const ::testing::TestParamInfo<Element3d::ParamType>& info) {
                           return std::get<0>(info.param) + "_" + cleanName(std::get<1>(info.param));
                         });

// ----------------------------------------------------------- finite strain

class FiniteStrain3d : public Element3d {};

TEST_P(FiniteStrain3d, RigidRotationIsStressFree) {
  // 90 degrees about an axis along no coordinate direction.
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixXd X = distortedNodes(cell());
  const Eigen::Matrix3d R = rotation(Eigen::Vector3d(1, 2, 3), std::acos(0.0));
  const Eigen::MatrixXd u = homogeneousDisplacement(X, R);
  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  ddc::ElementPostResult post;
  el->postprocess(X, u, post);
  RecordProperty("rotation_energy", scientific(r.energy));
  RecordProperty("rotation_max_stress", scientific(cauchyTensor(post).cwiseAbs().maxCoeff()));
  // Reference magnitudes: E times the volume (~8) for the energy, E times
  // the size (~2) for forces, E for stresses.
  EXPECT_LT(std::abs(r.energy), kRoundoff * kTestE * 8.0);
  EXPECT_LT(r.residual.norm(), kRoundoff * kTestE * 2.0);
  for (double s : post.cauchy) EXPECT_LT(std::abs(s), kRoundoff * kTestE);
  EXPECT_LT(relDiff(post.minDetJ, 1.0), kRoundoff);
  // The same displacement is a large strain for the small-strain law, which
  // shows this test can fail.
  makeTestElement(elem(), "Linear Elastic")->compute(X, u, ddc::kEnergy, r);
  EXPECT_GT(r.energy, 0.1 * kTestE);
}

TEST_P(FiniteStrain3d, RejectsNonPositiveDetF) {
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixXd X = distortedNodes(cell());
  const Eigen::Matrix3d F = Eigen::Vector3d(-1, 1, 1).asDiagonal();  // reflection, det F = -1
  ddc::test::expectDetFRejected(*el, X, F);
}

INSTANTIATE_TEST_SUITE_P(NeoHookeanAndSVK, FiniteStrain3d,
                         ::testing::Combine(::testing::ValuesIn(k3dElements),
                                            ::testing::Values("Neo-Hookean", "St. Venant-Kirchhoff")),
                         [](const ::testing::TestParamInfo<FiniteStrain3d::ParamType>& info) {
                           return std::get<0>(info.param) + "_" + cleanName(std::get<1>(info.param));
                         });

// ------------------------------------------------------ multi-element meshes

/// A structured mesh of the box [0, n]^3: n^3 hexahedra, or 6 n^3 tetrahedra
/// (each cube cut into the 6 tetrahedra around its main diagonal, the same
/// way in every cube, so faces match). Nodes live on the grid of half steps
/// (index 0..2n per direction); `interior` marks nodes off the box surface.
struct BoxMesh {
  CellType cell;
  int n;
  Eigen::MatrixXd X;                      // node coordinates
  std::vector<std::vector<int>> elements;  // nodes in reference-cell order
  std::vector<bool> interior;
  std::vector<std::array<int, 3>> gridIndex;
};

BoxMesh boxMesh(CellType cell, int n) {
  const auto& ref = ddc::referenceCell(cell);
  BoxMesh m{cell, n, {}, {}, {}, {}};
  std::map<std::array<int, 3>, int> id;
  auto node = [&](const std::array<int, 3>& g) {
    auto [it, fresh] = id.emplace(g, static_cast<int>(m.gridIndex.size()));
    if (fresh) m.gridIndex.push_back(g);
    return it->second;
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::array<int, 3> base{2 * i, 2 * j, 2 * k};
        if (!ref.simplex) {
          // Reference coordinate -1, 0, 1 -> half-step offset 0, 1, 2.
          std::vector<int> e;
          for (const auto& x : ref.nodes)
            e.push_back(node({base[0] + static_cast<int>(x[0] + 1), base[1] + static_cast<int>(x[1] + 1),
                              base[2] + static_cast<int>(x[2] + 1)}));
          m.elements.push_back(e);
          continue;
        }
        // Kuhn subdivision: for each permutation p, the path 0 -> e_p0 ->
        // e_p0 + e_p1 -> (1,1,1); odd permutations are reflected, so swap
        // two corners to keep det(dX/dxi) > 0.
        int perm[3] = {0, 1, 2};
        do {
          std::array<std::array<int, 3>, 4> v{};
          for (int s = 1; s < 4; ++s) {
            v[s] = v[s - 1];
            v[s][perm[s - 1]] += 2;
          }
          const bool odd = (perm[0] == 0 && perm[1] == 2) || (perm[0] == 2 && perm[1] == 1) ||
                           (perm[0] == 1 && perm[1] == 0);
          if (odd) std::swap(v[1], v[2]);
          std::vector<int> e;
          for (int c = 0; c < 4; ++c) e.push_back(node({base[0] + v[c][0], base[1] + v[c][1], base[2] + v[c][2]}));
          for (const auto& edge : ref.edges) {
            if (edge.middle < 0) continue;
            std::array<int, 3> mid;
            for (int d = 0; d < 3; ++d) mid[d] = base[d] + (v[edge.start][d] + v[edge.end][d]) / 2;
            e.push_back(node(mid));
          }
          m.elements.push_back(e);
        } while (std::next_permutation(perm, perm + 3));
      }
  const int nn = static_cast<int>(m.gridIndex.size());
  m.X.resize(nn, 3);
  m.interior.resize(nn);
  for (int a = 0; a < nn; ++a) {
    bool in = true;
    for (int d = 0; d < 3; ++d) {
      m.X(a, d) = 0.5 * m.gridIndex[a][d];
      in = in && m.gridIndex[a][d] > 0 && m.gridIndex[a][d] < 2 * n;
    }
    m.interior[a] = in;
  }
  return m;
}

/// Move every node by a smooth deterministic field of amplitude 0.08 (in
/// units of the cell size 1): elements become non-affine and, for quadratic
/// hexahedra, curved. For Tet10 the mid-edge nodes are then put back at the
/// middles of their (moved) edges: a 4-point rule does not integrate the
/// interior-force terms of a curved Tet10 exactly (degree 3), so only the
/// straight-edged distorted Tet10 mesh passes the patch test to round-off.
void distort(BoxMesh& m) {
  for (int a = 0; a < m.X.rows(); ++a) {
    const auto& g = m.gridIndex[a];
    m.X.row(a) += 0.08 * Eigen::RowVector3d(std::sin(1.3 * g[0] + 2.1 * g[1] + 0.7 * g[2]),
                                            std::cos(0.9 * g[0] + 1.7 * g[1] + 2.3 * g[2]),
                                            std::sin(2.2 * g[0] + 0.4 * g[1] + 1.1 * g[2] + 0.5));
  }
  if (m.cell != CellType::Tet10) return;
  const auto& ref = ddc::referenceCell(m.cell);
  for (const auto& e : m.elements)
    for (const auto& edge : ref.edges) m.X.row(e[edge.middle]) = 0.5 * (m.X.row(e[edge.start]) + m.X.row(e[edge.end]));
}

/// Global residual and (optionally) tangent of a mesh at displacement u.
void assemble(const BoxMesh& m, const ddc::Element& el, const Eigen::MatrixXd& u, Eigen::VectorXd& f,
              Eigen::MatrixXd* K) {
  const int nn = static_cast<int>(m.X.rows());
  f.setZero(3 * nn);
  if (K) K->setZero(3 * nn, 3 * nn);
  ddc::ElementResult r;
  for (const auto& e : m.elements) {
    const int ne = static_cast<int>(e.size());
    Eigen::MatrixXd Xe(ne, 3), ue(ne, 3);
    for (int a = 0; a < ne; ++a) Xe.row(a) = m.X.row(e[a]), ue.row(a) = u.row(e[a]);
    el.compute(Xe, ue, K ? ddc::kAll : ddc::kResidual, r);
    for (int a = 0; a < ne; ++a)
      for (int i = 0; i < 3; ++i) {
        f(3 * e[a] + i) += r.residual(3 * a + i);
        if (K)
          for (int b = 0; b < ne; ++b)
            for (int j = 0; j < 3; ++j) (*K)(3 * e[a] + i, 3 * e[b] + j) += r.tangent(3 * a + i, 3 * b + j);
      }
  }
}

/// Cells per direction of the patch: 3 for linear cells (8 interior
/// vertices), 2 for quadratic ones (27 interior nodes per hexahedral cell
/// layout, 125 nodes).
int patchCells(CellType t) { return t == CellType::Hex8 || t == CellType::Tet4 ? 3 : 2; }

class PatchTest : public Element3d {};

TEST_P(PatchTest, AffineFieldIsReproducedOnDistortedMesh) {
  // Constant-stress patch test (Zienkiewicz & Taylor, vol. 1, ch. 10): the
  // boundary nodes carry the affine displacement u = H X; (a) with the
  // affine field everywhere, the interior nodes are in equilibrium; (b)
  // started from zero, Newton on the interior nodes finds the affine field;
  // every element then holds the closed-form stress.
  auto el = makeTestElement(elem(), mat());
  BoxMesh m = boxMesh(cell(), patchCells(cell()));
  distort(m);
  for (const auto& e : m.elements) {
    Eigen::MatrixXd Xe(e.size(), 3);
    for (size_t a = 0; a < e.size(); ++a) Xe.row(a) = m.X.row(e[a]);
    ASSERT_GT(el->minReferenceJacobian(Xe), 0.0);
  }
  Eigen::Matrix3d H;
  H << 0.04, 0.012, -0.008,  //
      0.004, -0.02, 0.01,    //
      0.008, 0.006, 0.012;
  const Eigen::MatrixXd uExact = m.X * H.transpose();
  std::vector<int> free;  // interior DOFs
  for (int a = 0; a < m.X.rows(); ++a)
    if (m.interior[a])
      for (int i = 0; i < 3; ++i) free.push_back(3 * a + i);
  ASSERT_FALSE(free.empty());

  // (a) Equilibrium of the interior nodes under the affine field, relative
  // to the largest nodal force (the boundary reactions).
  Eigen::VectorXd f;
  assemble(m, *el, uExact, f, nullptr);
  double interiorForce = 0;
  for (int i : free) interiorForce = std::max(interiorForce, std::abs(f(i)));
  const double residualError = interiorForce / f.cwiseAbs().maxCoeff();
  RecordProperty("patch_interior_residual_rel", scientific(residualError));
  EXPECT_LT(residualError, kRoundoff);

  // (b) Solve for the interior nodes from u = 0 there.
  Eigen::MatrixXd u = uExact;
  for (int a = 0; a < m.X.rows(); ++a)
    if (m.interior[a]) u.row(a).setZero();
  Eigen::MatrixXd K;
  const int nf = static_cast<int>(free.size());
  for (int it = 0; it < 20; ++it) {
    assemble(m, *el, u, f, &K);
    Eigen::VectorXd rf(nf);
    Eigen::MatrixXd Kff(nf, nf);
    for (int p = 0; p < nf; ++p) {
      rf(p) = f(free[p]);
      for (int q = 0; q < nf; ++q) Kff(p, q) = K(free[p], free[q]);
    }
    const Eigen::VectorXd du = Kff.ldlt().solve(-rf);
    for (int p = 0; p < nf; ++p) u(free[p] / 3, free[p] % 3) += du(p);
    if (du.norm() < 1e-14 * uExact.norm()) break;
  }
  const double uError = (u - uExact).cwiseAbs().maxCoeff() / uExact.cwiseAbs().maxCoeff();
  const ClosedForm exact = closedForm(mat(), Eigen::Matrix3d::Identity() + H);
  double stressError = 0;
  for (const auto& e : m.elements) {
    Eigen::MatrixXd Xe(e.size(), 3), ue(e.size(), 3);
    for (size_t a = 0; a < e.size(); ++a) Xe.row(a) = m.X.row(e[a]), ue.row(a) = u.row(e[a]);
    ddc::ElementPostResult post;
    el->postprocess(Xe, ue, post);
    stressError = std::max(stressError, (cauchyTensor(post) - exact.sigma).norm() / exact.sigma.norm());
  }
  RecordProperty("patch_displacement_rel_error", scientific(uError));
  RecordProperty("patch_stress_rel_error", scientific(stressError));
  EXPECT_LT(uError, kRoundoff);
  EXPECT_LT(stressError, kRoundoff);
}

INSTANTIATE_TEST_SUITE_P(AllElementsAndMaterials, PatchTest,
                         ::testing::Combine(::testing::ValuesIn(k3dElements), ::testing::ValuesIn(kMaterials)),
                         [](const ::testing::TestParamInfo<PatchTest::ParamType>& info) {
                           return std::get<0>(info.param) + "_" + cleanName(std::get<1>(info.param));
                         });

class NeoHookeanCube : public ::testing::TestWithParam<std::string> {};

TEST_P(NeoHookeanCube, HomogeneousStretchMatchesClosedForm) {
  // Unit cube, x = diag(l1, l2, l3) X. Closed form (Bonet & Wood, ch. 6):
  //   W = mu/2 (l1^2 + l2^2 + l3^2 - 3) - mu ln J + lambda/2 (ln J)^2,
  //   sigma_ii = (mu (l_i^2 - 1) + lambda ln J) / J,
  //   P_ii = mu (l_i - 1/l_i) + lambda ln J / l_i (force per reference area).
  const CellType cell = cellOf(GetParam());
  auto el = makeTestElement(GetParam(), "Neo-Hookean");
  const BoxMesh m = boxMesh(cell, 1);
  const Eigen::Vector3d l(1.3, 0.8, 1.1);
  const Eigen::MatrixXd u = homogeneousDisplacement(m.X, Eigen::Matrix3d(l.asDiagonal()));
  const double mu = kTestE / (2 * (1 + kTestNu)), la = kTestE * kTestNu / ((1 + kTestNu) * (1 - 2 * kTestNu));
  const double J = l.prod(), lnJ = std::log(J);
  const double W = 0.5 * mu * (l.squaredNorm() - 3) - mu * lnJ + 0.5 * la * lnJ * lnJ;

  double energy = 0, stressError = 0;
  for (const auto& e : m.elements) {
    Eigen::MatrixXd Xe(e.size(), 3), ue(e.size(), 3);
    for (size_t a = 0; a < e.size(); ++a) Xe.row(a) = m.X.row(e[a]), ue.row(a) = u.row(e[a]);
    ddc::ElementResult r;
    el->compute(Xe, ue, ddc::kEnergy, r);
    energy += r.energy;
    ddc::ElementPostResult post;
    el->postprocess(Xe, ue, post);
    for (int i = 0; i < 3; ++i)
      stressError = std::max(stressError, relDiff(post.cauchy[i], (mu * (l(i) * l(i) - 1) + la * lnJ) / J));
    for (int k = 3; k < 6; ++k) stressError = std::max(stressError, std::abs(post.cauchy[k]) / kTestE);
  }
  // Resultant force on the face X_i = 1 = P_ii times its reference area 1.
  Eigen::VectorXd f;
  assemble(m, *el, u, f, nullptr);
  double forceError = 0;
  for (int i = 0; i < 3; ++i) {
    double resultant = 0;
    for (int a = 0; a < m.X.rows(); ++a)
      if (m.gridIndex[a][i] == 2) resultant += f(3 * a + i);
    forceError = std::max(forceError, relDiff(resultant, mu * (l(i) - 1 / l(i)) + la * lnJ / l(i)));
  }
  RecordProperty("stretch_energy_rel_error", scientific(relDiff(energy, W)));
  RecordProperty("stretch_stress_rel_error", scientific(stressError));
  RecordProperty("stretch_face_force_rel_error", scientific(forceError));
  EXPECT_LT(relDiff(energy, W), kRoundoff);
  EXPECT_LT(stressError, kRoundoff);
  EXPECT_LT(forceError, kRoundoff);
}

INSTANTIATE_TEST_SUITE_P(Every3dElement, NeoHookeanCube, ::testing::ValuesIn(k3dElements));

// ------------------------------------------------- plane-strain consistency

/// The prism of depth `depth` over a 2-D element: node a of the hexahedron
/// sits over the quadrilateral node with its in-plane reference
/// coordinates, at z = (zeta + 1)/2 depth; returns that quad node per node.
std::vector<int> extrusion(CellType hex, CellType quad) {
  const auto& h = ddc::referenceCell(hex);
  const auto& q = ddc::referenceCell(quad);
  std::vector<int> of;
  for (const auto& x : h.nodes)
    for (int b = 0; b < q.numNodes; ++b)
      if (q.nodes[b][0] == x[0] && q.nodes[b][1] == x[1]) {
        of.push_back(b);
        break;
      }
  return of;
}

class PlaneStrainConsistency
    : public ::testing::TestWithParam<std::tuple<std::pair<std::string, std::string>, std::string>> {};

TEST_P(PlaneStrainConsistency, ExtrudedHexMatchesQuadPerUnitDepth) {
  // A plane-strain state (u_z = 0, u independent of z) of a prism over a
  // quadrilateral: the hexahedron's energy, in-plane forces summed through
  // the depth, tangent and stress equal the plane-strain element's.
  const auto& [pair, mat] = GetParam();
  const auto& [hexName, quadName] = pair;
  auto hex = makeTestElement(hexName, mat);
  auto quad = makeTestElement(quadName, mat);
  const std::vector<int> of = extrusion(cellOf(hexName), cellOf(quadName));
  ASSERT_EQ(static_cast<int>(of.size()), hex->numNodes());
  // A distorted, curved quadrilateral and a random in-plane state.
  const auto& qref = ddc::referenceCell(cellOf(quadName));
  Eigen::MatrixXd Xq(quad->numNodes(), 2);
  for (int b = 0; b < quad->numNodes(); ++b)
    Xq.row(b) = (geometryMap().topLeftCorner<2, 2>() * Eigen::Vector2d(qref.nodes[b][0], qref.nodes[b][1])).transpose() +
                0.05 * Eigen::RowVector2d(std::sin(2.0 * b + 1), std::cos(3.0 * b));
  const Eigen::MatrixXd uq = randomNodal(quad->numNodes(), 2, kDisplacementScale, 31);
  const auto& href = ddc::referenceCell(cellOf(hexName));
  Eigen::MatrixXd Xh(hex->numNodes(), 3), uh = Eigen::MatrixXd::Zero(hex->numNodes(), 3);
  for (int a = 0; a < hex->numNodes(); ++a) {
    Xh.row(a) << Xq(of[a], 0), Xq(of[a], 1), 0.5 * (href.nodes[a][2] + 1);  // depth 1
    uh.row(a).head<2>() = uq.row(of[a]);
  }
  ddc::ElementResult rq, rh;
  quad->compute(Xq, uq, ddc::kAll, rq);
  hex->compute(Xh, uh, ddc::kAll, rh);
  EXPECT_LT(relDiff(rh.energy, rq.energy), kRoundoff);
  // u_hex = P u_quad, so f_quad = P^T f_hex and K_quad = P^T K_hex P.
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 * hex->numNodes(), 2 * quad->numNodes());
  for (int a = 0; a < hex->numNodes(); ++a)
    for (int i = 0; i < 2; ++i) P(3 * a + i, 2 * of[a] + i) = 1;
  EXPECT_LT((P.transpose() * rh.residual - rq.residual).norm(), kRoundoff * rq.residual.norm());
  EXPECT_LT((P.transpose() * rh.tangent * P - rq.tangent).norm(), kRoundoff * rq.tangent.norm());
  ddc::ElementPostResult pq, ph;
  quad->postprocess(Xq, uq, pq);
  hex->postprocess(Xh, uh, ph);
  double scale = 0;
  for (double s : pq.cauchy) scale = std::max(scale, std::abs(s));
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(ph.cauchy[k], pq.cauchy[k], kRoundoff * scale) << "component " << k;
  EXPECT_LT(relDiff(ph.energyDensity, pq.energyDensity), kRoundoff);
}

INSTANTIATE_TEST_SUITE_P(
    HexOverQuad, PlaneStrainConsistency,
    ::testing::Combine(::testing::Values(std::make_pair(std::string("Hex8"), std::string("Quad4")),
                                         std::make_pair(std::string("Hex27"), std::string("Quad9"))),
                       ::testing::ValuesIn(kMaterials)),
    [](const ::testing::TestParamInfo<PlaneStrainConsistency::ParamType>& info) {
      return std::get<0>(info.param).first + "_" + cleanName(std::get<1>(info.param));
    });

// ------------------------------------------------ inverted and degenerate

TEST(ContinuumElement3d, InvertedHexAndFlatTetAreRejected) {
  ddc::ElementResult r;
  for (const char* name : {"Hex8", "Hex20", "Hex27"}) {
    auto el = makeTestElement(name, "Neo-Hookean");
    const auto& ref = ddc::referenceCell(cellOf(name));
    // Mirror the element through z = 0: the same nodes in reflected order.
    Eigen::MatrixXd X = affineNodes(cellOf(name));
    for (int a = 0; a < ref.numNodes; ++a) X(a, 2) = -X(a, 2);
    EXPECT_LE(el->minReferenceJacobian(X), 0.0) << name;
    EXPECT_THROW(el->compute(X, Eigen::MatrixXd::Zero(ref.numNodes, 3), ddc::kAll, r), ddc::InadmissibleDeformation)
        << name;
  }
  for (const char* name : {"Tet4", "Tet10"}) {
    auto el = makeTestElement(name, "Neo-Hookean");
    const auto& ref = ddc::referenceCell(cellOf(name));
    // All nodes in the plane z = 0: a flat tetrahedron, det(dX/dxi) = 0.
    Eigen::MatrixXd X = affineNodes(cellOf(name));
    X.col(2).setZero();
    EXPECT_LE(el->minReferenceJacobian(X), 0.0) << name;
    EXPECT_THROW(el->compute(X, Eigen::MatrixXd::Zero(ref.numNodes, 3), ddc::kAll, r), ddc::InadmissibleDeformation)
        << name;
  }
  // A mid-edge node pulled past the far corner folds the Tet10 map at a
  // corner although the corners alone look fine.
  auto tet10 = makeTestElement("Tet10", "Neo-Hookean");
  Eigen::MatrixXd X = affineNodes(CellType::Tet10);
  X.row(4) = X.row(0) + 0.9 * (X.row(1) - X.row(0));  // edge 0-1, middle node 4
  EXPECT_LT(tet10->minReferenceJacobian(X), 0.0);
}

TEST(ContinuumElement3d, WrongSizesAreCallerBugs) {
  auto hex = makeTestElement("Hex8", "St. Venant-Kirchhoff");
  ddc::ElementResult r;
  EXPECT_THROW(hex->compute(Eigen::MatrixXd::Zero(8, 2), Eigen::MatrixXd::Zero(8, 2), ddc::kAll, r),
               std::invalid_argument);
  EXPECT_THROW(hex->compute(Eigen::MatrixXd::Zero(4, 3), Eigen::MatrixXd::Zero(4, 3), ddc::kAll, r),
               std::invalid_argument);
  EXPECT_THROW(hex->minReferenceJacobian(Eigen::MatrixXd::Zero(8, 2)), std::invalid_argument);
  hex->compute(affineNodes(CellType::Hex8), Eigen::MatrixXd::Zero(8, 3), ddc::kAll, r);
  EXPECT_EQ(r.residual.size(), 24);
  EXPECT_EQ(r.tangent.rows(), 24);
  EXPECT_EQ(r.energy, 0.0);
}

TEST(ContinuumElement3d, VonMisesOfUniaxialAndShearStress) {
  ddc::ElementPostResult p;
  p.cauchy[0] = 3.0;  // uniaxial: sigma_vM = |sigma_xx|
  EXPECT_NEAR(p.vonMises(), 3.0, kRoundoff);
  p = ddc::ElementPostResult();
  p.cauchy[3] = 2.0;  // pure shear: sigma_vM = sqrt(3) |tau|
  EXPECT_NEAR(p.vonMises(), 2.0 * std::sqrt(3.0), kRoundoff);
}

}  // namespace
