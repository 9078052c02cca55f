// compare_history A.csv B.csv RTOL [COLUMN...]
// Compares two history.csv files column by column: the same number of rows,
// and |a - b| <= RTOL * max(|a|, |b|, FLOOR) for the named columns, found by
// name in each file (a run with the decomposed contact element has columns
// a plain run has not); without named columns the headers must be the same
// and every column is compared except the rank-dependent wall_seconds and
// contact_bytes. FLOOR = 1e-4 * the column's largest magnitude: values that
// are round-off (e.g. 1e-14 strain energy of a rigid motion when the peak is
// O(1)) then compare absolutely, to RTOL * 1e-4 of the peak. The columns
// that are running sums over the steps (external_work,
// frictional_dissipation) compare relative to at least the largest
// magnitude they reached up to the row: a sum's round-off grows with what
// was summed (Σ |increment| ≥ that peak), so a work that loads and unloads
// back near zero (4e-4 of its peak at the half rings' last step) differs
// by ~steps * eps * peak between two rank counts, not by eps * its value.
// Prints the worst relative difference per column; exit 1 on mismatch.
//
// compare_history A.csv B.csv exact
// The same header, and every field the same text except wall_seconds (a
// restarted run's history against the uninterrupted run's).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {
using Table = std::vector<std::vector<std::string>>;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  return out;
}

bool read(const char* file, std::vector<std::string>& header, Table& rows) {
  std::ifstream in(file);
  if (!in) return false;
  std::string line;
  if (!std::getline(in, line)) return false;
  header = split(line);
  while (std::getline(in, line))
    if (!line.empty()) rows.push_back(split(line));
  return true;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: compare_history A.csv B.csv RTOL [COLUMN...] | compare_history A.csv B.csv exact\n";
    return 2;
  }
  std::vector<std::string> ha, hb;
  Table a, b;
  if (!read(argv[1], ha, a) || !read(argv[2], hb, b)) {
    std::cerr << "compare_history: cannot read " << argv[1] << " or " << argv[2] << "\n";
    return 1;
  }
  if (std::string(argv[3]) == "exact") {
    if (ha != hb || a.size() != b.size() || a.empty()) {
      std::cerr << "compare_history: headers or row counts differ (" << a.size() << " vs " << b.size() << " rows)\n";
      return 1;
    }
    const size_t wall = std::find(ha.begin(), ha.end(), "wall_seconds") - ha.begin();
    int differences = 0;
    for (size_t i = 0; i < a.size(); ++i)
      for (size_t j = 0; j < std::max(a[i].size(), b[i].size()); ++j) {
        const std::string x = j < a[i].size() ? a[i][j] : "(none)", y = j < b[i].size() ? b[i][j] : "(none)";
        if (j == wall || x == y) continue;
        if (++differences <= 10)
          std::cerr << "compare_history: row " << i + 1 << ", " << (j < ha.size() ? ha[j] : "column " + std::to_string(j))
                    << ": " << x << " vs " << y << "\n";
      }
    std::cout << differences << " fields differ (wall_seconds not compared)\n";
    return differences == 0 ? 0 : 1;
  }
  const double rtol = std::atof(argv[3]);
  std::vector<std::string> cols(argv + 4, argv + argc);
  if (cols.empty() && ha != hb) {
    std::cerr << "compare_history: headers differ\n";
    return 1;
  }
  if (a.size() != b.size() || a.empty()) {
    std::cerr << "compare_history: row counts differ or are zero (" << a.size() << " vs " << b.size() << ")\n";
    return 1;
  }
  if (cols.empty())
    for (const auto& h : ha)
      if (h != "wall_seconds" && h != "contact_bytes") cols.push_back(h);
  bool ok = true;
  for (const auto& c : cols) {
    const auto ia = std::find(ha.begin(), ha.end(), c), ib = std::find(hb.begin(), hb.end(), c);
    if (ia == ha.end() || ib == hb.end()) {
      std::cerr << "compare_history: no column '" << c << "' in " << (ia == ha.end() ? argv[1] : argv[2]) << "\n";
      return 1;
    }
    const size_t ja = ia - ha.begin(), jb = ib - hb.begin();
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i].size() <= ja || b[i].size() <= jb) {
        std::cerr << "compare_history: row " << i + 1 << " has too few fields\n";
        return 1;
      }
    double scale = 0.0, worst = 0.0, reached = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
      scale = std::max({scale, std::abs(std::atof(a[i][ja].c_str())), std::abs(std::atof(b[i][jb].c_str()))});
    const bool runningSum = c == "external_work" || c == "frictional_dissipation";
    for (size_t i = 0; i < a.size(); ++i) {
      const double x = std::atof(a[i][ja].c_str()), y = std::atof(b[i][jb].c_str());
      if (runningSum) reached = std::max({reached, std::abs(x), std::abs(y)});
      const double rel = std::abs(x - y) / std::max({std::abs(x), std::abs(y), 1e-4 * scale, reached, 1e-300});
      worst = std::max(worst, rel);
    }
    std::cout << c << ": worst relative difference " << worst << "\n";
    if (worst > rtol) ok = false;
  }
  if (!ok) std::cerr << "compare_history: differences above " << rtol << "\n";
  return ok ? 0 : 1;
}
