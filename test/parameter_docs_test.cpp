// The README's parameter table says what the code and the shipped presets do:
// one row per row of the engine's parameter table, in its order, with its
// type, engine default, range or choices and live flag, and the value each
// preset (config/pipe.yaml, config/generic.yaml) sets, blank where it sets
// none. cfg_matches_table_test checks the dynamic_reconfigure side.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bowg/parameters/parameter_table.h"

namespace bowg_ros {
namespace {

const std::string kRepo = BOWG_REPO_DIR;
const char* const kHeader =
    "| name | type | default | `pipe.yaml` | `generic.yaml` | range / choices | live | "
    "description |";

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

// The first 7 cells of a table row and the rest (the description).
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::size_t at = row.find('|') + 1;
  for (int i = 0; i < 7; ++i) {
    const std::size_t next = row.find('|', at);
    out.push_back(trim(row.substr(at, next - at)));
    at = next + 1;
  }
  out.push_back(trim(row.substr(at)));
  return out;
}

// The README table's rows, in order.
std::vector<std::vector<std::string>> readmeRows() {
  const std::string readme = readAll(kRepo + "/README.md");
  std::vector<std::vector<std::string>> rows;
  const std::size_t header = readme.find(kHeader);
  if (header == std::string::npos) return rows;
  std::istringstream lines(readme.substr(header));
  std::string line;
  std::getline(lines, line);  // the header
  std::getline(lines, line);  // |---|
  while (std::getline(lines, line) && line.compare(0, 2, "| ") == 0) rows.push_back(cells(line));
  return rows;
}

// A preset's flat `key: value` lines, comments dropped.
std::map<std::string, std::string> preset(const std::string& name) {
  std::map<std::string, std::string> values;
  std::istringstream lines(readAll(kRepo + "/config/" + name));
  std::string line;
  while (std::getline(lines, line)) {
    line = line.substr(0, line.find('#'));
    const std::size_t colon = line.find(':');
    if (colon != std::string::npos)
      values[trim(line.substr(0, colon))] = trim(line.substr(colon + 1));
  }
  return values;
}

// A number as the table writes it: decimal, 1e6, or 2^30.
double number(const std::string& text) {
  const std::size_t caret = text.find('^');
  if (caret != std::string::npos) {
    return std::pow(std::atof(text.substr(0, caret).c_str()),
                    std::atof(text.substr(caret + 1).c_str()));
  }
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' ? v : std::nan("");
}

std::string expectedRange(const bowg::ParameterInfo& p) {
  switch (p.type) {
    case bowg::ParameterType::kEnum: {
      std::string s;
      for (const std::string& c : p.choices) s += (s.empty() ? "" : ", ") + c;
      return s;
    }
    case bowg::ParameterType::kString:
      return "path";
    case bowg::ParameterType::kBool:
      return "";
    default:
      return "";  // numbers: compared by value
  }
}

TEST(ParameterDocs, TheReadmeTableFollowsTheCodeAndThePresets) {
  const std::vector<std::vector<std::string>> rows = readmeRows();
  const std::vector<bowg::ParameterInfo>& table = bowg::parameterTable();
  ASSERT_EQ(rows.size(), table.size()) << "README rows against the parameter table's";
  const std::map<std::string, std::string> pipe = preset("pipe.yaml");
  const std::map<std::string, std::string> generic = preset("generic.yaml");
  for (std::size_t i = 0; i < table.size(); ++i) {
    const bowg::ParameterInfo& p = table[i];
    const std::vector<std::string>& r = rows[i];
    SCOPED_TRACE(p.name);
    ASSERT_EQ(r[0], "`" + p.name + "`") << "row " << i << ": the table's order";
    EXPECT_EQ(r[1], bowg::toString(p.type));
    const std::string default_value = bowg::defaultValue(p.name);
    const bool numeric =
        p.type == bowg::ParameterType::kInt || p.type == bowg::ParameterType::kDouble;
    if (numeric) {
      EXPECT_EQ(number(r[2]), std::stod(default_value)) << r[2];
      const std::size_t comma = r[5].find(", ");
      ASSERT_TRUE(r[5].size() > 4 && r[5].front() == '[' && r[5].back() == ']' &&
                  comma != std::string::npos)
          << r[5];
      EXPECT_EQ(number(r[5].substr(1, comma - 1)), p.min_value) << r[5];
      EXPECT_EQ(number(r[5].substr(comma + 2, r[5].size() - comma - 3)), p.max_value) << r[5];
    } else {
      EXPECT_EQ(r[2], default_value.empty() ? "\"\"" : default_value);
      EXPECT_EQ(r[5], expectedRange(p));
    }
    EXPECT_EQ(r[3], pipe.count(p.name) ? pipe.at(p.name) : "") << "config/pipe.yaml";
    EXPECT_EQ(r[4], generic.count(p.name) ? generic.at(p.name) : "") << "config/generic.yaml";
    EXPECT_EQ(r[6], p.live ? "yes" : "");
    EXPECT_FALSE(r[7].empty()) << "no description";
  }
  // Every key of a preset is a row (the loaders refuse others too).
  for (const auto* values : {&pipe, &generic}) {
    for (const auto& kv : *values) EXPECT_NE(bowg::findParameter(kv.first), nullptr) << kv.first;
  }
}

}  // namespace
}  // namespace bowg_ros
