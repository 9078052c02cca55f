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
#include <vector>

namespace ddc {

/// The resolution of the stepped value (load factor or time), as a
/// fraction of the larger of its current and its final value: a nominal
/// step's end counts as reached within it, and a step smaller than it no
/// longer changes the value in a way the steps can tell apart (about 45
/// units of round-off, 2^-52 each, of the value; doc/user-guide.md, "Step
/// control"). Halving stops there, and the smallest step size is at least
/// this much of the final value.
constexpr double kStepResolution = 1e-14;

/// The smallest step that still changes `value` within steps ending at
/// `finalValue` (kStepResolution).
double stepResolution(double value, double finalValue);

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

/// What a controller makes of a converged step's error indicator.
enum class StepVerdict {
  Accept,  ///< accept the step: accept() next
  /// Solve the same step again (propose() returns it): the caller keeps what
  /// it refreshed at the step's end and measured the error with (the
  /// decomposed contact element's pairing), and restores the rest of the
  /// step's start.
  Repeat,
  /// Solve a smaller step from the same value (propose()): the caller
  /// restores the whole state of the step's start.
  Reduce,
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
  /// Whether the controller judges converged steps by an error indicator
  /// (judge()): the analysis computes the indicator before accepting.
  virtual bool controlsError() const { return false; }
  /// The converged step `p` has the error indicator `error`: accept it,
  /// repeat it, or try a smaller one (StepVerdict). The default accepts.
  virtual StepVerdict judge(const StepProposal& /*p*/, double /*error*/) { return StepVerdict::Accept; }
  /// The state after an accepted step, for a checkpoint: numbers that
  /// restoreState() of a controller of the same kind takes back. Empty: this
  /// controller cannot be checkpointed (the default).
  virtual std::vector<double> saveState() const { return {}; }
  /// Continue from `state` (saveState() of a built-in controller, possibly
  /// built with other settings: a restart may change the final value and
  /// the step sizes) after `acceptedSteps` accepted steps. From a controller
  /// of the same kind and settings, the steps that follow are those the
  /// saved one would have proposed; otherwise they start afresh from the
  /// saved current value. Returns false if `state` is not a saved state.
  virtual bool restoreState(const std::vector<double>& /*state*/, int /*acceptedSteps*/) { return false; }
  /// The limits that made reject() give up, for the failure message, with
  /// `stepping` the parameter list the steps come from (e.g. "Load
  /// Stepping/Max Bisections = 6"); "" to say nothing (the default).
  virtual std::string limits(const std::string& /*stepping*/) const { return ""; }
  /// The last accepted step was accepted at the smallest size the
  /// controller allows although its error indicator exceeded the tolerance
  /// (the loop warns). The default: never.
  virtual bool atMinimum() const { return false; }
  /// A note on the last judge() or reject() the loop passes on (e.g. why
  /// repeats stopped early), then forgets; "" for none (the default).
  virtual std::string takeNote() { return ""; }
};

/// Nominal steps of equal size up to a final value, each cut in halves on
/// Newton failure up to a maximum bisection depth per nominal step
/// (Load Stepping/Number of Steps, Final Load Factor, Max Bisections). After
/// a cut the sub-steps keep the halved size until the nominal step's end.
/// Halving also stops where the halved step would fall below the
/// resolution of the value (stepResolution()): a smaller step no longer
/// changes it.
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
  /// "<stepping>/Max Bisections = n", and the resolution if halving
  /// stopped there.
  std::string limits(const std::string& stepping) const override;
  std::vector<double> saveState() const override;
  bool restoreState(const std::vector<double>& state, int acceptedSteps) override;

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
  bool atResolution_ = false;  ///< reject() gave up at the resolution, not at Max Bisections
};

