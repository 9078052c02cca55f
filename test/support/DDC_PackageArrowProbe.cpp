// One header of a DDContact package, included by a translation unit that
// sees only the include path of another package (test/suites/packaging.cmake,
// "package arrows"): it compiles where the arrows of doc/architecture.md
// allow the use and fails where they do not.
#include DDC_PROBE_HEADER

int ddcPackageArrowProbe() { return 0; }
