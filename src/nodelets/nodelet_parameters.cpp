// LoopDetectorNodelet: the private parameters. The nodelet's own are read
// here; every other one must be a row of the engine's parameter table.
#include <cmath>
#include <sstream>

#include "loop_detector_nodelet.h"

namespace bowg_ros {

namespace {

/// The nodelet's own private parameters (not engine options); every other
/// private parameter must be a row of the engine's parameter table.
const char* const kNodeParameters[] = {
    "vocabulary_path",
    "queue_size",
    "min_keyframe_interval",
    "min_keyframe_distance",
    "use_compressed",
    "use_features_input",
    "publish_correspondences",
    "database_load_path",
    "database_save_path",
    "debug_image_cache",
    "image_transport",
    "diagnostic_period",
    "reset_on_time_jump",
    "debug_thumbnail_size",
    "diagnostics_window",
    "mission_name",
    "mission_id",
    "reference_maps",
    "odometry_wait",
};

bool isNodeParameter(const std::string& name) {
  for (const char* p : kNodeParameters) {
    if (name == p) return true;
  }
  return false;
}

}  // namespace

bool LoopDetectorNodelet::loadParameters(ros::NodeHandle& pnh) {
  pnh.param<std::string>("vocabulary_path", vocabulary_path_, "");
  pnh.param("queue_size", queue_size_, 2);
  pnh.param("min_keyframe_interval", gate_options_.min_interval, 0.0);
  pnh.param("min_keyframe_distance", gate_options_.min_distance, 0.0);
  pnh.param("reset_on_time_jump", gate_options_.time_jump_reset, 0.0);
  pnh.param("use_compressed", use_compressed_, false);
  pnh.param("use_features_input", use_features_input_, false);
  pnh.param("publish_correspondences", publish_correspondences_, false);
  pnh.param<std::string>("database_load_path", database_load_path_, "");
  pnh.param<std::string>("database_save_path", database_save_path_, "");
  if (pnh.hasParam("mission_name") && !pnh.getParam("mission_name", mission_name_)) {
    return fatal("~mission_name must be a string (a name like 2025 needs quotes: '2025')");
  }
  pnh.param("mission_id", mission_id_, -1);
  if (pnh.hasParam("reference_maps") && !pnh.getParam("reference_maps", reference_maps_)) {
    std::string one;
    if (!pnh.getParam("reference_maps", one)) {
      return fatal("~reference_maps must be a list of database files (or one file name)");
    }
    reference_maps_.assign(1, one);
  }
  if (mission_id_ < -1) {
    return fatal("~mission_id must be >= 0, or -1 for the next free id (got " +
                 std::to_string(mission_id_) + ")");
  }
  int debug_image_cache = 200;
  pnh.param("debug_image_cache", debug_image_cache, debug_image_cache);
  ThumbnailOptions thumbnail_options;
  pnh.param("debug_thumbnail_size", thumbnail_options.max_side, thumbnail_options.max_side);
  pnh.param("diagnostics_window", diagnostics_window_, 30.0);
  if (!(diagnostics_window_ > 0.0) || !std::isfinite(diagnostics_window_)) {
    return fatal("~diagnostics_window must be a finite number of seconds > 0 (got " +
                 std::to_string(diagnostics_window_) + ")");
  }
  pnh.param("odometry_wait", odometry_wait_, 0.2);
  if (!(odometry_wait_ >= 0.0) || !std::isfinite(odometry_wait_)) {
    return fatal("~odometry_wait must be a finite number of seconds >= 0 (got " +
                 std::to_string(odometry_wait_) + ")");
  }
  if (queue_size_ < 1) {
    return fatal("~queue_size must be >= 1 (got " + std::to_string(queue_size_) + ")");
  }
  try {
    gate_options_.validate();
    debug_images_ = DebugImagePublisher(thumbnail_options, debug_image_cache);
  } catch (const std::exception& e) {
    return fatal(e.what());
  }
  return loadEngineParameters(pnh);
}

bool LoopDetectorNodelet::loadEngineParameters(ros::NodeHandle& pnh) {
  // Engine options: every other private parameter must be a table row, so a
  // misspelled key is an error instead of a silently ignored setting.
  std::vector<std::string> names;
  ros::param::getParamNames(names);
  const std::string prefix = pnh.getNamespace() + "/";
  std::map<std::string, std::string> values;
  for (const std::string& full : names) {
    if (full.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string name = full.substr(prefix.size());
    if (name.find('/') != std::string::npos || isNodeParameter(name)) continue;
    XmlRpc::XmlRpcValue v;
    if (!pnh.getParam(name, v)) continue;
    switch (v.getType()) {
      case XmlRpc::XmlRpcValue::TypeBoolean:
        values[name] = bool(v) ? "true" : "false";
        break;
      case XmlRpc::XmlRpcValue::TypeInt:
        values[name] = std::to_string(int(v));
        break;
      case XmlRpc::XmlRpcValue::TypeDouble: {
        std::ostringstream s;
        s.precision(17);
        s << double(v);
        values[name] = s.str();
        break;
      }
      case XmlRpc::XmlRpcValue::TypeString:
        values[name] = std::string(v);
        break;
      default:
        return fatal("parameter " + full + ": only scalars are allowed");
    }
  }
  try {
    bowg::applyParameters(values, &options_, pnh.getNamespace());
  } catch (const std::exception& e) {
    return fatal(std::string("invalid parameters: ") + e.what());
  }
  return true;
}

}  // namespace bowg_ros
