#include "DDC_StepLoop.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_Memory.hpp"

namespace ddc {

namespace {
double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

/// The attempts of the step being worked on: the exchanges (also of
/// attempts Newton failed on) and the Newton and dual iterations of the
/// attempts the step control sent back count in the accepted step's row
/// (its cost); the contact state of the step's start, which a repeat with
/// the geometry of the step's end keeps.
struct StepLoop::Attempts {
  long exchanges0 = 0, bytes0 = 0;      ///< the model's counters when the step began
  int rejections = 0, corrections = 0;  ///< sent back smaller / repeated
  int newton = 0, dual = 0;             ///< iterations of the attempts sent back
  std::vector<ContactSlot> startSlots;
  bool repeating = false;  ///< the next attempt repeats the step with the geometry of its end
};

/// What measure() found of a converged attempt besides its record.
struct StepLoop::Measured {
  Teuchos::RCP<Vector> fint;  ///< f_int at the attempt's end
  ContactSummary contact;     ///< at convergence, before the step-end re-pairing
  std::vector<ContactSlot> convergedSlots;
};

StepLoop::StepLoop(std::shared_ptr<Model> model, SolutionStrategy& strategy, Dynamics* dynamics,
                   NewtonSettings newton, std::unique_ptr<StepController> controller, StepLoopSettings settings)
    : model_(std::move(model)), strategy_(strategy), dynamics_(dynamics), controller_(std::move(controller)),
      settings_(std::move(settings)),
      newton_(*model_, strategy_, newton, dynamics_, timing_, [this](const std::string& line) { note(line); }),
      attempts_(std::make_unique<Attempts>()) {
  DDC_CHECK(controller_ != nullptr, "a step loop needs a step controller");
  // The unloaded state; the initial acceleration balances the body force
  // (u = 0 and every load-factor-scaled load 0 at t = 0).
  state_.u = model_->createVector();
  state_.fint = model_->createVector();
  state_.reaction = model_->createVector();
  if (dynamics_) {
    dynamics_->start(*model_, *state_.u);
    dynamics_->integrator().inertiaForce(*model_, *state_.reaction);  // M a0 (+ C v0)
  }
  state_.controllerState = controller_->saveState();
  trial_ = model_->createVector();
}

StepLoop::~StepLoop() = default;

RunKind StepLoop::kind() const {
  return RunKind{dynamics_ != nullptr, model_->decomposedContact(), model_->dim(),
                 model_->hasContact() && model_->contactOptions().frictional()};
}

std::string StepLoop::stepLabel(int n) const {
  char b[40];
  if (controller_->numSteps() > 0)
    std::snprintf(b, sizeof b, "%3d/%d", n, controller_->numSteps());
  else
    std::snprintf(b, sizeof b, "%3d", n);
  return b;
}

void StepLoop::note(const std::string& line) {
  for (StepObserver* o : observers_) o->note(*this, line);
}

void StepLoop::contactWarnings() {
  for (const auto& w : model_->takeContactWarnings()) note("warning: " + w);
}

void StepLoop::run() {
  start_ = now();
  const bool contact = model_->hasContact();
  *attempts_ = Attempts{};
  attempts_->exchanges0 = model_->exchanges();
  attempts_->bytes0 = model_->bytesExchanged();
  for (StepObserver* o : observers_) o->started(*this);
  if (contact) contactWarnings();  // from the initial pairing
  if (contact && dynamics_ && !restarted_) {
    penetration_ = initialPenetration(*model_);
    if (penetration_.depth > 0.0) note(initialPenetrationWarning(penetration_));
    initialEnergy_ = model_->kineticEnergy(dynamics_->integrator().velocity());  // unstrained
  }
  try {
    while (!controller_->done()) {
      const StepProposal p = controller_->propose();
      StepRecord rec;
      rec.step = p.step;
      if (!attempt(p, rec)) {
        newtonFailed(p, rec);
        continue;
      }
      Measured m = measure(p, rec);
      const StepVerdict verdict = controller_->judge(p, rec.geometryError);
      const std::string why = controller_->takeNote();
      if (!why.empty()) note("warning: step " + std::to_string(p.step) + ": " + why);
      if (verdict != StepVerdict::Accept) {
        sentBack(p, rec, verdict);
        continue;
      }
      accept(p, rec, m);
    }
  } catch (const SolverError& e) {
    fail(e);
  }
  // The validators make every run step (Number of Steps > 0, Final Load
  // Factor > 0 and finite); should anything still leave no converged step,
  // the run must fail rather than commit a history without rows.
  if (state_.history.empty() || !(controller_->current() > 0.0)) {
    std::ostringstream os;
    os << "the analysis made no converged step (" << settings_.stepping << ": " << settings_.numSteps
       << " steps to " << settings_.finalValue << "), so there are no results";
    throw SolverError(os.str());
  }
  reduceTiming();
  // Every slot's values on every rank, once per run, for a host that reads
  // contactSlots() after the run.
  if (contact) model_->shareContactValues();
  for (StepObserver* o : observers_) o->finished(*this);
}

bool StepLoop::startsInContact() const {
  const ContactOptions& o = model_->contactOptions();
  if (!o.initialInContact) return false;
  if (!o.inContactOnlyWhenNoneActive) return true;
  const auto& slots = model_->contactSlots();  // replicated: the same answer on every rank
  return std::none_of(slots.begin(), slots.end(), [](const ContactSlot& s) { return s.active; });
}

bool StepLoop::attempt(const StepProposal& p, StepRecord& rec) {
  Attempts& att = *attempts_;
  // The contact state at the step's start (a repeat with the geometry of
  // the step's end keeps the one saved before it).
  if (model_->hasContact() && !att.repeating) att.startSlots = model_->contactSlots();
  att.repeating = false;
  if (model_->hasContact() && startsInContact()) model_->activateAllPaired();
  if (dynamics_) dynamics_->beginStep(*model_, p.from, p.size, *state_.fint);
  Activity activity("solving step " + std::to_string(p.step) + " (" + settings_.factorName + " " +
                    std::to_string(p.from) + " -> " + std::to_string(p.to) + ", " +
                    std::to_string(model_->ownedMap()->getGlobalNumElements()) + " unknowns; " +
                    settings_.estimatedMemory + ")");
  if (faults_) {
    faults_->beforeAttempt(p.step);
    rec.failure = faults_->injectedFailure(p.step);
    if (!rec.failure.empty()) return false;
  }
  trial_->assign(*state_.u);
  return newton_.solve(p.from, p.to, *trial_, rec);
}

void StepLoop::newtonFailed(const StepProposal& p, const StepRecord& rec) {
  if (model_->hasContact()) model_->restoreContactState(attempts_->startSlots);
  if (!controller_->reject(p)) {
    std::ostringstream os;
    os << "Newton did not converge in step " << p.step << " (" << settings_.factorName << " " << p.from << " -> "
       << p.to << ") after " << p.depth << " bisections";
    const std::string limits = controller_->limits(settings_.stepping);
    if (!limits.empty()) os << " (" << limits << ")";
    os << ": " << rec.failure;
    if (!rec.residualHistory.empty()) os << "; residual history:";
    for (double x : rec.residualHistory) os << " " << x;
    if (!settings_.failureNote.empty()) os << "; note: " << settings_.failureNote;
    throw SolverError(os.str());
  }
  const StepProposal next = controller_->propose();
  for (StepObserver* o : observers_) o->rejected(*this, RejectedStep{RejectedStep::Reason::NewtonFailed, p, next, rec});
}

StepLoop::Measured StepLoop::measure(const StepProposal& p, StepRecord& rec) {
  Measured m;
  rec.loadFactor = p.to;
  rec.bisections = p.depth;
  rec.stepSize = p.size;
  m.fint = model_->createVector();
  AssemblyRequest energy;
  energy.fint = m.fint.get();
  rec.strainEnergy = model_->assemble(*trial_, p.to, energy).strainEnergy;
  if (!model_->hasContact()) return m;
  // Converged: refresh the pairing once per step, with a global search
  // (tracking cannot see another part of the surface come nearer). The
  // decomposed element freezes the new projections and normals.
  // Multipliers, gaps and normals of the converged state are read first:
  // after re-pairing, the decomposed slots hold the next step's normals.
  // Their values are current on the slots' owners, where the sums over
  // the slots are taken (ContactComponent::updateActiveSet()).
  const bool decomposed = model_->decomposedContact();
  model_->updateActiveSet(*trial_, /*everySlot=*/false);
  m.contact = model_->reduceContactSummary();
  m.convergedSlots = model_->contactSlots();
  model_->updatePairing(*trial_, true, decomposed);
  contactWarnings();
  if (decomposed) {
    // The frozen-geometry error indicator (doc/contact.md, "Step control
    // by the frozen-geometry error"), relative to the energy of the state.
    double energyNow = rec.strainEnergy;
    if (dynamics_) {
      auto v = model_->createVector();
      dynamics_->integrator().velocity(*trial_, *v);
      energyNow += model_->kineticEnergy(*v);
    }
    const double w = model_->contact()->frozenGeometryError(m.convergedSlots).total();
    rec.geometryError = energyNow > 0.0 ? w / energyNow : 0.0;
  }
  return m;
}

void StepLoop::sentBack(const StepProposal& p, const StepRecord& rec, StepVerdict verdict) {
  // Back to the step's start: the displacements are the accepted state's
  // (the integrator and f_int were not advanced) and, to try a smaller step,
  // the contact state; a repeat keeps the pairing just refreshed at the
  // step's end, so the step is solved again with the projections and
  // normals of its end.
  Attempts& att = *attempts_;
  const bool repeat = verdict == StepVerdict::Repeat;
  att.repeating = repeat;
  att.newton += rec.newtonIterations;
  att.dual += rec.dualIterations;
  if (repeat) {
    ++att.corrections;
  } else {
    model_->restoreContactState(att.startSlots);
    ++att.rejections;
  }
  const StepProposal next = controller_->propose();
  const auto reason = repeat ? RejectedStep::Reason::Repeat : RejectedStep::Reason::Reduce;
  for (StepObserver* o : observers_) o->rejected(*this, RejectedStep{reason, p, next, rec});
}

void StepLoop::accept(const StepProposal& p, StepRecord& rec, Measured& m) {
  Attempts& att = *attempts_;
  controller_->accept(p);
  state_.controllerState = controller_->saveState();
  rec.rejections = att.rejections;
  rec.corrections = att.corrections;
  rec.newtonIterations += att.newton;
  rec.dualIterations += att.dual;
  // The forces the prescribed DOFs exert: f_int, and in dynamics also the
  // inertia and damping of the prescribed nodes (a moving support
  // accelerates its nodes' mass).
  auto reaction = model_->createVector();
  reaction->assign(*m.fint);
  if (dynamics_) {
    dynamics_->integrator().acceptStep(*trial_);
    rec.kineticEnergy = model_->kineticEnergy(dynamics_->integrator().velocity());
    auto f = model_->createVector();
    dynamics_->integrator().inertiaForce(*model_, *f);
    reaction->update(1.0, *f, 1.0);
  }
  state_.externalWork += externalWorkIncrement(*state_.reaction, *state_.u, p.from, *reaction, *trial_, p.to);
  rec.externalWork = state_.externalWork;
  state_.fint = m.fint;
  state_.reaction = reaction;
  state_.u->assign(*trial_);
  if (model_->hasContact()) {
    state_.convergedSlots = std::move(m.convergedSlots);
    rec.frictionalDissipation = (state_.history.empty() ? 0.0 : state_.history.back().frictionalDissipation) +
                                model_->contact()->frictionalWork(state_.convergedSlots);
    rec.activeContacts = m.contact.active;
    for (int c = 0; c < 3; ++c) rec.contactForce[c] = m.contact.force[c];
    rec.contactExchanges = model_->exchanges() - att.exchanges0;
    rec.contactBytes = model_->bytesExchanged() - att.bytes0;
  }
  att = Attempts{};  // of the next step
  att.exchanges0 = model_->exchanges();
  att.bytes0 = model_->bytesExchanged();
  if (controller_->atMinimum()) {
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "warning: step %d: frozen-geometry error %.3g above Step Control/Error Tolerance at the minimum "
                  "step size %.3g (Step Control/Minimum Step Size); accepted",
                  p.step, rec.geometryError, p.size);
    note(buf);
  }
  if (penetration_.depth > 0.0 && state_.history.empty())
    note(injectedEnergyWarning(penetration_, initialEnergy_, rec.kineticEnergy + rec.strainEnergy, rec.externalWork,
                               rec.frictionalDissipation));
  rec.wallSeconds = now() - start_ + state_.wallOffset;
  state_.history.push_back(rec);
  const bool last = controller_->done();
  for (StepObserver* o : observers_) o->accepted(*this, state_.history.back(), last);
}

double StepLoop::externalWorkIncrement(const Vector& fint0, const Vector& u0, double lambda0, const Vector& fint1,
                                       const Vector& u1, double lambda1) const {
  // Trapezoidal rule in the load factor: reactions at prescribed DOFs (the
  // force there: RunState::reaction) and applied tractions and body forces,
  // times the displacement step.
  const auto& map = *model_->ownedMap();
  const GO first = map.getMinGlobalIndex();
  auto f0 = fint0.getData(), f1 = fint1.getData(), a = u0.getData(), b = u1.getData();
  auto fe = model_->externalForce().getData();
  Teuchos::ArrayRCP<const double> fb;  // the constant body force, if any
  if (model_->bodyForce()) fb = model_->bodyForce()->getData();
  double w = 0.0;
  for (size_t l = 0; l < map.getNodeNumElements(); ++l) {
    const double step = b[l] - a[l];
    if (model_->isConstrained(first + GO(l)))
      w += 0.5 * (f0[l] + f1[l]) * step;
    else
      w += (0.5 * (lambda0 + lambda1) * fe[l] + (fb.is_null() ? 0.0 : fb[l])) * step;
  }
  double sum = 0.0;
  Teuchos::reduceAll(*model_->comm(), Teuchos::REDUCE_SUM, w, Teuchos::outArg(sum));
  return sum;
}

void StepLoop::fail(const SolverError& e) {
  // The state is the last accepted step's: a failed attempt left state_.u
  // alone; its contact state goes back to the step's start.
  if (model_->hasContact() && !attempts_->startSlots.empty()) model_->restoreContactState(attempts_->startSlots);
  std::string appended;
  for (StepObserver* o : observers_) appended += o->failed(*this, e.what());
  if (appended.empty()) throw;  // the handled exception, as it was
  throw SolverError(std::string(e.what()) + appended);
}

void StepLoop::reduceTiming() {
  const auto& comm = *model_->comm();
  const double mine = peakResidentBytes() / (1024.0 * 1024.0);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(timing_.peakMemoryMiB));
  double t[3] = {timing_.assembly, timing_.linearSetup, timing_.linearSolve}, tmax[3];
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 3, t, tmax);
  timing_.assembly = tmax[0], timing_.linearSetup = tmax[1], timing_.linearSolve = tmax[2];
  const auto b = model_->contactValueBytesReceived();
  const long long bytes[2] = {b[0], b[1]};
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 2, bytes, timing_.contactValueBytes.data());
}

}  // namespace ddc
