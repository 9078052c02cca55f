// The one table of a step's record (DDC_StepRecord.hpp): the history's
// stable columns come first and in their documented order, every output
// takes its names and values from the table, and a checkpoint's records
// round-trip bit for bit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_StepRecord.hpp"

using ddc::RunKind;
using ddc::StepRecord;
using ::testing::ElementsAreArray;

namespace {

std::vector<std::string> tableNames() {
  std::vector<std::string> names;
  for (const auto& f : ddc::stepFields()) names.push_back(f.name);
  return names;
}

/// True if `sub` appears in `all` in the same order.
bool inTableOrder(const std::vector<std::string>& sub, const std::vector<std::string>& all) {
  size_t at = 0;
  for (const auto& name : sub) {
    const auto it = std::find(all.begin() + long(at), all.end(), name);
    if (it == all.end()) return false;
    at = size_t(it - all.begin()) + 1;
  }
  return true;
}

StepRecord sample() {
  StepRecord r;
  r.step = 7;
  r.loadFactor = 0.1 + 0.2;  // not a short decimal: round-trips exactly or not at all
  r.strainEnergy = 1.0 / 3.0;
  r.newtonIterations = 4;
  r.dualIterations = 123;
  r.bisections = 2;
  r.wallSeconds = 12.345678901234567;
  r.residualHistory = {1.0, 1e-3, 1e-9};
  r.externalWork = -2.0 / 7.0;
  r.activeContacts = 17;
  r.contactForce[0] = 1e-300;
  r.contactForce[1] = -5.5;
  r.contactForce[2] = 3.25;
  r.contactExchanges = 3;
  r.contactBytes = 4096;
  r.kineticEnergy = 0.125;
  r.stepSize = 0.01;
  r.rejections = 1;
  r.corrections = 2;
  r.geometryError = 4.2e-3;
  return r;
}

}  // namespace

TEST(StepRecord, StableHistoryColumnsFirst) {
  const std::vector<std::string> stable = {"step",           "load_factor",     "strain_energy",
                                           "newton_iterations", "dual_iterations", "active_contacts",
                                           "contact_force_x",   "contact_force_y", "contact_exchanges",
                                           "wall_seconds"};
  for (const RunKind kind : {RunKind{false, false, 2}, RunKind{true, true, 3}}) {
    const auto columns = ddc::historyColumns(kind);
    ASSERT_GE(columns.size(), stable.size());
    EXPECT_THAT(std::vector<std::string>(columns.begin(), columns.begin() + long(stable.size())),
                ElementsAreArray(stable));
  }
}

TEST(StepRecord, EveryOutputTakesItsNamesFromTheTable) {
  const auto all = tableNames();
  EXPECT_EQ(std::set<std::string>(all.begin(), all.end()).size(), all.size()) << "a name appears twice";
  for (const bool dynamic : {false, true})
    for (const bool decomposed : {false, true})
      for (const int dim : {2, 3}) {
        const RunKind kind{dynamic, decomposed, dim};
        EXPECT_TRUE(inTableOrder(ddc::historyColumns(kind), all));
        EXPECT_TRUE(inTableOrder(ddc::exodusGlobalNames(kind), all));
        const StepRecord r = sample();
        EXPECT_EQ(ddc::historyRow(r, kind).size(), ddc::historyColumns(kind).size());
        EXPECT_EQ(ddc::exodusGlobals(r, kind).size(), ddc::exodusGlobalNames(kind).size());
      }
  EXPECT_TRUE(inTableOrder(ddc::checkpointFieldNames(), all));
  // The run kinds select what they say: dynamics adds time and energies,
  // the decomposed element its step-control columns, 3-D the z force in Exodus II.
  const auto plain = ddc::historyColumns(RunKind{false, false, 2});
  const auto dynamic = ddc::historyColumns(RunKind{true, false, 2});
  const auto decomposed = ddc::historyColumns(RunKind{false, true, 2});
  EXPECT_EQ(std::count(plain.begin(), plain.end(), "kinetic_energy"), 0);
  EXPECT_EQ(std::count(dynamic.begin(), dynamic.end(), "total_energy"), 1);
  EXPECT_EQ(std::count(decomposed.begin(), decomposed.end(), "geometry_error"), 1);
  const auto exodus2 = ddc::exodusGlobalNames(RunKind{false, false, 2});
  const auto exodus3 = ddc::exodusGlobalNames(RunKind{true, false, 3});
  EXPECT_EQ(std::count(exodus2.begin(), exodus2.end(), "contact_force_z"), 0);
  EXPECT_EQ(std::count(exodus3.begin(), exodus3.end(), "contact_force_z"), 1);
  EXPECT_EQ(std::count(exodus2.begin(), exodus2.end(), "load_factor"), 1);
  EXPECT_EQ(std::count(exodus3.begin(), exodus3.end(), "time"), 1);
}

TEST(StepRecord, HistoryRowHoldsTheRecordsValues) {
  const StepRecord r = sample();
  const RunKind kind{true, true, 3};
  const auto columns = ddc::historyColumns(kind);
  const auto row = ddc::historyRow(r, kind);
  auto value = [&](const std::string& name) {
    return row[size_t(std::find(columns.begin(), columns.end(), name) - columns.begin())];
  };
  EXPECT_EQ(value("step"), 7.0);
  EXPECT_EQ(value("dual_iterations"), 123.0);
  EXPECT_EQ(value("contact_force_z"), 3.25);
  EXPECT_EQ(value("time"), r.loadFactor);
  EXPECT_EQ(value("total_energy"), r.kineticEnergy + r.strainEnergy);
  EXPECT_EQ(value("geometry_corrections"), 2.0);
}

TEST(StepRecord, CheckpointRecordsRoundTripExactly) {
  std::vector<StepRecord> records = {sample(), sample()};
  records[1].step = 8;
  records[1].residualHistory.clear();
  const auto back = ddc::unpackStepRecords(ddc::packStepRecords(records), "test.ddc");
  ASSERT_EQ(back.size(), records.size());
  const RunKind all{true, true, 3};
  for (size_t i = 0; i < records.size(); ++i) {
    EXPECT_EQ(ddc::historyRow(back[i], all), ddc::historyRow(records[i], all));
    EXPECT_EQ(back[i].residualHistory, records[i].residualHistory);
  }
  // Cut short: refused, naming the file and the row.
  auto packed = ddc::packStepRecords(records);
  packed.pop_back();
  packed.pop_back();
  try {
    ddc::unpackStepRecords(std::vector<double>(packed.begin(), packed.begin() + 5), "cut.ddc");
    FAIL() << "a record cut short was read";
  } catch (const ddc::InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("checkpoint 'cut.ddc': history row 1 is cut short"));
  }
}
