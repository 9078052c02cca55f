// Error handling for DDContact.
//
// Two levels, as in deal.II / MFEM: user input and run-time failures throw an
// exception that carries full context; internal invariants use DDC_CHECK,
// which throws std::logic_error. Both are on in every build type.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace ddc {

/// A user-given text as a message repeats it: at most kMaxEchoed characters
/// (the start, then how many more there are), so that a 1 MB value in a deck
/// is not printed back in full.
constexpr std::size_t kMaxEchoed = 200;
inline std::string echoed(const std::string& text) {
  if (text.size() <= kMaxEchoed) return text;
  return text.substr(0, kMaxEchoed) + "... (" + std::to_string(text.size()) + " characters)";
}

/// Bad user input: malformed XML, unknown names, misspelt parameters, missing
/// or inconsistent meshes, impossible combinations. The message names the
/// file / parameter path / mesh entity and what was expected.
class InputError : public std::runtime_error {
 public:
  /// \param what the complete message (what() returns it)
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// A run-time failure of the analysis that is not the user's input: Newton
/// or active-set non-convergence after all bisections, a failed factorisation.
class SolverError : public std::runtime_error {
 public:
  /// \param what the complete message (what() returns it)
  explicit SolverError(const std::string& what) : std::runtime_error(what) {}
};

/// The results could not be written: a full disk, a failed write, sync or
/// close, a permission problem, a directory in use by another run or holding
/// files DDContact did not write. The message names the path and the
/// operating system's reason. Earlier results are never touched by the
/// failure (doc/user-guide.md, "The output directory").
class OutputError : public std::runtime_error {
 public:
  /// \param what the complete message (what() returns it)
  explicit OutputError(const std::string& what) : std::runtime_error(what) {}
};

/// The run stopped on request (a signal, requestStop()) at the end of a
/// converged step, after writing its checkpoint; not a failure of the input,
/// the solver or the output.
class RunInterrupted : public std::runtime_error {
 public:
  /// \param what the complete message (what() returns it)
  /// \param signal the signal the stop was requested with (e.g. SIGTERM)
  RunInterrupted(const std::string& what, int signal) : std::runtime_error(what), signal_(signal) {}
  /// The signal the stop was requested with.
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// "'a', 'b', 'c'": the names quoted and comma separated, or `none` when there
/// are none; how error messages list the valid choices.
template <class Names>
std::string quotedNames(const Names& names, const char* none = "(none)") {
  std::ostringstream os;
  bool first = true;
  for (const auto& n : names) {
    os << (first ? "'" : ", '") << n << "'";
    first = false;
  }
  if (first) os << none;
  return os.str();
}

/// The last non-empty line of a Trilinos exception's message: Teuchos'
/// TEUCHOS_TEST_FOR_EXCEPTION puts the file, line and failed test before it.
inline std::string lastLineOf(const std::exception& e) {
  std::string m = e.what();
  while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
  const auto nl = m.rfind('\n');
  return nl == std::string::npos ? m : m.substr(nl + 1);
}

}  // namespace ddc

/// Throw ddc::InputError with a streamed message if `cond` is false.
/// Example: DDC_INPUT_REQUIRE(n > 0, "Load Stepping/Number of Steps must be > 0, got " << n);
#define DDC_INPUT_REQUIRE(cond, msg)                       \
  do {                                                     \
    if (!(cond)) {                                         \
      std::ostringstream ddc_oss_;                         \
      ddc_oss_ << msg;                                     \
      throw ::ddc::InputError(ddc_oss_.str());             \
    }                                                      \
  } while (0)

/// Throw an exception of type `Type` with a streamed message.
#define DDC_THROW(Type, msg)                               \
  do {                                                     \
    std::ostringstream ddc_oss_;                           \
    ddc_oss_ << msg;                                       \
    throw Type(ddc_oss_.str());                            \
  } while (0)

/// Throw std::logic_error ("internal error at FILE:LINE: check 'cond'
/// failed: msg") if `cond` is false. Always on, in every build type: it
/// guards what must hold before an index or a dereference, where a wrong
/// value would otherwise read or write out of bounds. Input is checked by
/// DDC_INPUT_REQUIRE, with a message for the user.
#define DDC_CHECK(cond, msg)                                                      \
  do {                                                                            \
    if (!(cond)) {                                                                \
      std::ostringstream ddc_oss_;                                                \
      ddc_oss_ << "internal error at " << __FILE__ << ":" << __LINE__ << ": check '" \
               << #cond << "' failed: " << msg;                                    \
      throw std::logic_error(ddc_oss_.str());                                     \
    }                                                                             \
  } while (0)
