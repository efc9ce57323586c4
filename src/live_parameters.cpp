// dynamic_reconfigure <-> options by name (see live_parameters.h).
#include "bowg_ros/live_parameters.h"

#include <string>

#include "bowg/core/errors.h"

namespace bowg_ros {

void applyLiveConfig(const dynamic_reconfigure::Config& config, bowg::PipelineOptions* options) {
  for (const dynamic_reconfigure::BoolParameter& p : config.bools) {
    bowg::setParameter(p.name, p.value ? 1.0 : 0.0, options);
  }
  for (const dynamic_reconfigure::IntParameter& p : config.ints) {
    bowg::setParameter(p.name, static_cast<double>(p.value), options);
  }
  for (const dynamic_reconfigure::DoubleParameter& p : config.doubles) {
    bowg::setParameter(p.name, p.value, options);
  }
  if (!config.strs.empty()) {
    throw bowg::InvalidParameter("live parameter " + config.strs.front().name +
                                 ": string parameters cannot be tuned live");
  }
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
