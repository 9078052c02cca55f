// ddcontact-figure4: the strain-energy error study of Fang & Izzuddin (2022),
// Figure 4, from ddcontact history.csv files (doc/figure4.md).
//
//   ddcontact-figure4 --reference REF/history.csv --run LABEL=DIR/history.csv ...
//                     [--csv figure4.csv] [--check] [--check-floor F]
//                     [--decomposed LABEL]... [--monolithic20 LABEL]
//                     [--adaptive-run LABEL=DIR/history.csv ...] [--max-error E]
//                     [--max-peak-error P] [--max-exchanges N]
//
// For every run it takes the rows at nominal step ends, looks up the
// reference strain energy at the same load factor (tolerance 1e-9) and
// reports e(λ) = |U − U_ref| / U_ref where U_ref > 1e-8 · max U_ref. It prints
// a summary table (errors, Newton / dual iterations, contact exchanges,
// bisections, wall time), the errors by loading phase and the ratio
// max e(finest decomposed run) / max e(20-step monolithic run); --csv writes
// the reported points in long format; --check asserts the paper's findings.
//
// Exit status: 0 success, 1 a --check assertion failed, 2 bad input (unknown
// option, missing / empty / malformed file, missing column, a load factor
// the reference does not have).
//
// Plain C++17, no Trilinos: it only reads CSV files.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const char* kUsage =
    "usage: ddcontact-figure4 --reference REF/history.csv --run LABEL=DIR/history.csv [--run ...]\n"
    "                         [--csv FILE] [--check] [--check-floor F]\n"
    "                         [--decomposed LABEL]... [--monolithic20 LABEL]\n"
    "                         [--adaptive-run LABEL=FILE]... [--max-error E] [--max-peak-error P]\n"
    "                         [--max-exchanges N]\n"
    "\n"
    "Strain-energy error of ddcontact runs against a reference run (Fang & Izzuddin 2022,\n"
    "Figure 4; doc/figure4.md).\n"
    "\n"
    "  --reference FILE      history.csv of the reference (the 100-step monolithic run); it must\n"
    "                        have a row at every load factor the runs stop at (tolerance 1e-9)\n"
    "  --run LABEL=FILE      a run to compare (repeatable); LABEL is free text without ',' or '\"'\n"
    "  --csv FILE            write the reported points, long format:\n"
    "                        run,load_factor,strain_energy,reference_energy,relative_error\n"
    "  --check               assert the paper's findings (exit 1 on failure):\n"
    "                        (a) max error falls with the step count over the decomposed runs;\n"
    "                        (c) no accumulation: in every decomposed run the strain energy\n"
    "                            off contact (U_ref <= 1e-8 max U_ref, after release) is <= 1e-8\n"
    "                            max U_ref; every run must reach the reference's final load factor;\n"
    "                        (b) in every decomposed run the max error for load factor > 0.75 is\n"
    "                            not above the peak for 0.25 < load factor <= 0.75: printed, and\n"
    "                            asserted only with --assert-phases (doc/figure4.md says why)\n"
    "  --assert-phases       make (b) part of --check\n"
    "  --check-floor F       --check (and the phase table) consider only points with\n"
    "                        U_ref > F * max U_ref (default 1e-8, the reporting threshold)\n"
    "  --decomposed LABEL    a decomposed run for --check (repeatable; ordered by step count);\n"
    "                        default: those of the labels decomposed-20, decomposed-50,\n"
    "                        decomposed-100 that are given\n"
    "  --monolithic20 LABEL  the 20-step monolithic run for the error ratio (default: monolithic-20)\n"
    "  --adaptive-run LABEL=FILE  a run with Step Control (repeatable): every row is a step end,\n"
    "                        and where the reference has no row at its load factor, U_ref is the\n"
    "                        cubic through the four nearest reference rows (its error, estimated\n"
    "                        from every other reference row, is printed)\n"
    "  --max-error E         assert (exit 1) that every adaptive run's max error above the check\n"
    "                        floor is <= E\n"
    "  --max-peak-error P    assert that every adaptive run's peak strain energy is within P\n"
    "                        (relative) of the reference's\n"
    "  --max-exchanges N     assert that every adaptive run made fewer than N contact exchanges\n"
    "  --help                print this text\n"
    "\n"
    "Nominal step ends: history.csv has one row per converged step and per sub-step after\n"
    "bisection; the end of step s is its row with load_factor = s * (load factor of the end of\n"
    "step 1) to 1e-12. Rows of step 0, if any, are ignored. Errors e = |U - U_ref| / U_ref are\n"
    "reported where U_ref > 1e-8 * max U_ref (max over all reference rows).\n"
    "\n"
    "Exit status: 0 success, 1 --check failed, 2 bad input.\n";

const double kMatchTol = 1e-9;        // load factor lookup in the reference
const double kNominalTol = 1e-12;     // nominal step end: load_factor = s * delta
const double kReportThreshold = 1e-8; // report e where U_ref > 1e-8 max U_ref (doc/figure4.md)

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

