// Which kernels the BLAS library runs, and whether the CPU offers faster
// ones (doc/performance.md, "The BLAS kernels").
//
// OpenBLAS built with DYNAMIC_ARCH (as Debian builds it) chooses its kernels
// at load time from the CPU's family and model. A model newer than the
// library falls back to its oldest x86-64 kernels (Prescott: SSE3, no AVX),
// even on a CPU with AVX2 or AVX-512; the dense fronts of a large coarse
// factorisation then take up to twice as long. The environment variable
// OPENBLAS_CORETYPE overrides the choice, but only before the library is
// loaded, so a run can only say so.
#pragma once

#include <string>

namespace ddc {

/// What is known of the BLAS kernels and of the CPU.
struct BlasKernels {
  std::string library;  ///< "OpenBLAS", or "" if the BLAS is not OpenBLAS
  std::string core;     ///< OpenBLAS' kernel family, e.g. "Prescott", "Haswell", "SkylakeX"
  bool cpuHasAvx2 = false;
  bool cpuHasAvx512 = false;  ///< AVX-512 F
};

/// The BLAS loaded into this process (found by symbol, no link dependency)
/// and the CPU's vector extensions.
BlasKernels detectBlasKernels();

/// "" if the kernels suit the CPU; otherwise one sentence: which kernels run,
/// what the CPU has, and the OPENBLAS_CORETYPE value that selects faster ones.
std::string blasKernelAdvice(const BlasKernels& k);

}  // namespace ddc
