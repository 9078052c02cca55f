// The step loop's test seam (DDCONTACT_FAULT_INJECTION, packages/io/src/
// DDC_ResultFile.hpp): "sigterm@n" raises SIGTERM on rank 0 when step n is
// first attempted (once: a second SIGTERM ends the process), and
// "newton-failure@n" makes every attempt of step n fail as Newton does.
// The restart tests (test/tools/restart_cases.sh) stop and fail runs with it.
#pragma once

#include <memory>

#include <Teuchos_Comm.hpp>

#include "DDC_StepLoop.hpp"

namespace ddc {

/// The seam when fault injection is active in this process, else null.
std::unique_ptr<StepFaults> makeFaultInjectionSeam(Teuchos::RCP<const Teuchos::Comm<int>> comm);

}  // namespace ddc
