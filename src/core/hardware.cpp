#include "swarm_transport/core/hardware.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace swarm_transport {
namespace core {
namespace {

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }

double Clamp(double v, double limit) {
  if (!std::isfinite(v)) return 0.0;
  return std::max(-limit, std::min(limit, v));
}

}  // namespace

bool ParsePoseSource(const std::string& name, PoseSource* out) {
  if (name == "odom") {
    *out = PoseSource::kOdom;
  } else if (name == "tf") {
    *out = PoseSource::kTf;
  } else {
    return false;
  }
  return true;
}

const char* PoseSourceName(PoseSource source) { return source == PoseSource::kTf ? "tf" : "odom"; }

std::string HardwareOptions::Validate() const {
  std::ostringstream os;
  if (!Positive(max_linear_m_s)) {
    os << "~max_linear_m_s must be a speed > 0 (m/s) but is " << max_linear_m_s;
  } else if (!Positive(max_angular_rad_s)) {
    os << "~max_angular_rad_s must be a turn rate > 0 (rad/s) but is " << max_angular_rad_s;
  } else if (!Positive(pose_timeout_s)) {
    os << "~pose_timeout_s must be an age > 0 (s) but is " << pose_timeout_s;
  } else if (!Positive(heard_timeout_s)) {
    os << "~heard_timeout_s must be an age > 0 (s) but is " << heard_timeout_s;
  } else if (!std::isfinite(radio_loss) || radio_loss < 0.0 || radio_loss > 1.0) {
    os << "/swarm/radio_loss must be a probability in [0, 1] but is " << radio_loss;
  } else if (pose_source == PoseSource::kOdom && odom_topic.empty()) {
    os << "~odom_topic must name a topic";
  } else if (pose_source == PoseSource::kTf && (fixed_frame.empty() || base_frame.empty())) {
    os << "~fixed_frame and ~base_frame must name frames";
  } else if (pose_source == PoseSource::kTf && fixed_frame == base_frame) {
    os << "~fixed_frame and ~base_frame must differ but both are " << fixed_frame;
  }
  return os.str();
}

Velocity LimitSpeed(const Velocity& command, double max_linear_m_s, double max_angular_rad_s) {
  return Velocity{Clamp(command.linear, max_linear_m_s), Clamp(command.angular, max_angular_rad_s)};
}

void PoseWatch::Took(double stamp_s) {
  if (!std::isfinite(stamp_s)) return;
  if (!has_pose_ || stamp_s > stamp_s_) stamp_s_ = stamp_s;
  has_pose_ = true;
}

double PoseWatch::AgeS(double now_s) const {
  return has_pose_ ? now_s - stamp_s_ : std::numeric_limits<double>::infinity();
}

bool PoseWatch::Check(double now_s, Change* change) {
  const bool fresh = has_pose_ && AgeS(now_s) <= timeout_s_;
  *change = fresh == fresh_ ? Change::kNone : (fresh ? Change::kFresh : Change::kStale);
  fresh_ = fresh;
  return fresh;
}

}  // namespace core
}  // namespace swarm_transport
