// Helpers shared by the element tests: elements from the factory, nodal
// arrays of any dimension, flattening to node-major DOF vectors, random and
// homogeneous displacement fields, central finite differences.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "DDC_ElementFactory.hpp"

namespace ddc::test {

/// Young's modulus and Poisson's ratio of the test materials.
constexpr double kTestE = 1000.0;
constexpr double kTestNu = 0.3;

/// Finite-difference step relative to the element size (~2): small enough
/// for an O(h^2) truncation error of ~1e-12, large enough that cancellation
/// (eps * |f| / h) stays ~1e-10 relative; see kFiniteDifference.
constexpr double kFdStep = 1e-6;

/// Displacement amplitude of the random states: gives strains of ~10 %,
/// well into the nonlinear range but with det F > 0 (checked).
constexpr double kDisplacementScale = 0.08;

/// An element of a built-in type with a material ("Neo-Hookean", ...).
inline std::shared_ptr<Element> makeTestElement(const std::string& elem, const std::string& mat) {
  Teuchos::ParameterList p;
  p.set("Type", elem);
  p.sublist("Material").set("Type", mat);
  p.sublist("Material").set("Young's Modulus", kTestE);
  p.sublist("Material").set("Poisson's Ratio", kTestNu);
  return ElementFactory::withBuiltins().create(p, "Element");
}

/// Node-major DOF vector (u0x, u0y, [u0z,] u1x, ...) of a nodal array.
inline Eigen::VectorXd flatten(const Eigen::MatrixXd& u) {
  Eigen::VectorXd v(u.size());
  for (Eigen::Index a = 0; a < u.rows(); ++a)
    for (Eigen::Index k = 0; k < u.cols(); ++k) v(a * u.cols() + k) = u(a, k);
  return v;
}

/// The nodal array (n x dim) of a node-major DOF vector.
inline Eigen::MatrixXd unflatten(const Eigen::VectorXd& v, int dim) {
  Eigen::MatrixXd u(v.size() / dim, dim);
  for (Eigen::Index a = 0; a < u.rows(); ++a)
    for (int k = 0; k < dim; ++k) u(a, k) = v(a * dim + k);
  return u;
}

/// Uniform random nodal values in [-scale, scale] (a fixed seed: reproducible).
inline Eigen::MatrixXd randomNodal(int n, int dim, double scale, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-scale, scale);
  Eigen::MatrixXd u(n, dim);
  for (int a = 0; a < n; ++a)
    for (int k = 0; k < dim; ++k) u(a, k) = d(gen);
  return u;
}

/// Displacement of the homogeneous deformation x = F X: u_a = (F - I) X_a.
inline Eigen::MatrixXd homogeneousDisplacement(const Eigen::MatrixXd& X, const Eigen::MatrixXd& F) {
  return X * (F - Eigen::MatrixXd::Identity(F.rows(), F.cols())).transpose();
}

/// Expect compute() at the homogeneous deformation x = F X (det F <= 0) to
/// throw InadmissibleDeformation naming det F.
inline void expectDetFRejected(const Element& el, const Eigen::MatrixXd& X, const Eigen::MatrixXd& F) {
  try {
    ElementResult r;
    el.compute(X, homogeneousDisplacement(X, F), kAll, r);
    ADD_FAILURE() << "no InadmissibleDeformation";
  } catch (const InadmissibleDeformation& e) {
    EXPECT_NE(std::string(e.what()).find("det F"), std::string::npos) << e.what();
  }
}

/// Central finite differences of a vector function g of the DOF vector v:
/// column i is (g(v + h e_i) - g(v - h e_i)) / 2h.
template <class Fn>
Eigen::MatrixXd centralDifferences(Fn g, const Eigen::VectorXd& v, double h) {
  Eigen::MatrixXd out;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    Eigen::VectorXd vp = v, vm = v;
    vp(i) += h;
    vm(i) -= h;
    const Eigen::VectorXd d = (g(vp) - g(vm)) / (2 * h);
    if (i == 0) out.resize(d.size(), v.size());
    out.col(i) = d;
  }
  return out;
}

/// "1.23e-15": a measured error for RecordProperty (the test's XML/JSON
/// report keeps the numbers next to the tolerances they were checked against).
inline std::string scientific(double v) {
  std::ostringstream os;
  os.precision(2);
  os << std::scientific << v;
  return os.str();
}

}  // namespace ddc::test
