#include "reconfigure.h"

namespace marble_maze_ros {
namespace mm = marble_maze;

namespace {

const char* typeName(mm::ParamInfo::Type type) {
  switch (type) {
    case mm::ParamInfo::Type::Number:
      return "double";
    case mm::ParamInfo::Type::Whole:
      return "int";
    default:
      return "str";
  }
}

/// dynamic_reconfigure's enum description (a Python literal its GUI reads).
std::string enumOf(const mm::ParamInfo& info) {
  if (info.type != mm::ParamInfo::Type::Choice) return "";
  std::string items;
  for (const std::string& name : info.choices)
    items += (items.empty() ? "" : ", ") + std::string("{'name': '") + name +
             "', 'type': 'str', 'value': '" + name + "', 'srcline': 0, 'srcfile': '', " +
             "'cconsttype': 'const char * const', 'ctype': 'std::string', 'description': ''}";
  return "{'enum': [" + items + "], 'enum_description': '" + info.key + "'}";
}

void add(const mm::ParamInfo& info, const std::string& value, dynamic_reconfigure::Config* c) {
  double number = 0;
  const bool numeric = mm::parseFiniteNumber(value, &number);
  if (info.type == mm::ParamInfo::Type::Number) {
    dynamic_reconfigure::DoubleParameter p;
    p.name = info.key;
    p.value = numeric ? number : 0;
    c->doubles.push_back(p);
  } else if (info.type == mm::ParamInfo::Type::Whole) {
    dynamic_reconfigure::IntParameter p;
    p.name = info.key;
    p.value = numeric ? static_cast<int>(number) : 0;
    c->ints.push_back(p);
  } else {
    dynamic_reconfigure::StrParameter p;
    p.name = info.key;
    p.value = value;
    c->strs.push_back(p);
  }
}

}  // namespace

Reconfigure::Reconfigure(std::vector<mm::ParamInfo> extra,
                         std::function<std::string(const Changes&)> apply,
                         std::function<std::string(const std::string&)> current)
    : apply_(std::move(apply)), current_(std::move(current)) {
  for (const mm::ParamInfo& info : mm::paramInfos())
    if (info.live) keys_.push_back(info);
  keys_.insert(keys_.end(), extra.begin(), extra.end());
}

void Reconfigure::advertise(ros::NodeHandle pnh) {
  descriptions_pub_ =
      pnh.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true);
  updates_pub_ = pnh.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true);
  descriptions_pub_.publish(description());
  publishUpdate();
  set_srv_ = pnh.advertiseService("set_parameters", &Reconfigure::onSet, this);
}

dynamic_reconfigure::ConfigDescription Reconfigure::description() const {
  dynamic_reconfigure::ConfigDescription description;
  dynamic_reconfigure::Group group;
  group.name = "Default";
  group.id = 0;
  group.parent = 0;
  for (const mm::ParamInfo& info : keys_) {
    dynamic_reconfigure::ParamDescription p;
    p.name = info.key;
    p.type = typeName(info.type);
    p.level = 0;
    p.description = info.help + (info.unit.empty() ? "" : " [" + info.unit + "]");
    p.edit_method = enumOf(info);
    group.parameters.push_back(p);
  }
  description.groups.push_back(group);
  description.min =
      config([](const mm::ParamInfo& i) { return i.choices.empty() ? mm::exactText(i.min) : ""; });
  description.max =
      config([](const mm::ParamInfo& i) { return i.choices.empty() ? mm::exactText(i.max) : ""; });
  description.dflt = config([this](const mm::ParamInfo& i) { return current_(i.key); });
  return description;
}

dynamic_reconfigure::Config Reconfigure::config(
    const std::function<std::string(const mm::ParamInfo&)>& value) const {
  dynamic_reconfigure::Config c;
  for (const mm::ParamInfo& info : keys_) add(info, value(info), &c);
  dynamic_reconfigure::GroupState state;
  state.name = "Default";
  state.state = true;
  state.id = 0;
  state.parent = 0;
  c.groups.push_back(state);
  return c;
}

void Reconfigure::publishUpdate() {
  if (updates_pub_)
    updates_pub_.publish(config([this](const mm::ParamInfo& i) { return current_(i.key); }));
}

bool Reconfigure::onSet(dynamic_reconfigure::Reconfigure::Request& req,
                        dynamic_reconfigure::Reconfigure::Response& res) {
  // Only what differs from the values in force: a client sends them all.
  Changes changes;
  const auto consider = [&](const std::string& key, const std::string& value) {
    for (const mm::ParamInfo& info : keys_) {
      if (info.key != key) continue;
      double asked = 0, now = 0;
      const std::string in_force = current_(key);
      const bool same = (mm::parseFiniteNumber(value, &asked) &&
                         mm::parseFiniteNumber(in_force, &now) && asked == now) ||
                        value == in_force;
      if (!same) changes.emplace_back(key, value);
      return;
    }
    ROS_WARN("reconfigure: '%s' is not a key this node changes while running; ignored",
             key.c_str());
  };
  for (const auto& p : req.config.doubles) consider(p.name, mm::exactText(p.value));
  for (const auto& p : req.config.ints) consider(p.name, std::to_string(p.value));
  for (const auto& p : req.config.strs) consider(p.name, p.value);
  for (const auto& p : req.config.bools) consider(p.name, p.value ? "true" : "false");
  if (!changes.empty()) {
    const std::string why = apply_(changes);
    if (!why.empty())
      ROS_WARN("reconfigure refused, nothing changed: %s", why.c_str());
    else
      for (const auto& [key, value] : changes)
        ROS_INFO("reconfigure: %s = %s", key.c_str(), current_(key).c_str());
  }
  res.config = config([this](const mm::ParamInfo& i) { return current_(i.key); });
  if (updates_pub_) updates_pub_.publish(res.config);
  return true;
}

}  // namespace marble_maze_ros