#define FIG4_INPUT_ERROR(msg)            \
  do {                                   \
    std::ostringstream os_;              \
    os_ << msg;                          \
    throw InputError(os_.str());         \
  } while (0)

struct Row {
  long step = 0;
  double lf = 0, U = 0, wall = 0;
  double newton = 0, dual = 0, exchanges = 0;
  long bisections = 0;
  long rejected = 0, corrections = 0;  // Step Control columns (0 when absent)
  double indicator = -1;               // geometry_error (-1 when absent)
  size_t line = 0;
};

struct History {
  std::string label, file;
  std::vector<Row> rows;
  std::vector<size_t> nominal;  // indices into rows: nominal step ends, in order
  bool hasBisections = false;
  bool adaptive = false;  // --adaptive-run: every row is a step end
  bool complete = true;  // the last step in the file reached its nominal end
  long stoppedInStep = 0;
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::stringstream ss(line);
  while (std::getline(ss, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

double toDouble(const std::string& s, const std::string& file, size_t line, const std::string& col) {
  const char* b = s.c_str();
  char* e = nullptr;
  errno = 0;
  const double v = std::strtod(b, &e);
  if (s.empty() || e == b || *e != '\0' || errno == ERANGE)
    FIG4_INPUT_ERROR(file << ":" << line << ": column '" << col << "': cannot read '" << s << "' as a number");
  return v;
}

long toLong(const std::string& s, const std::string& file, size_t line, const std::string& col) {
  const double v = toDouble(s, file, line, col);
  if (!std::isfinite(v) || v != std::floor(v))
    FIG4_INPUT_ERROR(file << ":" << line << ": column '" << col << "': expected an integer, got '" << s << "'");
  return static_cast<long>(v);
}

History readHistory(const std::string& label, const std::string& file, bool adaptive = false) {
  History h;
  h.label = label;
  h.adaptive = adaptive;
  h.file = file;
  std::ifstream in(file);
  if (!in) FIG4_INPUT_ERROR(file << ": cannot open file" << (label.empty() ? "" : " (run '" + label + "')"));
  std::string line;
  size_t lineNo = 0;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    ++lineNo;
    if (!trim(line).empty()) {
      header = splitCsv(line);
      break;
    }
  }
  if (header.empty()) FIG4_INPUT_ERROR(file << ": empty file (expected a history.csv header)");
  std::map<std::string, size_t> col;
  for (size_t j = 0; j < header.size(); ++j) col.emplace(header[j], j);
  // The stable history.csv columns (doc/user-guide.md) that the study uses;
  // 'bisections' is an extra column and optional.
  const std::vector<std::string> required = {"step", "load_factor", "strain_energy", "newton_iterations",
                                             "dual_iterations", "contact_exchanges", "wall_seconds"};
  for (const auto& c : required)
    if (!col.count(c))
      FIG4_INPUT_ERROR(file << ": missing column '" << c << "' in the header (is this a ddcontact history.csv?)");
  h.hasBisections = col.count("bisections") > 0;
  while (std::getline(in, line)) {
    ++lineNo;
    if (trim(line).empty()) continue;
    const auto cells = splitCsv(line);
    if (cells.size() < header.size())
      FIG4_INPUT_ERROR(file << ":" << lineNo << ": " << cells.size() << " fields, the header has " << header.size());
    auto get = [&](const char* c) { return cells[col.at(c)]; };
    Row r;
    r.line = lineNo;
    r.step = toLong(get("step"), file, lineNo, "step");
    r.lf = toDouble(get("load_factor"), file, lineNo, "load_factor");
    r.U = toDouble(get("strain_energy"), file, lineNo, "strain_energy");
    r.newton = toDouble(get("newton_iterations"), file, lineNo, "newton_iterations");
    r.dual = toDouble(get("dual_iterations"), file, lineNo, "dual_iterations");
    r.exchanges = toDouble(get("contact_exchanges"), file, lineNo, "contact_exchanges");
    r.wall = toDouble(get("wall_seconds"), file, lineNo, "wall_seconds");
    if (h.hasBisections) r.bisections = toLong(get("bisections"), file, lineNo, "bisections");
    if (col.count("rejected_steps")) r.rejected = toLong(get("rejected_steps"), file, lineNo, "rejected_steps");
    if (col.count("geometry_error")) r.indicator = toDouble(get("geometry_error"), file, lineNo, "geometry_error");
    if (col.count("geometry_corrections"))
      r.corrections = toLong(get("geometry_corrections"), file, lineNo, "geometry_corrections");
    if (!std::isfinite(r.lf) || !std::isfinite(r.U))
      FIG4_INPUT_ERROR(file << ":" << lineNo << ": load_factor / strain_energy not finite");
    if (!h.rows.empty() && r.step < h.rows.back().step)
      FIG4_INPUT_ERROR(file << ":" << lineNo << ": step " << r.step << " after step " << h.rows.back().step
                            << " (steps must not decrease)");
    h.rows.push_back(r);
  }
  if (h.rows.empty()) FIG4_INPUT_ERROR(file << ": no data rows (only a header)");
  if (adaptive) {
    // Step Control: the steps have no nominal size, every row ends one.
    for (size_t i = 0; i < h.rows.size(); ++i)
      if (h.rows[i].step >= 1) h.nominal.push_back(i);
    if (h.nominal.empty()) FIG4_INPUT_ERROR(file << ": no step (no row with step >= 1)");
    return h;
  }

  // Nominal step ends. Rows of one step are consecutive; the end of step s is
  // the row at s * delta, delta = the load factor at the end of the first step.
  double delta = std::numeric_limits<double>::quiet_NaN();
  size_t i = 0;
  while (i < h.rows.size()) {
    const long s = h.rows[i].step;
    size_t j = i;
    while (j < h.rows.size() && h.rows[j].step == s) ++j;  // rows [i, j) belong to step s
    const bool lastGroup = (j == h.rows.size());
    if (s >= 1) {
      if (std::isnan(delta)) delta = h.rows[j - 1].lf / static_cast<double>(s);
      const double target = static_cast<double>(s) * delta;
      size_t found = j;
      for (size_t k = i; k < j; ++k)
        if (std::abs(h.rows[k].lf - target) <= kNominalTol * std::max(1.0, std::abs(target))) found = k;
      if (found < j) {
        h.nominal.push_back(found);
      } else if (lastGroup) {
        h.complete = false;
        h.stoppedInStep = s;
      } else {
        FIG4_INPUT_ERROR(file << ":" << h.rows[j - 1].line << ": step " << s << " has no row at its nominal end, load factor "
                              << target << " (= step x " << delta << ")");
      }
    }
    i = j;
  }
  if (h.nominal.empty()) FIG4_INPUT_ERROR(file << ": no complete load step (no row with step >= 1 at its nominal end)");
  return h;
}

struct Point {
  double lf, U, Uref, e;
  double indicator = -1;  // the row's geometry_error (-1: none)
};

struct RunResult {
  const History* h = nullptr;
  std::vector<Point> points;  // reported points (U_ref above the reporting threshold)
  double maxUOff = 0;         // max |U| at nominal step ends where U_ref is below the threshold
  double maxErr = 0, maxErrLf = 0, meanErr = 0;
  double newton = 0, dual = 0, exchanges = 0, wall = 0;
  size_t steps = 0, subRows = 0;
  long maxDepth = 0;
  double finalLf = 0;
  long rejected = 0, corrections = 0;  // Step Control: totals over the rows
  double peakU = 0;                    // max strain energy over the rows
};

/// U at load factor x from the cubic through the four reference points
/// nearest to it (fewer at the ends of the table: then the Lagrange
/// polynomial through what there is). `table` sorted by load factor.
double interpolateCubic(const std::vector<std::pair<double, double>>& table, double x) {
  const size_t n = table.size();
  if (n == 1) return table[0].second;
  const size_t m = std::min<size_t>(4, n);
  size_t hi = std::lower_bound(table.begin(), table.end(), std::make_pair(x, -HUGE_VAL)) - table.begin();
  size_t lo = hi >= m / 2 ? hi - m / 2 : 0;
  lo = std::min(lo, n - m);
  double v = 0;
  for (size_t a = lo; a < lo + m; ++a) {
    double w = 1;
    for (size_t b = lo; b < lo + m; ++b)
      if (a != b) w *= (x - table[b].first) / (table[a].first - table[b].first);
    v += w * table[a].second;
  }
  return v;
}

/// The error of interpolateCubic() on `table`, estimated from every other
/// point: the largest relative miss, at the points left out, over the
/// points with U > thr of a table of twice the spacing, divided by 16 (the
/// cubic's error falls as the fourth power of the spacing).
double interpolationErrorEstimate(const std::vector<std::pair<double, double>>& table, double thr) {
  std::vector<std::pair<double, double>> even;
  for (size_t i = 0; i < table.size(); i += 2) even.push_back(table[i]);
  double worst = 0;
  if (even.size() < 4) return worst;
  for (size_t i = 1; i < table.size(); i += 2)
    if (table[i].second > thr)
      worst = std::max(worst, std::abs(interpolateCubic(even, table[i].first) - table[i].second) / table[i].second);
  return worst / 16.0;
}

RunResult analyse(const History& h, const History& ref, double thr) {
  RunResult r;
  r.h = &h;
  // Reference lookup: every reference row (nominal or sub-step), sorted by load factor.
  std::vector<std::pair<double, double>> table;
  for (const auto& row : ref.rows) table.emplace_back(row.lf, row.U);
  std::sort(table.begin(), table.end());
  for (size_t idx : h.nominal) {
    const Row& row = h.rows[idx];
    auto it = std::lower_bound(table.begin(), table.end(), std::make_pair(row.lf - kMatchTol, -HUGE_VAL));
    if (h.adaptive && (it == table.end() || it->first > row.lf + kMatchTol)) {
      const double Uref = interpolateCubic(table, row.lf);
      if (Uref > thr)
        r.points.push_back({row.lf, row.U, Uref, std::abs(row.U - Uref) / Uref, row.indicator});
      else
        r.maxUOff = std::max(r.maxUOff, std::abs(row.U));
      continue;
    }
    if (it == table.end() || it->first > row.lf + kMatchTol)
      FIG4_INPUT_ERROR("run '" << h.label << "' (" << h.file << ":" << row.line << "): load factor " << row.lf << " (step "
                               << row.step << ") has no row in the reference " << ref.file << " (tolerance " << kMatchTol
                               << "); the reference must stop at every load factor of the runs, e.g. a step count that "
                                  "is a multiple of each run's");
    // Several reference rows within the tolerance: take the closest.
    auto best = it;
    for (auto k = it; k != table.end() && k->first <= row.lf + kMatchTol; ++k)
      if (std::abs(k->first - row.lf) < std::abs(best->first - row.lf)) best = k;
    const double Uref = best->second;
    if (Uref > thr)
      r.points.push_back({row.lf, row.U, Uref, std::abs(row.U - Uref) / Uref, row.indicator});
    else
      r.maxUOff = std::max(r.maxUOff, std::abs(row.U));
  }
  double sum = 0;
  for (const auto& p : r.points) {
    sum += p.e;
    if (p.e > r.maxErr || (&p == &r.points.front())) {
      r.maxErr = p.e;
      r.maxErrLf = p.lf;
    }
  }
  r.meanErr = r.points.empty() ? 0.0 : sum / r.points.size();
  size_t positiveRows = 0;
  for (const auto& row : h.rows) {
    r.rejected += row.rejected;
    r.corrections += row.corrections;
    r.peakU = std::max(r.peakU, row.U);
    r.newton += row.newton;
    r.dual += row.dual;
    r.exchanges += row.exchanges;
    r.maxDepth = std::max(r.maxDepth, row.bisections);
    if (row.step >= 1) ++positiveRows;
  }
  r.wall = h.rows.back().wall;
  r.steps = h.nominal.size();
  r.subRows = positiveRows - h.nominal.size();
  r.finalLf = h.rows[h.nominal.back()].lf;
  return r;
}

std::string fmtE(double v, int prec = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*e", prec, v);
  return buf;
}
std::string fmtF(double v, int prec) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", prec, v);
  return buf;
}
std::string fmtLf(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// Simple aligned text table.
void printTable(std::ostream& os, const std::vector<std::vector<std::string>>& t) {
  std::vector<size_t> w;
  for (const auto& r : t)
    for (size_t j = 0; j < r.size(); ++j) {
      if (w.size() <= j) w.push_back(0);
      w[j] = std::max(w[j], r[j].size());
    }
  for (size_t i = 0; i < t.size(); ++i) {
    std::string line;
    for (size_t j = 0; j < t[i].size(); ++j) {
      std::string c = t[i][j];
      if (j == 0)
        c += std::string(w[j] - c.size(), ' ');
      else
        c = std::string(w[j] - c.size(), ' ') + c;
      line += (j ? "  " : "") + c;
    }
    os << "  " << line << "\n";
    if (i == 0) {
      size_t total = 0;
      for (size_t j = 0; j < w.size(); ++j) total += w[j] + (j ? 2 : 0);
      os << "  " << std::string(total, '-') << "\n";
    }
  }
}

struct PhaseMax {
  double v = -1, lf = 0;
  size_t n = 0;
  void add(const Point& p) {
    ++n;
    if (p.e > v) {
      v = p.e;
      lf = p.lf;
    }
  }
  std::string str() const { return n ? fmtE(v) + " @" + fmtLf(lf) : "-"; }
};

struct Phases {
  PhaseMax all, early, middle, late;  // all; λ <= 0.25; 0.25 < λ <= 0.75; λ > 0.75
};

Phases phases(const RunResult& r, double floorAbs) {
  Phases ph;
  for (const auto& p : r.points) {
    if (!(p.Uref > floorAbs)) continue;
    ph.all.add(p);
    if (p.lf <= 0.25 + kMatchTol)
      ph.early.add(p);
    else if (p.lf <= 0.75 + kMatchTol)
      ph.middle.add(p);
    else
      ph.late.add(p);
  }
  return ph;
}

/// The command line (kUsage).
struct Options {
  std::string refFile, csvFile, mono20Label;
  std::vector<std::pair<std::string, std::string>> runSpecs;
  std::vector<bool> runAdaptive;  // per runSpecs entry: --adaptive-run
  std::vector<std::string> decomposedLabels;
  bool help = false;  // --help: print kUsage, nothing else
  bool check = false, assertPhases = false;
  double maxError = HUGE_VAL, maxPeakError = HUGE_VAL, maxExchanges = HUGE_VAL;
  double checkFloor = kReportThreshold;
};

/// One --run or --adaptive-run LABEL=FILE into o.runSpecs.
void addRunSpec(Options& o, const std::string& a, const std::string& v) {
  const auto eq = v.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == v.size())
    FIG4_INPUT_ERROR("option " << a << " '" << v << "': expected LABEL=PATH/history.csv");
  const std::string label = v.substr(0, eq);
  if (label.find_first_of(",\"\n") != std::string::npos)
    FIG4_INPUT_ERROR("option " << a << " '" << v << "': the label must not contain ',' or '\"'");
  for (const auto& rs : o.runSpecs)
    if (rs.first == label) FIG4_INPUT_ERROR("option " << a << ": label '" << label << "' given twice");
  o.runSpecs.emplace_back(label, v.substr(eq + 1));
  o.runAdaptive.push_back(a == "--adaptive-run");
}

/// The options; stops at --help. \throws InputError for a bad command line.
Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) FIG4_INPUT_ERROR("option " << a << " needs a value\n\n" << kUsage);
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      o.help = true;
      return o;
    } else if (a == "--reference") {
      o.refFile = value();
    } else if (a == "--run" || a == "--adaptive-run") {
      addRunSpec(o, a, value());
    } else if (a == "--max-error" || a == "--max-peak-error" || a == "--max-exchanges") {
      const std::string v = value();
      char* e = nullptr;
      const double x = std::strtod(v.c_str(), &e);
      if (v.empty() || *e != '\0' || !(x > 0) || !std::isfinite(x))
        FIG4_INPUT_ERROR("option " << a << " '" << v << "': expected a positive number");
      (a == "--max-error" ? o.maxError : a == "--max-peak-error" ? o.maxPeakError : o.maxExchanges) = x;
    } else if (a == "--csv") {
      o.csvFile = value();
    } else if (a == "--check") {
      o.check = true;
    } else if (a == "--assert-phases") {
      o.assertPhases = true;
    } else if (a == "--check-floor") {
      const std::string v = value();
      char* e = nullptr;
      o.checkFloor = std::strtod(v.c_str(), &e);
      if (v.empty() || *e != '\0' || !(o.checkFloor >= 0) || !(o.checkFloor < 1))
        FIG4_INPUT_ERROR("option --check-floor '" << v << "': expected a number in [0, 1)");
    } else if (a == "--decomposed") {
      o.decomposedLabels.push_back(value());
    } else if (a == "--monolithic20") {
      o.mono20Label = value();
    } else {
      FIG4_INPUT_ERROR("unknown option '" << a << "'\n\n" << kUsage);
    }
  }
  if (o.refFile.empty()) FIG4_INPUT_ERROR("missing --reference FILE\n\n" << kUsage);
  if (o.runSpecs.empty())
    FIG4_INPUT_ERROR("missing --run or --adaptive-run LABEL=FILE (at least one run)\n\n" << kUsage);
  return o;
}