/// Steps controlled by an error indicator whose error grows as the square
/// of the step size and that a repeat of the step with what its end
/// refreshed can reduce: the frozen-geometry error of the decomposed
/// contact element (doc/contact.md, "Step control by the frozen-geometry
/// error"). A converged step whose indicator exceeds the tolerance is
/// repeated with the geometry of its end, up to maxCorrections times
/// (StepVerdict::Repeat); then, or with maxCorrections = 0 at once, it is
/// tried again smaller (StepVerdict::Reduce): kSafety·sqrt(tolerance /
/// error) times the size, between kMinRejectFactor and kMaxRejectFactor
/// times. After a step accepted without a repeat the next size is
/// kSafety·sqrt(tolerance / error) times this one, at most kMaxGrowth
/// times (with repeats allowed it never shrinks then: a repeat is cheaper
/// than the steps a smaller size would add). Sizes stay within
/// [minimum, maximum]; a step at the minimum size is accepted whatever its
/// error (atMinimum()). Newton failure halves the step, up to a number of
/// consecutive halvings and not below the minimum. Every accepted step is
/// its own nominal step. Repeats stop early, and the step is reduced, when
/// a repeat does not reduce the indicator (it sits at round-off, or the
/// geometry does not settle): more repeats would not either (takeNote()
/// says so).
class AdaptiveSteps final : public StepController {
 public:
  /// Next size as a multiple of the size the indicator asks for
  /// (sqrt(tolerance / error) times the step).
  static constexpr double kSafety = 0.9;
  /// Largest growth of the step from one accepted step to the next.
  static constexpr double kMaxGrowth = 2.0;
  /// Largest and smallest factor of a reduced step's size (a reduction at
  /// least halves the step: the indicator varies by a factor of several
  /// between neighbouring steps, and a barely smaller retry would likely be
  /// rejected again).
  static constexpr double kMaxRejectFactor = 0.5, kMinRejectFactor = 0.125;
  /// The last step may be this fraction longer than the step size rather
  /// than leave a sliver behind.
  static constexpr double kStretch = 0.1;

  /// \param finalValue the end value (> 0)
  /// \param initialSize the first step's size
  /// \param minSize, maxSize the bounds of the step size,
  ///        0 < minSize <= initialSize <= maxSize < inf
  /// \param tolerance the largest accepted indicator (> 0)
  /// \param maxHalvings consecutive Newton-failure halvings allowed (>= 0)
  /// \param maxCorrections repeats of a step with its end's geometry
  ///        before it is reduced (>= 0)
  /// \throws std::invalid_argument for values out of these ranges
  AdaptiveSteps(double finalValue, double initialSize, double minSize, double maxSize, double tolerance,
                int maxHalvings, int maxCorrections);

  bool done() const override;
  StepProposal propose() const override;
  void accept(const StepProposal& p) override;
  bool reject(const StepProposal& p) override;
  double current() const override { return current_; }
  /// 0: the number of steps is not known in advance.
  int numSteps() const override { return 0; }
  bool endsNominalStep(const StepProposal&) const override { return true; }
  bool controlsError() const override { return true; }
  StepVerdict judge(const StepProposal& p, double error) override;
  /// The last accepted step was accepted at the minimum size with its error
  /// above the tolerance.
  bool atMinimum() const override { return atMinimum_; }
  std::string takeNote() override;
  /// "<stepping>/Max Bisections = n, Step Control/Minimum Step Size = h".
  std::string limits(const std::string& stepping) const override;
  /// Repeats of the step being worked on (StepVerdict::Repeat) so far.
  int corrections() const { return corrections_; }
  /// The bounds of the step size.
  double minSize() const { return min_; }
  double maxSize() const { return max_; }
  std::vector<double> saveState() const override;
  bool restoreState(const std::vector<double>& state, int acceptedSteps) override;

 private:
  double final_, min_, max_, tolerance_;
  int maxHalvings_, maxCorrections_;
  double current_ = 0.0;
  double size_;          ///< the next step's size
  double nextSize_ = 0;  ///< set by judge() on Accept: the size after the step
  int accepted_ = 0;     ///< accepted steps
  int depth_ = 0;        ///< Newton-failure halvings since the last accepted step
  int corrections_ = 0;  ///< repeats of the current step
  double lastError_ = 0.0;  ///< the indicator of the attempt the last repeat followed
  bool atMinimum_ = false;
  std::string note_;  ///< takeNote()
};

}  // namespace ddc
