#include "DDC_Newton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

Teuchos::RCP<const Teuchos::ParameterList> NewtonSettings::getValidParameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Newton"));
  pl->set("Max Iterations", 25, "Maximum Newton iterations (linear solves) per load step.", greaterThan(0));
  pl->set("Residual Tolerance", 1e-8,
          "Converged when ||r|| <= tol * ||r_0|| (r_0: first residual of the step, with the consistent "
          "predictor of prescribed displacements) ...",
          atLeast(0.0));
  pl->set("Absolute Residual Tolerance", 1e-10, "... or when ||r|| <= this absolute value (force units)",
          atLeast(0.0));
  pl->set("Energy Tolerance", 1e-16,
          "and the energy norm |du . r| <= tol * |du_0 . r_0| (both criteria must hold).", atLeast(0.0));
  pl->set("Print Iterations", false, "Print the residual and energy norm of every Newton iteration.");
  pl->set("Forcing Term", "Eisenstat-Walker",
          "Relative tolerance of each iterative linear solve (FETI-DP's dual solve, Belos back ends; a direct "
          "solve is exact anyway). Constant: the solver's own Convergence Tolerance every time. "
          "Eisenstat-Walker (inexact Newton): the first solve of a step uses that tolerance; solve k > 0 "
          "eta_k = 0.9 (||r_k|| / ||r_k-1||)^2 (Eisenstat & Walker 1996, choice 2, safeguarded by "
          "0.9 eta_k-1^2; left out with contact), and no solve is asked for less than 'Forcing Term Floor' "
          "times the Newton target max(Residual Tolerance ||r_0||, Absolute Residual Tolerance) over "
          "||r_k||; divided by how much less the previous solve reduced ||r|| than its tolerance promised; "
          "the full tolerance again after ||r|| grew; always between the solver's tolerance and 'Maximum "
          "Forcing Term' (doc/user-guide.md, 'Solution method'). The converged result meets the same "
          "Newton criteria either way.",
          enumValidator({"Eisenstat-Walker", "Constant"}, "Forcing Term"));
  pl->set("Maximum Forcing Term", 0.1, "Loosest relative tolerance of a linear solve with Forcing Term = "
          "Eisenstat-Walker.", between(0.0, 1.0, Interval::Open));
  pl->set("Forcing Term Floor", 0.1,
          "With Forcing Term = Eisenstat-Walker, a linear solve need not reduce the residual below this "
          "fraction of the Newton target (the absolute floor of the forcing term).",
          between(0.0, 1.0, Interval::LeftOpen));
  return pl;
}

NewtonSettings NewtonSettings::fromParameters(const Teuchos::ParameterList& nw) {
  NewtonSettings s;
  s.maxIterations = nw.get<int>("Max Iterations");
  s.residualTolerance = nw.get<double>("Residual Tolerance");
  s.absoluteResidualTolerance = nw.get<double>("Absolute Residual Tolerance");
  s.energyTolerance = nw.get<double>("Energy Tolerance");
  s.printIterations = nw.get<bool>("Print Iterations");
  s.eisenstatWalker = nw.get<std::string>("Forcing Term") == "Eisenstat-Walker";
  s.maximumForcingTerm = nw.get<double>("Maximum Forcing Term");
  s.forcingTermFloor = nw.get<double>("Forcing Term Floor");
  DDC_INPUT_REQUIRE(s.residualTolerance > 0.0 || s.absoluteResidualTolerance > 0.0,
                    "'Newton/Residual Tolerance' and 'Newton/Absolute Residual Tolerance' are both 0: Newton would "
                    "need |r| = 0 exactly, which round-off never gives; set one of them > 0 (defaults 1e-8, 1e-10)");
  DDC_INPUT_REQUIRE(s.energyTolerance > 0.0,
                    "'Newton/Energy Tolerance' is 0: Newton would need |du.r| = 0 exactly, which round-off never "
                    "gives; set it > 0 (default 1e-16)");
  return s;
}

/// What one iteration measured, for the convergence test and the report.
struct Newton::Iteration {
  int it = 0;
  double rnorm = 0.0, energy = 0.0;
  StrategySolveInfo info;
  std::vector<int> changed, repaired;  ///< contact slots that changed state / master facet
  bool pairingChanged = false;
};

Newton::Newton(Model& model, SolutionStrategy& strategy, NewtonSettings settings, Dynamics* dynamics,
               RunTiming& timing, Note note)
    : model_(model), strategy_(strategy), settings_(settings), dynamics_(dynamics), timing_(timing),
      note_(std::move(note)) {}