/// The run labelled `label`; none: an InputError naming option `opt`, or
/// nullptr without one.
const History* findRun(const std::vector<History>& runs, const std::string& label, const char* opt) {
  for (const auto& h : runs)
    if (h.label == label) return &h;
  if (opt) FIG4_INPUT_ERROR("option " << opt << " '" << label << "': no --run with that label");
  return nullptr;
}

/// The decomposed runs the check and the ratio use, by step count.
std::vector<const History*> decomposedRuns(const Options& o, const std::vector<History>& runs) {
  std::vector<const History*> decomposed;
  if (!o.decomposedLabels.empty()) {
    for (const auto& l : o.decomposedLabels) decomposed.push_back(findRun(runs, l, "--decomposed"));
  } else {
    for (const char* l : {"decomposed-20", "decomposed-50", "decomposed-100"})
      if (const History* h = findRun(runs, l, nullptr)) decomposed.push_back(h);
  }
  std::stable_sort(decomposed.begin(), decomposed.end(),
                   [](const History* a, const History* b) { return a->nominal.size() < b->nominal.size(); });
  if (o.check && decomposed.size() < 2)
    FIG4_INPUT_ERROR("option --check needs at least two decomposed runs (labels decomposed-20, decomposed-50, "
                     "decomposed-100 or --decomposed LABEL), got "
                     << decomposed.size());
  return decomposed;
}

