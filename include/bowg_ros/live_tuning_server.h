// The dynamic_reconfigure protocol of the nodelet: the ~set_parameters
// service, ~parameter_descriptions and ~parameter_updates (latched), as
// dynparam and rqt_reconfigure expect them. Our own rather than
// dynamic_reconfigure::Server because that server clamps a request into the
// cfg's ranges before its callback sees it: "min_score 99" would silently
// become 10. Here the callback gets the request as sent, so an out-of-range
// value is refused with a message naming the range, and a start-only
// parameter (listed in the description, live_parameters.h) with a message
// saying so.
#pragma once

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

#include <functional>
#include <mutex>

namespace bowg_ros {

class LiveTuningServer {
 public:
  /// Gets the request as the client sent it (only the parameters it sets);
  /// returns the live values in force afterwards (applied, corrected or kept).
  using Apply = std::function<dynamic_reconfigure::Config(const dynamic_reconfigure::Config&)>;

  /// Advertises on `pnh` and publishes `description` and `in_force`.
  LiveTuningServer(const ros::NodeHandle& pnh,
                   const dynamic_reconfigure::ConfigDescription& description,
                   const dynamic_reconfigure::Config& in_force, Apply apply);

 private:
  bool set(dynamic_reconfigure::Reconfigure::Request& req,
           dynamic_reconfigure::Reconfigure::Response& res);
  /// Publishes the values in force and writes them to the parameter server
  /// (as dynamic_reconfigure's server does), so that `rosparam get` agrees.
  void publish(const dynamic_reconfigure::Config& in_force);

  ros::NodeHandle pnh_;
  Apply apply_;
  std::mutex mutex_;  ///< one request at a time, published in order
  ros::Publisher descriptions_, updates_;
  ros::ServiceServer service_;
};

}  // namespace bowg_ros