namespace {

/// The contact state whose repetition is cycling: the active set with the
/// stick/slip states and the pairing (a slave flipping between two segments
/// cycles as surely as one flipping its state).
std::vector<int> activeSetSignature(const Model& model) {
  std::vector<int> a;
  for (const auto& sl : model.contactSlots())
    a.insert(a.end(), {int(sl.contactState()), sl.master[0], sl.master[1], sl.segment});
  return a;
}

/// The non-finite failure of iteration `it`: "<what>" and where.
std::string nonFinite(const Model& model, int it, const char* what, const Vector& v) {
  const std::string where = model.describeNonFinite(v);
  return "Newton iteration " + std::to_string(it) + ": non-finite " + what + (where.empty() ? "" : ": " + where);
}

}  // namespace

bool Newton::solve(double lambda0, double lambda1, Vector& uStart, StepRecord& rec) {
  const NewtonSettings& s = settings_;
  // Inexact Newton (doc/user-guide.md "Solution method"): only iterative
  // solves have a tolerance to set.
  const double linTol = strategy_.linearTolerance();
  forcing_ = linTol > 0.0 && s.eisenstatWalker;
  eta_ = solveTol_ = linTol, mismatch_ = 1.0, rPrev_ = 0.0;
  const bool contact = model_.hasContact();
  const bool conventional = contact && !model_.decomposedContact();

  auto u = model_.createVector();
  u->assign(uStart);
  auto dp = model_.createVector();
  model_.prescribedIncrement(lambda0, lambda1, *dp);
  auto r = model_.createVector();
  auto du = model_.createVector();
  double r0 = 0.0, e0 = 0.0;
  double lastEnergy = 0.0;  // |du.r| of the last iteration (for the failure message)
  rec.residualHistory.clear();
  rec.failure.clear();
  seen_.clear();
  grossSlip_.clear();
  if (contact) seen_.push_back(activeSetSignature(model_));
  // Conventional element, Contact/Pairing Cycles = Freeze: once the pairing
  // cycles, it is kept for the rest of the increment (doc/contact.md).
  pairingFrozen_ = false;
  if (contact) model_.beginContactStep(*u);  // the slip of frictional pairs starts here
  strategy_.beginIncrement();
  for (int it = 0; it < s.maxIterations; ++it) {
    Iteration i;
    i.it = it;
    if (!assemble(it, *u, lambda0, lambda1, *r, it == 0 ? dp.get() : nullptr, rec)) return false;
    i.rnorm = r->norm2();
    rec.residualHistory.push_back(i.rnorm);
    if (!std::isfinite(i.rnorm)) return fail(nonFinite(model_, it, "residual", *r), rec);
    if (it == 0) r0 = i.rnorm;
    const bool residualOk = it > 0 && i.rnorm <= std::max(s.residualTolerance * r0, s.absoluteResidualTolerance);
    if (forcing_) setForcingTerm(it, i.rnorm, r0);

    r->scale(-1.0);
    i.info = strategy_.solve(*r, *du);
    timing_.linearSetup += i.info.setupSeconds;
    timing_.linearSolve += i.info.solveSeconds;
    rec.dualIterations += i.info.iterations;
    for (int k = 0; k < 6; ++k) timing_.feti[k] += i.info.feti[k];
    ++timing_.linearSolves;
    // |du·r|: the energy norm of the correction.
    i.energy = std::abs(du->dot(*r));
    if (it == 0) {
      du->update(1.0, *dp, 1.0);  // constrained rows solved to 0; impose the increment
      e0 = i.energy;
    }
    u->update(1.0, *du, 1.0);
    rec.newtonIterations = it + 1;

    // Contact: follow the current configuration (conventional NTS), then
    // check the contact state on the multipliers (release in tension,
    // activate on penetration).
    if (contact && !updateContact(*u, conventional, i, rec)) return false;
    printIteration(i);
    if (!std::isfinite(i.energy)) return fail(nonFinite(model_, it, "correction", *du), rec);
    if (!contactSettled(i, rec)) {
      if (!rec.failure.empty()) return false;
      continue;  // the pairing was frozen: one more iteration
    }
    lastEnergy = i.energy;
    if (residualOk && i.energy <= s.energyTolerance * e0 && i.changed.empty() && !i.pairingChanged) {
      uStart.assign(*u);
      return true;
    }
  }
  rec.failure = "no convergence in " + std::to_string(s.maxIterations) + " iterations (Newton/Max Iterations)" +
                unmetCriterion(rec.residualHistory, lastEnergy, e0, lambda1 - lambda0) +
                (grossSlip_.empty() ? "" : "; " + grossSlip_);
  return false;
}

