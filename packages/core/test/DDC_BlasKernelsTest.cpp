// The BLAS kernel check (doc/performance.md, "The BLAS kernels"): the advice
// on given figures, and the detection in this process, whose kernels the
// test's environment may force with OPENBLAS_CORETYPE.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "DDC_BlasKernels.hpp"

namespace {

using ddc::BlasKernels;
using ddc::blasKernelAdvice;

// The fallback on a CPU with AVX2 and AVX-512 is named, with both remedies.
TEST(BlasKernelAdvice, NamesTheFallbackAndTheRemedy) {
  const std::string a = blasKernelAdvice({"OpenBLAS", "Prescott", true, true});
  EXPECT_NE(a.find("OpenBLAS runs its Prescott kernels, but this CPU has AVX2 and AVX-512"), std::string::npos) << a;
  EXPECT_NE(a.find("OPENBLAS_CORETYPE=Haswell (or SkylakeX)"), std::string::npos) << a;
  const std::string b = blasKernelAdvice({"OpenBLAS", "Nehalem", true, false});
  EXPECT_NE(b.find("this CPU has AVX2 (the library"), std::string::npos) << b;
  EXPECT_EQ(b.find("SkylakeX"), std::string::npos) << b;
}

// Kernels that match the CPU, a CPU without AVX2, or another BLAS: silence.
TEST(BlasKernelAdvice, SilentWhenTheKernelsSuitTheCpu) {
  EXPECT_EQ(blasKernelAdvice({"OpenBLAS", "Haswell", true, true}), "");
  EXPECT_EQ(blasKernelAdvice({"OpenBLAS", "SkylakeX", true, true}), "");
  EXPECT_EQ(blasKernelAdvice({"OpenBLAS", "Zen", true, false}), "");
  EXPECT_EQ(blasKernelAdvice({"OpenBLAS", "Prescott", false, false}), "");
  EXPECT_EQ(blasKernelAdvice({"", "", true, true}), "");
}

// In this process: the linked BLAS is Debian's OpenBLAS; a core forced by
// OPENBLAS_CORETYPE is the one detected, and the advice follows it.
TEST(DetectBlasKernels, FindsTheCoreThisProcessRuns) {
  const BlasKernels k = ddc::detectBlasKernels();
  ASSERT_EQ(k.library, "OpenBLAS") << "the tests link Debian's OpenBLAS (cmake/setup.sh)";
  EXPECT_FALSE(k.core.empty());
  const char* forced = std::getenv("OPENBLAS_CORETYPE");
  if (!forced) GTEST_SKIP() << "OPENBLAS_CORETYPE not set: core " << k.core;
  if (!k.cpuHasAvx2) GTEST_SKIP() << "no AVX2 here: OpenBLAS may refuse the forced core " << forced;
  EXPECT_EQ(k.core, forced);
  const bool fallback = std::string(forced) == "Prescott" && k.cpuHasAvx2;
  EXPECT_EQ(blasKernelAdvice(k).empty(), !fallback) << blasKernelAdvice(k);
}

}  // namespace
