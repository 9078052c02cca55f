#include "DDC_InputDeck.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLObject.hpp>
#include <Teuchos_XMLParameterListReader.hpp>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include "DDC_Error.hpp"
#include "DDC_FileFingerprint.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_OutputDirectory.hpp"
#include "DDC_Parameters.hpp"

namespace fs = std::filesystem;

namespace ddc {

namespace {

/// Teuchos prefixes its messages with a source location and the failed test;
/// the last paragraph is the readable part ("XML parse error at line 4: ...").
std::string essence(const std::exception& e) {
  std::string what = e.what();
  while (!what.empty() && (what.back() == '\n' || what.back() == ' ')) what.pop_back();
  const auto cut = what.rfind("\n\n");
  if (cut != std::string::npos) what = what.substr(cut + 2);
  return what;
}

std::string invalidListPrefix(const std::string& fileName) {
  return "input file '" + fileName + "' is not a valid Teuchos XML parameter list: ";
}

/// Checks one <ParameterList> element and, recursively, its children
/// (the depth is at most kMaxDeckDepth here).
class DeckChecker {
 public:
  explicit DeckChecker(const std::string& fileName) : file_(fileName) {}

  void checkList(const Teuchos::XMLObject& list, const std::string& path, bool root) const {
    const std::string where = path.empty() ? std::string("the top-level list") : "sublist '" + path + "'";
    // What each name of this list is, to find a name given twice.
    std::map<std::string, std::string> seen;
    for (int i = 0; i < list.numChildren(); ++i) {
      const Teuchos::XMLObject& child = list.getChild(i);
      const std::string& tag = child.getTag();
      if (root && (tag == "Validators" || tag == "Dependencies")) continue;  // Teuchos reads these at the top
      const bool isList = tag == "ParameterList";
      DDC_INPUT_REQUIRE(isList || tag == "Parameter",
                        "input file '" << file_ << "': unexpected element <" << tag << "> in " << where
                                       << "; a parameter list holds <ParameterList> and <Parameter> elements");
      const std::string kind = isList ? "sublist" : "parameter";
      DDC_INPUT_REQUIRE(child.hasAttribute("name"),
                        "input file '" << file_ << "': a <" << tag << "> in " << where << " has no name attribute");
      const std::string& name = child.getRequired("name");
      const std::string childPath = joinPath(path, name);
      const auto [it, fresh] = seen.emplace(name, kind);
      DDC_INPUT_REQUIRE(fresh, "input file '" << file_ << "': '" << childPath << "' is given twice in " << where
                                              << " (as a " << it->second << " and as a " << kind
                                              << "); every name may appear once in a list");
      if (isList) {
        checkList(child, childPath, false);
      } else {
        checkParameter(child, childPath);
      }
    }
  }

 private:
  void checkParameter(const Teuchos::XMLObject& p, const std::string& path) const {
    const std::string what = "input file '" + file_ + "': parameter '" + path + "'";
    DDC_INPUT_REQUIRE(p.hasAttribute("type"), what << " has no type attribute (int, double, bool or string)");
    DDC_INPUT_REQUIRE(p.hasAttribute("value"), what << " has no value attribute");
    const std::string& type = p.getRequired("type");
    const auto& types = parsableTypes();
    DDC_INPUT_REQUIRE(std::find(types.begin(), types.end(), type) != types.end(),
                      what << " has type '" << type << "'; parameters have type int, double, bool or string");
    parseValue(type, p.getRequired("value"), what);  // throws with the text
  }

