#include "DDC_StepRecord.hpp"

#include "DDC_Error.hpp"

namespace ddc {

bool present(When when, const RunKind& kind) {
  switch (when) {
    case When::Never: return false;
    case When::Always: return true;
    case When::QuasiStatic: return !kind.dynamic;
    case When::Dynamic: return kind.dynamic;
    case When::Decomposed: return kind.decomposed;
    case When::ThreeD: return kind.dim == 3;
    case When::Frictional: return kind.frictional;
  }
  return false;
}

const std::vector<StepField>& stepFields() {
  using R = StepRecord;
  using W = When;
  // name, unit, history, Exodus II, get, set (null: derived, not in a checkpoint)
  static const std::vector<StepField> fields = {
      {"step", "1", W::Always, W::Never, [](const R& r) { return double(r.step); }, [](R& r, double v) { r.step = int(v); }},
      {"load_factor", "load", W::Always, W::QuasiStatic, [](const R& r) { return r.loadFactor; }, [](R& r, double v) { r.loadFactor = v; }},
      {"strain_energy", "energy", W::Always, W::Always, [](const R& r) { return r.strainEnergy; }, [](R& r, double v) { r.strainEnergy = v; }},
      {"newton_iterations", "1", W::Always, W::Never, [](const R& r) { return double(r.newtonIterations); }, [](R& r, double v) { r.newtonIterations = int(v); }},
      {"dual_iterations", "1", W::Always, W::Never, [](const R& r) { return double(r.dualIterations); }, [](R& r, double v) { r.dualIterations = int(v); }},
      {"active_contacts", "1", W::Always, W::Always, [](const R& r) { return double(r.activeContacts); }, [](R& r, double v) { r.activeContacts = int(v); }},
      {"contact_force_x", "force", W::Always, W::Always, [](const R& r) { return r.contactForce[0]; }, [](R& r, double v) { r.contactForce[0] = v; }},
      {"contact_force_y", "force", W::Always, W::Always, [](const R& r) { return r.contactForce[1]; }, [](R& r, double v) { r.contactForce[1] = v; }},
      {"contact_exchanges", "1", W::Always, W::Never, [](const R& r) { return double(r.contactExchanges); }, [](R& r, double v) { r.contactExchanges = long(v); }},
      {"wall_seconds", "s", W::Always, W::Never, [](const R& r) { return r.wallSeconds; }, [](R& r, double v) { r.wallSeconds = v; }},
      {"external_work", "energy", W::Always, W::Always, [](const R& r) { return r.externalWork; }, [](R& r, double v) { r.externalWork = v; }},
      {"contact_bytes", "bytes", W::Always, W::Never, [](const R& r) { return double(r.contactBytes); }, [](R& r, double v) { r.contactBytes = long(v); }},
      {"bisections", "1", W::Always, W::Never, [](const R& r) { return double(r.bisections); }, [](R& r, double v) { r.bisections = int(v); }},
      {"contact_force_z", "force", W::Always, W::ThreeD, [](const R& r) { return r.contactForce[2]; }, [](R& r, double v) { r.contactForce[2] = v; }},
      {"time", "load", W::Dynamic, W::Dynamic, [](const R& r) { return r.loadFactor; }, nullptr},
      {"kinetic_energy", "energy", W::Dynamic, W::Dynamic, [](const R& r) { return r.kineticEnergy; }, [](R& r, double v) { r.kineticEnergy = v; }},
      {"total_energy", "energy", W::Dynamic, W::Never, [](const R& r) { return r.kineticEnergy + r.strainEnergy; }, nullptr},
      {"step_size", "load", W::Decomposed, W::Never, [](const R& r) { return r.stepSize; }, [](R& r, double v) { r.stepSize = v; }},
      {"rejected_steps", "1", W::Decomposed, W::Never, [](const R& r) { return double(r.rejections); }, [](R& r, double v) { r.rejections = int(v); }},
      {"geometry_corrections", "1", W::Decomposed, W::Never, [](const R& r) { return double(r.corrections); }, [](R& r, double v) { r.corrections = int(v); }},
      {"geometry_error", "1", W::Decomposed, W::Never, [](const R& r) { return r.geometryError; }, [](R& r, double v) { r.geometryError = v; }},
      {"frictional_dissipation", "energy", W::Frictional, W::Frictional, [](const R& r) { return r.frictionalDissipation; }, [](R& r, double v) { r.frictionalDissipation = v; }},
  };
  return fields;
}

namespace {

template <class Select>
std::vector<std::string> namesWhere(Select select) {
  std::vector<std::string> names;
  for (const StepField& f : stepFields())
    if (select(f)) names.push_back(f.name);
  return names;
}

template <class Select>
std::vector<double> valuesWhere(const StepRecord& r, Select select) {
  std::vector<double> values;
  for (const StepField& f : stepFields())
    if (select(f)) values.push_back(f.get(r));
  return values;
}

}  // namespace

std::vector<std::string> historyColumns(const RunKind& kind) {
  return namesWhere([&](const StepField& f) { return present(f.history, kind); });
}

std::vector<double> historyRow(const StepRecord& record, const RunKind& kind) {
  return valuesWhere(record, [&](const StepField& f) { return present(f.history, kind); });
}

std::vector<std::string> exodusGlobalNames(const RunKind& kind) {
  return namesWhere([&](const StepField& f) { return present(f.exodus, kind); });
}

std::vector<double> exodusGlobals(const StepRecord& record, const RunKind& kind) {
  return valuesWhere(record, [&](const StepField& f) { return present(f.exodus, kind); });
}

std::vector<std::string> checkpointFieldNames() {
  return namesWhere([](const StepField& f) { return f.set != nullptr; });
}

std::vector<double> packStepRecords(const std::vector<StepRecord>& records) {
  std::vector<double> out;
  for (const StepRecord& r : records) {
    const auto values = valuesWhere(r, [](const StepField& f) { return f.set != nullptr; });
    out.insert(out.end(), values.begin(), values.end());
    out.push_back(double(r.residualHistory.size()));
    out.insert(out.end(), r.residualHistory.begin(), r.residualHistory.end());
  }
  return out;
}

std::vector<StepRecord> unpackStepRecords(const std::vector<double>& packed, const std::string& file) {
  std::vector<const StepField*> stored;
  for (const StepField& f : stepFields())
    if (f.set) stored.push_back(&f);
  const size_t fixed = stored.size() + 1;  // the fields and the residual count
  std::vector<StepRecord> records;
  size_t i = 0;
  while (i < packed.size()) {
    DDC_INPUT_REQUIRE(i + fixed <= packed.size(),
                      "checkpoint '" << file << "': history row " << records.size() + 1 << " is cut short");
    StepRecord r;
    for (size_t k = 0; k < stored.size(); ++k) stored[k]->set(r, packed[i + k]);
    const size_t n = size_t(packed[i + stored.size()]);
    i += fixed;
    DDC_INPUT_REQUIRE(n <= packed.size() - i,
                      "checkpoint '" << file << "': history row " << records.size() + 1 << " is cut short");
    r.residualHistory.assign(packed.begin() + long(i), packed.begin() + long(i + n));
    i += n;
    records.push_back(std::move(r));
  }
  return records;
}

}  // namespace ddc
