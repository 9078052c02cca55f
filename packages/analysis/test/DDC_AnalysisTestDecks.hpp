// Shared by the analysis tests: in-memory input decks (rectangle and box bodies,
// boundary conditions, quiet run options), the communicators, the
// displacement field gathered by mesh node, and the checks of a cantilever
// refinement series.
#pragma once

#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Core.hpp>
#include <mpi.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_TestTolerances.hpp"

namespace ddc::test {

using PL = Teuchos::ParameterList;
using Comm = Teuchos::RCP<const Teuchos::Comm<int>>;

inline Comm worldComm() { return Tpetra::getDefaultComm(); }
inline Comm selfComm() { return Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF)); }
inline bool isRoot() { return worldComm()->getRank() == 0; }

/// A "Rectangle" body with one element type and material.
struct RectangleSpec {
  double originX = 0.0, originY = 0.0, lengthX = 1.0, lengthY = 1.0;
  int nx = 4, ny = 4;
  double distortion = 0.0;
  std::string element = "Quad4";
  std::string material = "Neo-Hookean";
  double E = 1000.0, nu = 0.3;
};

/// The Element sublist of a body: type and material with E and nu.
inline void setElement(PL& body, const std::string& element, const std::string& material, double E, double nu) {
  PL& el = body.sublist("Element");
  el.set("Type", element);
  PL& mat = el.sublist("Material");
  mat.set("Type", material);
  mat.set("Young's Modulus", E);
  mat.set("Poisson's Ratio", nu);
}

/// Add body `name` (sublist Mesh/Bodies/<name>) and return its sublist.
inline PL& addRectangle(PL& deck, const std::string& name, const RectangleSpec& s) {
  PL& body = deck.sublist("Mesh").sublist("Bodies").sublist(name);
  body.set("Generator", std::string("Rectangle"));
  PL& r = body.sublist("Rectangle");
  r.set("Origin X", s.originX);
  r.set("Origin Y", s.originY);
  r.set("Length X", s.lengthX);
  r.set("Length Y", s.lengthY);
  r.set("Elements X", s.nx);
  r.set("Elements Y", s.ny);
  r.set("Distortion", s.distortion);
  setElement(body, s.element, s.material, s.E, s.nu);
  return body;
}

/// Add a displacement condition and return its sublist for further values.
inline PL& addDisplacement(PL& deck, const std::string& name, const std::string& set, const std::string& components) {
  PL& c = deck.sublist("Boundary Conditions").sublist(name);
  c.set("Type", std::string("Displacement"));
  c.set("Set", set);
  c.set("Components", components);
  return c;
}

inline void addTraction(PL& deck, const std::string& name, const std::string& set, double tx, double ty) {
  PL& c = deck.sublist("Boundary Conditions").sublist(name);
  c.set("Type", std::string("Traction"));
  c.set("Set", set);
  c.set("Traction X", tx);
  c.set("Traction Y", ty);
}

/// A Box body (Mesh/Bodies/<name>) with one element type and material.
struct BoxSpec {
  double origin[3] = {0.0, 0.0, 0.0}, length[3] = {1.0, 1.0, 1.0};
  int elements[3] = {2, 2, 2};
  std::string element = "Hex8";
  std::string material = "Linear Elastic";
  double E = 1000.0, nu = 0.3;
};

inline PL& addBox(PL& deck, const std::string& name, const BoxSpec& s) {
  PL& body = deck.sublist("Mesh").sublist("Bodies").sublist(name);
  body.set("Generator", std::string("Box"));
  PL& b = body.sublist("Box");
  for (int c = 0; c < 3; ++c) {
    const std::string axis(1, "XYZ"[c]);
    b.set("Origin " + axis, s.origin[c]);
    b.set("Length " + axis, s.length[c]);
    b.set("Elements " + axis, s.elements[c]);
  }
  setElement(body, s.element, s.material, s.E, s.nu);
  return body;
}

inline void addTraction3(PL& deck, const std::string& name, const std::string& set, const std::array<double, 3>& t) {
  addTraction(deck, name, set, t[0], t[1]);
  deck.sublist("Boundary Conditions").sublist(name).set("Traction Z", t[2]);
}

/// The common run options of test decks: `steps` load steps, no progress
/// lines, no VTK files.
inline void setRunOptions(PL& deck, int steps) {
  deck.sublist("Load Stepping").set("Number of Steps", steps);
  deck.sublist("Output").set("Progress", false);
  deck.sublist("Output").set("VTK", false);
}

/// The whole displacement field on every rank of the model's communicator,
/// indexed [d n + c] by mesh node n (d = 2 or 3, the model's dimension;
/// independent of the DOF numbering; each rank contributes its owned DOFs).
/// Collective.
inline std::vector<double> gatherDisplacement(const ddc::Model& m, const ddc::Vector& u) {
  const auto& map = *u.getMap();
  auto d = u.getData();
  const int dim = m.dim(), size = dim * m.mesh().numNodes();
  std::vector<double> local(size, 0.0), global(size, 0.0);
  for (int n = 0; n < m.mesh().numNodes(); ++n)
    for (int c = 0; c < dim; ++c) {
      const auto l = map.getLocalElement(m.dof(n, c));
      if (l != Teuchos::OrdinalTraits<ddc::LO>::invalid()) local[dim * n + c] = d[l];
    }
  Teuchos::reduceAll(*m.comm(), Teuchos::REDUCE_SUM, size, local.data(), global.data());
  return global;
}

inline std::vector<double> gatherDisplacement(const ddc::Analysis& a) {
  return gatherDisplacement(a.model(), a.displacement());
}

/// One run of a cantilever refinement series (checkCantileverSeries()).
struct CantileverRun {
  std::string mesh;  ///< e.g. "40 x 4" or "40 x 4 x 4 (19683 DOFs)", for the printed line
  double tip;        ///< deflection at the loaded end
  double energy;     ///< strain energy U
  double fu;         ///< f_ext . u
};

/// Runs a mesh-refinement series of a linear elastic cantilever and checks
/// each mesh against the beam reference: the error decreases, the
/// deflection stays below the reference (a displacement method, and a
/// clamp, are too stiff), and U = 1/2 f.u (kEnergyIdentity). Prints one
/// line per mesh on rank 0, prefixed by `label`.
/// \param run the analysis of element type `element` on mesh number i
/// \return the relative error of the last (finest) mesh
template <class Run>
double checkCantileverSeries(const std::string& label, const std::string& element, int numMeshes,
                             double reference, Run run) {
  double previous = 1e300;
  for (int i = 0; i < numMeshes; ++i) {
    const CantileverRun r = run(i);
    const double err = relDiff(r.tip, reference);
    if (isRoot())
      std::printf("[%s] %-5s %s  tip deflection = %.8e  reference = %.8e  rel. error = %.3e  "
                  "(U = %.6e, 1/2 f.u = %.6e)\n",
                  label.c_str(), element.c_str(), r.mesh.c_str(), r.tip, reference, err, r.energy, 0.5 * r.fu);
    EXPECT_LT(err, previous) << element << " " << r.mesh << ": error did not decrease";
    EXPECT_LT(r.tip, reference) << element << " " << r.mesh << ": should be stiffer than the beam";
    previous = err;
    // Linear elasticity: the energy identity holds on every mesh.
    EXPECT_LE(relDiff(r.energy, 0.5 * r.fu), kEnergyIdentity) << element << " " << r.mesh;
  }
  return previous;
}

}  // namespace ddc::test
