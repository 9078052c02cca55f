#include "DDC_RunCheckpoint.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include <climits>
#include <csignal>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_OutputObservers.hpp"
#include "DDC_StopRequest.hpp"

namespace ddc {

namespace {

/// The checkpoint's record of the run: its layout version, the ranks that
/// wrote it, the number of step records and the external work. Layout 2:
/// the step records' fields are those the "history fields" section names.
/// Layout 3: the section kInputFilesSection identifies the mesh and
/// element-map files the run read.
/// Layout 4: the contact slots carry Coulomb friction's state; 5: their
/// master facets in the order of (element id, side); 6: the slots are
/// vectors written by their owners (ownedSlotsVector()).
constexpr double kCheckpointLayout = 6.0;
/// The first layout that records the input files.
constexpr double kFirstLayoutWithInputFiles = 3.0;

/// The same entries as `v` (on model.ownedMap()) on a map of the
/// partition-free DOF ids (Model::partitionFreeDof()), in the same local
/// order: a checkpoint's vectors read back on any number of ranks.
Teuchos::RCP<Vector> partitionFreeVector(const Model& model, const Vector& v) {
  const Map& owned = *model.ownedMap();
  std::vector<GO> ids(owned.getNodeNumElements());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = model.partitionFreeDof(owned.getGlobalElement(LO(i)));
  const Teuchos::ArrayView<const GO> view(ids.data(), ids.size());
  auto map = Teuchos::rcp(new Map(owned.getGlobalNumElements(), view, 0, owned.getComm()));
  auto out = Teuchos::rcp(new Vector(map));
  auto src = v.getData();
  auto dst = out->getDataNonConst();
  for (size_t i = 0; i < ids.size(); ++i) dst[i] = src[i];
  return out;
}

/// The slots this rank owns (ContactComponent::ownedSlots()) of `slots` as
/// a distributed vector: entry k L + j is number j of slot k's packSlots()
/// record (L = packedSlotSize()). Each owner writes its own slots, whose
/// values are current there, so no rank gathers the contact surface.
Teuchos::RCP<Vector> ownedSlotsVector(const Model& model, const std::vector<ContactSlot>& slots) {
  const std::vector<int>& owned = model.contact()->ownedSlots();
  const size_t L = packedSlotSize();
  DDC_CHECK(slots.size() == model.contactSlots().size(),
            "checkpoint: " << slots.size() << " contact slots for the model's " << model.contactSlots().size());
  std::vector<ContactSlot> mine;
  for (int k : owned) mine.push_back(slots[size_t(k)]);
  const std::vector<double> packed = packSlots(mine);
  std::vector<GO> ids(packed.size());
  for (size_t i = 0; i < owned.size(); ++i)
    for (size_t j = 0; j < L; ++j) ids[i * L + j] = GO(owned[i]) * GO(L) + GO(j);
  const Teuchos::ArrayView<const GO> view(ids.data(), ids.size());
  auto map = Teuchos::rcp(new Map(GO(slots.size() * L), view, 0, model.comm()));
  auto v = Teuchos::rcp(new Vector(map));
  auto dst = v->getDataNonConst();
  for (size_t i = 0; i < packed.size(); ++i) dst[i] = packed[i];
  return v;
}

/// Every one of the `count` slots of the checkpoint's vector `name`
/// (ownedSlotsVector()), on every rank: each rank reads an even range of
/// the slots, and the ranges are gathered, because every rank holds every
/// slot (ContactComponent::slots()). Collective.
std::vector<ContactSlot> readSlots(const Model& model, const CheckpointReader& c, const std::string& name,
                                   size_t count) {
  const int P = model.comm()->getSize(), r = model.comm()->getRank();
  const size_t L = packedSlotSize();
  DDC_CHECK(count * L <= size_t(INT_MAX), "checkpoint: " << count << " contact slots are too many to gather");
  auto first = [&](int q) { return count * size_t(q) / size_t(P); };
  std::vector<GO> ids;
  for (size_t k = first(r); k < first(r + 1); ++k)
    for (size_t j = 0; j < L; ++j) ids.push_back(GO(k * L + j));
  const Teuchos::ArrayView<const GO> view(ids.data(), ids.size());
  Vector v(Teuchos::rcp(new Map(GO(count * L), view, 0, model.comm())));
  c.vector(name, v);
  std::vector<int> sizes(P), offsets(P);
  for (int q = 0; q < P; ++q) sizes[q] = int((first(q + 1) - first(q)) * L), offsets[q] = int(first(q) * L);
  std::vector<double> all(count * L);
  auto mine = v.getData();
  MPI_Allgatherv(mine.getRawPtr(), sizes[r], MPI_DOUBLE, all.data(), sizes.data(), offsets.data(), MPI_DOUBLE,
                 rawComm(model.comm()));
  return unpackSlots(all);
}

/// The names of checkpointFieldNames() joined by ','.
std::string historyFieldList() {
  std::string list;
  for (const auto& name : checkpointFieldNames()) list += (list.empty() ? "" : ",") + name;
  return list;
}

/// "SIGTERM", "SIGINT", "SIGUSR1", or "signal N".
std::string signalName(int signal) {
  if (signal == SIGTERM) return "SIGTERM";
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGUSR1) return "SIGUSR1";
  return "signal " + std::to_string(signal);
}

}  // namespace

