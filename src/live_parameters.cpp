// dynamic_reconfigure <-> options by name (see live_parameters.h).
#include "bowg_ros/live_parameters.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg_ros/BoWGConfig.h"

namespace bowg_ros {

namespace {

// A table row that is not live: its changes are reported, never applied.
bool isStartOnly(const std::string& name) {
  const bowg::ParameterInfo* info = bowg::findParameter(name);
  return info != nullptr && !info->live;
}

const char* descriptionType(bowg::ParameterType type) {
  switch (type) {
    case bowg::ParameterType::kBool:
      return "bool";
    case bowg::ParameterType::kInt:
      return "int";
    case bowg::ParameterType::kDouble:
      return "double";
    default:
      return "str";  // strings and the enumerations' names
  }
}

// Appends `name` = its value in force (`text`, the table's spelling) to
// `config` in the list of its type.
void addValue(const bowg::ParameterInfo& info, const std::string& text,
              dynamic_reconfigure::Config* config) {
  switch (info.type) {
    case bowg::ParameterType::kBool: {
      dynamic_reconfigure::BoolParameter p;
      p.name = info.name;
      p.value = text == "true";
      config->bools.push_back(p);
      return;
    }
    case bowg::ParameterType::kInt: {
      dynamic_reconfigure::IntParameter p;
      p.name = info.name;
      p.value = std::stoi(text);
      config->ints.push_back(p);
      return;
    }
    case bowg::ParameterType::kDouble: {
      dynamic_reconfigure::DoubleParameter p;
      p.name = info.name;
      p.value = std::stod(text);
      config->doubles.push_back(p);
      return;
    }
    default: {
      dynamic_reconfigure::StrParameter p;
      p.name = info.name;
      p.value = text;
      config->strs.push_back(p);
    }
  }
}

// The value `requested` gives `name`, as text setParameter parses; false
// when it gives none.
bool requestedText(const dynamic_reconfigure::Config& requested, const std::string& name,
                   std::string* text) {
  bool found = false;
  for (const dynamic_reconfigure::BoolParameter& p : requested.bools) {
    if (p.name == name) *text = p.value ? "true" : "false", found = true;
  }
  for (const dynamic_reconfigure::IntParameter& p : requested.ints) {
    if (p.name == name) *text = std::to_string(p.value), found = true;
  }
  for (const dynamic_reconfigure::DoubleParameter& p : requested.doubles) {
    if (p.name != name) continue;
    std::ostringstream exact;
    exact.precision(17);
    exact << p.value;
    *text = exact.str();
    found = true;
  }
  for (const dynamic_reconfigure::StrParameter& p : requested.strs) {
    if (p.name == name) *text = p.value, found = true;
  }
  return found;
}

}  // namespace

void applyLiveConfig(const dynamic_reconfigure::Config& config, bowg::PipelineOptions* options) {
  for (const dynamic_reconfigure::BoolParameter& p : config.bools) {
    if (!isStartOnly(p.name)) bowg::setParameter(p.name, p.value ? 1.0 : 0.0, options);
  }
  for (const dynamic_reconfigure::IntParameter& p : config.ints) {
    if (!isStartOnly(p.name)) bowg::setParameter(p.name, static_cast<double>(p.value), options);
  }
  for (const dynamic_reconfigure::DoubleParameter& p : config.doubles) {
    if (!isStartOnly(p.name)) bowg::setParameter(p.name, p.value, options);
  }
  for (const dynamic_reconfigure::StrParameter& p : config.strs) {
    if (isStartOnly(p.name)) continue;
    throw bowg::InvalidParameter("live parameter " + p.name +
                                 ": string parameters cannot be tuned live");
  }
}

dynamic_reconfigure::Config liveConfig(const bowg::PipelineOptions& options) {
  dynamic_reconfigure::Config config;
  BoWGConfig::__getDefault__().__toMessage__(config);
  writeLiveConfig(options, &config);
  return config;
}

dynamic_reconfigure::ConfigDescription describeWithStartOnly(const bowg::PipelineOptions& options) {
  dynamic_reconfigure::ConfigDescription description = BoWGConfig::__getDescriptionMessage__();
  dynamic_reconfigure::Group group;
  group.name = "start_only";
  group.type = "collapse";
  group.parent = 0;
  group.id = 0;
  for (const dynamic_reconfigure::Group& g : description.groups) group.id = std::max(group.id, g.id);
  ++group.id;
  for (const bowg::ParameterInfo& info : bowg::parameterTable()) {
    if (info.live) continue;
    dynamic_reconfigure::ParamDescription p;
    p.name = info.name;
    p.type = descriptionType(info.type);
    p.level = 0;
    p.description = "start-only (read when the nodelet starts): " + info.description;
    group.parameters.push_back(p);
    // Default, minimum and maximum: the value in force, so that a GUI shows
    // it and offers no other.
    const std::string text = bowg::getParameter(info.name, options);
    addValue(info, text, &description.dflt);
    addValue(info, text, &description.min);
    addValue(info, text, &description.max);
  }
  description.groups.push_back(group);
  return description;
}

std::vector<std::string> startOnlyRequests(const dynamic_reconfigure::Config& requested,
                                           const bowg::PipelineOptions& options) {
  std::vector<std::string> messages;
  for (const bowg::ParameterInfo& info : bowg::parameterTable()) {
    if (info.live) continue;
    // The requested value in the table's spelling, read back through a copy
    // of the options so that 8 and 8.0, or "1" and true, compare equal.
    std::string text;
    if (!requestedText(requested, info.name, &text)) continue;
    const std::string in_force = bowg::getParameter(info.name, options);
    bowg::PipelineOptions wanted = options;
    try {
      bowg::setParameter(info.name, text, &wanted);
      if (bowg::getParameter(info.name, wanted) == in_force) continue;
    } catch (const bowg::InvalidParameter&) {
      // Not even a valid value: reported as a start-only change all the same.
    }
    messages.push_back(info.name + " is start-only (read when the nodelet starts): set it in "
                       "the preset or on the parameter server and restart the nodelet; " +
                       in_force + " stays in force");
  }
  return messages;
}

void writeLiveConfig(const bowg::PipelineOptions& options, dynamic_reconfigure::Config* config) {
  // getParameter's text is the form setParameter parses: "true"/"false" for
  // booleans, decimal numbers otherwise.
  for (dynamic_reconfigure::BoolParameter& p : config->bools) {
    p.value = bowg::getParameter(p.name, options) == "true";
  }
  for (dynamic_reconfigure::IntParameter& p : config->ints) {
    p.value = std::stoi(bowg::getParameter(p.name, options));
  }
  for (dynamic_reconfigure::DoubleParameter& p : config->doubles) {
    p.value = std::stod(bowg::getParameter(p.name, options));
  }
}

}  // namespace bowg_ros
