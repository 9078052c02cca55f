// The step loop as a run sees it: the history header, the Exodus II global
// variables and the checkpoint's record fields of a run all come from the
// one table of DDC_StepRecord.hpp; a host's observer (Analysis::
// addObserver()) is told of every step, in order, and of a failure; a
// checkpoint of another record layout is refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Teuchos_XMLParameterListHelpers.hpp>
#include <exodusII.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_Checkpoint.hpp"
#include "DDC_Error.hpp"

using namespace ddc::test;  // deck builders, communicators (DDC_AnalysisTestDecks.hpp)
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;

namespace {

/// A block pulled in 2 load steps (2-D), or a brick shaken in 2 time steps
/// (3-D dynamics); results with Exodus II and a checkpoint every step.
PL outputDeck(bool dynamic3d) {
  PL deck("DDContact");
  if (dynamic3d) {
    BoxSpec b;
    b.elements[0] = 2;
    b.elements[1] = b.elements[2] = 1;
    addBox(deck, "Brick", b).sublist("Element").sublist("Material").set("Density", 1.0);
    addDisplacement(deck, "Clamped", "Brick/left", "XYZ");
    addTraction3(deck, "Load", "Brick/right", {10.0, 0.0, 5.0});
    deck.sublist("Dynamics").set("Integrator", std::string("Newmark"));
    deck.sublist("Dynamics").set("Final Time", 0.2);
    deck.sublist("Dynamics").set("Time Step", 0.1);
  } else {
    RectangleSpec r;
    r.nx = 4;
    r.ny = 2;
    addRectangle(deck, "Block", r);
    addDisplacement(deck, "Clamped", "Block/left", "XY");
    addTraction(deck, "Load", "Block/right", 10.0, 2.0);
  }
  setRunOptions(deck, 2);
  deck.sublist("Output").set("Exodus", true);
  deck.sublist("Output").set("Checkpoint Interval", 1);
  return deck;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}

std::vector<std::string> exodusGlobals(const std::string& file) {
  int cpu = 8, io = 0;
  float version = 0.0f;
  const int id = ex_open(file.c_str(), EX_READ, &cpu, &io, &version);
  EXPECT_GE(id, 0) << file;
  if (id < 0) return {};
  int n = 0;
  ex_get_variable_param(id, EX_GLOBAL, &n);
  std::vector<std::vector<char>> buffers(size_t(n), std::vector<char>(MAX_STR_LENGTH + 1, '\0'));
  std::vector<char*> names;
  for (auto& b : buffers) names.push_back(b.data());
  ex_get_variable_names(id, EX_GLOBAL, n, names.data());
  ex_close(id);
  std::vector<std::string> out;
  for (auto& b : buffers) out.emplace_back(b.data());
  return out;
}

/// Records what a host observer is told.
struct Recorder : ddc::StepObserver {
  std::vector<std::string> events;
  std::vector<double> loads;
  void started(const ddc::StepLoop&) override { events.push_back("started"); }
  void accepted(const ddc::StepLoop& loop, const ddc::StepRecord& r, bool last) override {
    events.push_back(last ? "accepted last" : "accepted");
    loads.push_back(r.loadFactor);
    EXPECT_EQ(&r, &loop.history().back());
  }
  void rejected(const ddc::StepLoop&, const ddc::RejectedStep& s) override {
    events.push_back(s.reason == ddc::RejectedStep::Reason::NewtonFailed ? "newton failed" : "sent back");
  }
  std::string failed(const ddc::StepLoop&, const std::string& error) override {
    events.push_back("failed: " + error.substr(0, 31));
    return "; noted by the host";
  }
  void finished(const ddc::StepLoop&) override { events.push_back("finished"); }
};

}  // namespace