void writeRunCheckpoint(const std::string& path, const StepLoop& loop, const Teuchos::ParameterList& params,
                        const std::string& inputFiles, const std::vector<std::pair<int, double>>& vtkSteps) {
  const Model& model = loop.model();
  const RunState& st = loop.state();
  CheckpointWriter w(model.comm());
  std::ostringstream xml;
  Teuchos::writeParameterListToXmlOStream(params, xml);
  w.putBytes("parameters", xml.str());
  w.putDoubles("run", {kCheckpointLayout, double(model.comm()->getSize()), double(st.history.size()), st.externalWork});
  w.putDoubles("controller", st.controllerState);
  w.putBytes("history fields", historyFieldList());
  w.putBytes(kInputFilesSection, inputFiles);
  w.putDoubles("history", packStepRecords(st.history));
  std::vector<double> vtk;
  for (const auto& [step, time] : vtkSteps) vtk.insert(vtk.end(), {double(step), time});
  w.putDoubles("vtk steps", vtk);
  auto put = [&](const std::string& name, const Vector& v) { w.putVector(name, *partitionFreeVector(model, v)); };
  put("displacement", *st.u);
  put("internal force", *st.fint);
  put("reaction", *st.reaction);
  if (const Dynamics* d = loop.dynamics()) {
    put("velocity", d->integrator().velocity());
    put("acceleration", d->integrator().accelerationNow());
  }
  if (model.hasContact()) {
    w.putDoubles("contact slot count", {double(model.contactSlots().size())});
    w.putVector("contact slots", *ownedSlotsVector(model, model.contactSlots()));
    w.putVector("converged contact slots", *ownedSlotsVector(model, st.convergedSlots));
    const auto paired = model.contact()->pairedRecord();
    w.putBytes("paired contact pairs", std::string(paired.begin(), paired.end()));
  }
  w.write(path);
}

void requireContactSlotCount(const std::vector<double>& count, size_t now, const std::string& file) {
  DDC_INPUT_REQUIRE(count.size() == 1 && count[0] == double(now),
                    "checkpoint '" << file << "': its contact slave nodes are not this model's");
}

void requireSameContactSlots(const std::vector<ContactSlot>& saved, const std::vector<ContactSlot>& now,
                             const std::string& file) {
  bool same = saved.size() == now.size();
  for (size_t k = 0; same && k < saved.size(); ++k)
    same = saved[k].pair == now[k].pair && saved[k].slaveNode == now[k].slaveNode;
  DDC_INPUT_REQUIRE(same, "checkpoint '" << file << "': its contact slave nodes are not this model's");
}