/// --csv: the reported points in long format.
void writeCsv(const std::string& csvFile, const std::vector<RunResult>& results) {
  std::ofstream out(csvFile);
  if (!out) FIG4_INPUT_ERROR(csvFile << ": cannot write (option --csv)");
  out << "run,load_factor,strain_energy,reference_energy,relative_error\n";
  out.precision(17);
  for (const auto& r : results)
    for (const auto& p : r.points) out << r.h->label << "," << p.lf << "," << p.U << "," << p.Uref << "," << p.e << "\n";
  out.close();
  if (!out) FIG4_INPUT_ERROR(csvFile << ": write failed (option --csv)");
}

/// The summary table: errors, iterations, exchanges, bisections and wall
/// time of every run and of the reference.
void printSummary(const std::string& refFile, const History& ref, double maxUref, double thr,
                  const std::vector<RunResult>& results, const RunResult& refStats) {
  std::cout << "Figure 4: relative strain-energy error e = |U - U_ref| / U_ref against the reference\n"
            << "  " << refFile << " (" << ref.nominal.size() << " steps, max U_ref = " << fmtE(maxUref, 6)
            << " at load factor ";
  for (const auto& row : ref.rows)
    if (row.U == maxUref) {
      std::cout << fmtLf(row.lf);
      break;
    }
  std::cout << "), reported where U_ref > " << fmtE(thr, 2) << " (1e-8 max U_ref)\n\n";

  std::vector<std::vector<std::string>> t = {{"run", "steps", "points", "max error", "at load", "mean error", "wall [s]",
                                              "Newton", "dual", "Newton/step", "dual/Newton", "exchanges",
                                              "sub-steps/depth"}};
  auto statsRow = [&](const std::string& label, const RunResult& r, bool isRef) {
    const History& h = *r.h;
    std::string bis = h.hasBisections ? std::to_string(r.subRows) + "/" + std::to_string(r.maxDepth)
                                      : std::to_string(r.subRows) + "/-";
    t.push_back({label, std::to_string(r.steps) + (h.complete ? "" : "*"),
                 isRef ? "-" : std::to_string(r.points.size()), isRef ? "(reference)" : fmtE(r.maxErr),
                 isRef || r.points.empty() ? "-" : fmtLf(r.maxErrLf), isRef ? "-" : fmtE(r.meanErr),
                 fmtF(r.wall, 2), fmtF(r.newton, 0), fmtF(r.dual, 0), fmtF(r.newton / r.steps, 2),
                 r.newton > 0 ? fmtF(r.dual / r.newton, 2) : "-", fmtF(r.exchanges, 0), bis});
  };
  for (const auto& r : results) statsRow(r.h->label, r, false);
  statsRow("reference", refStats, true);
  printTable(std::cout, t);
  std::cout << "  (steps: nominal steps" << ", * = the run stopped inside a step; Newton, dual, exchanges: totals over all\n"
            << "   rows; wall: wall_seconds of the last row; sub-steps/depth: rows that are not nominal step ends /\n"
            << "   max bisection depth)\n";
}

