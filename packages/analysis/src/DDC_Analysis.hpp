// The analysis: builds a model from a validated Teuchos::ParameterList and
// runs load stepping (or, with Dynamics/Integrator = Newmark, time steps of
// implicit dynamics) with full Newton and automatic bisection.
//
// Embedding lifecycle (Tribol style), for host codes:
//   1. Analysis a(comm, params);                 // validate + build (collective)
//      or Analysis a(comm, params, factory);     // with host element types
//   2. a.run("out/dir");                         // or a.run("") for no files
//   3. a.history(), a.model(), a.displacement()  // results
// Nothing here reads files other than meshes named in the parameters.
#pragma once

#include <Teuchos_Comm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "DDC_DirectSolver.hpp"
#include "DDC_ElementFactory.hpp"
#include "DDC_FetiDpSolver.hpp"
#include "DDC_Memory.hpp"
#include "DDC_MemoryEstimate.hpp"
#include "DDC_Model.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_Restart.hpp"
#include "DDC_SolutionStrategy.hpp"
#include "DDC_StepController.hpp"
#include "DDC_TimeIntegrator.hpp"

namespace ddc {

/// One converged (sub)step.
struct StepRecord {
  int step = 0;              ///< nominal step number (1-based); sub-steps repeat it
  double loadFactor = 0.0;    ///< load factor λ at the end of the (sub)step (dynamics: the time t)
  double strainEnergy = 0.0;  ///< total strain energy U (per unit thickness in 2-D)
  /// Linear solves in this (sub)step, including those of the attempts Step
  /// Control repeated or reduced before accepting it (not those of attempts
  /// Newton failed on).
  int newtonIterations = 0;
  int dualIterations = 0;    ///< Belos iterations of FETI-DP summed over the (sub)step (as newtonIterations)
  int bisections = 0;        ///< bisection depth used to reach this load factor
  double wallSeconds = 0.0;  ///< since the start of run()
  std::vector<double> residualHistory;  ///< ||r|| per Newton iteration
  double externalWork = 0.0;  ///< work of reactions and tractions, trapezoidal in λ, since λ = 0
  int activeContacts = 0;  ///< active contact slots at the end of the (sub)step
  double contactForce[3] = {0.0, 0.0, 0.0};  ///< resultant on the slave bodies (Σ −λ n); z = 0 in 2-D
  long contactExchanges = 0;  ///< contact-geometry exchanges in this (sub)step (Model::exchanges())
  long contactBytes = 0;      ///< bytes those exchanges moved between ranks
  std::string failure;        ///< why the last attempt failed (empty when converged)
  double kineticEnergy = 0.0;  ///< dynamics: ½ vᵀ M v at the end of the (sub)step (0 quasi-static)
  double stepSize = 0.0;       ///< the step's size (StepProposal::size)
  /// Attempts of this step the step control's error test sent back to be
  /// tried smaller before it was accepted (Newton failures are counted in
  /// `bisections`).
  int rejections = 0;
  /// Repeats of this step with the geometry of its end (Step Control/Geometry
  /// Corrections) before it was accepted.
  int corrections = 0;
  /// Decomposed contact: the frozen-geometry error indicator of the step,
  /// |Σ λ (g − g^p)| / (U + kinetic energy) (frozenGeometryEnergy(); 0
  /// without active contact or without energy).
  double geometryError = 0.0;
};

/// Where the time of a run went (seconds, max over ranks after run()).
struct RunTiming {
  double assembly = 0.0;     ///< element evaluation and global/subdomain assembly
  double linearSetup = 0.0;  ///< factorisations / preconditioner set-up (incl. FETI-DP coarse problem)
  double linearSolve = 0.0;  ///< triangular solves / Krylov iterations
  int linearSolves = 0;        ///< number of linear solves (Newton iterations)
  double peakMemoryMiB = 0.0;  ///< peak resident memory, max over ranks
  /// FETI-DP breakdown (this rank): local, coarse, Dirichlet factorisation;
  /// local solves, coarse solves, preconditioner applications.
  std::array<double, 6> feti{{0, 0, 0, 0, 0, 0}};
};

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

  /// Continue the next run() from the checkpoint of an earlier run of this
  /// model (findRestartSource(); doc/user-guide.md, "Checkpoints and
  /// restart") instead of from the unloaded state: its displacements,
  /// velocities, contact state, step controller, history rows and output
  /// series. The run's output directory may be the earlier run's (then
  /// opened with RunDescription::resumeWith = kCheckpointFileName) or
  /// another. Collective.
  /// \throws InputError when this analysis' parameters differ from the
  ///         checkpointed run's beyond what a restart may change
  ///         (checkRestartParameters()), or the checkpoint does not fit
  ///         this model
  void setRestart(RestartSource source);

