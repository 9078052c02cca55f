#include "DDC_FaultSeam.hpp"

#include <csignal>
#include <string>

#include "DDC_ResultFile.hpp"

namespace ddc {

namespace {

class FaultInjectionSeam final : public StepFaults {
 public:
  explicit FaultInjectionSeam(Teuchos::RCP<const Teuchos::Comm<int>> comm) : comm_(std::move(comm)) {}
  void beforeAttempt(int step) override {
    if (comm_->getRank() == 0 && !raised_ && faultInjection("sigterm", std::to_string(step))) {
      raised_ = true;
      std::raise(SIGTERM);
    }
  }
  std::string injectedFailure(int step) override {
    return faultInjection("newton-failure", std::to_string(step))
               ? "test fault injection: newton-failure@" + std::to_string(step)
               : std::string();
  }

 private:
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  bool raised_ = false;
};

}  // namespace

std::unique_ptr<StepFaults> makeFaultInjectionSeam(Teuchos::RCP<const Teuchos::Comm<int>> comm) {
  if (!faultInjectionActive()) return nullptr;
  return std::make_unique<FaultInjectionSeam>(std::move(comm));
}

}  // namespace ddc