/// A warning for every run that stops before the reference's final load
/// factor; whether there is one.
bool warnIncomplete(const History& ref, const std::vector<RunResult>& results) {
  bool anyIncomplete = false;
  const double refFinal = ref.rows[ref.nominal.back()].lf;
  for (const auto& r : results)
    if (!r.h->complete || r.finalLf < refFinal - kMatchTol) {
      anyIncomplete = true;
      std::cout << "  warning: run '" << r.h->label << "' stopped at load factor " << fmtLf(r.finalLf)
                << (r.h->complete ? "" : " (inside step " + std::to_string(r.h->stoppedInStep) + ")")
                << ", the reference reaches " << fmtLf(refFinal) << "\n";
    }
  return anyIncomplete;
}

/// The max error of every run by loading phase.
void printPhaseTable(const std::vector<RunResult>& results, double checkFloor, double floorAbs, double maxUref) {
  std::cout << "\nMax error by loading phase (points with U_ref > " << fmtE(checkFloor, 1)
            << " max U_ref; value @ load factor):\n";
  std::vector<std::vector<std::string>> pt = {
      {"run", "all", "load <= 0.25", "0.25 < load <= 0.75", "load > 0.75", "max U off-contact / max U_ref"}};
  for (const auto& r : results) {
    const Phases ph = phases(r, floorAbs);
    pt.push_back({r.h->label, ph.all.str(), ph.early.str(), ph.middle.str(), ph.late.str(), fmtE(r.maxUOff / maxUref, 1)});
  }
  printTable(std::cout, pt);
  std::cout << "  (off-contact: step ends where U_ref <= 1e-8 max U_ref, before contact and after release; a small\n"
            << "   value there means no error is left over once the rings separate)\n";
}