namespace {

/// The contact state of a checkpoint into `model`.
void restoreContact(Model& model, RunState& st, const CheckpointReader& c) {
  const std::string& file = c.path();
  const auto& now = model.contactSlots();
  requireContactSlotCount(c.doubles("contact slot count"), now.size(), file);
  auto slots = readSlots(model, c, "contact slots", now.size());
  requireSameContactSlots(slots, now, file);
  model.restoreContactState(slots);
  st.convergedSlots = readSlots(model, c, "converged contact slots", now.size());
  const std::string& paired = c.bytes("paired contact pairs");
  DDC_INPUT_REQUIRE(paired.size() == model.contact()->pairedRecord().size(),
                    "checkpoint '" << file << "': its contact pairs are not this model's");
  model.addPairedRecord(std::vector<char>(paired.begin(), paired.end()));
}

}  // namespace

void requireCheckpointLayout(const CheckpointReader& c) {
  const std::string& file = c.path();
  const auto run = c.has("run") ? c.doubles("run") : std::vector<double>();
  DDC_INPUT_REQUIRE(run.size() != 4 || run[0] >= kFirstLayoutWithInputFiles,
                    "checkpoint '" << file << "': written by another version of DDContact (layout " << run[0]
                                   << ", which does not record the mesh and element-map files the run read, so a "
                                      "restart cannot check that they are unchanged): start the run anew (without "
                                      "--restart)");
  DDC_INPUT_REQUIRE(run.size() == 4 && run[0] == kCheckpointLayout && c.has("history fields") &&
                        c.bytes("history fields") == historyFieldList() && c.has(kInputFilesSection),
                    "checkpoint '" << file << "': written by another version of DDContact (sections 'run', "
                                      "'history fields', '" << kInputFilesSection
                                   << "'): restart it with that version, or start the run anew (without --restart)");
}

StepRecord checkpointLastStep(const CheckpointReader& c) {
  const auto history = unpackStepRecords(c.doubles("history"), c.path());
  DDC_INPUT_REQUIRE(!history.empty(), "checkpoint '" << c.path() << "' holds no converged step");
  return history.back();
}

std::vector<std::pair<int, double>> restoreRunCheckpoint(StepLoop& loop, Model& model, const CheckpointReader& c) {
  const std::string& file = c.path();
  RunState& st = loop.state();
  requireCheckpointLayout(c);
  st.externalWork = c.doubles("run")[3];
  st.history = unpackStepRecords(c.doubles("history"), file);
  DDC_INPUT_REQUIRE(!st.history.empty(), "checkpoint '" << file << "' holds no converged step");
  StepController& steps = loop.controller();
  DDC_INPUT_REQUIRE(steps.restoreState(c.doubles("controller"), int(st.history.size())),
                    "checkpoint '" << file
                                   << "': its step controller cannot be restored (a host's own controller "
                                      "(Analysis::setStepController()) saves none)");
  st.controllerState = steps.saveState();
  st.wallOffset = st.history.back().wallSeconds;
  // Read on this model's partition-free ids, kept in the owned map's order.
  auto get = [&](const std::string& name, Vector& v) {
    auto tmp = partitionFreeVector(model, v);
    c.vector(name, *tmp);
    auto src = tmp->getData();
    auto dst = v.getDataNonConst();
    for (size_t i = 0; i < v.getLocalLength(); ++i) dst[i] = src[i];
  };
  get("displacement", *st.u);
  get("internal force", *st.fint);
  get("reaction", *st.reaction);
  if (Dynamics* d = loop.dynamics()) {
    DDC_INPUT_REQUIRE(c.has("velocity") && c.has("acceleration"),
                      "checkpoint '" << file << "' is of a quasi-static run; this one is dynamic");
    auto v = model.createVector(), a = model.createVector();
    get("velocity", *v);
    get("acceleration", *a);
    d->integrator().restoreState(*st.u, *v, *a);
  }
  if (model.hasContact()) restoreContact(model, st, c);
  loop.markRestarted();
  const auto vtk = c.doubles("vtk steps");
  std::vector<std::pair<int, double>> series;
  for (size_t i = 0; i + 1 < vtk.size(); i += 2) series.emplace_back(int(vtk[i]), vtk[i + 1]);
  return series;
}

