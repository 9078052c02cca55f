// Embedding API (doc/user-guide.md, "Embedding in a host code"): a host
// code assembles the parameters in memory, registers its own element types
// in an ElementFactory, runs the analysis and reads the results. Also the two
// input errors a host meets first: an unknown element type and a misspelt
// parameter. Runs on 1 and 2 ranks; input errors are raised on every rank.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_ContinuumElement.hpp"
#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using PL = Teuchos::ParameterList;
using ddc::test::relDiff;
using namespace ddc::test;  // deck builders, communicators (DDC_AnalysisTestDecks.hpp)


// ---------------------------------------------------------------------------
// Host element types.

/// Wraps another element and counts its evaluations: proves the analysis
/// really calls the host's element.
class CountingElement : public ddc::Element {
 public:
  CountingElement(std::shared_ptr<ddc::Element> inner, std::shared_ptr<std::atomic<long>> calls)
      : inner_(std::move(inner)), calls_(std::move(calls)) {}
  int numNodes() const override { return inner_->numNodes(); }
  int dim() const override { return inner_->dim(); }
  void compute(const ddc::NodalArray& X, const ddc::NodalArray& u, unsigned what,
               ddc::ElementResult& out) const override {
    ++*calls_;
    inner_->compute(X, u, what, out);
  }
  void postprocess(const ddc::NodalArray& X, const ddc::NodalArray& u, ddc::ElementPostResult& out) const override {
    inner_->postprocess(X, u, out);
  }
  double minReferenceJacobian(const ddc::NodalArray& X) const override { return inner_->minReferenceJacobian(X); }

 private:
  std::shared_ptr<ddc::Element> inner_;
  std::shared_ptr<std::atomic<long>> calls_;
};

/// A host element with a parameter of its own: the built-in Quad4 with its
/// energy, forces and tangent multiplied by "Stiffness Scale" (a material s
/// times stiffer).
class ScaledElement : public ddc::Element {
 public:
  ScaledElement(std::shared_ptr<ddc::Element> inner, double scale) : inner_(std::move(inner)), scale_(scale) {}
  int numNodes() const override { return inner_->numNodes(); }
  int dim() const override { return inner_->dim(); }
  void compute(const ddc::NodalArray& X, const ddc::NodalArray& u, unsigned what,
               ddc::ElementResult& out) const override {
    inner_->compute(X, u, what, out);
    out.energy *= scale_;
    if (what & ddc::kResidual) out.residual *= scale_;
    if (what & ddc::kTangent) out.tangent *= scale_;
  }
  void postprocess(const ddc::NodalArray& X, const ddc::NodalArray& u, ddc::ElementPostResult& out) const override {
    inner_->postprocess(X, u, out);
    for (double& s : out.cauchy) s *= scale_;
    out.energyDensity *= scale_;
  }
  double minReferenceJacobian(const ddc::NodalArray& X) const override { return inner_->minReferenceJacobian(X); }

 private:
  std::shared_ptr<ddc::Element> inner_;
  double scale_;
};

/// The built-ins plus "Host Quad4" (counting wrapper of Quad4) and "Scaled
/// Quad4" (Quad4 with a stiffness factor), as a host code would register them.
ddc::ElementFactory hostFactory(std::shared_ptr<std::atomic<long>> calls) {
  ddc::ElementFactory f = ddc::ElementFactory::withBuiltins();
  const ddc::ElementFactory::Entry quad4 = f.entry("Quad4");

  ddc::ElementFactory::Entry counting = quad4;
  counting.create = [quad4, calls](const PL& p) -> std::shared_ptr<ddc::Element> {
    return std::make_shared<CountingElement>(quad4.create(p), calls);
  };
  counting.description = "Quad4 wrapped by the host, counting evaluations.";
  f.add("Host Quad4", counting);

  auto scaledParams = Teuchos::rcp(new PL(*ddc::ContinuumElement::getValidParameters()));
  scaledParams->set("Stiffness Scale", 1.0, "Factor on energy, forces and tangent (> 0).");
  ddc::ElementFactory::Entry scaled{
      [quad4](const PL& p) -> std::shared_ptr<ddc::Element> {
        PL inner;
        inner.set("Material", p.sublist("Material"));
        return std::make_shared<ScaledElement>(quad4.create(inner), p.get<double>("Stiffness Scale"));
      },
      scaledParams, "Quad4 with a stiffness factor (host element with its own parameter).", 4};
  f.add("Scaled Quad4", scaled);
  return f;
}

