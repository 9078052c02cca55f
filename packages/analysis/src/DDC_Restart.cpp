#include "DDC_Restart.hpp"

#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_RunCheckpoint.hpp"

namespace ddc {

namespace fs = std::filesystem;

namespace {

/// Why `given` (as --restart names it, normalised to `final`) is not the
/// output directory of a run, or "": a file (the checkpoint itself) or a
/// staging directory ("D.partial") names the wrong thing.
std::string notAnOutputDirectory(const std::string& given, const std::string& final) {
  std::error_code ec;
  const std::string suffix = ".partial";
  if (fs::is_regular_file(final, ec)) {
    const fs::path parent = fs::path(final).parent_path();
    std::string d = parent.string();
    if (d.size() > suffix.size() && d.compare(d.size() - suffix.size(), suffix.size(), suffix) == 0)
      d.resize(d.size() - suffix.size());
    return "--restart '" + given + "' names a file; name the output directory of the run to continue instead " +
           "(for '" + final + "' that is --restart '" + d + "')";
  }
  // A staging directory: named "*.partial", its manifest not complete (a
  // finished run's output directory may be named so too).
  std::ifstream manifest(fs::path(final) / OutputDirectory::manifestFileName());
  const std::string text((std::istreambuf_iterator<char>(manifest)), std::istreambuf_iterator<char>());
  if (final.size() > suffix.size() && final.compare(final.size() - suffix.size(), suffix.size(), suffix) == 0 &&
      fs::is_directory(final, ec) && text.find("\nstatus: complete\n") == std::string::npos)
    return "--restart '" + given + "' names the staging directory of a run; name the run's output directory " +
           "instead: --restart '" + final.substr(0, final.size() - suffix.size()) + "'";
  return "";
}

/// Where the checkpoint of the run with output directory `final` is (rank
/// 0): D.partial's (the run did not finish) else D's; "" with `error` set
/// when there is none to take (see findRestartSource()).
std::string locateCheckpoint(const std::string& given, const std::string& final, std::string& error) {
  std::error_code ec;
  const std::string staging = final + ".partial";
  for (const std::string& d : {staging, final}) {
    const fs::path p = fs::path(d) / kCheckpointFileName;
    if (!fs::exists(fs::symlink_status(p, ec))) continue;
    if (!fs::is_regular_file(fs::status(p, ec))) {
      error = "--restart '" + given + "': '" + p.string() + "' is not a regular file (" +
              (fs::is_directory(fs::status(p, ec)) ? "a directory"
                                                   : "a link to a device, a missing file or a special file") +
              "), so it is no checkpoint; move it away, or name another run";
      return "";
    }
    if (d == final && fs::is_directory(staging, ec)) {
      error = "--restart '" + given + "': the run that did not finish in '" + staging + "' left no checkpoint (" +
              kCheckpointFileName + "), and '" + p.string() + "' belongs to the earlier, finished run committed in '" +
              final + "', not to it; to continue the finished run, move '" + staging + "' away first; to redo the " +
              "unfinished one, start it anew without --restart";
      return "";
    }
    return d;
  }
  error = "--restart '" + given + "': no checkpoint in '" + staging + "' or '" + final + "' (" + kCheckpointFileName +
          "); the run writes one after every Output/Checkpoint Interval converged steps, when it fails or is "
          "stopped, and at its end, unless the interval is 0";
  return "";
}

}  // namespace

RestartSource findRestartSource(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& dir) {
  RestartSource s;
  s.finalPath = OutputDirectory::normalisedPath(dir);
  // Rank 0 looks; every rank reads the same answer.
  std::string found, error;
  if (comm->getRank() == 0) {
    error = notAnOutputDirectory(dir, s.finalPath);
    if (error.empty()) found = locateCheckpoint(dir, s.finalPath, error);
  }
  const auto answer = broadcastStrings(*comm, {found, error});
  DDC_INPUT_REQUIRE(answer[1].empty(), answer[1]);
  s.directory = answer[0];
  s.unfinished = s.directory != s.finalPath;
  s.checkpoint = std::make_shared<CheckpointReader>(comm, (fs::path(s.directory) / kCheckpointFileName).string());
  // Another layout is refused before the output directory is opened.
  requireCheckpointLayout(*s.checkpoint);
  return s;
}

const std::vector<std::string>& restartChangeableParameters() {
  static const std::vector<std::string> paths = {
      "Load Stepping/", "Step Control/", "Dynamics/Final Time", "Dynamics/Time Step", "Dynamics/Max Bisections",
      "Newton/",        "Solver/",       "Partition/",          "Output/"};
  return paths;
}

namespace {

bool changeable(const std::string& path) {
  for (const std::string& p : restartChangeableParameters())
    if (p.back() == '/' ? path.compare(0, p.size(), p) == 0 : path == p) return true;
  return false;
}

/// The list as the checkpoint holds it: written to XML and read back, so
/// that both sides of the comparison are printed and parsed alike.
Teuchos::RCP<Teuchos::ParameterList> roundTrip(const Teuchos::ParameterList& list) {
  std::ostringstream xml;
  Teuchos::writeParameterListToXmlOStream(list, xml);
  return Teuchos::getParametersFromXmlString(xml.str());
}

/// The first path below `prefix` where a and b differ outside the
/// changeable parameters; fills the two values ("(none)" when absent).
bool firstDifference(const Teuchos::ParameterList& a, const Teuchos::ParameterList& b, const std::string& prefix,
                     std::string& path, std::string& va, std::string& vb) {
  auto describe = [](const Teuchos::ParameterList& l, const std::string& name) -> std::string {
    if (!l.isParameter(name)) return "(none)";
    if (l.isSublist(name)) return "a sublist";
    std::ostringstream os;
    os.precision(15);
    os << l.getEntry(name).getAny(false);
    return "'" + echoed(os.str()) + "'";
  };
  auto compare = [&](const Teuchos::ParameterList& x, const Teuchos::ParameterList& y, const std::string& name) {
    const std::string p = prefix + name;
    if (x.isSublist(name) && y.isSublist(name)) {
      if (changeable(p + "/")) return false;
      return firstDifference(x.sublist(name), y.sublist(name), p + "/", path, va, vb);
    }
    if (changeable(p)) return false;
    const bool same = x.isParameter(name) && y.isParameter(name) && !x.isSublist(name) && !y.isSublist(name) &&
                      x.getEntry(name).getAny(false) == y.getEntry(name).getAny(false);
    if (same) return false;
    path = p;
    va = describe(a, name);
    vb = describe(b, name);
    return true;
  };
  for (auto it = a.begin(); it != a.end(); ++it)
    if (compare(a, b, a.name(it))) return true;
  for (auto it = b.begin(); it != b.end(); ++it)
    if (!a.isParameter(b.name(it)) && compare(b, a, b.name(it))) return true;
  return false;
}

}  // namespace

void checkRestartParameters(const Teuchos::ParameterList& saved, const Teuchos::ParameterList& now,
                            const std::string& checkpointPath) {
  std::string path, before, after;
  if (!firstDifference(*roundTrip(saved), *roundTrip(now), "", path, before, after)) return;
  std::ostringstream what;
  for (const std::string& p : restartChangeableParameters())
    what << (what.tellp() > 0 ? ", " : "") << (p.back() == '/' ? p.substr(0, p.size() - 1) : p);
  throw InputError("restart: parameter '" + path + "' is " + after + " in this deck but was " + before +
                   " in the run that wrote the checkpoint '" + checkpointPath +
                   "'; a restart continues that run, so it may change only " + what.str() +
                   " (doc/user-guide.md, 'Checkpoints and restart')");
}

std::string describeInputFiles(const std::vector<InputFileIdentity>& files) {
  std::ostringstream os;
  for (const auto& f : files) os << f.size << ' ' << f.hash << ' ' << f.parameter << '\t' << f.file << '\n';
  return os.str();
}

void checkRestartInputFiles(const std::string& saved, const std::vector<InputFileIdentity>& now,
                            const std::string& checkpointPath) {
  std::istringstream lines(saved);
  std::vector<InputFileIdentity> before;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream is(line);
    InputFileIdentity f;
    is >> f.size >> f.hash >> std::ws;
    std::getline(is, f.parameter, '\t');
    std::getline(is, f.file);
    before.push_back(f);
  }
  for (const auto& f : now)
    for (const auto& b : before) {
      if (b.parameter != f.parameter || (b.size == f.size && b.hash == f.hash)) continue;
      throw InputError("restart: the file '" + f.file + "' ('" + f.parameter + "') changed since the run that "
                       "wrote the checkpoint '" + checkpointPath + "' read it (then " + std::to_string(b.size) +
                       " bytes, now " + std::to_string(f.size) + " bytes" +
                       (b.size == f.size ? " with other content" : "") +
                       "); a restart continues that run's displacements on its mesh, so its mesh and element-map "
                       "files must be unchanged: restore the file, or start the run anew without --restart "
                       "(doc/user-guide.md, 'Checkpoints and restart')");
    }
}

void checkRestartFinalValue(const StepRecord& last, const StepLoopSettings& settings,
                            const std::string& checkpointPath) {
  // Beyond the final value by more than round-off (the step sizes are
  // fractions of it; the step controllers count a step end within 1e-14
  // of it as reached, DDC_StepController.cpp).
  constexpr double kRoundOff = 1e-12;
  if (last.loadFactor - settings.finalValue <= kRoundOff * std::abs(settings.finalValue)) return;
  const std::string parameter =
      settings.stepping + (settings.stepping == "Dynamics" ? "/Final Time" : "/Final Load Factor");
  std::ostringstream os;
  os.precision(15);
  os << "restart: '" << parameter << "' = " << settings.finalValue << " lies below the " << settings.factorName << " "
     << last.loadFactor << " the checkpoint '" << checkpointPath << "' reached (step " << last.step
     << "); the result would end beyond the value asked for: set '" << parameter << "' to at least "
     << last.loadFactor << ", or start the run anew without --restart";
  throw InputError(os.str());
}

}  // namespace ddc
