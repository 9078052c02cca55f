#include "DDC_StepController.hpp"

#include <sstream>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ddc {

namespace {
/// A nominal step's end counts as reached within this fraction of the final
/// value (the sub-step sizes are binary fractions of the nominal size, so
/// only round-off separates their sum from the target).
constexpr double kReached = kStepResolution;
/// A sub-step within this fraction of the remaining distance ends exactly
/// on the nominal step's end (no sliver step).
constexpr double kSnap = 1e-12;
}  // namespace

double stepResolution(double value, double finalValue) {
  return kStepResolution * std::max(std::abs(value), std::abs(finalValue));
}

BisectingSteps::BisectingSteps(double finalValue, int numSteps, int maxBisections)
    : final_(finalValue), numSteps_(numSteps), maxBisections_(maxBisections) {
  if (!(finalValue > 0.0) || !std::isfinite(finalValue))
    throw std::invalid_argument("BisectingSteps: the final value must be > 0 and finite");
  if (numSteps < 1) throw std::invalid_argument("BisectingSteps: at least one step");
  if (maxBisections < 0) throw std::invalid_argument("BisectingSteps: a negative number of bisections");
  size_ = final_ / numSteps_;
  advance();
}

double BisectingSteps::target(int n) const { return final_ * n / numSteps_; }

void BisectingSteps::advance() {
  while (step_ <= numSteps_ && !(current_ < target(step_) - kReached * std::abs(final_))) {
    ++step_;
    if (step_ <= numSteps_) {
      size_ = final_ / numSteps_;
      depth_ = 0;
    }
  }
}

bool BisectingSteps::done() const { return step_ > numSteps_; }

StepProposal BisectingSteps::propose() const {
  const double t = target(step_);
  StepProposal p;
  p.step = step_;
  p.from = current_;
  p.to = (t - current_ <= size_ * (1 + kSnap)) ? t : current_ + size_;
  p.depth = depth_;
  p.size = size_;
  return p;
}

void BisectingSteps::accept(const StepProposal& p) {
  current_ = p.to;
  advance();
}

bool BisectingSteps::reject(const StepProposal&) {
  if (depth_ >= maxBisections_) return false;
  if (0.5 * size_ < stepResolution(current_, final_)) {
    atResolution_ = true;  // a smaller step no longer changes the value
    return false;
  }
  ++depth_;
  size_ *= 0.5;
  return true;
}

bool BisectingSteps::endsNominalStep(const StepProposal& p) const {
  return !(p.to < target(p.step) - kReached * std::abs(final_));
}