  /// The discrete model (mesh, DOF numbering, contact component).
  const Model& model() const { return *model_; }
  /// The displacements of the last converged step on model().ownedMap()
  /// (contact multipliers appended; model().dof(node, component) indexes it).
  const Vector& displacement() const { return *u_; }
  /// Dynamics: the velocities of the last converged step (owned map, like
  /// displacement()); nullptr in a quasi-static analysis.
  const Vector* velocity() const { return integrator_ ? &integrator_->velocity() : nullptr; }
  /// One record per converged (sub)step, in order (the rows of history.csv).
  const std::vector<StepRecord>& history() const { return history_; }
  /// Where the time went (after run(): maxima over ranks).
  const RunTiming& timing() const { return timing_; }
  /// The memory estimate made before the model was built (doc/user-guide.md, "Memory").
  const MemoryEstimate& memoryEstimate() const { return memoryEstimate_; }
  /// The validated parameters with every default filled in.
  const Teuchos::ParameterList& parameters() const { return params_; }

 private:
  /// What the steps carry forward besides the displacements u_ and the
  /// step controller's state: the external-work integral and its last
  /// point, the output counter and the contact state of the last converged
  /// step (for contact_nodes.csv).
  struct RunState {
    Teuchos::RCP<Vector> fint;          ///< internal force at the step just converged
    /// The force at the prescribed DOFs at the step just converged (f_int,
    /// plus M a + C v in dynamics) and at the one before (trapezoidal work).
    Teuchos::RCP<Vector> reaction, reactionPrev;
    Teuchos::RCP<Vector> uPrev;         ///< displacements of the step before
    double externalWork = 0.0;      ///< StepRecord::externalWork so far
    int outputCount = 0;            ///< converged (sub)steps (Output/VTK Interval)
    std::vector<ContactSlot> convergedSlots;
  };
  void runSteps(OutputDirectory* dir);
  /// The checkpoint of the state after the last accepted step (collective):
  /// `controllerState` is the step controller's saveState() then,
  /// `vtkSteps` the VTK series written so far.
  void writeCheckpoint(const std::string& path, const RunState& st, const std::vector<double>& controllerState,
                       const std::vector<std::pair<int, double>>& vtkSteps) const;
  /// Restore what writeCheckpoint() saved from restart_ (collective);
  /// returns the VTK series to continue.
  std::vector<std::pair<int, double>> restoreCheckpoint(RunState& st, StepController& steps);
  std::unique_ptr<RestartSource> restart_;  ///< setRestart()
  /// Step Control, resolved (setUpStepControl()): tolerance 0 = off.
  struct StepControlSettings {
    double tolerance = 0.0;
    double first = 0.0, minSize = 0.0, maxSize = 0.0;  ///< step sizes (load factor or time)
    int corrections = 0;  ///< Geometry Corrections
  };
  /// Check the "Step Control" list against the run (decomposed contact, the
  /// sizes) and resolve its defaults.
  void setUpStepControl(const Teuchos::ParameterList& params);
  StepControlSettings stepControl_;
  std::unique_ptr<StepController> hostController_;  ///< setStepController()
  /// Dynamics: check the masses and the time step, build the integrator and
  /// the initial velocities from the validated "Dynamics" list.
  void setUpDynamics(Teuchos::ParameterList& dynamics);
  /// contact_nodes.csv (Output/Contact Nodes): one row per slot, written by
  /// rank 0 from the replicated slots; errors agreed on every rank.
  void writeContactNodes(const std::string& path, const std::vector<ContactSlot>& slots) const;
  bool solveIncrement(double lambda0, double lambda1, StepRecord& rec);
  double externalWorkIncrement(const Vector& fint0, const Vector& u0, double lambda0, const Vector& fint1,
                               const Vector& u1, double lambda1) const;
  void progress(const std::string& line) const;

  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  Teuchos::ParameterList params_;
  ElementFactory factory_;
  std::shared_ptr<Model> model_;
  std::unique_ptr<SolutionStrategy> strategy_;  ///< Monolithic or FETI-DP
  Teuchos::RCP<Vector> u_;
  std::vector<StepRecord> history_;
  RunTiming timing_;
  MemoryEstimate memoryEstimate_;
  /// The bodies whose Poisson's ratio makes them nearly incompressible ("" if none).
  std::string nearlyIncompressible_;
  /// Why Newton did not converge: the criterion not met, and whether the
  /// residual stagnated (for the failure message).
  std::string unmetCriterion(const std::vector<double>& residuals, double rtol, double atol, double energy,
                             double etol, double e0, double increment) const;
  bool progressEnabled_ = true;
  bool dynamic_ = false;  ///< Dynamics/Integrator is not None
  std::unique_ptr<NewmarkIntegrator> integrator_;
  Teuchos::RCP<Vector> initialVelocity_, acceleration_, velocity_;
  Inertia inertia_;  ///< the strategy's inertia term (acceleration_ and c, updated per iterate)
};

/// Build the mesh described by "Mesh" (validated in place). Exposed for tools
/// and tests. Cell types follow each body's element type in `factory`.
/// \param budget if given, the memory a rank may use for the replicated mesh
///        (Mesh::setMemoryBudget(): generators refuse a body that does not fit)
/// \param budgetHint what the user can do about it, for that message
std::shared_ptr<Mesh> buildMesh(Teuchos::ParameterList& meshParams, const ElementFactory& factory,
                                const std::string& baseDirectory, const MemoryLimit* budget = nullptr,
                                const std::string& budgetHint = "");

}  // namespace ddc
