// The memory check's decision (ddc::judgeMemory) on given figures, and its
// collective forms on the ranks of this test (doc/user-guide.md, "Memory").
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>
#include <limits>

#include "DDC_Memory.hpp"

namespace {

constexpr double GiB = 1024.0 * 1024.0 * 1024.0;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMargin = 1.25;

// Eight ranks of 1 GiB each and 9 GiB on the host: enough without a margin,
// too little with 25 %; the message names the host and the margin.
TEST(JudgeMemory, TheMarginRefusesWhatTheEstimateAloneWouldPass) {
  const auto plain = ddc::judgeMemory(1 * GiB, 8 * GiB, 9 * GiB, 8, kInf, 1.0);
  EXPECT_TRUE(plain.fits);
  const auto b = ddc::judgeMemory(1 * GiB, 8 * GiB, 9 * GiB, 8, kInf, kMargin);
  EXPECT_FALSE(b.fits);
  EXPECT_DOUBLE_EQ(b.headroom, 9.0 / 10.0);
  EXPECT_DOUBLE_EQ(b.available, 9 * GiB / (kMargin * 8));
  EXPECT_EQ(b.source.rfind("host, less a margin of 25 % for what the estimate may miss", 0), 0u) << b.source;
}

// The host's ranks are judged by what they need together: one heavy rank
// (a factor gathered on rank 0) and three light ones fit 6 GiB.
TEST(JudgeMemory, TheRanksOfAHostAreJudgedTogether) {
  const auto b = ddc::judgeMemory(3 * GiB, 4.5 * GiB, 6 * GiB, 4, kInf, kMargin);
  EXPECT_TRUE(b.fits);
  EXPECT_NEAR(b.headroom, 6.0 / (1.25 * 4.5), 1e-15);
}

// An address-space limit smaller than the host's share decides.
TEST(JudgeMemory, TheProcessLimitDecidesWhenSmaller) {
  const auto b = ddc::judgeMemory(0.9 * GiB, 1.8 * GiB, 20 * GiB, 2, 1 * GiB, kMargin);
  EXPECT_FALSE(b.fits);
  EXPECT_DOUBLE_EQ(b.available, 1 * GiB / kMargin);
  EXPECT_EQ(b.source.rfind("process, less a margin", 0), 0u) << b.source;
}

TEST(JudgeMemory, NoLimitFoundFits) {
  const auto b = ddc::judgeMemory(1e15, 1e15, kInf, 1, kInf, kMargin);
  EXPECT_TRUE(b.fits);
  EXPECT_TRUE(std::isinf(b.headroom));
  EXPECT_TRUE(b.source.empty());
}

// On every rank the same verdict and text, from the rank shortest of memory.
TEST(MemoryBudget, EveryRankGetsTheSameVerdict) {
  auto comm = Tpetra::getDefaultComm();
  const bool heavy = comm->getRank() == comm->getSize() - 1;
  const auto b = ddc::memoryBudget(*comm, heavy ? 1e30 : 1.0, kMargin);
  EXPECT_FALSE(b.fits);  // 1e30 bytes fit no host
  EXPECT_NE(b.source.find("less a margin of 25 %"), std::string::npos) << b.source;
  const auto small = ddc::memoryBudget(*comm, 1.0, kMargin);
  EXPECT_TRUE(small.fits);
  EXPECT_GT(small.hostLimit, ddc::residentBytes());
}

// The watch: nothing to say within the limits, the host's ranks and their
// resident size once above the fraction.
TEST(MemoryAboveBudget, SaysWhatIsAboveTheFraction) {
  auto comm = Tpetra::getDefaultComm();
  ddc::MemoryBudget roomy;
  EXPECT_EQ(ddc::memoryAboveBudget(*comm, roomy, 0.9), "");
  ddc::MemoryBudget tight;
  tight.hostLimit = 1024.0;  // 1 KiB: every process holds more
  const std::string why = ddc::memoryAboveBudget(*comm, tight, 0.9);
  EXPECT_NE(why.find("above 90 % of the 1.0 KiB the memory check allowed"), std::string::npos) << why;
  ddc::MemoryBudget mapped;
  mapped.processLimit = 1024.0;
  EXPECT_NE(ddc::memoryAboveBudget(*comm, mapped, 0.5).find("above 50 % of its address-space limit 1.0 KiB"),
            std::string::npos);
}

}  // namespace