namespace {
/// The first number of a saved state: which controller saved it.
constexpr double kBisectingKind = 1.0, kAdaptiveKind = 2.0;
/// The current value of a saved state of either kind; NaN if it is neither.
double savedCurrent(const std::vector<double>& s) {
  if (s.size() == 7 && s[0] == kBisectingKind) return s[3];
  if (s.size() == 4 && s[0] == kAdaptiveKind) return s[1];
  return std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

std::vector<double> BisectingSteps::saveState() const {
  return {kBisectingKind, final_, double(numSteps_), current_, double(step_), size_, double(depth_)};
}

bool BisectingSteps::restoreState(const std::vector<double>& s, int) {
  const double current = savedCurrent(s);
  if (std::isnan(current)) return false;
  current_ = current;
  if (s[0] == kBisectingKind && s[1] == final_ && s[2] == double(numSteps_)) {
    // The same steps: where the saved controller was, bisected sub-steps
    // included.
    step_ = int(s[4]);
    size_ = s[5];
    depth_ = int(s[6]);
    return true;
  }
  // Other steps: the nominal step the current value lies in, at full size.
  step_ = 1;
  size_ = final_ / numSteps_;
  depth_ = 0;
  advance();
  return true;
}

AdaptiveSteps::AdaptiveSteps(double finalValue, double initialSize, double minSize, double maxSize,
                             double tolerance, int maxHalvings, int maxCorrections)
    : final_(finalValue), min_(minSize), max_(maxSize), tolerance_(tolerance), maxHalvings_(maxHalvings),
      maxCorrections_(maxCorrections), size_(initialSize) {
  if (!(finalValue > 0.0) || !std::isfinite(finalValue))
    throw std::invalid_argument("AdaptiveSteps: the final value must be > 0 and finite");
  if (!(minSize > 0.0) || !(minSize <= initialSize) || !(initialSize <= maxSize) || !std::isfinite(maxSize))
    throw std::invalid_argument("AdaptiveSteps: the sizes must satisfy 0 < minimum <= initial <= maximum < inf");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw std::invalid_argument("AdaptiveSteps: the tolerance must be > 0 and finite");
  if (maxHalvings < 0 || maxCorrections < 0)
    throw std::invalid_argument("AdaptiveSteps: a negative number of halvings or corrections");
}

bool AdaptiveSteps::done() const { return !(current_ < final_ - kReached * final_); }

StepProposal AdaptiveSteps::propose() const {
  StepProposal p;
  p.step = accepted_ + 1;
  p.from = current_;
  p.depth = depth_;
  const double rest = final_ - current_;
  if (rest <= size_ * (1 + kStretch) && rest <= max_ * (1 + kSnap)) {
    p.to = final_;
    p.size = rest;
  } else if (rest < size_ + min_) {
    // No sliver below the minimum size at the end: two equal steps.
    p.size = 0.5 * rest;
    p.to = current_ + p.size;
  } else {
    p.size = size_;
    p.to = current_ + size_;
  }
  return p;
}

StepVerdict AdaptiveSteps::judge(const StepProposal& p, double error) {
  if (!(error >= 0.0)) error = std::numeric_limits<double>::infinity();  // NaN: never accepted as small
  const double ideal = error > 0.0 ? kSafety * std::sqrt(tolerance_ / error) : kMaxGrowth;
  atMinimum_ = false;
  if (error > tolerance_) {
    // A repeat that did not reduce the indicator: further ones would not.
    const bool stalled = corrections_ > 0 && !(error < lastError_);
    if (corrections_ < maxCorrections_ && !stalled) {
      ++corrections_;  // propose() gives the same step again
      lastError_ = error;
      return StepVerdict::Repeat;
    }
    if (stalled && corrections_ < maxCorrections_) {
      std::ostringstream os;
      os << "geometry correction " << corrections_ << " did not reduce the frozen-geometry error (" << lastError_
         << " -> " << error << ", Step Control/Error Tolerance = " << tolerance_
         << "), so the step is not repeated again (Step Control/Geometry Corrections = " << maxCorrections_
         << " not used up)";
      note_ = os.str();
    }
    if (p.size > min_ * (1 + kSnap)) {
      corrections_ = 0;
      size_ = std::max(min_, p.size * std::clamp(ideal, kMinRejectFactor, kMaxRejectFactor));
      return StepVerdict::Reduce;
    }
    atMinimum_ = true;  // nothing smaller is allowed: accepted as it is
  }
  double factor = std::min(ideal, kMaxGrowth);
  if (maxCorrections_ > 0) factor = corrections_ > 0 ? 1.0 : std::max(factor, 1.0);
  // From the controller's size, not the step's: the last steps may be
  // stretched or split to meet the end.
  nextSize_ = std::clamp(size_ * factor, min_, max_);
  return StepVerdict::Accept;
}

std::string AdaptiveSteps::takeNote() {
  std::string n;
  n.swap(note_);
  return n;
}

void AdaptiveSteps::accept(const StepProposal& p) {
  current_ = p.to;
  ++accepted_;
  depth_ = 0;
  corrections_ = 0;
  if (nextSize_ > 0.0) size_ = nextSize_;
  nextSize_ = 0.0;
}

std::vector<double> AdaptiveSteps::saveState() const {
  return {kAdaptiveKind, current_, size_, double(accepted_)};
}

bool AdaptiveSteps::restoreState(const std::vector<double>& s, int acceptedSteps) {
  const double current = savedCurrent(s);
  if (std::isnan(current)) return false;
  current_ = current;
  // The saved size, within the bounds (they may have changed); from the
  // other kind, the initial size.
  if (s[0] == kAdaptiveKind) size_ = std::clamp(s[2], min_, max_);
  accepted_ = acceptedSteps;
  depth_ = 0;
  corrections_ = 0;
  nextSize_ = 0.0;
  atMinimum_ = false;
  return true;
}

bool AdaptiveSteps::reject(const StepProposal& p) {
  if (depth_ >= maxHalvings_ || 0.5 * p.size < min_ * (1 - kSnap)) return false;
  ++depth_;
  corrections_ = 0;
  size_ = 0.5 * p.size;
  return true;
}

std::string BisectingSteps::limits(const std::string& stepping) const {
  const std::string max = stepping + "/Max Bisections = " + std::to_string(maxBisections_);
  if (!atResolution_) return max;
  std::ostringstream os;
  const double scale = std::max(std::abs(current_), std::abs(final_));
  os << max << " not used up: half of the step " << size_ << " is below the resolution of the value at " << scale
     << " (" << kStepResolution << " x " << scale << "), where a smaller step no longer changes it";
  return os.str();
}

std::string AdaptiveSteps::limits(const std::string& stepping) const {
  std::ostringstream os;
  os << stepping << "/Max Bisections = " << maxHalvings_ << ", Step Control/Minimum Step Size = " << min_;
  return os.str();
}

}  // namespace ddc
