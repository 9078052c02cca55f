#include "DDC_OutputObservers.hpp"

#include <Teuchos_XMLParameterListHelpers.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <system_error>

#include "DDC_Error.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_ModelOutput.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_ResultFile.hpp"

namespace ddc {

// ---- history.csv ----------------------------------------------------------------

HistoryObserver::HistoryObserver(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& directory,
                                 const RunKind& kind)
    : kind_(kind), writer_(std::move(comm), directory + "/" + HistoryWriter::defaultFileName(), historyColumns(kind)) {}

void HistoryObserver::started(const StepLoop& loop) {
  if (loop.restarted())
    for (const StepRecord& r : loop.history()) writer_.appendRow(historyRow(r, kind_));
}

void HistoryObserver::accepted(const StepLoop&, const StepRecord& record, bool) {
  writer_.appendRow(historyRow(record, kind_));
}

void HistoryObserver::finished(const StepLoop&) { writer_.close(); }

// ---- vtk/ -------------------------------------------------------------------------

VtkObserver::VtkObserver(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& directory, int interval,
                         ProgressPrinter progress)
    : writer_(std::move(comm), directory, "solution.pvd"), interval_(interval), progress_(std::move(progress)) {}

void VtkObserver::continueSeries(std::string directory, std::vector<std::pair<int, double>> steps) {
  sourceDirectory_ = std::move(directory);
  sourceSteps_ = std::move(steps);
}

void VtkObserver::write(const StepLoop& loop, int step, double time) {
  const Dynamics* d = loop.dynamics();
  if (d)
    writeVtkStep(writer_, loop.model(), *loop.state().u, step, time, &d->integrator().velocity(),
                 &d->integrator().accelerationNow());
  else
    writeVtkStep(writer_, loop.model(), *loop.state().u, step, time);
}

void VtkObserver::started(const StepLoop& loop) {
  if (!loop.restarted()) {
    write(loop, 0, 0.0);
    return;
  }
  const auto missing = writer_.adoptSteps(sourceDirectory_, sourceSteps_);
  if (!missing.empty())
    progress_("warning: restart: " + std::to_string(missing.size()) + " VTK steps of the checkpointed run are "
              "missing in '" + sourceDirectory_ + "/vtk' (VTK was off, or the files were removed); the series "
              "goes on without them");
}

void VtkObserver::accepted(const StepLoop& loop, const StepRecord& record, bool last) {
  const int count = static_cast<int>(loop.history().size());
  if (count % interval_ == 0 || last) write(loop, count, record.loadFactor);
}

// ---- results.e --------------------------------------------------------------------

ExodusObserver::ExodusObserver(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& directory,
                               const Model& model, const RunKind& kind, const std::string& restartSource,
                               ProgressPrinter progress)
    : comm_(std::move(comm)), kind_(kind), source_(restartSource), progress_(std::move(progress)) {
  const std::string path = directory + "/results.e";
  // A restart continuing in the staging directory of the run it continues:
  // that run's results.e (or its pieces, ExodusWriter::resultFiles()) is
  // moved aside before this run's is created, copied from and removed (a
  // restart that failed before that finds it aside).
  origin_ = source_;
  if (!source_.empty()) {
    std::string error;
    std::error_code ec;
    const std::string sourceDirectory = std::filesystem::path(source_).parent_path().string();
    const std::string aside = directory + "/results.e.before-restart";
    std::string missing;
    const bool sameDirectory = std::filesystem::equivalent(sourceDirectory, directory, ec);
    const auto sourceFiles = comm_->getRank() == 0 ? ExodusWriter::resultFiles(source_) : std::vector<std::string>();
    const auto asideFiles = comm_->getRank() == 0 ? ExodusWriter::resultFiles(aside) : std::vector<std::string>();
    if (comm_->getRank() == 0 && sourceFiles.empty() && !(sameDirectory && !asideFiles.empty())) missing = "1";
    sourceMissing_ = !broadcastStrings(*comm_, {missing}).front().empty();
    if (sourceMissing_) source_.clear();
    if (comm_->getRank() == 0 && !sourceMissing_ && sameDirectory) {
      // results.e -> results.e.before-restart, results.e.P.r -> results.e.before-restart.P.r
      if (asideFiles.empty())
        for (const std::string& f : sourceFiles)
          if (!ec) std::filesystem::rename(f, aside + f.substr(source_.size()), ec);
      if (ec) error = "cannot move '" + source_ + "' aside for the restart: " + ec.message();
      source_ = aside;
      sourceAside_ = true;
    }
    error = firstErrorOnAnyRank(*comm_, error);
    if (!error.empty()) throw OutputError(error);
    source_ = broadcastStrings(*comm_, {source_}).front();
  }
  writer_ = std::make_unique<ExodusWriter>(comm_, path, model.mesh(),
                                           exodusVariables(model, kind.dynamic, exodusGlobalNames(kind)));
}

void ExodusObserver::started(const StepLoop& loop) {
  if (!loop.restarted()) return;
  const int count = static_cast<int>(loop.history().size());
  if (sourceMissing_) {
    progress_("warning: restart: results.e holds none of the " + std::to_string(count) +
              " steps before the checkpoint: the run that wrote it left no results.e ('" + origin_ +
              "'; Output/Exodus was false in that run, or the file was removed); history.csv holds them all");
    return;
  }
  if (source_.empty()) return;
  auto [copied, why] = writer_->copySteps(source_, count);
  // The earlier run's file by the name the user knows (not the name it was moved aside to).
  for (auto at = why.find(source_); at != std::string::npos; at = why.find(source_, at + origin_.size()))
    why.replace(at, source_.size(), origin_);
  if (copied < count)
    progress_("warning: restart: results.e holds " + std::to_string(copied) + " of the " + std::to_string(count) +
              " steps before the checkpoint (" + why + ")");
  std::error_code ec;
  if (sourceAside_)  // rank 0's flag
    for (const std::string& f : ExodusWriter::resultFiles(source_)) std::filesystem::remove(f, ec);
}

void ExodusObserver::accepted(const StepLoop& loop, const StepRecord& record, bool) {
  const Dynamics* d = loop.dynamics();
  writeExodusStep(*writer_, loop.model(), record.loadFactor, *loop.state().u,
                  d ? &d->integrator().velocity() : nullptr, d ? &d->integrator().accelerationNow() : nullptr,
                  exodusGlobals(record, kind_));
}

void ExodusObserver::finished(const StepLoop&) { writer_->close(); }

// ---- contact_nodes.csv ------------------------------------------------------------

void ContactNodesObserver::finished(const StepLoop& loop) {
  const Model& model = loop.model();
  std::string error;
  // The converged values, from the slots' owners to rank 0, which writes.
  std::vector<ContactSlot> slots = loop.state().convergedSlots;
  const bool writer = model.comm()->getRank() == 0;
  model.contact()->shareSlotValues(slots, writer ? slotIndices(slots.size()) : std::vector<int>());
  if (writer) {
    std::ostringstream os;
    os << "pair,node,x,y,z,gap,multiplier,tributary_area,pressure,active,tangential_x,tangential_y,tangential_z,"
          "slip,state\n";
    os.precision(17);
    for (const auto& s : slots) {
      const Eigen::Vector3d X = model.contactNodeReference(s.slaveNode);  // rank 0 may not hold the node
      const Eigen::Vector3d t = s.tangentialForce() + Eigen::Vector3d::Zero();  // + 0: no "-0" when zero
      os << s.pair << ',' << s.slaveNode << ',' << X[0] << ',' << X[1] << ',' << (model.dim() == 3 ? X[2] : 0.0)
         << ',' << (s.paired() ? s.gap : 0.0) << ',' << (s.active ? s.state.multiplier : 0.0) << ','
         << s.tributaryLength << ',' << s.pressure() << ',' << (s.active ? 1 : 0) << ',' << t[0] << ',' << t[1]
         << ',' << t[2] << ',' << s.slip << ',' << int(s.contactState()) << '\n';
    }
    try {
      writeFileAtomically(path_, os.str());
    } catch (const OutputError& e) {
      error = e.what();
    }
  }
  error = firstErrorOnAnyRank(*model.comm(), error);
  if (!error.empty()) throw OutputError(error);
}

// ---- progress -----------------------------------------------------------------------

ProgressObserver::ProgressObserver(ProgressPrinter progress, std::string warning)
    : progress_(std::move(progress)), warning_(std::move(warning)) {}

void ProgressObserver::started(const StepLoop&) {
  if (!warning_.empty()) progress_("warning: " + warning_);
}

void ProgressObserver::note(const StepLoop&, const std::string& line) { progress_(line); }

void ProgressObserver::rejected(const StepLoop& loop, const RejectedStep& s) {
  const char* factor = loop.settings().factorName.c_str();
  char buf[300];
  if (s.reason == RejectedStep::Reason::NewtonFailed) {
    std::snprintf(buf, sizeof buf, "  step %d: Newton failed at %s %.6g; bisecting (depth %d), next %.6g",
                  s.attempt.step, factor, s.attempt.to, s.next.depth, s.next.to);
    progress_(buf);
    return;
  }
  const bool repeat = s.reason == RejectedStep::Reason::Repeat;
  std::snprintf(buf, sizeof buf, "  step %d: frozen-geometry error %.3g above Step Control/Error Tolerance at %s %.6g; %s",
                s.attempt.step, s.record.geometryError, factor, s.attempt.to,
                repeat ? "repeating it with the projections and normals of its end" : "repeating it smaller");
  std::string line = buf;
  if (!repeat) {
    std::snprintf(buf, sizeof buf, " (size %.3g -> %.3g)", s.attempt.size, s.next.size);
    line += buf;
  }
  progress_(line);
}

void ProgressObserver::accepted(const StepLoop& loop, const StepRecord& rec, bool) {
  char buf[300];
  const std::string label = loop.stepLabel(rec.step);
  if (loop.dynamics())
    std::snprintf(buf, sizeof buf,
                  "step %s  time %.6g (dt %.3g)  Newton %2d  |r| %.3e -> %.3e  strain %.6e  kinetic %.6e  %.2f s",
                  label.c_str(), rec.loadFactor, rec.stepSize, rec.newtonIterations, rec.residualHistory.front(),
                  rec.residualHistory.back(), rec.strainEnergy, rec.kineticEnergy, rec.wallSeconds);
  else
    std::snprintf(buf, sizeof buf, "step %s  load %.6g  Newton %2d  |r| %.3e -> %.3e  energy %.6e  %.2f s",
                  label.c_str(), rec.loadFactor, rec.newtonIterations, rec.residualHistory.front(),
                  rec.residualHistory.back(), rec.strainEnergy, rec.wallSeconds);
  std::string line = buf;
  if (loop.controller().controlsError()) {
    std::snprintf(buf, sizeof buf, "  size %.3g  error %.3g", rec.stepSize, rec.geometryError);
    line += buf;
  }
  if (loop.model().hasContact()) {
    std::snprintf(buf, sizeof buf, "  contacts %d  force (%.4g, %.4g)", rec.activeContacts, rec.contactForce[0],
                  rec.contactForce[1]);
    line += buf;
    // z after the 2-D pair, so the line reads the same in 2-D.
    if (loop.model().dim() == 3) {
      std::snprintf(buf, sizeof buf, " z %.4g", rec.contactForce[2]);
      line += buf;
    }
  }
  progress_(line);
}

void ProgressObserver::finished(const StepLoop& loop) {
  const Model& model = loop.model();
  if (model.hasContact()) {
    const auto c = model.searchCounters();
    std::ostringstream os;
    os << "contact: " << model.exchanges() << " contact-geometry exchanges (" << model.bytesExchanged()
       << " bytes between ranks); slave queries: " << c[0] << " by tracking (" << c[1]
       << " fell back to the global search), " << c[2] << " by the global search";
    if (model.decomposedContact()) {
      const auto n = model.contactValueUpdates();
      const auto& b = loop.timing().contactValueBytes;
      os << "; active-set updates: " << n[0] << " with the evaluated slots' values (at most " << b[0]
         << " bytes received by a rank), " << n[1] << " with every slot's (at most " << b[1] << ")";
    }
    progress_(os.str());
    for (const auto& pair : model.neverPairedPairs())
      progress_("warning: " + pair + " never paired a slave node in this run: no master facet within the search "
                "radius (Contact/Search Radius) faced any of its slave nodes, so contact was not enforced there "
                "(doc/contact.md, 'Which slave nodes pair')");
  }
  const RunTiming& t = loop.timing();
  int dual = 0;
  for (const auto& r : loop.history()) dual += r.dualIterations;
  char buf[300];
  std::snprintf(buf, sizeof buf,
                "timing (max over ranks): assembly %.3f s, linear setup %.3f s, linear solve %.3f s over %d "
                "solves (%d dual/Krylov iterations); peak memory per rank %.1f MiB",
                t.assembly, t.linearSetup, t.linearSolve, t.linearSolves, dual, t.peakMemoryMiB);
  progress_(buf);
  const std::string breakdown = loop.strategy().timingReport(t.feti);  // collective
  if (!breakdown.empty()) progress_(breakdown);
}

void writeParametersFile(const Teuchos::Comm<int>& comm, const std::string& path, const Teuchos::ParameterList& params) {
  std::string error;
  if (comm.getRank() == 0) {
    try {
      std::ostringstream xml;
      Teuchos::writeParameterListToXmlOStream(params, xml);
      writeFileAtomically(path, xml.str());
    } catch (const OutputError& e) {
      error = e.what();
    }
  }
  error = firstErrorOnAnyRank(comm, error);
  if (!error.empty()) throw OutputError(error);
}

}  // namespace ddc
