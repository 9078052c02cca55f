// Sanitizer build only (CMake option DDContact_ENABLE_SANITIZERS,
// doc/verification.md "Sanitizer build").
//
// LeakSanitizer symbolises allocation stacks at process exit. Open MPI loads
// its components (mca_*.so) with dlopen and unloads them in MPI_Finalize;
// a leak allocated inside an unloaded component then shows as
// "<unknown module>", which no suppression can match (LeakSanitizer
// limitation, google/sanitizers issue 89). Defining dlclose here as a no-op
// interposes the C library's definition for every library in the process
// (this library is linked before libc), so components stay mapped until exit
// and their leaks are attributed and suppressed (test/sanitizers/lsan.supp).
// Programs built without the option never contain this definition.
#ifdef DDC_SANITIZER_BUILD
#include <dlfcn.h>

extern "C" int dlclose(void* /*handle*/) noexcept { return 0; }
#endif
