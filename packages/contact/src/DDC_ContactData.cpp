// Checkpoint form of the contact slots, and slot lists (see DDC_ContactData.hpp).
#include "DDC_ContactData.hpp"

#include <numeric>
#include <stdexcept>
#include <string>

namespace ddc {

namespace {
/// Numbers per slot in packSlots().
constexpr size_t kPackedSlot = 48;
}  // namespace

size_t packedSlotSize() { return kPackedSlot; }

std::vector<int> slotIndices(size_t count) {
  std::vector<int> out(count);
  std::iota(out.begin(), out.end(), 0);
  return out;
}

std::vector<double> packSlots(const std::vector<ContactSlot>& slots) {
  std::vector<double> out;
  out.reserve(slots.size() * kPackedSlot);
  for (const ContactSlot& s : slots) {
    out.insert(out.end(), {double(s.pair), double(s.slaveNode)});
    for (int m : s.master) out.push_back(m);
    out.insert(out.end(), {double(s.numMaster), double(s.segment), double(s.masterElement), double(s.active),
                           double(s.state.active), s.state.multiplier, s.state.frozenXi, s.state.frozenNormal.x(),
                           s.state.frozenNormal.y(), s.frozen.xi[0], s.frozen.xi[1], s.frozen.normal.x(),
                           s.frozen.normal.y(), s.frozen.normal.z(), s.gap, s.normal.x(), s.normal.y(), s.normal.z(),
                           s.tributaryLength});
    // Coulomb friction: the bases, the tangential multipliers, the state and the slip.
    for (const auto* basis : {&s.tangent, &s.frozen.tangent})
      for (const Eigen::Vector3d& t : *basis) out.insert(out.end(), {t.x(), t.y(), t.z()});
    out.insert(out.end(), {s.tangential[0], s.tangential[1], double(int(s.friction)), s.tangentialSlip[0],
                           s.tangentialSlip[1], s.slip});
  }
  return out;
}

std::vector<ContactSlot> unpackSlots(const std::vector<double>& packed) {
  if (packed.size() % kPackedSlot != 0)
    throw std::invalid_argument("unpackSlots: " + std::to_string(packed.size()) + " numbers are not whole slots of " +
                                std::to_string(kPackedSlot));
  std::vector<ContactSlot> slots(packed.size() / kPackedSlot);
  const double* p = packed.data();
  for (ContactSlot& s : slots) {
    s.pair = int(*p++);
    s.slaveNode = int(*p++);
    for (int& m : s.master) m = int(*p++);
    s.numMaster = int(*p++);
    s.segment = int(*p++);
    s.masterElement = int(*p++);
    s.active = *p++ != 0.0;
    s.state.active = *p++ != 0.0;
    s.state.multiplier = *p++;
    s.state.frozenXi = *p++;
    s.state.frozenNormal.x() = *p++;
    s.state.frozenNormal.y() = *p++;
    s.frozen.xi[0] = *p++;
    s.frozen.xi[1] = *p++;
    for (int c = 0; c < 3; ++c) s.frozen.normal(c) = *p++;
    s.gap = *p++;
    for (int c = 0; c < 3; ++c) s.normal(c) = *p++;
    s.tributaryLength = *p++;
    for (auto* basis : {&s.tangent, &s.frozen.tangent})
      for (Eigen::Vector3d& t : *basis)
        for (int c = 0; c < 3; ++c) t(c) = *p++;
    s.tangential[0] = *p++;
    s.tangential[1] = *p++;
    s.friction = FrictionState(int(*p++));
    s.tangentialSlip[0] = *p++;
    s.tangentialSlip[1] = *p++;
    s.slip = *p++;
  }
  return slots;
}

}  // namespace ddc
