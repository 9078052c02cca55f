// Step control: which (sub)step the analysis attempts next, and what it does
// when Newton fails on one. The analysis' stepping loop asks a StepController
// for a step, solves it and reports the outcome; the controller holds the
// stepping state (where the nominal steps are, the current step size, the
// bisection depth) as one object, so that another scheme (steps chosen by an
// error indicator, time steps of a dynamic analysis) is another
// implementation of the same interface, and a restart can save it whole.
//
// The parameter the steps advance is the load factor of the quasi-static
// analysis (doc/user-guide.md, "Solution method"); in a dynamic analysis it
// will be time.
#pragma once

#include <string>

namespace ddc {

/// One (sub)step the controller proposes: from `from` to `to` within
/// nominal step `step` (1-based), at bisection depth `depth`.
struct StepProposal {
  int step = 0;
  double from = 0.0;
  double to = 0.0;
  int depth = 0;
  /// The step size: the same number for every step of one size (to − from
  /// differs from it, and from step to step, by round-off; a time
  /// integrator whose matrices depend on the step size uses this, so a
  /// constant step keeps them the same bit for bit).
  double size = 0.0;
};

/// Chooses the steps of an analysis (see the top of this file).
class StepController {
 public:
  virtual ~StepController() = default;
  /// True when the end has been reached (no further step).
  virtual bool done() const = 0;
  /// The next step from the current (last accepted) value.
  /// \pre !done()
  virtual StepProposal propose() const = 0;
  /// The proposed step converged: its end becomes the current value.
  virtual void accept(const StepProposal& p) = 0;
  /// Newton failed on the proposed step. Returns false when the controller
  /// gives up (no smaller step is allowed); otherwise the next propose()
  /// is a smaller step from the same value.
  virtual bool reject(const StepProposal& p) = 0;
  /// The current (last accepted) value.
  virtual double current() const = 0;
  /// Number of nominal steps (progress lines "step n/N").
  virtual int numSteps() const = 0;
  /// True if the accepted step `p` ended its nominal step.
  virtual bool endsNominalStep(const StepProposal& p) const = 0;
};

/// Nominal steps of equal size up to a final value, each cut in halves on
/// Newton failure up to a maximum bisection depth per nominal step
/// (Load Stepping/Number of Steps, Final Load Factor, Max Bisections). After
/// a cut the sub-steps keep the halved size until the nominal step's end.
class BisectingSteps final : public StepController {
 public:
  /// \param finalValue the value at the end of the last nominal step (> 0)
  /// \param numSteps nominal steps (> 0)
  /// \param maxBisections cuts allowed per nominal step (>= 0)
  /// \throws std::invalid_argument for values out of these ranges
  BisectingSteps(double finalValue, int numSteps, int maxBisections);

  bool done() const override;
  StepProposal propose() const override;
  void accept(const StepProposal& p) override;
  bool reject(const StepProposal& p) override;
  double current() const override { return current_; }
  int numSteps() const override { return numSteps_; }
  bool endsNominalStep(const StepProposal& p) const override;
  /// Cuts allowed per nominal step.
  int maxBisections() const { return maxBisections_; }

 private:
  /// The end of nominal step n.
  double target(int n) const;
  /// The first nominal step whose end is not yet reached (numSteps_ + 1 when done).
  void advance();

  double final_;
  int numSteps_, maxBisections_;
  double current_ = 0.0;
  int step_ = 1;       ///< the nominal step being worked on
  double size_ = 0.0;  ///< the sub-step size within it
  int depth_ = 0;      ///< cuts made in it so far
};

}  // namespace ddc
