#include "DDC_BlasKernels.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <array>
#include <cctype>

namespace ddc {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

/// OpenBLAS' x86 kernel families without AVX2 (its driver/others/dynamic.c
/// names): on a CPU with AVX2 each is a fallback, not a match.
bool withoutAvx2(const std::string& core) {
  static const std::array<const char*, 12> names{"katmai", "coppermine", "northwood", "prescott", "banias", "atom",
                                                 "core2", "penryn", "dunnington", "nehalem", "sandybridge",
                                                 "unknown"};
  const std::string c = lower(core);
  return std::any_of(names.begin(), names.end(), [&](const char* n) { return c == n; });
}

}  // namespace

BlasKernels detectBlasKernels() {
  BlasKernels k;
  using CoreName = char* (*)();
  if (auto f = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"))) {
    k.library = "OpenBLAS";
    if (const char* name = f()) k.core = name;
  }
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  k.cpuHasAvx2 = __builtin_cpu_supports("avx2");
  k.cpuHasAvx512 = __builtin_cpu_supports("avx512f");
#endif
  return k;
}

std::string blasKernelAdvice(const BlasKernels& k) {
  if (k.library != "OpenBLAS" || !k.cpuHasAvx2 || !withoutAvx2(k.core)) return "";
  return "OpenBLAS runs its " + k.core + " kernels, but this CPU has AVX2" +
         (k.cpuHasAvx512 ? std::string(" and AVX-512") : std::string()) +
         " (the library does not know its model): dense factorisations, e.g. a large coarse problem, take up "
         "to twice as long. Set OPENBLAS_CORETYPE=Haswell" +
         (k.cpuHasAvx512 ? std::string(" (or SkylakeX)") : std::string()) +
         " in the environment of every rank (mpirun -x OPENBLAS_CORETYPE=...) to select faster kernels "
         "(doc/performance.md, 'The BLAS kernels')";
}

}  // namespace ddc
