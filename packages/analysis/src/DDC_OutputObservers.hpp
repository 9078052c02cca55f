// The observers that write a run's results into its output directory
// (doc/user-guide.md, "The output directory"): history.csv, the VTK
// series, the Exodus II results and contact_nodes.csv, each a StepObserver
// of the step loop (DDC_StepObserver.hpp), and the progress lines on rank 0.
// Each one's constructor creates its file (collective), its accepted()
// appends a step, its finished() closes it; after a restart its started()
// continues the series of the run it continues.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "DDC_ExodusWriter.hpp"
#include "DDC_HistoryWriter.hpp"
#include "DDC_StepLoop.hpp"
#include "DDC_VtkWriter.hpp"

namespace ddc {

/// Prints a line for the user (rank 0, Output/Progress).
using ProgressPrinter = std::function<void(const std::string&)>;

/// history.csv: the header of the run's kind (historyColumns()) and one row
/// per accepted step; after a restart the restored rows first.
class HistoryObserver final : public StepObserver {
 public:
  HistoryObserver(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& directory, const RunKind& kind);
  void started(const StepLoop& loop) override;
  void accepted(const StepLoop& loop, const StepRecord& record, bool last) override;
  void finished(const StepLoop& loop) override;

 private:
  RunKind kind_;
  HistoryWriter writer_;
};

/// vtk/: step 0 (the unloaded state) and every Output/VTK Interval accepted
/// steps (the last always); after a restart the earlier run's files are
/// adopted instead of step 0.
class VtkObserver final : public StepObserver {
 public:
  VtkObserver(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& directory, int interval,
              ProgressPrinter progress);
  /// A restart: the series of the run it continues, in `directory`/vtk
  /// (adopted by started()).
  void continueSeries(std::string directory, std::vector<std::pair<int, double>> steps);
  void started(const StepLoop& loop) override;
  void accepted(const StepLoop& loop, const StepRecord& record, bool last) override;
  /// The steps written so far (a checkpoint's).
  const std::vector<std::pair<int, double>>& steps() const { return writer_.steps(); }

 private:
  void write(const StepLoop& loop, int step, double time);
  VtkWriter writer_;
  int interval_;
  ProgressPrinter progress_;
  std::string sourceDirectory_;
  std::vector<std::pair<int, double>> sourceSteps_;
};

/// results.e: the mesh, every accepted step's fields and its record's
/// Exodus II globals (exodusGlobalNames()); after a restart the earlier
/// run's steps are copied first.
class ExodusObserver final : public StepObserver {
 public:
  /// \param restartSource the results.e of the run a restart continues
  ///        ("" for none); when it is the file this run writes (a restart
  ///        in its own staging directory) it is moved aside first.
  ExodusObserver(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& directory, const Model& model,
                 const RunKind& kind, const std::string& restartSource, ProgressPrinter progress);
  void started(const StepLoop& loop) override;
  void accepted(const StepLoop& loop, const StepRecord& record, bool last) override;
  void finished(const StepLoop& loop) override;

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  RunKind kind_;
  std::string source_;   ///< the restart's results.e ("" none)
  std::string origin_;   ///< its name before it was moved aside, for messages
  bool sourceMissing_ = false;  ///< the run a restart continues left no results.e
  bool sourceAside_ = false;  ///< source_ was moved aside and is removed once copied
  ProgressPrinter progress_;
  std::unique_ptr<ExodusWriter> writer_;
};

/// contact_nodes.csv: one row per contact slave node at the last converged
/// step (Output/Contact Nodes), written when the run finishes.
class ContactNodesObserver final : public StepObserver {
 public:
  explicit ContactNodesObserver(std::string path) : path_(std::move(path)) {}
  void finished(const StepLoop& loop) override;

 private:
  std::string path_;
};

/// The progress lines: one per accepted step, the bisections and repeats,
/// the notes of the loop, and at the end the contact and timing summaries.
/// Registered on every rank (the summaries need collective reductions);
/// `progress` prints on rank 0 when Output/Progress is on.
class ProgressObserver final : public StepObserver {
 public:
  /// \param warning printed at the start (e.g. nearly incompressible bodies), "" none
  ProgressObserver(ProgressPrinter progress, std::string warning);
  void started(const StepLoop& loop) override;
  void note(const StepLoop& loop, const std::string& line) override;
  void rejected(const StepLoop& loop, const RejectedStep& step) override;
  void accepted(const StepLoop& loop, const StepRecord& record, bool last) override;
  void finished(const StepLoop& loop) override;

 private:
  ProgressPrinter progress_;
  std::string warning_;
};

/// Write the validated parameters (defaults included) to `path`, checked (a
/// full disk must not leave an empty file behind). Collective.
void writeParametersFile(const Teuchos::Comm<int>& comm, const std::string& path, const Teuchos::ParameterList& params);

}  // namespace ddc
