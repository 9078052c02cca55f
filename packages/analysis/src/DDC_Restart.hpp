// Restart: where a run's checkpoint is, and what a restarted run may change
// (doc/user-guide.md, "Checkpoints and restart").
//
// A run with an output directory D writes its checkpoint to
// D.partial/checkpoint.ddc while it runs (the staging directory,
// OutputDirectory); the checkpoint is committed into D with the results.
// A run that fails or is stopped leaves it in D.partial. A restart from D
// reads D.partial's checkpoint if there is one (the newest state), else D's.
#pragma once

#include <Teuchos_Comm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>
#include <vector>

#include "DDC_Checkpoint.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_StepLoop.hpp"
#include "DDC_StepRecord.hpp"

namespace ddc {

/// The checkpoint file's name in a result or staging directory.
constexpr const char* kCheckpointFileName = "checkpoint.ddc";

/// The checkpoint an earlier run left for a restart, read and checked.
struct RestartSource {
  std::string finalPath;    ///< the earlier run's output directory (OutputDirectory::normalisedPath())
  std::string directory;    ///< where its files are: finalPath + ".partial" (unfinished) or finalPath
  bool unfinished = false;  ///< `directory` is the staging directory of a run that did not finish
  std::shared_ptr<const CheckpointReader> checkpoint;
};

/// Find and read the checkpoint of the run whose output directory was `dir`
/// (collective; see the top of this file).
/// \throws InputError naming `dir` when neither it nor its staging
///         directory has a checkpoint (or `dir` names the staging directory
///         or a file, the checkpoint is not a regular file, or the finished
///         run's checkpoint would stand in for an unfinished run's),
///         CheckpointReader's errors for a corrupted, truncated, foreign or
///         too large file, and requireCheckpointLayout()'s for another layout
RestartSource findRestartSource(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& dir);

/// The parameters a restart may change: the steps (Load Stepping, Step
/// Control, Dynamics' final time, time step and bisections), the solution
/// method (Newton, Solver, Partition) and the output (Output). Paths of
/// sublists end in "/".
const std::vector<std::string>& restartChangeableParameters();

/// Check that the validated parameters `now` differ from those of the
/// checkpointed run, `saved`, only where restartChangeableParameters() allows.
/// \throws InputError naming the first parameter that differs (its path,
///         both values, the checkpoint) and what may change
void checkRestartParameters(const Teuchos::ParameterList& saved, const Teuchos::ParameterList& now,
                            const std::string& checkpointPath);

/// The files a run read, as its checkpoint records them: one line per file,
/// "<size> <fingerprint> <parameter>\t<file>".
std::string describeInputFiles(const std::vector<InputFileIdentity>& files);

/// Check that each file this run reads (`now`) is, byte for byte as far as
/// size and fingerprint tell, the one the checkpointed run read (`saved`,
/// describeInputFiles()): a restart continues that run's state on its mesh.
/// \throws InputError naming the parameter, the file, both sizes and the
///         checkpoint, and what to do
void checkRestartInputFiles(const std::string& saved, const std::vector<InputFileIdentity>& now,
                            const std::string& checkpointPath);

/// Check that the checkpoint's last step `last` does not lie beyond this
/// run's final load factor (or final time), `settings.finalValue`: the
/// result would end beyond what was asked for.
/// \throws InputError naming the parameter, both values and the checkpoint
void checkRestartFinalValue(const StepRecord& last, const StepLoopSettings& settings,
                            const std::string& checkpointPath);

}  // namespace ddc