// One table, three formats: history.csv's header, results.e's global
// variables and checkpoint.ddc's "history fields" are the table's names for
// the run's kind, quasi-static 2-D and dynamic 3-D.
TEST(StepLoop, HistoryExodusAndCheckpointNamesComeFromOneTable) {
  for (const bool dynamic3d : {false, true}) {
    const std::string dir = std::string("step_record_outputs_") + (dynamic3d ? "dynamic" : "static") + "_np" +
                            std::to_string(worldComm()->getSize());
    PL deck = outputDeck(dynamic3d);
    ddc::Analysis a(worldComm(), deck);
    a.run(dir);
    const ddc::RunKind kind{dynamic3d, false, dynamic3d ? 3 : 2};
    std::ifstream in(dir + "/history.csv");
    std::string header;
    std::getline(in, header);
    EXPECT_THAT(split(header), ElementsAreArray(ddc::historyColumns(kind)));
    EXPECT_THAT(exodusGlobals(dir + "/results.e"), ElementsAreArray(ddc::exodusGlobalNames(kind)));
    const ddc::CheckpointReader c(worldComm(), dir + "/checkpoint.ddc");
    EXPECT_THAT(split(c.bytes("history fields")), ElementsAreArray(ddc::checkpointFieldNames()));
    if (dynamic3d) {
      EXPECT_THAT(split(header), ::testing::Contains("total_energy"));
      EXPECT_THAT(exodusGlobals(dir + "/results.e"), ::testing::Contains("contact_force_z"));
    }
  }
}

// A host's observer sees the run start, every accepted step in order (the
// last one flagged) and its end; the loads are the history's.
TEST(StepLoop, HostObserverSeesEveryStep) {
  PL deck = outputDeck(false);
  deck.sublist("Load Stepping").set("Number of Steps", 3);
  auto recorder = std::make_shared<Recorder>();
  ddc::Analysis a(worldComm(), deck);
  a.addObserver(recorder);
  a.run("");
  EXPECT_THAT(recorder->events, ElementsAreArray({"started", "accepted", "accepted", "accepted last", "finished"}));
  ASSERT_EQ(recorder->loads.size(), a.history().size());
  for (size_t i = 0; i < a.history().size(); ++i) EXPECT_EQ(recorder->loads[i], a.history()[i].loadFactor);
}

// A step Newton cannot solve: the observer sees each halving, then the
// failure, and what it returns from failed() ends the error's message.
TEST(StepLoop, HostObserverSeesBisectionsAndTheFailure) {
  PL deck = outputDeck(false);
  deck.sublist("Newton").set("Max Iterations", 1);
  deck.sublist("Load Stepping").set("Max Bisections", 1);
  auto recorder = std::make_shared<Recorder>();
  ddc::Analysis a(worldComm(), deck);
  a.addObserver(recorder);
  try {
    a.run("");
    FAIL() << "Newton converged in one iteration";
  } catch (const ddc::SolverError& e) {
    EXPECT_THAT(e.what(), HasSubstr("Newton did not converge in step 1"));
    EXPECT_THAT(e.what(), HasSubstr("(Load Stepping/Max Bisections = 1)"));
    EXPECT_THAT(std::string(e.what()), ::testing::EndsWith("; noted by the host"));
  }
  EXPECT_THAT(recorder->events,
              ElementsAreArray({"started", "newton failed", "failed: Newton did not converge in step"}));
}

// A checkpoint whose step records are laid out otherwise (another version
// of DDContact: no "history fields", or other ones) is refused by name
// before anything is restored.
TEST(StepLoop, CheckpointOfAnotherRecordLayoutIsRefused) {
  for (const bool withFields : {false, true}) {
    PL deck = outputDeck(false);
    ddc::Analysis a(worldComm(), deck);
    std::ostringstream xml;
    Teuchos::writeParameterListToXmlOStream(a.parameters(), xml);
    const std::string file = "step_loop_other_layout_np" + std::to_string(worldComm()->getSize()) + ".ddc";
    {
      ddc::CheckpointWriter w(worldComm());
      w.putBytes("parameters", xml.str());
      w.putDoubles("run", {withFields ? 2.0 : 1.0, double(worldComm()->getSize()), 1.0, 0.0});
      if (withFields) w.putBytes("history fields", "step,load_factor");
      w.putDoubles("history", {1.0, 0.5});
      w.write(file);
    }
    ddc::RestartSource source;
    source.checkpoint = std::make_shared<const ddc::CheckpointReader>(worldComm(), file);
    a.setRestart(source);
    try {
      a.run("");
      FAIL() << "a checkpoint of another record layout was restored";
    } catch (const ddc::InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("checkpoint '" + file + "': written by another version of DDContact"));
    }
  }
}
