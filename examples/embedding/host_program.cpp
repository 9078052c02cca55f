// A host code embedding DDContact: it assembles the parameters in memory (no
// XML file), registers its own element type next to the built-ins, watches
// the steps with its own observer, runs the analysis and checks the result
// against the built-in element.
#include <DDC_Analysis.hpp>
#include <DDC_Error.hpp>
#include <Tpetra_Core.hpp>
#include <atomic>
#include <cmath>
#include <iostream>
#include <vector>

namespace {

std::atomic<long> hostCalls{0};

/// A host element: delegates to the built-in Quad4 and counts evaluations.
class CountingQuad4 : public ddc::Element {
 public:
  explicit CountingQuad4(std::shared_ptr<ddc::Element> inner) : inner_(std::move(inner)) {}
  int numNodes() const override { return inner_->numNodes(); }
  int dim() const override { return inner_->dim(); }
  void compute(const ddc::NodalArray& X, const ddc::NodalArray& u, unsigned what,
               ddc::ElementResult& out) const override {
    ++hostCalls;
    inner_->compute(X, u, what, out);
  }
  void postprocess(const ddc::NodalArray& X, const ddc::NodalArray& u, ddc::ElementPostResult& out) const override {
    inner_->postprocess(X, u, out);
  }
  double minReferenceJacobian(const ddc::NodalArray& X) const override { return inner_->minReferenceJacobian(X); }

 private:
  std::shared_ptr<ddc::Element> inner_;
};

/// A host's step observer (doc/embedding.md, "Observing the steps"): told
/// of every accepted step, e.g. to feed the host's own monitoring.
class EnergyMonitor : public ddc::StepObserver {
 public:
  void accepted(const ddc::StepLoop&, const ddc::StepRecord& step, bool last) override {
    energies.push_back(step.strainEnergy);
    finalSeen = finalSeen || last;
  }
  std::vector<double> energies;
  bool finalSeen = false;
};

Teuchos::ParameterList deck(const std::string& elementType) {
  Teuchos::ParameterList p("host");
  auto& body = p.sublist("Mesh").sublist("Bodies").sublist("Plate");
  body.set("Generator", "Rectangle");
  body.sublist("Rectangle").set("Elements X", 6).set("Elements Y", 3).set("Length X", 2.0);
  body.sublist("Element").set("Type", elementType);
  body.sublist("Element").sublist("Material").set("Type", "Neo-Hookean");
  auto& fix = p.sublist("Boundary Conditions").sublist("Fixed");
  fix.set("Type", "Displacement").set("Set", "Plate/left");
  auto& pull = p.sublist("Boundary Conditions").sublist("Pulled");
  pull.set("Type", "Traction").set("Set", "Plate/right").set("Traction X", 50.0);
  p.sublist("Load Stepping").set("Number of Steps", 3);
  p.sublist("Output").set("Progress", false);
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  int failures = 0;
  try {
    ddc::ElementFactory factory = ddc::ElementFactory::withBuiltins();
    ddc::ElementFactory::Entry quad4 = factory.entry("Quad4");
    ddc::ElementFactory::Entry entry = quad4;
    entry.description = "host: counting wrapper of Quad4";
    entry.create = [quad4](const Teuchos::ParameterList& pl) {
      return std::make_shared<CountingQuad4>(quad4.create(pl));
    };
    factory.add("Host Quad4", entry);

    auto hostDeck = deck("Host Quad4");
    ddc::Analysis host(comm, hostDeck, factory);
    auto monitor = std::make_shared<EnergyMonitor>();
    host.addObserver(monitor);
    host.run("");
    auto builtinDeck = deck("Quad4");
    ddc::Analysis builtin(comm, builtinDeck);
    builtin.run("");

    const double eh = host.history().back().strainEnergy, eb = builtin.history().back().strainEnergy;
    // Same element underneath, same partition: identical up to round-off.
    const double tol = 1e-12;
    if (hostCalls == 0) ++failures, std::cerr << "host element was never evaluated\n";
    // The observer saw every step of the history, the last one flagged.
    if (monitor->energies.size() != host.history().size() || !monitor->finalSeen ||
        monitor->energies.back() != eh)
      ++failures, std::cerr << "the observer saw " << monitor->energies.size() << " of "
                            << host.history().size() << " steps\n";
    if (!(eh > 0) || std::abs(eh - eb) > tol * eb) ++failures, std::cerr << "energies differ: " << eh << " vs " << eb << "\n";
    try {
      auto bad = deck("No Such Element");
      ddc::Analysis a(comm, bad, factory);
      ++failures;
      std::cerr << "unknown element type was accepted\n";
    } catch (const ddc::InputError& e) {
      if (std::string(e.what()).find("Host Quad4") == std::string::npos) ++failures, std::cerr << e.what() << "\n";
    }
    if (comm->getRank() == 0)
      std::cout << "host program: energy " << eh << " (built-in " << eb << "), host element calls on rank 0: "
                << hostCalls << "\n";
  } catch (const std::exception& e) {
    std::cerr << "host program: " << e.what() << "\n";
    ++failures;
  }
  if (comm->getRank() == 0) std::cout << (failures ? "host program: FAILED" : "host program: OK") << std::endl;
  return failures ? 1 : 0;
}
