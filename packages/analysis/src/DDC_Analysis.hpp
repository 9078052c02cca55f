// The analysis: builds a model from a validated Teuchos::ParameterList and
// runs its steps — load stepping, or with Dynamics/Integrator set the time
// steps of implicit dynamics — in the step loop of the steps package
// (DDC_StepLoop.hpp), with the observers that write its output.
//
// Embedding lifecycle (Tribol style), for host codes:
//   1. Analysis a(comm, params);                 // validate + build (collective)
//      or Analysis a(comm, params, factory);     // with host element types
//   2. a.addObserver(myObserver);                // optional: see every step
//   3. a.run("out/dir");                         // or a.run("") for no files
//   4. a.history(), a.model(), a.displacement()  // results
// Nothing here reads files other than meshes named in the parameters.
#pragma once

#include <Teuchos_Comm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>
#include <vector>

#include "DDC_DirectSolver.hpp"
#include "DDC_ElementFactory.hpp"
#include "DDC_FetiDpSolver.hpp"
#include "DDC_Memory.hpp"
#include "DDC_MemoryEstimate.hpp"
#include "DDC_MeshInRanges.hpp"
#include "DDC_Model.hpp"
#include "DDC_ModelSetUp.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_Restart.hpp"
#include "DDC_SolutionStrategy.hpp"
#include "DDC_StepController.hpp"
#include "DDC_StepLoop.hpp"
#include "DDC_StepObserver.hpp"
#include "DDC_StepRecord.hpp"
#include "DDC_StepsSetUp.hpp"

namespace ddc {

/// A whole analysis (depth (a) of doc/embedding.md): mesh, partition,
/// boundary conditions, contact, the solution strategy and the Newton load
/// stepping built from one parameter list. Every member function is
/// collective over the communicator given to the constructor.
class Analysis {
 public:
  /// Every valid parameter, with defaults and doc strings, for the element
  /// types in `factory`. Sublists named "<...>" are templates (any name).
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters(
      const ElementFactory& factory = ElementFactory::withBuiltins());

  /// Validate `params` (filled with defaults in place) and build the model.
  /// Collective over `comm`.
  /// \param comm the ranks of the analysis (the model's DOFs and subdomains
  ///        are distributed over them)
  /// \param params the deck's parameters (doc/parameters.md); validated and
  ///        filled with defaults in place
  /// \param factory element types for Mesh/Bodies/\<name\>/Element/Type (the
  ///        built-in continuum elements by default); the contact elements
  ///        are added to it if missing
  /// \param baseDirectory directory relative mesh file names are resolved in
  ///        (the input deck's directory).
  /// \throws InputError naming the parameter path / file / mesh entity.
  Analysis(Teuchos::RCP<const Teuchos::Comm<int>> comm, Teuchos::ParameterList& params,
           ElementFactory factory = ElementFactory::withBuiltins(), const std::string& baseDirectory = ".");
  ~Analysis();

  /// Run every load step. With a non-empty `outputDirectory`, write
  /// history.csv, vtk/ and the validated parameters there: results are
  /// staged in "<dir>.partial" and replace "<dir>" only when the run succeeds.
  /// \throws SolverError when a step fails after all bisections, or when the
  ///         run ends without a converged step (nothing is committed then);
  ///         OutputError when the results cannot be written (earlier results
  ///         in the directory stay as they were).
  void run(const std::string& outputDirectory);

  /// Run every load step, writing into `dir` (opened by the caller, e.g. the
  /// ddcontact application before it builds the analysis, so that a
  /// directory in use or not written by DDContact stops the run before any
  /// work). Commits `dir` when the run succeeds. The caller prints
  /// dir.recoveryNotes() (run(const std::string&) does).
  void run(OutputDirectory& dir);

  /// Take the steps of the next run() from `controller` instead of the one
  /// the parameters describe (Load Stepping, Dynamics, Step Control): a
  /// host's own step-size rule. Its values are load factors (time in
  /// dynamics) from 0; it is used by one run() and released. With
  /// controlsError() it is given each step's frozen-geometry indicator
  /// (StepRecord::geometryError) in judge().
  void setStepController(std::unique_ptr<StepController> controller) { hostController_ = std::move(controller); }

  /// Tell `observer` of the steps of every following run() (after the
  /// analysis' own observers: history, progress, Exodus II, VTK,
  /// checkpoints, stop requests): a host's own monitoring
  /// (doc/embedding.md, "Observing the steps"). Shared, so it outlives the run.
  void addObserver(std::shared_ptr<StepObserver> observer) { hostObservers_.push_back(std::move(observer)); }

