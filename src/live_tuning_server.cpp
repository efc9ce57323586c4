// The nodelet's dynamic_reconfigure protocol (see live_tuning_server.h).
#include "bowg_ros/live_tuning_server.h"

#include <utility>

namespace bowg_ros {

LiveTuningServer::LiveTuningServer(const ros::NodeHandle& pnh,
                                   const dynamic_reconfigure::ConfigDescription& description,
                                   const dynamic_reconfigure::Config& in_force, Apply apply)
    : pnh_(pnh), apply_(std::move(apply)) {
  descriptions_ =
      pnh_.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true);
  updates_ = pnh_.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true);
  descriptions_.publish(description);
  publish(in_force);
  service_ = pnh_.advertiseService("set_parameters", &LiveTuningServer::set, this);
}

bool LiveTuningServer::set(dynamic_reconfigure::Reconfigure::Request& req,
                           dynamic_reconfigure::Reconfigure::Response& res) {
  std::lock_guard<std::mutex> lock(mutex_);
  res.config = apply_(req.config);
  publish(res.config);
  return true;
}

void LiveTuningServer::publish(const dynamic_reconfigure::Config& in_force) {
  for (const auto& p : in_force.bools) pnh_.setParam(p.name, static_cast<bool>(p.value));
  for (const auto& p : in_force.ints) pnh_.setParam(p.name, p.value);
  for (const auto& p : in_force.doubles) pnh_.setParam(p.name, p.value);
  for (const auto& p : in_force.strs) pnh_.setParam(p.name, p.value);
  updates_.publish(in_force);
}

}  // namespace bowg_ros
