#include "bowg_evaluation/csv_cells.h"

#include <cstdlib>

#include "bowg/core/errors.h"

namespace bowg {
namespace eval {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r");
    const auto e = cell.find_last_not_of(" \t\r");
    cells.push_back(b == std::string::npos ? std::string() : cell.substr(b, e - b + 1));
  }
  return cells;
}

bool toDouble(const std::string& s, double* v) {
  if (s.empty()) return false;
  char* end = nullptr;
  *v = std::strtod(s.c_str(), &end);
  return *end == '\0';
}

CsvLines::CsvLines(const std::string& text, const std::string& source)
    : in_(text), source_(source) {}

bool CsvLines::next(std::vector<std::string>* cells) {
  std::string line;
  while (std::getline(in_, line)) {
    ++line_;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    *cells = splitCsv(line);
    return true;
  }
  return false;
}

void CsvLines::fail(const std::string& why) const {
  throw FormatError(source_ + ":" + std::to_string(line_) + ": " + why);
}

}  // namespace eval
}  // namespace bowg