  std::string file_;
};

/// FNV-1a: a content fingerprint to compare a file between ranks.
std::uint64_t fingerprint(const std::string& bytes) { return fnv1a(bytes.data(), bytes.size()) ^ bytes.size(); }

/// Whole file, or false if it cannot be read as a regular file.
bool readWhole(const std::string& fileName, std::string& bytes) {
  std::error_code ec;
  if (!fs::is_regular_file(fileName, ec)) return false;
  std::ifstream in(fileName, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return false;
  bytes = ss.str();
  return true;
}

}  // namespace

ElementDepth maxElementDepth(const std::string& text, int limit) {
  ElementDepth deepest;
  const std::size_t n = text.size();
  std::size_t i = 0;
  int depth = 0;
  int line = 1;
  // Move i past the next `end` (or to the end of the text), counting lines.
  auto skipPast = [&](const char* end) {
    const std::size_t j = text.find(end, i);
    const std::size_t stop = j == std::string::npos ? n : j + std::strlen(end);
    line += static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(i),
                                        text.begin() + static_cast<std::ptrdiff_t>(stop), '\n'));
    i = stop;
  };
  auto startsWith = [&](const char* s) { return text.compare(i, std::strlen(s), s) == 0; };
  while (i < n) {
    const char c = text[i];
    if (c != '<') {
      if (c == '\n') ++line;
      ++i;
      continue;
    }
    if (startsWith("<!--")) {
      i += 4;
      skipPast("-->");
    } else if (startsWith("<![CDATA[")) {
      i += 9;
      skipPast("]]>");
    } else if (startsWith("<?")) {
      i += 2;
      skipPast("?>");
    } else if (startsWith("<!")) {  // <!DOCTYPE ...>
      i += 2;
      skipPast(">");
    } else if (startsWith("</")) {
      i += 2;
      skipPast(">");
      if (depth > 0) --depth;
    } else {
      // A start tag: up to the '>' outside quoted attribute values.
      const int tagLine = line;
      ++i;
      char quote = 0;
      bool selfClosing = false;
      while (i < n) {
        const char d = text[i++];
        if (d == '\n') ++line;
        if (quote) {
          if (d == quote) quote = 0;
        } else if (d == '"' || d == '\'') {
          quote = d;
        } else if (d == '>') {
          selfClosing = text[i - 2] == '/';
          break;
        }
      }
      const int level = depth + 1;
      if (level > deepest.depth) {
        deepest = {level, tagLine};
        if (level > limit) return deepest;
      }
      if (!selfClosing) depth = level;
    }
  }
  return deepest;
}

/// A deck must be UTF-8 (or ASCII): a UTF-16 or UTF-32 file (as some
/// Windows editors save one) is named as such instead of failing in the XML
/// parser on its NUL bytes. A UTF-8 byte-order mark is skipped.
static std::string utf8Text(const std::string& text, const std::string& fileName) {
  const auto starts = [&](const char* bom, std::size_t n) { return text.compare(0, n, bom, n) == 0; };
  if (starts("\xEF\xBB\xBF", 3)) return text.substr(3);
  const char* encoding = nullptr;
  if (starts("\x00\x00\xFE\xFF", 4) || starts("\xFF\xFE\x00\x00", 4))
    encoding = "UTF-32";
  else if (starts("\xFE\xFF", 2) || starts("\xFF\xFE", 2))
    encoding = "UTF-16";
  else if (text.find('\0') != std::string::npos)
    encoding = "not UTF-8 (it contains NUL bytes; UTF-16 without a byte-order mark?)";
  DDC_INPUT_REQUIRE(encoding == nullptr, "input file '" << fileName << "' is " << encoding
                                                        << "; a deck must be UTF-8 (or ASCII): save it as UTF-8");
  return text;
}

Teuchos::RCP<Teuchos::ParameterList> parseDeck(const std::string& rawText, const std::string& fileName) {
  const std::string text = utf8Text(rawText, fileName);
  const ElementDepth d = maxElementDepth(text, kMaxDeckDepth);
  DDC_INPUT_REQUIRE(d.depth <= kMaxDeckDepth,
                    "input file '" << fileName << "': elements nest more than " << kMaxDeckDepth
                                   << " levels deep (line " << d.line << "); a deck may nest at most "
                                   << kMaxDeckDepth << " levels");
  Teuchos::XMLObject xml;
  try {
    xml = Teuchos::StringInputSource(text).getObject();
  } catch (const std::exception& e) {
    DDC_THROW(InputError, invalidListPrefix(fileName) << essence(e));
  }
  DDC_INPUT_REQUIRE(!xml.isEmpty(), invalidListPrefix(fileName) << "it contains no XML element");
  DDC_INPUT_REQUIRE(xml.getTag() == "ParameterList",
                    invalidListPrefix(fileName) << "the root element is <" << xml.getTag()
                                                << ">, expected <ParameterList>");
  DeckChecker(fileName).checkList(xml, "", true);
  try {
    return Teuchos::rcp(new Teuchos::ParameterList(Teuchos::XMLParameterListReader().toParameterList(xml)));
  } catch (const std::exception& e) {
    // E.g. a <Validators> section Teuchos cannot convert.
    DDC_THROW(InputError, invalidListPrefix(fileName) << essence(e));
  }
}