// ---- the observers ---------------------------------------------------------------

CheckpointObserver::CheckpointObserver(std::string path, std::string finalPath, int interval,
                                       const Teuchos::ParameterList& params, std::string inputFiles,
                                       const VtkObserver* vtk)
    : path_(std::move(path)),
      finalPath_(std::move(finalPath)),
      inputFiles_(std::move(inputFiles)),
      interval_(interval),
      params_(params),
      vtk_(vtk) {}

void CheckpointObserver::write(const StepLoop& loop) {
  writeRunCheckpoint(path_, loop, params_, inputFiles_, vtk_ ? vtk_->steps() : std::vector<std::pair<int, double>>());
  rows_ = loop.history().size();
}

void CheckpointObserver::writeIfStale(const StepLoop& loop) {
  if (rows_ != loop.history().size()) write(loop);
}

void CheckpointObserver::accepted(const StepLoop& loop, const StepRecord&, bool last) {
  if (loop.history().size() % size_t(interval_) == 0 || last) write(loop);
}

std::string CheckpointObserver::failed(const StepLoop& loop, const std::string&) {
  // The state is the last converged step's (the loop restored it).
  const auto& history = loop.history();
  if (history.empty()) return "";
  std::ostringstream os;
  try {
    writeIfStale(loop);
    os << "; the checkpoint of step " << history.back().step << " (" << loop.settings().factorName << " "
       << history.back().loadFactor << ") is '" << path_ << "': continue with --restart '" << finalPath_
       << "' (changing the steps or the solver settings)";
  } catch (const OutputError& w) {
    // The failure is the news; that its checkpoint is missing comes second.
    os << "; the checkpoint of the last converged step could not be written: " << w.what();
  }
  return os.str();
}

std::string StopObserver::checkpointSentence(const StepLoop& loop, const std::string& continueHow) const {
  if (!checkpoint_) return "; no checkpoint (" + noCheckpoint_ + ")";
  checkpoint_->writeIfStale(loop);
  return "; its checkpoint is '" + checkpoint_->path() + "': continue with --restart '" + checkpoint_->finalPath() +
         "'" + continueHow;
}

void StopObserver::accepted(const StepLoop& loop, const StepRecord& record, bool last) {
  // A stop requested by a signal on any rank (requestStop()): after this
  // step, on every rank.
  const auto& comm = *loop.model().comm();
  int stop = stopRequested(), stopAll = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, stop, Teuchos::outArg(stopAll));
  if (last) return;
  std::ostringstream os;
  os << " after step " << record.step << " (" << loop.settings().factorName << " " << record.loadFactor << ")";
  if (stopAll) throw RunInterrupted("stopped by " + signalName(stopAll) + os.str() + checkpointSentence(loop, ""), stopAll);
  // Memory near what the check allowed: stop before the kernel kills a rank.
  const std::string memory = watch_.active ? memoryAboveBudget(comm, watch_.budget, watch_.fraction) : "";
  if (!memory.empty())
    throw RunInterrupted("stopped" + os.str() + " before memory runs out: " + memory +
                             " (doc/user-guide.md, 'Memory'; 'Solver/Memory Stop Fraction')" +
                             checkpointSentence(loop, " with fewer ranks per host, on more hosts, or with a lighter "
                                                      "solver (FETI-DP, or Belos-MueLu instead of a direct solver)"),
                         0);
}

}  // namespace ddc