/// max e(finest decomposed run) / max e(20-step monolithic run).
void printRatio(const std::vector<RunResult>& results, const std::vector<const History*>& decomposed,
                const History* mono20) {
  const RunResult* finest = nullptr;
  for (const auto& r : results)
    if (!decomposed.empty() && r.h == decomposed.back()) finest = &r;
  const RunResult* m20 = nullptr;
  for (const auto& r : results)
    if (mono20 && r.h == mono20) m20 = &r;
  std::cout << "\n";
  if (finest && m20) {
    std::cout << "Ratio max error(" << finest->h->label << ") / max error(" << m20->h->label << ") = ";
    if (m20->maxErr > 0)
      std::cout << fmtE(finest->maxErr / m20->maxErr) << "  (" << fmtE(finest->maxErr) << " / " << fmtE(m20->maxErr)
                << "; the paper: comparable, i.e. about 1)\n";
    else
      std::cout << "inf (" << m20->h->label << " has zero error)\n";
  } else {
    std::cout << "Ratio max error(finest decomposed) / max error(20-step monolithic): not computed ("
              << (finest ? "" : "no decomposed run; ") << (m20 ? "" : "no monolithic-20 run") << ")\n";
  }
}

/// Runs of the decomposed element have the frozen-geometry indicator of
/// each step (geometry_error): how the error measured here compares.
void printIndicatorTable(const std::vector<RunResult>& results, double checkFloor, double floorAbs) {
  std::vector<std::vector<std::string>> it = {{"run", "points", "min", "median", "max"}};
  for (const auto& r : results) {
    std::vector<double> ratio;
    for (const auto& p : r.points)
      if (p.Uref > floorAbs && p.indicator > 0) ratio.push_back(p.e / p.indicator);
    if (ratio.empty()) continue;
    std::sort(ratio.begin(), ratio.end());
    const size_t n = ratio.size();
    const double median = n % 2 ? ratio[n / 2] : 0.5 * (ratio[n / 2 - 1] + ratio[n / 2]);
    it.push_back({r.h->label, std::to_string(n), fmtF(ratio.front(), 2), fmtF(median, 2), fmtF(ratio.back(), 2)});
  }
  if (it.size() > 1) {
    std::cout << "\nError / frozen-geometry indicator (geometry_error) at the points with U_ref > "
              << fmtE(checkFloor, 1) << " max U_ref:\n";
    printTable(std::cout, it);
  }
}

