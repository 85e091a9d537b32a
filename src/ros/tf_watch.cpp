#include "tf_watch.h"

#include "clock_owner.h"

namespace marble_maze_ros {

TfWatch::TfWatch(ros::NodeHandle& nh, Frames frames) : nh_(nh), frames_(std::move(frames)) {
  look_ = nh_.createWallTimer(ros::WallDuration(2.0),
                              [this](const ros::WallTimerEvent&) { lookAtPublishers(); });
  lookAtPublishers();
}

void TfWatch::lookAtPublishers() {
  const bool others = !otherPublishers("/tf", ros::this_node::getName()).empty();
  if (others && !tf_sub_)
    tf_sub_ = nh_.subscribe("/tf", 100, &TfWatch::onTf, this);  // (tf2_ros broadcasts on /tf)
  else if (!others && tf_sub_)
    tf_sub_.shutdown();
}

void TfWatch::onTf(const ros::MessageEvent<const tf2_msgs::TFMessage>& event) {
  const std::string& publisher = event.getPublisherName();
  if (publisher == ros::this_node::getName()) return;
  const std::string frame = ownFrameIn(*event.getConstMessage(), frames_);
  if (!frame.empty())
    ROS_WARN_THROTTLE(10,
                      "tf: %s broadcasts '%s' too, a frame of this node's; give each its own "
                      "~board_frame and ~marble_frame (a namespace gives them by default)",
                      publisher.c_str(), frame.c_str());
}

}  // namespace marble_maze_ros