std::string readDeckFile(const std::string& fileName) {
  DDC_INPUT_REQUIRE(!fileName.empty(), "input file name is empty");
  std::error_code ec;
  const fs::file_status st = fs::status(fileName, ec);
  DDC_INPUT_REQUIRE(fs::exists(st), "input file '" << fileName << "' does not exist");
  DDC_INPUT_REQUIRE(!fs::is_directory(st),
                    "input file '" << fileName << "' is a directory, expected a Teuchos XML parameter file");
  DDC_INPUT_REQUIRE(fs::is_regular_file(st), "input file '" << fileName
                                                            << "' is not a regular file, expected a Teuchos XML "
                                                               "parameter file");
  const auto size = fs::file_size(fileName, ec);
  DDC_INPUT_REQUIRE(!ec, "input file '" << fileName << "' cannot be read: " << ec.message());
  DDC_INPUT_REQUIRE(size <= kMaxDeckBytes, "input file '" << fileName << "' has " << size
                                                          << " bytes; a deck may have at most " << kMaxDeckBytes);
  std::ifstream in(fileName, std::ios::binary);
  DDC_INPUT_REQUIRE(in, "input file '" << fileName << "' cannot be read: " << std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  DDC_INPUT_REQUIRE(!in.bad(), "input file '" << fileName << "' cannot be read");
  return ss.str();
}

Teuchos::RCP<Teuchos::ParameterList> readDeck(const Teuchos::Comm<int>& comm, const std::string& fileName) {
  const bool root = comm.getRank() == 0;
  std::string text, error;
  Teuchos::RCP<Teuchos::ParameterList> params;
  if (root) {
    try {
      text = readDeckFile(fileName);
      params = parseDeck(text, fileName);
    } catch (const InputError& e) {
      error = e.what();
    } catch (const std::exception& e) {
      error = invalidListPrefix(fileName) + essence(e);
    }
  }
  error = firstErrorOnAnyRank(comm, error);
  if (!error.empty()) throw InputError(error);
  text = broadcastStrings(comm, {text}).front();
  // The text passed parseDeck() on rank 0, so it passes here too.
  if (!root) params = parseDeck(text, fileName);
  return params;
}

std::vector<std::string> broadcastStrings(const Teuchos::Comm<int>& comm, const std::vector<std::string>& strings) {
  const bool root = comm.getRank() == 0;
  // Lengths first (the count leads), then all bytes in one message.
  std::vector<long long> lengths;
  if (root)
    for (const auto& s : strings) lengths.push_back(static_cast<long long>(s.size()));
  int count = static_cast<int>(lengths.size());
  Teuchos::broadcast<int, int>(comm, 0, Teuchos::outArg(count));
  lengths.resize(count);
  if (count > 0) Teuchos::broadcast<int, long long>(comm, 0, count, lengths.data());
  long long total = 0;
  for (const long long l : lengths) total += l;
  DDC_INPUT_REQUIRE(total <= static_cast<long long>(INT_MAX), "broadcastStrings: " << total << " bytes are too many");
  std::string bytes;
  if (root)
    for (const auto& s : strings) bytes += s;
  bytes.resize(static_cast<std::size_t>(total));
  if (total > 0) Teuchos::broadcast<int, char>(comm, 0, static_cast<int>(total), &bytes[0]);
  std::vector<std::string> out;
  std::size_t at = 0;
  for (const long long l : lengths) {
    out.push_back(bytes.substr(at, static_cast<std::size_t>(l)));
    at += static_cast<std::size_t>(l);
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> namedInputFiles(const Teuchos::ParameterList& params,
                                                                 const std::string& baseDirectory) {
  std::vector<std::pair<std::string, std::string>> files;
  auto stringAt = [](const Teuchos::ParameterList& pl, const std::string& name) -> std::string {
    return pl.isType<std::string>(name) ? pl.get<std::string>(name) : std::string();
  };
  if (params.isSublist("Mesh") && params.sublist("Mesh").isSublist("Bodies")) {
    const auto& bodies = params.sublist("Mesh").sublist("Bodies");
    for (auto it = bodies.begin(); it != bodies.end(); ++it) {
      const std::string& body = bodies.name(it);
      // Mesh files: Gmsh and Exodus II bodies.
      if (!bodies.isSublist(body)) continue;
      const std::string gen = stringAt(bodies.sublist(body), "Generator");
      if ((gen != "Gmsh" && gen != "Exodus") || !bodies.sublist(body).isSublist(gen)) continue;
      const std::string file = stringAt(bodies.sublist(body).sublist(gen), "File");
      if (file.empty()) continue;
      // As readGmshBody() / readExodusBody() resolve it.
      files.emplace_back("Mesh/Bodies/" + body + "/" + gen + "/File", resolveDeckFile(file, baseDirectory));
    }
  }
  if (params.isSublist("Partition")) {
    const auto& part = params.sublist("Partition");
    const std::string file = stringAt(part, "Element Map File");
    if (stringAt(part, "Method") == "Element Map File" && !file.empty())
      // As the Analysis constructor resolves it.
      files.emplace_back("Partition/Element Map File", resolveDeckFile(file, baseDirectory));
  }
  return files;
}

std::vector<InputFileIdentity> requireSameFilesOnEveryRank(
    const Teuchos::Comm<int>& comm, const std::vector<std::pair<std::string, std::string>>& files) {
  std::vector<InputFileIdentity> identities;
  const int size = comm.getSize();
  const int rank = comm.getRank();
  // The file list is the same on every rank (it comes from the parameters).
  for (const auto& [param, file] : files) {
    // A directory is not an unreadable file: say what it is (the readers
    // saw an empty file).
    std::error_code ec;
    const int directory = fs::is_directory(file, ec) ? 1 : 0;
    int directories = 0;
    Teuchos::reduceAll<int, int>(comm, Teuchos::REDUCE_SUM, directory, Teuchos::outArg(directories));
    DDC_INPUT_REQUIRE(directories == 0, "'" << param << "' = '" << file << "' is a directory, expected a file");
    std::string bytes;
    const int readable = readWhole(file, bytes) ? 1 : 0;
    int readers = 0;
    Teuchos::reduceAll<int, int>(comm, Teuchos::REDUCE_SUM, readable, Teuchos::outArg(readers));
    if (readers == 0) continue;  // the reader's own message, the same on every rank
    if (readers < size) {
      int firstMissing = readable ? size : rank;
      int first = size;
      Teuchos::reduceAll<int, int>(comm, Teuchos::REDUCE_MIN, firstMissing, Teuchos::outArg(first));
      DDC_THROW(InputError, "'" << param << "' = '" << file << "': the file can be read on " << readers << " of "
                                << size << " ranks but not on rank " << first
                                << "; every rank reads it, so it must be on a file system all ranks share");
    }
    // Same contents everywhere: compare fingerprints (min and max over ranks).
    const std::uint64_t mine = fingerprint(bytes);
    std::uint64_t lo = 0, hi = 0;
    const MPI_Comm raw = rawComm(Teuchos::rcpFromRef(comm));
    MPI_Allreduce(&mine, &lo, 1, MPI_UINT64_T, MPI_MIN, raw);
    MPI_Allreduce(&mine, &hi, 1, MPI_UINT64_T, MPI_MAX, raw);
    DDC_INPUT_REQUIRE(lo == hi, "'" << param << "' = '" << file
                                    << "': the file differs between ranks; every rank reads it, so all must see "
                                       "the same file (a shared file system)");
    identities.push_back({param, file, std::uint64_t(bytes.size()), mine});
  }
  return identities;
}

}  // namespace ddc