/// The Step Control table (every run, for comparison) and the assertions
/// of --max-error, --max-peak-error and --max-exchanges on the adaptive
/// runs; what fails into `failures`.
void stepControlTable(const Options& o, const History& ref, const std::vector<RunResult>& results, double maxUref,
                      double floorAbs, std::vector<std::string>& failures) {
  std::vector<std::pair<double, double>> table;
  for (const auto& row : ref.rows) table.emplace_back(row.lf, row.U);
  std::sort(table.begin(), table.end());
  std::cout << "\nStep Control (and the other runs; max error over points with U_ref > " << fmtE(o.checkFloor, 1)
            << " max U_ref; U_ref interpolated between reference rows, its error estimated at "
            << fmtE(interpolationErrorEstimate(table, floorAbs), 1) << "):\n";
  std::vector<std::vector<std::string>> st = {{"run", "steps", "rejected", "corrections", "exchanges", "max error",
                                               "at load", "peak U", "peak error", "wall [s]"}};
  for (const auto& r : results) {
    const Phases ph = phases(r, floorAbs);
    const double peakError = (r.peakU - maxUref) / maxUref;
    st.push_back({r.h->label, std::to_string(r.steps), std::to_string(r.rejected), std::to_string(r.corrections),
                  fmtF(r.exchanges, 0), ph.all.n ? fmtE(ph.all.v) : "-", ph.all.n ? fmtLf(ph.all.lf) : "-",
                  fmtE(r.peakU, 4), fmtE(peakError, 2), fmtF(r.wall, 2)});
    if (!r.h->adaptive) continue;
    auto assertLe = [&](bool ok, const std::string& what) {
      std::cout << "  " << (ok ? "PASS " : "FAIL ") << r.h->label << ": " << what << "\n";
      if (!ok) failures.push_back(r.h->label + ": " + what);
    };
    if (o.maxError < HUGE_VAL)
      assertLe(ph.all.n && ph.all.v <= o.maxError,
               "max error " + (ph.all.n ? fmtE(ph.all.v) : std::string("(no point)")) + " <= " + fmtE(o.maxError, 2));
    if (o.maxPeakError < HUGE_VAL)
      assertLe(std::abs(peakError) <= o.maxPeakError,
               "peak strain energy error " + fmtE(peakError, 2) + " within " + fmtE(o.maxPeakError, 2));
    if (o.maxExchanges < HUGE_VAL)
      assertLe(r.exchanges < o.maxExchanges,
               "contact exchanges " + fmtF(r.exchanges, 0) + " < " + fmtF(o.maxExchanges, 0));
  }
  printTable(std::cout, st);
  std::cout << "  (steps: accepted steps or rows; rejected: steps repeated smaller; corrections: steps repeated with the\n"
            << "   geometry of their end; exchanges include those of rejected and repeated attempts; peak error:\n"
            << "   (max U - max U_ref) / max U_ref)\n";
}

/// Prints one finding; a failed one into `failures`.
void report(bool ok, const std::string& what, std::vector<std::string>& failures) {
  std::cout << "  " << (ok ? "PASS " : "FAIL ") << what << "\n";
  if (!ok) failures.push_back(what);
}

/// (a) The max error falls with the step count over the decomposed runs.
void checkErrorFalls(const std::vector<std::pair<const History*, Phases>>& dph, std::vector<std::string>& failures) {
  for (size_t k = 0; k + 1 < dph.size(); ++k) {
    const auto& a = dph[k];
    const auto& b = dph[k + 1];
    const bool ok = a.second.all.n && b.second.all.n && a.second.all.v > b.second.all.v;
    std::ostringstream os;
    os << "(a) max error " << a.first->label << " (" << a.first->nominal.size() << " steps) " << a.second.all.str()
       << (ok ? " > " : " NOT > ") << b.first->label << " (" << b.first->nominal.size() << " steps) "
       << b.second.all.str();
    report(ok, os.str(), failures);
  }
}

/// (c) No accumulation: once the rings separate (and before they touch)
/// the energy of every decomposed run is back to round-off of the peak.
void checkNoAccumulation(const std::vector<const History*>& decomposed, const std::vector<RunResult>& results,
                         double maxUref, std::vector<std::string>& failures) {
  for (const History* h : decomposed)
    for (const auto& r : results)
      if (r.h == h) {
        const double ratio = r.maxUOff / maxUref;
        const bool ok = ratio <= kReportThreshold;
        std::ostringstream os;
        os << "(c) " << h->label << ": max U off-contact / max U_ref " << fmtE(ratio, 1) << (ok ? " <= " : " > ")
           << fmtE(kReportThreshold, 1) << " (no energy error left once the rings separate)";
        report(ok, os.str(), failures);
      }
}