/// A 2 x 1 block, neo-Hookean unless told otherwise, clamped on the left,
/// pulled and sheared on the right (large deformation, several steps).
PL hostDeck(const std::string& elementType, const std::string& material = "Neo-Hookean") {
  PL deck("DDContact");
  PL& body = deck.sublist("Mesh").sublist("Bodies").sublist("Block");
  body.set("Generator", std::string("Rectangle"));
  PL& r = body.sublist("Rectangle");
  r.set("Length X", 2.0);
  r.set("Length Y", 1.0);
  r.set("Elements X", 8);
  r.set("Elements Y", 4);
  r.set("Distortion", 0.2);
  PL& el = body.sublist("Element");
  el.set("Type", elementType);
  el.sublist("Material").set("Type", material);
  PL& bcs = deck.sublist("Boundary Conditions");
  bcs.sublist("Clamped").set("Type", std::string("Displacement"));
  bcs.sublist("Clamped").set("Set", std::string("Block/left"));
  bcs.sublist("Load").set("Type", std::string("Traction"));
  bcs.sublist("Load").set("Set", std::string("Block/right"));
  bcs.sublist("Load").set("Traction X", 100.0);
  bcs.sublist("Load").set("Traction Y", 20.0);
  setRunOptions(deck, 3);
  return deck;
}

/// max |a - b| / max |b|.
double maxRelDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0, s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(a[i] - b[i]));
    s = std::max(s, std::abs(b[i]));
  }
  return d / s;
}

/// The InputError message of `f`, or a test failure if it does not throw one.
template <class Fn>
std::string inputErrorOf(Fn f) {
  try {
    f();
  } catch (const ddc::InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected ddc::InputError, got: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

bool contains(const std::string& s, const std::string& n) { return s.find(n) != std::string::npos; }

// ---------------------------------------------------------------------------

TEST(Embedding, HostElementIsUsedAndMatchesBuiltin) {
  auto calls = std::make_shared<std::atomic<long>>(0);
  PL hostParams = hostDeck("Host Quad4");
  ddc::Analysis host(worldComm(), hostParams, hostFactory(calls));
  host.run("");

  PL builtinParams = hostDeck("Quad4");
  ddc::Analysis builtin(worldComm(), builtinParams);
  builtin.run("");

  // The host element did the work on every rank that owns elements.
  const long local = calls->load();
  long total = 0;
  Teuchos::reduceAll(*worldComm(), Teuchos::REDUCE_SUM, local, Teuchos::outArg(total));
  EXPECT_GT(total, 0);
  if (!host.model().localElements().empty()) EXPECT_GT(local, 0);

  // Same element code behind it: identical histories and fields.
  const auto& hh = host.history();
  const auto& hb = builtin.history();
  ASSERT_EQ(hh.size(), hb.size());
  ASSERT_FALSE(hh.empty());
  for (size_t k = 0; k < hh.size(); ++k) {
    EXPECT_EQ(hh[k].newtonIterations, hb[k].newtonIterations);
    EXPECT_LE(relDiff(hh[k].strainEnergy, hb[k].strainEnergy), ddc::test::kRoundoff);
  }
  EXPECT_LE(maxRelDiff(gatherDisplacement(host), gatherDisplacement(builtin)), ddc::test::kRoundoff);
  // Large deformation actually happened (a few percent stretch at least).
  EXPECT_GT(hh.back().strainEnergy, 0.0);

  // The host's type shows in the parameter documentation built from the factory.
  std::ostringstream doc;
  ddc::printParameterDoc(*ddc::Analysis::getValidParameters(hostFactory(calls)), doc);
  EXPECT_TRUE(contains(doc.str(), "Host Quad4"));
  EXPECT_TRUE(contains(doc.str(), "Stiffness Scale"));
}

// history.csv of a run: the ten stable columns first, unchanged, then the
// extra columns with contact_force_z last (doc/user-guide.md, "The output
// directory").
TEST(Embedding, HistoryColumnsOfARun) {
  const std::string dir = "embedding_history_columns_np" + std::to_string(worldComm()->getSize());
  PL deck = hostDeck("Quad4");
  ddc::Analysis a(worldComm(), deck);
  a.run(dir);
  std::ifstream in(dir + "/history.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header,
            "step,load_factor,strain_energy,newton_iterations,dual_iterations,active_contacts,contact_force_x,"
            "contact_force_y,contact_exchanges,wall_seconds,external_work,contact_bytes,bisections,contact_force_z");
}

TEST(Embedding, HostElementParameterReachesTheElement) {
  // Linear elasticity under traction: a material s times stiffer gives
  // displacements 1/s and strain energy 1/s of the built-in element's.
  const double s = 4.0;
  auto calls = std::make_shared<std::atomic<long>>(0);
  PL scaledParams = hostDeck("Scaled Quad4", "Linear Elastic");
  scaledParams.sublist("Mesh").sublist("Bodies").sublist("Block").sublist("Element").set("Stiffness Scale", s);
  ddc::Analysis scaled(worldComm(), scaledParams, hostFactory(calls));
  scaled.run("");
  PL builtinParams = hostDeck("Quad4", "Linear Elastic");
  ddc::Analysis builtin(worldComm(), builtinParams);
  builtin.run("");
  ASSERT_FALSE(scaled.history().empty());
  EXPECT_LE(relDiff(s * scaled.history().back().strainEnergy, builtin.history().back().strainEnergy), 1e-10)
      << "energy of a linear solve: round-off times cond(K) (see kEnergyIdentity in DDC_TestTolerances.hpp)";
  auto us = gatherDisplacement(scaled);
  for (double& v : us) v *= s;
  EXPECT_LE(maxRelDiff(us, gatherDisplacement(builtin)), 1e-10);

  // A misspelt host parameter is rejected with its path.
  PL bad = hostDeck("Scaled Quad4");
  bad.sublist("Mesh").sublist("Bodies").sublist("Block").sublist("Element").set("Stiffness Scal", 2.0);
  const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), bad, hostFactory(calls)); });
  EXPECT_TRUE(contains(msg, "Mesh/Bodies/Block/Element/Stiffness Scal")) << msg;
}