bool Newton::assemble(int it, const Vector& u, double lambda0, double lambda1, Vector& r, const Vector* dp,
                      StepRecord& rec) {
  // One element pass: the residual and what the strategy solves with (the
  // global tangent, or the subdomain stiffness matrices).
  const auto start = std::chrono::steady_clock::now();
  if (dynamics_) dynamics_->updateIterate(u);  // a(u), v(u) and the factor of M at this iterate
  AssemblyResult assembled;
  try {
    assembled = strategy_.assemble(u, lambda1, r, dp);
  } catch (const InadmissibleDeformation& e) {
    return fail(std::string("Newton iteration ") + std::to_string(it) + ": " + e.what(), rec);
  }
  // A rigid motion nothing restrains makes the tangent singular; a direct
  // solver may factorise it anyway and return a drift along it (the same
  // on every rank: the check ends with a reduction).
  if (!assembled.freeMotions.empty()) {
    std::ostringstream os;
    if (!grossSlip_.empty()) os << grossSlip_ << "; then ";
    os << "the problem is singular in step " << rec.step << " (load factor " << lambda0 << " -> " << lambda1
       << "), Newton iteration " << it << ": no prescribed displacement and no active contact restrains "
       << assembled.freeMotions
       << ". Prescribe displacements (Boundary Conditions) that hold these motions; contact holds a body "
          "along its contact normals, and along the surface only where a pair with a 'Friction Coefficient' "
          "sticks (doc/user-guide.md, \"A singular problem\")";
    throw SolverError(os.str());
  }
  timing_.assembly += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

void Newton::setForcingTerm(int it, double rnorm, double r0) {
  const NewtonSettings& s = settings_;
  const double linTol = strategy_.linearTolerance();
  const double etaMax = std::max(s.maximumForcingTerm, linTol);
  const bool contact = model_.hasContact();
  if (it > 0) {
    // How much less the last solve reduced the Newton residual than its
    // tolerance promised (FETI-DP's tolerance is on the dual residual, an
    // interface jump, not on the force residual); nonlinearity and contact
    // changes count too, which errs towards tighter solves.
    mismatch_ = std::max(1.0, rnorm / (solveTol_ * rPrev_));
    if (rnorm > rPrev_) {
      eta_ = linTol;  // the residual grew: solve tightly again
    } else {
      // Eisenstat & Walker (1996), choice 2 (gamma 0.9, alpha 2), with their
      // safeguard against a sudden tightening; not with contact, whose
      // active-set decisions need accurate multipliers.
      const double safeguard = 0.9 * eta_ * eta_;
      eta_ = contact ? 0.0 : 0.9 * (rnorm / rPrev_) * (rnorm / rPrev_);
      if (!contact && safeguard > 0.1) eta_ = std::max(eta_, safeguard);
      // No need to go below a fraction of what Newton asks for.
      if (rnorm > 0.0)
        eta_ = std::max(eta_, s.forcingTermFloor * std::max(s.residualTolerance * r0, s.absoluteResidualTolerance) / rnorm);
      eta_ = std::min(eta_, etaMax);
    }
  }
  solveTol_ = std::min(std::max(eta_ / mismatch_, linTol), etaMax);
  strategy_.setSolveTolerance(solveTol_);
  rPrev_ = rnorm;
}

void Newton::printIteration(const Iteration& i) const {
  if (!settings_.printIterations || model_.comm()->getRank() != 0) return;
  char buf[200];
  std::snprintf(buf, sizeof buf, "    iter %2d  |r| = %.3e  |du.r| = %.3e", i.it, i.rnorm, i.energy);
  std::string line = buf;
  if (i.info.iterations > 0) line += "  dual/Krylov " + std::to_string(i.info.iterations);
  if (i.info.conditionEstimate > 0.0) {
    std::snprintf(buf, sizeof buf, " (condition ~%.3g)", i.info.conditionEstimate);
    line += buf;
  }
  if (forcing_) {
    std::snprintf(buf, sizeof buf, " (tol %.1e)", solveTol_);
    line += buf;
  }
  if (model_.hasContact())
    line += "  active " + std::to_string(model_.activeContacts()) + " (" + std::to_string(i.changed.size()) +
            " changed" + (i.pairingChanged ? ", new pairing" : "") + ")";
  std::cout << line << std::endl;
}

bool Newton::updateContact(const Vector& u, bool conventional, Iteration& i, StepRecord& rec) {
  // An iterate far from the solution (a body sliding away in gross slip,
  // say) may hold a geometry the contact update cannot evaluate: a failed
  // iteration, which the step controller bisects, as in assemble().
  try {
    if (conventional && !pairingFrozen_) i.pairingChanged = model_.updatePairing(u, false, false, &i.repaired);
    i.changed = model_.updateActiveSet(u, /*everySlot=*/false);
  } catch (const InadmissibleDeformation& e) {
    return fail(std::string("Newton iteration ") + std::to_string(i.it) + ", contact update: " + e.what(), rec);
  }
  noteGrossSlip(i.it);
  return true;
}

bool Newton::fail(const std::string& why, StepRecord& rec) const {
  rec.failure = grossSlip_.empty() ? why : grossSlip_ + "; then " + why;
  note_("    " + rec.failure);
  return false;
}

void Newton::noteGrossSlip(int it) {
  // Gross slip (doc/contact.md, "Friction"): every slave node in contact of
  // a frictional pair slips, so Coulomb friction holds the bodies along the
  // surface no more; the first one of the increment goes into the failure
  // messages.
  if (!grossSlip_.empty()) return;
  for (const std::string& pair : model_.pairsInGrossSlip())
    grossSlip_ += (grossSlip_.empty() ? "" : "; ") + std::string("gross slip: every slave node in contact of the pair ") +
                  pair + " slips at Newton iteration " + std::to_string(it) +
                  ": the tangential load exceeds what Coulomb friction can hold (the friction coefficient times the "
                  "normal load), so the bodies slide along each other without bound unless something else holds them";
}

bool Newton::contactSettled(const Iteration& i, StepRecord& rec) {
  if (i.changed.empty() && !i.pairingChanged) return true;
  auto a = activeSetSignature(model_);
  const bool repeated = std::find(seen_.begin(), seen_.end(), a) != seen_.end();
  if (repeated && i.pairingChanged && model_.contactOptions().freezeCyclingPairing) {
    pairingFrozen_ = true;
    note_("    Newton iteration " + std::to_string(i.it) + ": the pairing cycles (" + std::to_string(i.repaired.size()) +
          " slave nodes changed master facet); kept for the rest of this increment (Contact/Pairing Cycles = "
          "Freeze)");
    seen_.push_back(std::move(a));
    return false;
  }
  if (repeated) {
    std::ostringstream os;
    os << "the contact active set cycles (a set seen before in this increment returned)";
    auto list = [&](const char* what, const std::vector<int>& slots) {
      if (slots.empty()) return;
      os << "; " << what << ":";
      for (size_t k = 0; k < slots.size() && k < 10; ++k) os << "\n      " << model_.describeSlot(slots[k]);
      if (slots.size() > 10) os << "\n      ... and " << slots.size() - 10 << " more";
    };
    list("pairs changing state", i.changed);
    list("slave nodes changing master segment", i.repaired);
    return fail(os.str(), rec);
  }
  seen_.push_back(std::move(a));
  return true;
}

std::string Newton::unmetCriterion(const std::vector<double>& residuals, double energy, double e0,
                                   double increment) const {
  if (residuals.size() < 2) return "";
  const NewtonSettings& s = settings_;
  const double r0 = residuals.front(), r = residuals.back();
  const double target = std::max(s.residualTolerance * r0, s.absoluteResidualTolerance);
  std::ostringstream os;
  os.precision(3);
  if (r > target)
    os << ": |r| = " << r << " > max(Residual Tolerance x |r_0|, Absolute Residual Tolerance) = " << target;
  else if (energy > s.energyTolerance * e0)
    os << ": |r| met its tolerance, but |du.r| = " << energy << " > Energy Tolerance x |du_0.r_0| = "
       << s.energyTolerance << " x " << e0 << " = " << s.energyTolerance * e0;
  else
    return "";  // the contact state kept changing (reported where it does)
  // Stagnation: the last kStagnant residuals no lower than a tenth of the
  // lowest before them. Then more iterations do not help; the tolerance is
  // below what the arithmetic of this increment resolves.
  constexpr size_t kStagnant = 5;
  if (residuals.size() >= 2 * kStagnant) {
    const auto tail = residuals.end() - kStagnant;
    const double before = *std::min_element(residuals.begin(), tail);
    const double recent = *std::min_element(tail, residuals.end());
    const bool dynamic = dynamics_ != nullptr;
    if (recent >= 0.1 * before)
      os << "; the residual stagnates around " << recent << " (the first was " << r0
         << "), so more iterations do not help: either the tolerance is below the round-off of this increment ("
         << (dynamic ? "time step " : "load factor increment ") << increment << "; "
         << (dynamic ? "" : "fewer 'Load Stepping/Number of Steps' or ")
         << "a larger 'Newton/Absolute Residual Tolerance' / 'Newton/Energy Tolerance' help then) or the tangent "
            "does not fit the residual";
  }
  return os.str();
}

}  // namespace ddc
