// The cells of one line of the tools' CSV files (a header line naming the
// columns, comma-separated numbers): shared by the readers of odometry,
// trajectory and pose files.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace bowg {
namespace eval {

/// The comma-separated cells of `line`, each without surrounding blanks.
std::vector<std::string> splitCsv(const std::string& line);

/// True when all of `s` is a number (strtod); the value in *v.
bool toDouble(const std::string& s, double* v);

/// The non-blank lines of a CSV text as cells, counting lines for messages.
class CsvLines {
 public:
  /// `source` names the text in messages (its path).
  CsvLines(const std::string& text, const std::string& source);
  /// The cells of the next non-blank line; false at the end.
  bool next(std::vector<std::string>* cells);
  /// Throws bowg::FormatError "<source>:<line>: <why>" (the line last read).
  [[noreturn]] void fail(const std::string& why) const;

 private:
  std::istringstream in_;
  std::string source_;
  int line_ = 0;
};

}  // namespace eval
}  // namespace bowg
