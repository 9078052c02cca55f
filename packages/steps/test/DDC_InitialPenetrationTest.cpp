// The first-step warning of a dynamic run whose bodies start overlapped
// (DDC_InitialPenetration.hpp): the energy gained beyond the external work,
// with a frictional pair less what friction dissipated in that step
// (doc/user-guide.md, "Contact in dynamics").
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "DDC_InitialPenetration.hpp"

namespace {

ddc::InitialPenetration penetration() {
  ddc::InitialPenetration p;
  p.depth = 0.01;
  p.node = 20;
  p.pair = "Ends";
  return p;
}

std::string gainedText(double gained) {
  std::ostringstream os;
  os << ": " << gained << " beyond it";
  return os.str();
}

TEST(InjectedEnergyWarning, FrictionlessNamesNoDissipation) {
  const std::string w = ddc::injectedEnergyWarning(penetration(), 0.1, 0.15, 0.02);
  EXPECT_EQ(w.find("frictional dissipation"), std::string::npos) << w;
  EXPECT_NE(w.find("with external work 0.02" + gainedText(0.15 - 0.1 - 0.02)), std::string::npos) << w;
}

TEST(InjectedEnergyWarning, FrictionCountsAsEnergyKept) {
  // 0.1 + 0.02 supplied; 0.15 left and 0.03 dissipated: 0.06 beyond it.
  const std::string w = ddc::injectedEnergyWarning(penetration(), 0.1, 0.15, 0.02, 0.03);
  EXPECT_NE(w.find("with external work 0.02 and frictional dissipation 0.03" + gainedText(0.15 + 0.03 - 0.1 - 0.02)),
            std::string::npos)
      << w;
}

}  // namespace
