// Reading test/negative_cases.txt (DDC_NegativeCaseTable.hpp).
#include "DDC_NegativeCaseTable.hpp"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace ddc::test {

namespace {

const std::set<std::string> kStages = {"cli", "startup", "deck", "validation", "model", "run", "tool"};
// Keys only an application run can honour (the in-process check refuses them).
const std::set<std::string> kAppKeys = {"launcher", "env", "app", "mpmd"};

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

std::string substituted(std::string s, const Placeholders& placeholders) {
  for (const auto& [key, dir] : placeholders)
    for (auto at = s.find(key); at != std::string::npos; at = s.find(key, at + dir.size())) s.replace(at, key.size(), dir);
  return s;
}

/// One "key value" line into `c`.
void setField(NegativeCase& c, const std::string& key, const std::string& value, const Placeholders& placeholders) {
  if (key == "stage") {
    if (!kStages.count(value)) throw std::runtime_error("unknown stage '" + value + "'");
    c.stage = value;
  } else if (key == "ranks") {
    for (const auto& w : words(value)) c.ranks.push_back(std::stoi(w));
  } else if (key == "via") {
    c.via = words(value);
  } else if (key == "deck") {
    c.deck = substituted(value, placeholders);
  } else if (key == "set") {
    c.sets.push_back(substituted(value, placeholders));
  } else if (key == "arg") {
    c.args.push_back(substituted(value, placeholders));
  } else if (key == "regex") {
    c.regex = value;
  } else if (key == "fixture") {
    for (const auto& w : words(value)) c.fixtures.push_back(w);
  } else if (key == "labels") {
    for (const auto& w : words(value)) c.labels.push_back(w);
  } else if (kAppKeys.count(key)) {
    c.other.push_back(key);
  } else {
    throw std::runtime_error("unknown key '" + key + "'");
  }
}

/// The rules both readers rely on.
void check(const NegativeCase& c) {
  if (c.stage.empty() || c.ranks.empty() || c.regex.empty())
    throw std::runtime_error("case '" + c.id + "' needs a stage, ranks and a regex");
  if (c.inProcess() && (!c.args.empty() || !c.other.empty() || c.deck.empty()))
    throw std::runtime_error("case '" + c.id + "' is checked in process: it needs a deck and takes only set options");
}

}  // namespace

bool NegativeCase::inProcess() const {
  if (via.empty()) return stage == "deck" || stage == "validation";
  return std::find(via.begin(), via.end(), "in-process") != via.end();
}

bool NegativeCase::checkedOn(int n) const { return std::find(ranks.begin(), ranks.end(), n) != ranks.end(); }

std::vector<NegativeCase> readNegativeCases(const std::string& path, const Placeholders& placeholders) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the negative-case table '" + path + "'");
  std::vector<NegativeCase> cases;
  int lineNo = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNo;
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#') continue;
    const auto space = t.find_first_of(" \t");
    const std::string key = t.substr(0, space);
    const std::string value = space == std::string::npos ? "" : trimmed(t.substr(space));
    try {
      if (key == "case") {
        if (!cases.empty()) check(cases.back());
        cases.push_back(NegativeCase{});
        cases.back().id = value;
      } else if (cases.empty()) {
        throw std::runtime_error("'" + key + "' before the first 'case'");
      } else {
        setField(cases.back(), key, value, placeholders);
      }
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ":" + std::to_string(lineNo) + ": " + e.what());
    }
  }
  if (!cases.empty()) check(cases.back());
  return cases;
}

std::string ecmaScriptRegex(const std::string& cmakeRegex) {
  std::string out;
  bool inBracket = false;
  for (std::size_t i = 0; i < cmakeRegex.size(); ++i) {
    const char ch = cmakeRegex[i];
    if (ch == '\\' && i + 1 < cmakeRegex.size()) {
      out += cmakeRegex.substr(i++, 2);
    } else if (inBracket) {
      out += ch;
      if (ch == ']') inBracket = false;
    } else if (ch == '[') {
      out += ch;
      inBracket = true;
    } else if (ch == '.') {
      out += "[\\s\\S]";
    } else {
      out += ch;
    }
  }
  return out;
}

}  // namespace ddc::test