/// (b) The phase criterion (doc/figure4.md). Reported; asserted only with
/// --assert-phases: on the reconstructed benchmark the relative error is
/// largest at contact release (load ~0.8), where U_ref -> 0 and any lag of
/// the release gives a large ratio (doc/figure4.md).
void checkPhases(const std::vector<std::pair<const History*, Phases>>& dph, bool assertPhases,
                 std::vector<std::string>& failures) {
  for (const auto& d : dph) {
    const Phases& ph = d.second;
    std::ostringstream os;
    bool ok;
    if (!ph.middle.n) {
      ok = false;
      os << "(b) " << d.first->label << ": no point in the middle phase 0.25 < load <= 0.75";
    } else if (!ph.late.n) {
      ok = true;
      os << "(b) " << d.first->label << ": no point with load > 0.75 (nothing to accumulate), middle peak "
         << ph.middle.str();
    } else {
      ok = ph.late.v <= ph.middle.v;
      os << "(b) " << d.first->label << ": max error for load > 0.75 " << ph.late.str()
         << (ok ? " <= " : " > ") << "middle-phase peak " << ph.middle.str();
    }
    std::cout << "  " << (ok ? "PASS " : assertPhases ? "FAIL " : "NOT MET (reported, not asserted) ") << os.str()
              << "\n";
    if (!ok && assertPhases) failures.push_back(os.str());
  }
}

/// 0 without failures, else 1 after listing them on stderr.
int exitStatus(const std::vector<std::string>& failures) {
  if (failures.empty()) return 0;
  std::cerr << "ddcontact-figure4: check FAILED:\n";
  for (const auto& f : failures) std::cerr << "  " << f << "\n";
  return 1;
}

/// Reads the histories, prints the study and checks what the options ask
/// for; the exit status. \throws InputError for bad input.
int study(const Options& o) {
  const History ref = readHistory("", o.refFile);
  std::vector<History> runs;
  runs.reserve(o.runSpecs.size());
  for (size_t k = 0; k < o.runSpecs.size(); ++k)
    runs.push_back(readHistory(o.runSpecs[k].first, o.runSpecs[k].second, o.runAdaptive[k]));
  const std::vector<const History*> decomposed = decomposedRuns(o, runs);
  const History* mono20 =
      o.mono20Label.empty() ? findRun(runs, "monolithic-20", nullptr) : findRun(runs, o.mono20Label, "--monolithic20");

  double maxUref = -HUGE_VAL;
  for (const auto& row : ref.rows) maxUref = std::max(maxUref, row.U);
  if (!(maxUref > 0)) FIG4_INPUT_ERROR(o.refFile << ": the reference has no positive strain energy (max " << maxUref << ")");
  const double thr = kReportThreshold * maxUref;
  const RunResult refStats = analyse(ref, ref, thr);
  std::vector<RunResult> results;
  for (const auto& h : runs) results.push_back(analyse(h, ref, thr));

  if (!o.csvFile.empty()) writeCsv(o.csvFile, results);
  printSummary(o.refFile, ref, maxUref, thr, results, refStats);
  const bool anyIncomplete = warnIncomplete(ref, results);
  const double floorAbs = o.checkFloor * maxUref;
  printPhaseTable(results, o.checkFloor, floorAbs, maxUref);
  printRatio(results, decomposed, mono20);
  if (!o.csvFile.empty()) std::cout << "Points written to " << o.csvFile << "\n";
  printIndicatorTable(results, o.checkFloor, floorAbs);

  std::vector<std::string> failures;
  const bool anyAdaptive = std::find(o.runAdaptive.begin(), o.runAdaptive.end(), true) != o.runAdaptive.end();
  if (anyAdaptive) stepControlTable(o, ref, results, maxUref, floorAbs, failures);
  if (!o.check) return exitStatus(failures);

  std::cout << "\nCheck (points with U_ref > " << fmtE(o.checkFloor, 1) << " max U_ref):\n";
  std::vector<std::pair<const History*, Phases>> dph;
  for (const History* h : decomposed)
    for (const auto& r : results)
      if (r.h == h) dph.emplace_back(h, phases(r, floorAbs));
  checkErrorFalls(dph, failures);
  checkNoAccumulation(decomposed, results, maxUref, failures);
  checkPhases(dph, o.assertPhases, failures);
  if (anyIncomplete) failures.push_back("a run stopped before the reference's final load factor (see the warning above)");
  if (!failures.empty()) return exitStatus(failures);
  std::cout << "Check passed: the decomposed error falls with the step count and no energy error is left once "
               "the rings separate.\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parseOptions(argc, argv);
    if (o.help) {
      std::cout << kUsage;
      return 0;
    }
    return study(o);
  } catch (const InputError& e) {
    std::cerr << "ddcontact-figure4: " << e.what() << "\n";
    return 2;
  }
}
