// One converged step's record, and the one table that describes its fields.
//
// Every file format that holds the steps of a run is produced from
// stepFields(): the columns of history.csv (doc/user-guide.md, "The output
// directory"), the global variables of the Exodus II results and the
// history record of a checkpoint. A field is one line of that table: its
// name, its unit, in which runs each output has it, and how to read (and,
// if stored, restore) it. Adding a history column is adding a member to
// StepRecord and a line to the table (doc/architecture.md, "Adding a
// history column").
#pragma once

#include <string>
#include <vector>

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
  double wallSeconds = 0.0;  ///< since the start of the run (a restart goes on from the checkpoint's)
  std::vector<double> residualHistory;  ///< ||r|| per Newton iteration
  double externalWork = 0.0;  ///< work of reactions and tractions, trapezoidal in λ, since λ = 0
  /// Work of the friction forces against the slip since λ = 0: Σ over the
  /// steps and the slave nodes in contact of λ_t·u_t (doc/contact.md,
  /// "Friction"); ≥ 0.
  double frictionalDissipation = 0.0;
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

/// What kind of run the records belong to: which fields its outputs have.
struct RunKind {
  bool dynamic = false;     ///< implicit dynamics (the load factor is the time)
  bool decomposed = false;  ///< the decomposed contact element (step sizes, frozen-geometry error)
  int dim = 2;              ///< space dimension
  bool frictional = false;  ///< some contact pair has friction
};

/// In which runs an output has a field.
enum class When { Never, Always, QuasiStatic, Dynamic, Decomposed, ThreeD, Frictional };

/// True if an output with presence `when` has the field in a run of `kind`.
bool present(When when, const RunKind& kind);

/// One field of StepRecord (see the top of this file).
struct StepField {
  const char* name;  ///< history column, Exodus II global variable and checkpoint record name
  const char* unit;  ///< "1" (a count), "load", "energy", "force", "s", "bytes"; "load" is the load factor, the time in dynamics
  When history;      ///< a column of history.csv in these runs
  When exodus;       ///< a global variable of the Exodus II results in these runs
  /// The value of a record.
  double (*get)(const StepRecord&);
  /// Restores the value into a record (a checkpoint holds the field); null
  /// for a field derived from others (not stored).
  void (*set)(StepRecord&, double);
};

/// The fields, in the order of the history's columns.
const std::vector<StepField>& stepFields();

/// history.csv's header for a run of `kind`; its first ten columns are the
/// stable ones (doc/user-guide.md).
std::vector<std::string> historyColumns(const RunKind& kind);
/// history.csv's row of `record`, in the order of historyColumns().
std::vector<double> historyRow(const StepRecord& record, const RunKind& kind);
/// The global variables of the Exodus II results of a run of `kind`.
std::vector<std::string> exodusGlobalNames(const RunKind& kind);
/// Their values for `record`, in the order of exodusGlobalNames().
std::vector<double> exodusGlobals(const StepRecord& record, const RunKind& kind);

/// The fields a checkpoint stores of each record (those with a `set`), in
/// table order; the residual history follows them.
std::vector<std::string> checkpointFieldNames();
/// The records as numbers for a checkpoint: per record the fields of
/// checkpointFieldNames(), then its residual history (count, values). Every
/// number round-trips exactly (integers are far below 2^53).
std::vector<double> packStepRecords(const std::vector<StepRecord>& records);
/// The records packStepRecords() gave.
/// \throws InputError naming `file` when the numbers are cut short
std::vector<StepRecord> unpackStepRecords(const std::vector<double>& packed, const std::string& file);

}  // namespace ddc
