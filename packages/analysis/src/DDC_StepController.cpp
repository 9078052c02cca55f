#include "DDC_StepController.hpp"

#include <cmath>
#include <stdexcept>

namespace ddc {

namespace {
/// A nominal step's end counts as reached within this fraction of the final
/// value (the sub-step sizes are binary fractions of the nominal size, so
/// only round-off separates their sum from the target).
constexpr double kReached = 1e-14;
/// A sub-step within this fraction of the remaining distance ends exactly
/// on the nominal step's end (no sliver step).
constexpr double kSnap = 1e-12;
}  // namespace

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
  ++depth_;
  if (depth_ > maxBisections_) return false;
  size_ *= 0.5;
  return true;
}

bool BisectingSteps::endsNominalStep(const StepProposal& p) const {
  return !(p.to < target(p.step) - kReached * std::abs(final_));
}

}  // namespace ddc