TEST(Embedding, UnknownElementTypeListsKnownTypes) {
  auto calls = std::make_shared<std::atomic<long>>(0);
  PL params = hostDeck("Quad5");
  const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), params, hostFactory(calls)); });
  EXPECT_TRUE(contains(msg, "'Quad5'")) << msg;
  for (const char* known : {"'Host Quad4'", "'Quad4'", "'Quad9'", "'Scaled Quad4'"})
    EXPECT_TRUE(contains(msg, known)) << "known type " << known << " not listed: " << msg;
  // Names the body whose element it is.
  EXPECT_TRUE(contains(msg, "Mesh/Bodies/Block/Element")) << msg;

  // Without the host's registrations the host type is unknown too.
  PL params2 = hostDeck("Host Quad4");
  const std::string msg2 = inputErrorOf([&] { ddc::Analysis a(worldComm(), params2); });
  EXPECT_TRUE(contains(msg2, "'Host Quad4'")) << msg2;
  EXPECT_TRUE(contains(msg2, "'Quad4'") && contains(msg2, "'Quad9'")) << msg2;
}

// The parameter path in the message must be exactly the one of the entry
// (it once read 'Mesh/Bodies/Block/Element/Type/Type').
TEST(Embedding, UnknownElementTypeNamesExactPath) {
  PL params = hostDeck("Quad5");
  const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), params); });
  EXPECT_TRUE(contains(msg, "'Mesh/Bodies/Block/Element/Type'")) << msg;
  EXPECT_FALSE(contains(msg, "Type/Type")) << msg;
}

TEST(Embedding, MisspeltParameterNamesItsPath) {
  {
    PL params = hostDeck("Quad4");
    params.sublist("Load Stepping").set("Number of Step", 5);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), params); });
    EXPECT_TRUE(contains(msg, "Load Stepping/Number of Step")) << msg;
    EXPECT_TRUE(contains(msg, "Number of Steps")) << "valid names should be listed: " << msg;
  }
  {
    PL params = hostDeck("Quad4");
    params.sublist("Boundary Conditions").sublist("Clamped").set("Componets", std::string("X"));
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), params); });
    EXPECT_TRUE(contains(msg, "Boundary Conditions/Clamped/Componets")) << msg;
  }
  {
    PL params = hostDeck("Quad4");
    params.sublist("Mesh").sublist("Bodies").sublist("Block").sublist("Rectangle").set("Elements Z", 3);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), params); });
    EXPECT_TRUE(contains(msg, "Mesh/Bodies/Block/Rectangle/Elements Z")) << msg;
  }
  {
    PL params = hostDeck("Quad4");
    params.sublist("Mesh").sublist("Bodies").sublist("Block").sublist("Element").sublist("Material").set(
        "Youngs Modulus", 10.0);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), params); });
    EXPECT_TRUE(contains(msg, "Mesh/Bodies/Block/Element/Material/Youngs Modulus")) << msg;
  }
}

}  // namespace
