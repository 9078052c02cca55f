#include "DDC_Restart.hpp"

#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <filesystem>
#include <sstream>

#include "DDC_Error.hpp"
#include "DDC_InputDeck.hpp"
#include "DDC_OutputDirectory.hpp"

namespace ddc {

namespace fs = std::filesystem;

RestartSource findRestartSource(Teuchos::RCP<const Teuchos::Comm<int>> comm, const std::string& dir) {
  RestartSource s;
  s.finalPath = OutputDirectory::normalisedPath(dir);
  // Rank 0 looks; every rank reads the same answer.
  std::string found;
  if (comm->getRank() == 0) {
    std::error_code ec;
    for (const std::string& d : {s.finalPath + ".partial", s.finalPath})
      if (fs::is_regular_file(fs::path(d) / kCheckpointFileName, ec)) {
        found = d;
        break;
      }
  }
  found = broadcastStrings(*comm, {found}).front();
  DDC_INPUT_REQUIRE(!found.empty(), "--restart '" << dir << "': no checkpoint in '" << s.finalPath << ".partial' or '"
                                                  << s.finalPath << "' (" << kCheckpointFileName
                                                  << "); the run writes one after every Output/Checkpoint Interval "
                                                     "converged steps, when it fails or is stopped, and at its end, "
                                                     "unless the interval is 0");
  s.directory = found;
  s.unfinished = found != s.finalPath;
  s.checkpoint = std::make_shared<CheckpointReader>(comm, (fs::path(found) / kCheckpointFileName).string());
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

}  // namespace ddc