  /// Continue the next run() from the checkpoint of an earlier run of this
  /// model (findRestartSource(); doc/user-guide.md, "Checkpoints and
  /// restart") instead of from the unloaded state: its displacements,
  /// velocities, contact state, step controller, history rows and output
  /// series. The run's output directory may be the earlier run's (then
  /// opened with RunDescription::resumeWith = kCheckpointFileName) or
  /// another. Collective.
  /// \throws InputError when this analysis' parameters differ from the
  ///         checkpointed run's beyond what a restart may change
  ///         (checkRestartParameters()), a mesh or element-map file differs
  ///         from the one that run read (checkRestartInputFiles()), the
  ///         checkpoint is beyond this run's final load factor or time, or
  ///         the checkpoint does not fit this model
  void setRestart(RestartSource source);

  /// The discrete model (mesh, DOF numbering, contact component).
  const Model& model() const { return *model_; }
  /// The displacements of the last converged step on model().ownedMap()
  /// (contact multipliers appended; model().dof(node, component) indexes it).
  const Vector& displacement() const { return loop_ ? *loop_->state().u : *unloaded_; }
  /// Dynamics: the velocities of the last converged step (owned map, like
  /// displacement()); nullptr in a quasi-static analysis.
  const Vector* velocity() const { return dynamics_ ? &dynamics_->integrator().velocity() : nullptr; }
  /// One record per converged (sub)step, in order (the rows of history.csv).
  const std::vector<StepRecord>& history() const;
  /// Where the time went (after run(): maxima over ranks).
  const RunTiming& timing() const;
  /// The memory estimate made before the model was built (doc/user-guide.md, "Memory").
  const MemoryEstimate& memoryEstimate() const { return memoryEstimate_; }
  /// The validated parameters with every default filled in.
  const Teuchos::ParameterList& parameters() const { return params_; }

 private:
  /// The model from the validated parameters (the constructor's work).
  void buildModel(Teuchos::ParameterList& params, const std::string& baseDirectory);
  /// The partition of `mesh` ("Partition"), with the memory checked before
  /// (evenly sized subdomains) and after it (memoryEstimate_). A mesh
  /// built in ranges becomes this rank's part, its elements moved to the
  /// ranks of their subdomains. Collective.
  Partition partitionMesh(std::shared_ptr<Mesh>& mesh, const Teuchos::ParameterList& params,
                          const ContactOptions& contact, bool memoryCheck, const std::string& baseDirectory);
  /// Estimates the run's memory with `partition` (memoryEstimate_) and
  /// refuses the run when it does not fit with its margin
  /// (ddc::memoryBudget(); sets memoryBudget_).
  void requireMemory(const Mesh& mesh, const Partition& partition, const Teuchos::ParameterList& solver,
                     const ContactOptions& contact);
  /// The memory estimate of the run on `mesh` (a whole mesh, or this rank's
  /// part: then collective) with `partition`.
  MemoryEstimate estimate(const Mesh& mesh, const Partition& partition, const Teuchos::ParameterList& solver,
                          const ContactOptions& contact) const;
  /// The step loop of one run, with its observers writing into `dir` (null: no files).
  void runSteps(OutputDirectory* dir);
  /// The analysis' own observers of a run into `dir` (null: no files), in
  /// the order they are told.
  struct RunObservers;
  std::unique_ptr<RunObservers> makeObservers(OutputDirectory* dir);
  void progress(const std::string& line) const;

  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  Teuchos::ParameterList params_;
  ElementFactory factory_;
  std::shared_ptr<Model> model_;
  std::unique_ptr<SolutionStrategy> strategy_;  ///< Monolithic or FETI-DP
  std::unique_ptr<Dynamics> dynamics_;          ///< null: quasi-static
  StepControlSettings stepControl_;
  MemoryEstimate memoryEstimate_;
  /// What the memory check allowed (no limits when it is off).
  MemoryBudget memoryBudget_;
  /// Said at the start and with a Newton failure: nearly incompressible
  /// bodies.
  std::string caveats_;
  bool progressEnabled_ = true;
  /// Where the mesh came from (meshOrigin()): with Ranges no rank held it
  /// whole.
  MeshOrigin meshOrigin_ = MeshOrigin::EveryRank;
  bool dynamic_ = false;  ///< Dynamics/Integrator is not None
  NewtonSettings newton_;
  Teuchos::RCP<Vector> unloaded_;                   ///< displacement() before a run
  std::unique_ptr<StepController> hostController_;  ///< setStepController()
  std::unique_ptr<RestartSource> restart_;          ///< setRestart()
  /// The mesh and element-map files the model was built from (the
  /// checkpoint records them; a restart requires them unchanged).
  std::vector<InputFileIdentity> inputFiles_;
  std::vector<std::shared_ptr<StepObserver>> hostObservers_;  ///< addObserver()
  std::unique_ptr<StepLoop> loop_;                  ///< the last run's
};

}  // namespace ddc
