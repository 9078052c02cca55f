// A run's checkpoint (doc/user-guide.md, "Checkpoints and restart"): what
// it holds (the validated parameters, the step loop's state with the step
// controller's, the integrator's vectors, the contact slots, the VTK series),
// how a restart puts it back, and the observers that write it — every
// Output/Checkpoint Interval steps, after the last one, when a step fails for
// good, and when a stop is requested (SIGTERM, SIGINT, SIGUSR1).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "DDC_Checkpoint.hpp"
#include "DDC_Memory.hpp"
#include "DDC_StepLoop.hpp"

namespace ddc {

class VtkObserver;

/// The checkpoint section that identifies the mesh and element-map files
/// the run read (describeInputFiles(), DDC_Restart.hpp).
constexpr const char* kInputFilesSection = "input files";

/// Write the checkpoint of the state after `loop`'s last accepted step to
/// `path` (collective): `params` the run's validated parameters,
/// `inputFiles` the files it read (describeInputFiles()), `vtkSteps` the VTK
/// series written so far.
void writeRunCheckpoint(const std::string& path, const StepLoop& loop, const Teuchos::ParameterList& params,
                        const std::string& inputFiles, const std::vector<std::pair<int, double>>& vtkSteps);

/// Refuse a checkpoint of another layout than this version writes (an older
/// one lacks the identity of the input files), naming the file and what to do.
/// \throws InputError
void requireCheckpointLayout(const CheckpointReader& c);

/// Refuse a checkpoint whose "contact slot count" section (`count`) is not
/// the model's number of slots, `now`.
/// \throws InputError naming the file
void requireContactSlotCount(const std::vector<double>& count, size_t now, const std::string& file);

/// Refuse a checkpoint whose contact slots (`saved`) are not the model's
/// (`now`): another number of slots, or a slot of another pair or slave node.
/// \throws InputError naming the file
void requireSameContactSlots(const std::vector<ContactSlot>& saved, const std::vector<ContactSlot>& now,
                             const std::string& file);

/// The last converged step the checkpoint holds.
/// \throws InputError naming the file if it holds none
StepRecord checkpointLastStep(const CheckpointReader& c);

/// Put the state a checkpoint holds back into `loop` (and its model's
/// contact state, its controller, its integrator), before loop.run(); marks
/// the loop restarted. Returns the VTK series to continue. Collective.
/// \throws InputError when the checkpoint does not fit this model or
///         version, naming the file
std::vector<std::pair<int, double>> restoreRunCheckpoint(StepLoop& loop, Model& model, const CheckpointReader& c);

/// Writes the checkpoint (see the top of this file).
class CheckpointObserver final : public StepObserver {
 public:
  /// \param path the checkpoint in the staging directory
  /// \param finalPath the output directory a restart names
  /// \param vtk the VTK series (null: none)
  /// \param inputFiles the files the run read (describeInputFiles())
  CheckpointObserver(std::string path, std::string finalPath, int interval, const Teuchos::ParameterList& params,
                     std::string inputFiles, const VtkObserver* vtk);
  void accepted(const StepLoop& loop, const StepRecord& record, bool last) override;
  /// Writes the checkpoint of the last accepted step unless it is on disk,
  /// and says where it is (or why it is missing).
  std::string failed(const StepLoop& loop, const std::string& error) override;
  /// Write the checkpoint of the last accepted step unless it is on disk.
  void writeIfStale(const StepLoop& loop);
  const std::string& path() const { return path_; }
  const std::string& finalPath() const { return finalPath_; }

 private:
  void write(const StepLoop& loop);
  std::string path_, finalPath_, inputFiles_;
  int interval_;
  const Teuchos::ParameterList& params_;
  const VtkObserver* vtk_;
  size_t rows_ = 0;  ///< history rows of the checkpoint last written
};

/// What a running analysis watches its memory against: the limits the
/// memory check allowed and the fraction of them it may reach
/// (doc/user-guide.md, "Memory"). Inactive when the check is off.
struct MemoryWatch {
  bool active = false;
  MemoryBudget budget;
  double fraction = 0.9;  ///< Solver/Memory Stop Fraction
};

/// Stops the run after a step when a stop was requested on any rank
/// (requestStop(), DDC_StopRequest.hpp), or when its memory is above the
/// watch's fraction on any host or rank: its checkpoint is written and
/// RunInterrupted thrown on every rank (with the signal, or 0 for memory).
class StopObserver final : public StepObserver {
 public:
  /// \param checkpoint the checkpoint writer (null: the run writes none)
  /// \param noCheckpoint why there is none, for the message
  StopObserver(CheckpointObserver* checkpoint, std::string noCheckpoint, MemoryWatch watch = {})
      : checkpoint_(checkpoint), noCheckpoint_(std::move(noCheckpoint)), watch_(std::move(watch)) {}
  void accepted(const StepLoop& loop, const StepRecord& record, bool last) override;

 private:
  /// Writes the checkpoint if there is one; " ; its checkpoint is ..." or why there is none.
  std::string checkpointSentence(const StepLoop& loop, const std::string& continueHow) const;
  CheckpointObserver* checkpoint_;
  std::string noCheckpoint_;
  MemoryWatch watch_;
};

}  // namespace ddc
