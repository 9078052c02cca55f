// Catching the error a piece of input handling throws, so a test can check
// its message (negative tests, doc/verification.md).
#pragma once

#include <functional>
#include <string>

#include "DDC_Error.hpp"

namespace ddc::test {

/// What inputErrorOf returns when nothing (or no ddc::InputError) was thrown.
inline const std::string kNoInputError = "(no InputError)";

/// The message of the ddc::InputError that `f` throws, or kNoInputError.
/// Any other exception propagates (and fails the test).
inline std::string inputErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ddc::InputError& e) {
    return e.what();
  }
  return kNoInputError;
}

}  // namespace ddc::test
