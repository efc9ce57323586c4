// The parameter table: one row per user parameter (see parameter_table.h);
// the rows themselves are in parameter_rows_*.cpp. Ranges are the ones the
// options headers document; where they leave a side open (e.g. "> 0") the
// table picks a generous finite bound, because the dynamic reconfigure GUI
// and the README need one.
#include "bowg/parameters/parameter_table.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>

#include "bowg/core/bounded_file.h"
#include "bowg/core/errors.h"
#include "parameters/parameter_rows.h"

namespace bowg {
namespace {

using parameter_rows::Row;
using parameter_rows::rowOf;
using parameter_rows::rows;

/// Shortest text that reads back to the same double.
std::string formatDouble(double v) {
  for (int precision = 6; precision <= 17; ++precision) {
    std::ostringstream s;
    s.precision(precision);
    s << v;
    if (std::strtod(s.str().c_str(), nullptr) == v) return s.str();
  }
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

bool parseDouble(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*value);
}

bool parseBool(const std::string& text, bool* value) {
  // The spellings yaml 1.1 (rosparam, PyYAML) reads as booleans, plus 0/1.
  static const char* kTrue[] = {"true", "True", "TRUE", "yes", "Yes", "on", "On", "1"};
  static const char* kFalse[] = {"false", "False", "FALSE", "no", "No", "off", "Off", "0"};
  for (const char* t : kTrue) {
    if (text == t) return (*value = true), true;
  }
  for (const char* f : kFalse) {
    if (text == f) return (*value = false), true;
  }
  return false;
}

void checkRange(const ParameterInfo& info, double v) {
  if (v < info.min_value || v > info.max_value) {
    throw InvalidParameter(info.name + ": " + formatDouble(v) + " is outside [" +
                           formatDouble(info.min_value) + ", " + formatDouble(info.max_value) +
                           "]");
  }
}

void setNumeric(const Row& r, double v, PipelineOptions* o) {
  const ParameterInfo& info = r.info;
  switch (info.type) {
    case ParameterType::kBool:
      if (v != 0.0 && v != 1.0) {
        throw InvalidParameter(info.name + ": a boolean must be 0 or 1, got " + formatDouble(v));
      }
      *r.as_bool(o) = v != 0.0;
      return;
    case ParameterType::kInt:
      if (!std::isfinite(v) || std::floor(v) != v) {
        throw InvalidParameter(info.name + ": an integer is required, got " + formatDouble(v));
      }
      checkRange(info, v);
      *r.as_int(o) = static_cast<int>(v);
      return;
    case ParameterType::kDouble:
      if (!std::isfinite(v)) throw InvalidParameter(info.name + ": value is not finite");
      checkRange(info, v);
      *r.as_double(o) = v;
      return;
    case ParameterType::kString:
    case ParameterType::kEnum:
      break;
  }
  throw InvalidParameter(info.name + ": is a " + toString(info.type) +
                         " parameter and cannot take the number " + formatDouble(v));
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return std::string();
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

}  // namespace

const char* toString(ParameterType t) {
  switch (t) {
    case ParameterType::kBool:
      return "bool";
    case ParameterType::kInt:
      return "int";
    case ParameterType::kDouble:
      return "double";
    case ParameterType::kString:
      return "string";
    case ParameterType::kEnum:
      return "enum";
  }
  return "?";
}

void PipelineOptions::validate() const {
  detector.validate();
  features.validate();
}

const std::vector<ParameterInfo>& parameterTable() {
  static const std::vector<ParameterInfo> table = [] {
    std::vector<ParameterInfo> t;
    for (const Row& r : rows()) t.push_back(r.info);
    return t;
  }();
  return table;
}

const ParameterInfo* findParameter(const std::string& name) {
  for (const ParameterInfo& p : parameterTable()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

void setParameter(const std::string& name, const std::string& value, PipelineOptions* options) {
  const Row& r = rowOf(name);
  const ParameterInfo& info = r.info;
  switch (info.type) {
    case ParameterType::kBool: {
      bool b = false;
      if (!parseBool(value, &b)) {
        throw InvalidParameter(name + ": '" + value + "' is not a boolean (true/false)");
      }
      *r.as_bool(options) = b;
      return;
    }
    case ParameterType::kInt:
    case ParameterType::kDouble: {
      double v = 0;
      if (!parseDouble(value, &v)) {
        throw InvalidParameter(name + ": '" + value + "' is not a number");
      }
      setNumeric(r, v, options);
      return;
    }
    case ParameterType::kString:
      *r.as_string(options) = value;
      return;
    case ParameterType::kEnum: {
      if (std::find(info.choices.begin(), info.choices.end(), value) == info.choices.end()) {
        std::string list;
        for (const std::string& c : info.choices) list += (list.empty() ? "" : ", ") + c;
        throw InvalidParameter(name + ": '" + value + "' is not one of " + list);
      }
      r.set_enum(options, value);
      return;
    }
  }
}

void setParameter(const std::string& name, double value, PipelineOptions* options) {
  setNumeric(rowOf(name), value, options);
}

std::string getParameter(const std::string& name, const PipelineOptions& options) {
  const Row& r = rowOf(name);
  // The accessors take a pointer (they also write); reading through a copy
  // keeps `options` const.
  PipelineOptions copy = options;
  switch (r.info.type) {
    case ParameterType::kBool:
      return *r.as_bool(&copy) ? "true" : "false";
    case ParameterType::kInt:
      return std::to_string(*r.as_int(&copy));
    case ParameterType::kDouble:
      return formatDouble(*r.as_double(&copy));
    case ParameterType::kString:
      return *r.as_string(&copy);
    case ParameterType::kEnum:
      return r.get_enum(options);
  }
  return std::string();
}

std::string defaultValue(const std::string& name) { return getParameter(name, PipelineOptions()); }

void applyParameters(const std::map<std::string, std::string>& values, PipelineOptions* options,
                     const std::string& source) {
  const std::string where = source.empty() ? std::string() : source + ": ";
  PipelineOptions result = *options;
  for (const auto& kv : values) {
    try {
      setParameter(kv.first, kv.second, &result);
    } catch (const InvalidParameter& e) {
      throw InvalidParameter(where + e.what());
    }
  }
  try {
    result.validate();
  } catch (const InvalidParameter& e) {
    throw InvalidParameter(where + e.what());
  }
  *options = result;
}

std::map<std::string, std::string> readFlatYaml(const std::string& path) {
  // A regular file within BOWG_MAX_TEXT_MB (bounded_file.h), read whole.
  std::istringstream in(readBoundedFile(path, FileKind::kText, "parameter file"));
  std::map<std::string, std::string> values;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    // Strip a comment: '#' at the start or after a blank, outside quotes.
    char quote = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
        line.erase(i);
        break;
      }
    }
    if (trim(line).empty() || trim(line) == "---") continue;
    if (line[0] == ' ' || line[0] == '\t' || trim(line)[0] == '-') {
      throw FormatError(where + "only flat 'key: value' lines are supported (no nesting, lists)");
    }
    const auto colon = line.find(':');
    if (colon == std::string::npos) throw FormatError(where + "expected 'key: value'");
    const std::string key = trim(line.substr(0, colon));
    std::string value = trim(line.substr(colon + 1));
    if (key.empty()) throw FormatError(where + "empty key");
    if (value.empty()) {
      throw FormatError(where + "'" + key + "' has no value (nested maps are not supported)");
    }
    if (value[0] == '[' || value[0] == '{') {
      throw FormatError(where + "'" + key + "': lists and maps are not supported");
    }
    if (value.size() >= 2 && (value[0] == '"' || value[0] == '\'') && value.back() == value[0]) {
      value = value.substr(1, value.size() - 2);
    }
    if (!values.emplace(key, value).second) {
      throw FormatError(where + "duplicate key '" + key + "'");
    }
  }
  return values;
}

PipelineOptions loadParameterFile(const std::string& path, const PipelineOptions& base) {
  PipelineOptions options = base;
  applyParameters(readFlatYaml(path), &options, path);
  return options;
}

std::vector<std::string> correctLiveParameters(int vocabulary_depth, PipelineOptions* options) {
  std::vector<std::string> corrections;
  for (const Row& r : rows()) {
    const ParameterInfo& info = r.info;
    if (info.type == ParameterType::kDouble) {
      double* v = r.as_double(options);
      const double c = std::isfinite(*v) ? std::min(std::max(*v, info.min_value), info.max_value)
                                         : info.min_value;
      if (c != *v) {
        corrections.push_back(info.name + " " + formatDouble(*v) + " is outside [" +
                              formatDouble(info.min_value) + ", " + formatDouble(info.max_value) +
                              "]: set to " + formatDouble(c));
        *v = c;
      }
    } else if (info.type == ParameterType::kInt) {
      int* v = r.as_int(options);
      const int c = std::min(std::max(*v, static_cast<int>(info.min_value)),
                             static_cast<int>(info.max_value));
      if (c != *v) {
        corrections.push_back(info.name + " " + std::to_string(*v) + " is outside [" +
                              formatDouble(info.min_value) + ", " + formatDouble(info.max_value) +
                              "]: set to " + std::to_string(c));
        *v = c;
      }
    }
  }
  SimilarityOptions& s = options->detector.similarity;
  // Eq. 9 weighs eta_d by 1 - lambda_1 - lambda_2, which must not be negative;
  // lambda_1 is the one the user most likely just moved, so lambda_2 gives way.
  if (s.lambda_1 + s.lambda_2 > 1.0) {
    const double l2 = 1.0 - s.lambda_1;
    corrections.push_back("lambda_1 + lambda_2 = " + formatDouble(s.lambda_1 + s.lambda_2) +
                          " > 1: lambda_2 set to 1 - lambda_1 = " + formatDouble(l2));
    s.lambda_2 = l2;
  }
  int& level = options->detector.geometric.direct_index_level;
  if (vocabulary_depth > 0 && level > vocabulary_depth) {
    corrections.push_back("direct_index_level " + std::to_string(level) +
                          " exceeds the vocabulary depth L = " + std::to_string(vocabulary_depth) +
                          ": set to " + std::to_string(vocabulary_depth));
    level = vocabulary_depth;
  }
  return corrections;
}

}  // namespace bowg
