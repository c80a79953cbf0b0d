#include "swarm_transport/ros/simulator/visuals.h"

#include <geometry_msgs/TransformStamped.h>
#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <utility>

#include "swarm_transport/core/metrics.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace sim {
namespace {

constexpr std::uint32_t kMarkersQueue = 2;
// Marker look: z thickness of flat shapes (m), alpha of zones, objects and range circles.
constexpr double kFlatM = 0.02;
constexpr float kZoneAlpha = 0.35f;
constexpr float kObjectAlpha = 0.6f;
constexpr float kRangeAlpha = 0.08f;
constexpr float kTrailAlpha = 0.6f;
constexpr double kTargetDiameterM = 0.3;
constexpr double kLeaderRingM = 0.4;  // diameter of a leader's white ring
constexpr double kLineM = 0.03;       // width of lines: arena, trails, target outlines
constexpr double kArrowWidth = 0.35;  // an arrow's shaft width, of its length
constexpr double kArrowZ = 0.08;      // arrows above the flat shapes
constexpr double kLeaderZ = 0.04;     // leaders' rings above objects, below arrows
constexpr double kTextHeightM = 0.4;  // the status line above the arena
// 1 / golden ratio: consecutive ids get well separated hues.
constexpr double kHueStep = 0.618033988749895;

// HSV (all in [0, 1]) plus alpha to a colour.
std_msgs::ColorRGBA Hsv(double h, double s, double v, float alpha) {
  const double i = std::floor(h * 6.0);
  const double f = h * 6.0 - i;
  const double p = v * (1.0 - s);
  const double q = v * (1.0 - f * s);
  const double t = v * (1.0 - (1.0 - f) * s);
  const double rgb[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
  const int k = static_cast<int>(i) % 6;
  const double r = rgb[k][0], g = rgb[k][1], b = rgb[k][2];
  std_msgs::ColorRGBA c;
  c.r = static_cast<float>(r);
  c.g = static_cast<float>(g);
  c.b = static_cast<float>(b);
  c.a = alpha;
  return c;
}

std_msgs::ColorRGBA Rgba(float r, float g, float b, float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

// Swarm k's colour (swarms numbered by their lowest robot): first a palette of bright colours
// unlike the object's orange, the danger zones' red, the targets' green and the leaders' white;
// then well separated hues.
std_msgs::ColorRGBA SwarmColour(std::size_t k, float alpha) {
  static constexpr float kPalette[][3] = {
      {0.10f, 0.75f, 1.00f},  // sky blue
      {1.00f, 0.35f, 0.85f},  // magenta
      {1.00f, 0.92f, 0.20f},  // yellow
      {0.55f, 0.45f, 1.00f},  // violet
      {0.30f, 1.00f, 0.95f},  // cyan
      {1.00f, 0.65f, 0.75f},  // pink
      {0.75f, 0.90f, 0.35f},  // lime
      {0.35f, 0.50f, 0.95f},  // blue
  };
  constexpr std::size_t kColours = sizeof(kPalette) / sizeof(kPalette[0]);
  if (k < kColours) return Rgba(kPalette[k][0], kPalette[k][1], kPalette[k][2], alpha);
  return Hsv(std::fmod(0.55 + static_cast<double>(k - kColours) * kHueStep, 1.0), 0.6, 0.95, alpha);
}

geometry_msgs::Quaternion YawQuaternion(double yaw_rad) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(0.5 * yaw_rad);
  q.w = std::cos(0.5 * yaw_rad);
  return q;
}

visualization_msgs::Marker MakeMarker(const std::string& ns, int id, int type, ros::Time stamp) {
  visualization_msgs::Marker m;
  m.header.frame_id = names::kWorldFrame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  return m;
}

}  // namespace

Visuals::Visuals(ros::NodeHandle nh, VisualsParams params) : params_(std::move(params)) {
  markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>(names::kMarkers, kMarkersQueue);
  if (params_.tf) tf_broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();
}

void Visuals::Start(ros::WallTime now) { next_wall_ = now; }

bool Visuals::Due() {
  if (!(params_.rate_hz > 0.0)) return false;
  const ros::WallTime now = ros::WallTime::now();
  if (now < next_wall_) return false;
  const ros::WallDuration period(1.0 / params_.rate_hz);
  next_wall_ += period;
  if (next_wall_ < now) next_wall_ = now + period;
  return true;
}

void Visuals::Publish(const World2D& world, const LiveMissions& missions, ros::Time stamp,
                      std::uint64_t tick) {
  if (markers_pub_.getNumSubscribers() > 0) PublishMarkers(world, missions, stamp, tick);
  if (tf_broadcaster_) PublishTransforms(world, stamp);
}

void Visuals::Shutdown() {
  markers_pub_.shutdown();
  tf_broadcaster_.reset();
}

void Visuals::Record(const World2D& world) {
  if (params_.trail_ticks <= 0) return;
  const std::size_t keep = static_cast<std::size_t>(params_.trail_ticks) + 1;
  for (auto it = trails_.begin(); it != trails_.end();) {
    it = world.Find(it->first) == nullptr ? trails_.erase(it) : std::next(it);  // gone robots
  }
  for (const auto& entry : world.robots()) {
    std::deque<core::Vec2>& trail = trails_[entry.first];
    trail.push_back(entry.second.pose.position);
    while (trail.size() > keep) trail.pop_front();
  }
}

visualization_msgs::MarkerArray BuildMarkers(const World2D& world, const LiveMissions& missions,
                                             const VisualsParams& params, ros::Time stamp,
                                             std::uint64_t tick, const Trails& trails) {
  using visualization_msgs::Marker;
  const double r = world.params().robot_radius_m;
  const double size = world.params().world_size_m;
  visualization_msgs::MarkerArray array;
  auto add = [&array](const Marker& m) { array.markers.push_back(m); };
  auto point = [](double x, double y) {
    geometry_msgs::Point p;
    p.x = x;
    p.y = y;
    return p;
  };

  // The arena's border.
  Marker arena = MakeMarker("arena", 0, Marker::LINE_STRIP, stamp);
  for (const auto& corner :
       {std::make_pair(0.0, 0.0), std::make_pair(size, 0.0), std::make_pair(size, size),
        std::make_pair(0.0, size), std::make_pair(0.0, 0.0)}) {
    arena.points.push_back(point(corner.first, corner.second));
  }
  arena.scale.x = kLineM;
  arena.color = Rgba(0.75f, 0.75f, 0.75f, 1.0f);
  add(arena);

  // One colour per swarm (robots linked hop by hop within the local range).
  std::vector<core::Vec2> positions;
  positions.reserve(world.size());
  for (const auto& entry : world.robots()) positions.push_back(entry.second.pose.position);
  const core::SwarmComponents swarms(positions, params.local_range_m);
  const double length = std::max(3.0 * r, kArrowMinM);
  std::size_t index = 0;
  for (const auto& entry : world.robots()) {
    const core::Pose2& pose = entry.second.pose;
    const double yaw = pose.heading.radians();
    const std_msgs::ColorRGBA colour = SwarmColour(swarms.ComponentOf(index++), 1.0f);
    // An arrow centred on the robot, pointing where it heads.
    Marker arrow = MakeMarker("robots", entry.first, Marker::ARROW, stamp);
    arrow.pose.position.x = pose.position.x - 0.5 * length * std::cos(yaw);
    arrow.pose.position.y = pose.position.y - 0.5 * length * std::sin(yaw);
    arrow.pose.position.z = kArrowZ;
    arrow.pose.orientation = YawQuaternion(yaw);
    arrow.scale.x = length;
    arrow.scale.y = kArrowWidth * length;
    arrow.scale.z = kArrowWidth * length;
    arrow.color = colour;
    add(arrow);
    const auto trail = trails.find(entry.first);
    if (trail != trails.end() && trail->second.size() >= 2) {
      Marker line = MakeMarker("trails", entry.first, Marker::LINE_STRIP, stamp);
      for (const core::Vec2& p : trail->second) line.points.push_back(point(p.x, p.y));
      line.scale.x = kLineM;
      line.color = colour;
      line.color.a = kTrailAlpha;
      add(line);
    }
    if (params.range_circles) {
      Marker circle = MakeMarker("ranges", entry.first, Marker::CYLINDER, stamp);
      circle.pose.position.x = pose.position.x;
      circle.pose.position.y = pose.position.y;
      circle.scale.x = circle.scale.y = 2.0 * params.local_range_m;
      circle.scale.z = 0.5 * kFlatM;
      circle.color = colour;
      circle.color.a = kRangeAlpha;
      add(circle);
    }
  }

  int zone_part = 0;
  for (const core::Zone& zone : params.danger_zones) {
    for (const core::Primitive& part : zone.shape.parts()) {
      const bool is_rect = part.kind == core::Primitive::Kind::kRect;
      Marker m =
          MakeMarker("danger_zones", zone_part++, is_rect ? Marker::CUBE : Marker::CYLINDER, stamp);
      if (is_rect) {
        m.pose.position.x = part.rect.centre.x;
        m.pose.position.y = part.rect.centre.y;
        m.scale.x = part.rect.size.x;
        m.scale.y = part.rect.size.y;
      } else {
        m.pose.position.x = part.circle.centre.x;
        m.pose.position.y = part.circle.centre.y;
        m.scale.x = m.scale.y = 2.0 * part.circle.radius;
      }
      m.scale.z = kFlatM;
      m.color = Rgba(0.9f, 0.1f, 0.1f, kZoneAlpha);
      add(m);
    }
  }

  const std_msgs::ColorRGBA green = Rgba(0.2f, 0.85f, 0.3f, 0.9f);
  for (const auto& entry : missions) {
    const LiveMission& mission = entry.second;
    const bool has_object = mission.object_size.x > 0.0 && mission.object_size.y > 0.0;
    if (has_object) {
      Marker object = MakeMarker("objects", entry.first, Marker::CUBE, stamp);
      object.pose.position.x = mission.object_position.x;
      object.pose.position.y = mission.object_position.y;
      object.scale.x = mission.object_size.x;
      object.scale.y = mission.object_size.y;
      object.scale.z = 2.0 * kFlatM;
      object.color = Rgba(0.85f, 0.55f, 0.15f, kObjectAlpha);
      add(object);
      // Where it goes: its outline at the target.
      Marker outline = MakeMarker("target_outlines", entry.first, Marker::LINE_STRIP, stamp);
      const double hx = 0.5 * mission.object_size.x;
      const double hy = 0.5 * mission.object_size.y;
      const core::Vec2 t = mission.target;
      for (const auto& c :
           {std::make_pair(-hx, -hy), std::make_pair(hx, -hy), std::make_pair(hx, hy),
            std::make_pair(-hx, hy), std::make_pair(-hx, -hy)}) {
        outline.points.push_back(point(t.x + c.first, t.y + c.second));
      }
      outline.scale.x = kLineM;
      outline.color = green;
      add(outline);
      // And the way there: a line from the object's centre to the target.
      Marker way = MakeMarker("target_lines", entry.first, Marker::LINE_LIST, stamp);
      way.points.push_back(point(mission.object_position.x, mission.object_position.y));
      way.points.push_back(point(t.x, t.y));
      way.scale.x = 0.5 * kLineM;
      way.color = green;
      way.color.a = 0.5f;
      add(way);
    }
    Marker target = MakeMarker("targets", entry.first, Marker::CYLINDER, stamp);
    target.pose.position.x = mission.target.x;
    target.pose.position.y = mission.target.y;
    target.scale.x = target.scale.y = kTargetDiameterM;
    target.scale.z = kFlatM;
    target.color = green;
    add(target);
    // Leaders: a white ring under the robot's arrow.
    for (std::uint16_t id : mission.leaders) {
      const Robot* robot = world.Find(id);
      if (robot == nullptr) continue;
      Marker halo = MakeMarker("leaders", id, Marker::CYLINDER, stamp);
      halo.pose.position.x = robot->pose.position.x;
      halo.pose.position.y = robot->pose.position.y;
      halo.pose.position.z = kLeaderZ;
      halo.scale.x = halo.scale.y = kLeaderRingM;
      halo.scale.z = kFlatM;
      halo.color = Rgba(1.0f, 1.0f, 1.0f, 0.85f);
      add(halo);
    }
  }

  // The line of text above the arena: tick, swarm count, each mission's phase.
  std::ostringstream text;
  text << "tick " << tick << "   " << swarms.SwarmCount() << " swarm"
       << (swarms.SwarmCount() == 1 ? "" : "s");
  for (const auto& entry : missions) {
    text << "   mission " << entry.first << " "
         << (entry.second.phase >= 0
                 ? core::PhaseName(static_cast<core::MissionPhase>(entry.second.phase))
                 : "ordered");
  }
  Marker label = MakeMarker("status", 0, Marker::TEXT_VIEW_FACING, stamp);
  label.pose.position.x = 0.5 * size;
  label.pose.position.y = size + kTextHeightM;
  label.scale.z = kTextHeightM;
  label.color = Rgba(1.0f, 1.0f, 1.0f, 1.0f);
  label.text = text.str();
  add(label);
  return array;
}

void Visuals::PublishMarkers(const World2D& world, const LiveMissions& missions, ros::Time stamp,
                             std::uint64_t tick) {
  using visualization_msgs::Marker;
  visualization_msgs::MarkerArray array =
      BuildMarkers(world, missions, params_, stamp, tick, trails_);
  std::set<std::pair<std::string, int>> shown;
  for (const Marker& m : array.markers) shown.emplace(m.ns, m.id);

  // Whatever was on screen and is gone now (killed robots, deleted objects) is deleted.
  for (const auto& key : shown_) {
    if (shown.count(key) != 0) continue;
    Marker gone = MakeMarker(key.first, key.second, Marker::ARROW, stamp);
    gone.action = Marker::DELETE;
    array.markers.push_back(gone);
  }
  shown_ = std::move(shown);
  markers_pub_.publish(array);
}

void Visuals::PublishTransforms(const World2D& world, ros::Time stamp) {
  std::vector<geometry_msgs::TransformStamped> transforms;
  transforms.reserve(world.size());
  for (const auto& entry : world.robots()) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = names::kWorldFrame;
    // tf frame ids are not graph names: they cannot be resolved, so they are composed here.
    t.child_frame_id = names::RobotNamespace(entry.first) + "/" + names::kBaseLink;
    t.transform.translation.x = entry.second.pose.position.x;
    t.transform.translation.y = entry.second.pose.position.y;
    t.transform.rotation = YawQuaternion(entry.second.pose.heading.radians());
    transforms.push_back(t);
  }
  if (!transforms.empty()) tf_broadcaster_->sendTransform(transforms);
}

}  // namespace sim
}  // namespace swarm_transport
