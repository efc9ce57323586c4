// The cells of one line of the tools' CSV files (a header line naming the
// columns, comma-separated numbers): shared by the readers of odometry,
// trajectory and pose files.
#pragma once

#include <string>
#include <vector>

namespace bowg {
namespace eval {

/// The comma-separated cells of `line`, each without surrounding blanks.
std::vector<std::string> splitCsv(const std::string& line);

/// True when all of `s` is a number (strtod); the value in *v.
bool toDouble(const std::string& s, double* v);

}  // namespace eval
}  // namespace bowg
