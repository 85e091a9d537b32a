// Live tuning through dynamic_reconfigure (rqt_reconfigure, dynamic_reconfigure's clients): the
// protocol served by hand so that the description comes from the core's key table (each live
// key's type, range and choices) rather than from a second list in a .cfg file. A change is
// validated as the parameters are, takes effect at the next step, or is refused with a warning
// naming the key, the values in force staying.
#pragma once

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "marble_maze/params.h"

namespace marble_maze_ros {

class Reconfigure {
 public:
  using Changes = std::vector<std::pair<std::string, std::string>>;  // key, value as text
  /// `apply` makes the changes (all or none) and returns "", or why not; `current` gives a
  /// key's value in force as text. `extra` are keys of the node's own, described like the core's.
  Reconfigure(std::vector<marble_maze::ParamInfo> extra,
              std::function<std::string(const Changes&)> apply,
              std::function<std::string(const std::string&)> current);

  /// Serves the protocol under the private node handle: the latched description and values in
  /// force, and the set_parameters service.
  void advertise(ros::NodeHandle pnh);

  /// Tells the clients the values in force (after a change made otherwise, such as a new maze).
  void publishUpdate();

  /// Every live key with its type, help, choices, range and the value in force as its default.
  dynamic_reconfigure::ConfigDescription description() const;

  /// set_parameters: makes the keys whose values differ from those in force, all or none, and
  /// answers with the values in force afterwards (the old ones when refused).
  bool onSet(dynamic_reconfigure::Reconfigure::Request& req,
             dynamic_reconfigure::Reconfigure::Response& res);

 private:
  dynamic_reconfigure::Config config(
      const std::function<std::string(const marble_maze::ParamInfo&)>& value) const;

  std::vector<marble_maze::ParamInfo> keys_;
  std::function<std::string(const Changes&)> apply_;
  std::function<std::string(const std::string&)> current_;
  ros::Publisher descriptions_pub_, updates_pub_;
  ros::ServiceServer set_srv_;
};

}  // namespace marble_maze_ros
