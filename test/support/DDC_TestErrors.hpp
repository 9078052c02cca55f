// Catching the error a piece of input handling or a solver throws, so a test
// can check its message (negative tests, doc/verification.md).
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <initializer_list>
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

/// Expect `f` to throw E whose message contains every string in `needles`
/// (a different exception type, or none, is a test failure).
template <class E, class Fn>
void expectThrowWith(Fn f, std::initializer_list<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "expected an exception";
  } catch (const E& e) {
    const std::string what = e.what();
    for (const auto& n : needles) EXPECT_NE(what.find(n), std::string::npos) << "'" << n << "' not in: " << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
}

}  // namespace ddc::test
