#include "swarm_transport/ros/batch_run.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/Neighbors.h"
#include "swarm_transport/Robot_Continue.h"
#include "swarm_transport/Robot_Freeze.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/Update_Object.h"
#include "swarm_transport/core/metrics.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/core/robot_brain.h"
#include "swarm_transport/core/run_metrics.h"
#include "swarm_transport/ros/conversions.h"
#include "swarm_transport/ros/mission_relay.h"
#include "swarm_transport/ros/params.h"
#include "swarm_transport/ros/simulator_params.h"
#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/sim/radio.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace {

using core::MissionPhase;
using Clock = std::chrono::steady_clock;

// As launch/simulator.launch and launch/recorder.launch set them for an experiment.
constexpr double kIntegrationStepS = 0.01;
// The relay's sender of the run's order and the dispatcher's events.
constexpr char kDispatcherSender[] = "/mission_dispatcher";
constexpr double kSamplePeriodS = 10.0;

double Seconds(Clock::time_point from) {
  return std::chrono::duration<double>(Clock::now() - from).count();
}

// --- job.json ---------------------------------------------------------------------------------

template <typename T>
bool Get(const YAML::Node& root, const char* key, T* value, std::string* error,
         bool required = true) {
  const YAML::Node node = root[key];
  if (!node || node.IsNull()) {
    if (required) *error = std::string("job: '") + key + "' is missing";
    return !required;
  }
  try {
    *value = node.as<T>();
  } catch (const YAML::Exception&) {
    *error = std::string("job: '") + key + "' has the wrong type";
    return false;
  }
  return true;
}

// --- a small JSON writer for result.json ------------------------------------------------------

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out += buffer;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string JsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.17g", v);
  std::string text = buffer;
  // A float stays a float for the reader (Python's json: 0.0, not 0).
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text;
}

// Members in the order added; values are JSON text.
class JsonObject {
 public:
  JsonObject& Add(const std::string& key, const std::string& json) {
    members_.emplace_back(key, json);
    return *this;
  }
  // Nested objects get `indent` before their members.
  std::string Text(const std::string& indent = "") const {
    std::string out = "{";
    for (std::size_t i = 0; i < members_.size(); ++i) {
      out += i == 0 ? "\n" : ",\n";
      out += indent + " " + JsonString(members_[i].first) + ": " + members_[i].second;
    }
    return out + (members_.empty() ? "}" : "\n" + indent + "}");
  }

 private:
  std::vector<std::pair<std::string, std::string>> members_;
};

// --- the run ----------------------------------------------------------------------------------

// The leader's progress along its straight path and the size of its swarm at every tick (the
// experiment worker's LeaderTrack: thesis Fig. 7.6).
class LeaderTrack {
 public:
  LeaderTrack(std::uint16_t leader, core::Vec2 target, double local_range_m)
      : leader_(leader), target_(target), local_range_m_(local_range_m) {}

  void Add(const core::MetricsFrame& frame) {
    const long li = frame.IndexOf(leader_);
    if (li < 0) return;
    const core::Vec2 lp = frame.positions[static_cast<std::size_t>(li)];
    if (!start_) start_ = lp;
    const double total = std::hypot(target_.x - start_->x, target_.y - start_->y);
    const double left = std::hypot(target_.x - lp.x, target_.y - lp.y);
    const double progress =
        total > 0.0 ? std::min(1.0, std::max(0.0, 1.0 - left / total)) : 1.0;
    const core::SwarmComponents swarms(frame.positions, local_range_m_);
    const std::size_t swarm = swarms.SizeOfSwarmOf(static_cast<std::size_t>(li)) - 1;
    rows_.push_back({frame.tick, progress, swarm, swarms.SwarmCount()});
  }

  // The track ends at the arrival: later rows go, the arrival's row counts as the whole path.
  void Arrived(std::uint64_t tick) {
    rows_.erase(std::remove_if(rows_.begin(), rows_.end(),
                               [tick](const Row& r) { return r.tick > tick; }),
                rows_.end());
    if (!rows_.empty() && rows_.back().tick == tick) rows_.back().fraction = 1.0;
  }

  bool Write(const std::string& path) const {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (f == nullptr) return false;
    std::fputs("tick,path_fraction,leader_swarm,swarm_count\n", f);
    for (const Row& r : rows_) {
      std::fprintf(f, "%llu,%.6f,%zu,%zu\n", static_cast<unsigned long long>(r.tick), r.fraction,
                   r.swarm, r.count);
    }
    return std::fclose(f) == 0;
  }

 private:
  struct Row {
    std::uint64_t tick;
    double fraction;
    std::size_t swarm;
    std::size_t count;
  };
  std::uint16_t leader_;
  core::Vec2 target_;
  double local_range_m_;
  std::optional<core::Vec2> start_;
  std::vector<Row> rows_;
};

struct Robot {
  std::uint16_t id;
  core::RobotBrain brain;
  core::StatusSequencer statuses;
  Robot(std::uint16_t robot_id, const SwarmConfig& config) : id(robot_id), brain(robot_id, config) {}
};

class CsvOut {
 public:
  bool Open(const std::string& path, const char* header, std::string* error) {
    file_ = std::fopen(path.c_str(), "w");
    if (file_ == nullptr) {
      *error = "cannot write " + path;
      return false;
    }
    Line(header);
    return true;
  }
  void Line(const std::string& row) {
    if (file_ == nullptr) return;
    std::fputs(row.c_str(), file_);
    std::fputc('\n', file_);
  }
  bool Close() {
    if (file_ == nullptr) return true;
    const bool ok = std::fclose(file_) == 0;
    file_ = nullptr;
    return ok;
  }
  ~CsvOut() { Close(); }

 private:
  std::FILE* file_ = nullptr;
};

class Run {
 public:
  explicit Run(const BatchJob& job) : job_(job) {}

  bool SetUp(const XmlRpc::XmlRpcValue& base_config, std::string* error);
  void Tick();
  bool Finish(std::string* error);
  // result.json's members about the run (the job's come first).
  void AddResult(double setup_s, double ticking_s, double finish_s, JsonObject* o) const;
  bool over() const { return over_; }
  std::uint64_t tick() const { return tick_; }

 private:
  void TakeFrame();
  // One robot's tick on its round: what it says (its answer) and its command.
  void RobotTick(Robot* robot, const Neighbors& round, Tick_Answer* said, core::Velocity* command);
  void Observe(const Mission_Status& status);

  const BatchJob& job_;
  SwarmConfig config_;
  std::unique_ptr<sim::World2D> world_;
  std::unique_ptr<core::Rng> radio_rng_;
  std::unique_ptr<sim::Radio> radio_;
  std::vector<std::unique_ptr<Robot>> robots_;
  std::set<std::uint16_t> known_robots_;
  sim::LiveMissions missions_;
  std::optional<New_Mission> order_;  // released at tick 0
  std::unique_ptr<core::MissionBook> book_;  // the dispatcher's
  std::unique_ptr<core::RunMetrics> metrics_;
  std::unique_ptr<LeaderTrack> track_;
  std::string record_path_;
  CsvOut swarm_csv_;
  CsvOut missions_csv_;
  CsvOut trace_csv_;
  MissionRelay relay_;  // the simulator's lock-step relay
  std::uint64_t tick_ = 0;
  bool over_ = false;
  std::string end_;
  // What the experiment's runner sees of the mission: each new state with its tick, the last
  // status of a tick > 0, the last swarm sample.
  std::vector<std::pair<int, std::uint64_t>> phases_;
  std::optional<Mission_Status> last_status_;
  std::optional<core::SwarmSample> last_sample_;
  bool recorder_row_ = false;
  std::size_t logged_warnings_ = 0;
  // Collisions avoided while gathering: moves of mission robots before their transport (not
  // frozen for loading) that swerved or slowed for a robot in the way (result.json).
  std::uint64_t gathering_swerves_ = 0;
};

bool Run::SetUp(const XmlRpc::XmlRpcValue& base_config, std::string* error) {
  // /swarm as swarm.launch loads it: the base configuration, the run's YAML over it, the seed.
  XmlRpc::XmlRpcValue swarm = base_config;
  XmlRpc::XmlRpcValue over;
  if (!XmlRpcFromYamlFile(job_.config_path, &over, error)) return false;
  if (over.getType() == XmlRpc::XmlRpcValue::TypeStruct) MergeParams(over, &swarm);
  swarm["seed"] = static_cast<int>(job_.seed);
  if (!ConfigFromXmlRpc(swarm, &config_, error)) {
    *error = "/swarm: " + *error;
    return false;
  }
  // The simulator's parameters as swarm.launch sets them for a lock-step host_sim run.
  SimulatorParams sim_params;
  sim_params.swarm = config_;
  if (swarm.hasMember("radio_loss")) {
    XmlRpc::XmlRpcValue& loss = swarm["radio_loss"];
    if (loss.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
      sim_params.radio_loss = static_cast<double>(loss);
    } else if (loss.getType() == XmlRpc::XmlRpcValue::TypeInt) {
      sim_params.radio_loss = static_cast<int>(loss);
    } else {
      *error = "/swarm/radio_loss must be a number";
      return false;
    }
  }
  sim_params.robots = job_.robots;
  sim_params.placement = job_.placement;
  sim_params.placement_file = job_.placement_file;
  sim_params.clock = core::Clock::kLockstep;
  sim_params.integration_step_s = kIntegrationStepS;
  sim_params.radio_range_m = config_.flocking.local_range_m;
  *error = sim_params.Validate();
  if (error->empty()) *error = WorldParamsOf(sim_params).Validate();
  if (!error->empty()) return false;
  world_ = std::make_unique<sim::World2D>(WorldParamsOf(sim_params));
  int robots = job_.robots;
  if (!sim::PlaceInitialRobots(job_.placement, config_.seed, job_.placement_file, &robots,
                               world_.get(), error)) {
    if (error->empty()) *error = "the placement does not fit";
    return false;
  }
  radio_rng_ = std::make_unique<core::Rng>(config_.seed, sim::kRadioLossStream);
  radio_ = std::make_unique<sim::Radio>(RadioParamsOf(sim_params), radio_rng_.get());
  for (const auto& entry : world_->robots()) {
    robots_.push_back(std::make_unique<Robot>(entry.first, config_));
    known_robots_.insert(entry.first);
  }

  core::RunMetricsParams metrics;
  metrics.local_range_m = config_.flocking.local_range_m;
  metrics.goal_tolerance_m = config_.leader.goal_tolerance_m;
  metrics.sample_period_s = kSamplePeriodS;
  metrics.world_size_m = config_.flocking.world_size_m;
  metrics_ = std::make_unique<core::RunMetrics>(
      metrics, [this](core::RunMetrics::Level level, const std::string& text) {
        if (level == core::RunMetrics::Level::kWarn && logged_warnings_++ < 20) {
          std::fprintf(stderr, "%s/%s: recorder: %s\n", job_.setting.c_str(),
                       job_.run_name.c_str(), text.c_str());
        }
      });
  namespace fs = std::filesystem;
  std::error_code ec;
  record_path_ = (fs::path(job_.record_dir) / job_.run_name).string();
  fs::create_directories(record_path_, ec);
  if (ec) {
    *error = "cannot create " + record_path_ + ": " + ec.message();
    return false;
  }
  if (!swarm_csv_.Open(record_path_ + "/swarm_count.csv", core::RunMetrics::kSwarmHeader, error) ||
      !missions_csv_.Open(record_path_ + "/missions.csv", core::RunMetrics::kMissionsHeader,
                          error)) {
    return false;
  }
  if (job_.trace &&
      !trace_csv_.Open(job_.run_dir + "/trace.csv", "tick,robot_id,x,y,heading_deg", error)) {
    return false;
  }

  if (job_.has_mission) {
    // The dispatcher's ~submit: validated against the swarm, then published as its order.
    core::MissionBookParams book;
    book.world_size_m = config_.flocking.world_size_m;
    book.tick_period_s = config_.tick_period_s;
    book.loaded_delay_s = config_.loaded_delay_s;
    book.unloaded_delay_s = config_.unloaded_delay_s;
    book.static_zones = config_.danger_zones;
    book_ = std::make_unique<core::MissionBook>(book);
    const core::MissionBook::Verdict verdict =
        book_->Submit(ToMissionSpec(job_.mission), "service", true, false, known_robots_, 0.0);
    if (!verdict.accepted) {
      *error = "the dispatcher rejected the mission: " + verdict.message;
      return false;
    }
    order_ = ToNewMission(verdict.spec);
    order_->start_tick = 0;
    // The recorder follows it from the tick it enters (tick 0).
    const core::MissionSpec recorded = ToMissionSpec(*order_);
    core::MissionContext arena;
    arena.world_size_m = config_.flocking.world_size_m;
    if (core::ValidateMission(recorded, arena).empty()) metrics_->AddOrder(recorded, 0);
    if (job_.kind == "leader") {
      track_ = std::make_unique<LeaderTrack>(static_cast<std::uint16_t>(job_.leader_id),
                                             recorded.target, config_.flocking.local_range_m);
    }
  }
  return true;
}

void Run::TakeFrame() {
  core::MetricsFrame frame;
  frame.tick = tick_;
  frame.sim_time_s = static_cast<double>(tick_) * config_.tick_period_s;
  for (const auto& entry : world_->robots()) {
    // As /flock/positions carries them: float32.
    const Robot_Position p = ToRobotPosition(entry.first, entry.second.pose);
    if (!std::isfinite(p.pos_x) || !std::isfinite(p.pos_y)) continue;
    frame.ids.push_back(entry.first);
    frame.positions.push_back(core::Vec2{p.pos_x, p.pos_y});
    if (job_.trace) {
      char row[96];
      std::snprintf(row, sizeof(row), "%llu,%u,%.4f,%.4f,%.2f",
                    static_cast<unsigned long long>(tick_), static_cast<unsigned>(entry.first),
                    static_cast<double>(p.pos_x), static_cast<double>(p.pos_y),
                    static_cast<double>(p.angle));
      trace_csv_.Line(row);
    }
  }
  if (track_) track_->Add(frame);
  std::optional<core::SwarmSample> sample;
  metrics_->AddFrame(std::move(frame), &sample);
  if (sample) {
    swarm_csv_.Line(core::RunMetrics::SwarmRow(*sample));
    last_sample_ = sample;
  }
  for (const std::string& row : metrics_->TakeMissionRows()) {
    missions_csv_.Line(row);
    recorder_row_ = true;
  }
}

void Run::RobotTick(Robot* robot, const Neighbors& round, Tick_Answer* said,
                    core::Velocity* command) {
  core::RobotBrain& brain = robot->brain;
  // RobotNode::ApplyRelayed, in its order.
  for (const New_Mission& m : round.missions) {
    core::MissionTaken taken;
    if (brain.OnNewMission(ToMissionSpec(m), known_robots_, &taken).empty() &&
        taken.first_leader) {
      robot->statuses.Queue(taken.queued);
    }
  }
  for (const Update_Object& u : round.object_updates) {
    brain.OnObjectUpdate(u.mission_id, {u.object_position_x, u.object_position_y});
  }
  for (const Delete_Object& d : round.object_deletes) brain.OnObjectDelete(d.mission_id);
  for (const Robot_Freeze& f : round.freezes) brain.OnFreeze(f.robot_index_from, f.robot_index_to);
  for (const Robot_Continue& c : round.continues) {
    brain.OnContinue(c.robot_index_from, c.robot_index_to);
  }
  for (const Mission_Event& e : round.mission_events) {
    brain.OnEvent(e.mission_id, static_cast<core::MissionEventKind>(e.event), e.not_before_tick);
  }
  for (const Mission_Status& s : round.statuses) {
    brain.OnStatus(s.mission_id, static_cast<MissionPhase>(s.state));
  }
  // RobotNode::Tick: its outlets are always connected here.
  core::BrainTick step = brain.Tick(ToPerception(robot->id, round), round.tick, true);
  const std::optional<core::Carry>& carry = brain.last_plan().carry;
  if (carry && !carry->transport && !carry->loading && !brain.frozen() &&
      (step.move.outcome == core::MoveOutcome::kSwerved ||
       step.move.outcome == core::MoveOutcome::kSlowed)) {
    ++gathering_swerves_;
  }
  core::MissionOutbox& outbox = step.outbox;
  std::vector<core::StatusReport> progress;
  robot->statuses.Sequence(true, &outbox.statuses, &progress);
  *said = ToAnswerMessages(outbox, progress, round.tick, ros::Time(round.sim_time));
  // The simulator's OnCmdVel: a non-finite command stands.
  const geometry_msgs::Twist twist = ToTwist(step.command);
  *command = IsFinite(twist) ? ToVelocity(twist) : core::Velocity();
}

void Run::Observe(const Mission_Status& status) {
  // The runner: each new state with its tick; the last status of a tick > 0.
  if (job_.has_mission && status.mission_id == job_.mission.mission_id) {
    if (phases_.empty() || phases_.back().first != status.state) {
      phases_.emplace_back(status.state, status.tick);
    }
    if (status.tick > 0) last_status_ = status;
  }
  // The dispatcher: LOADED / UNLOADED at their stamped ticks (MissionDispatcher::OnStatus).
  if (book_ && status.state < 8 && std::isfinite(status.object_position_x) &&
      std::isfinite(status.object_position_y) && std::isfinite(status.distance_to_target)) {
    const double now_s = static_cast<double>(tick_) * config_.tick_period_s;
    for (const core::DueSignal& due : book_->OnStatus(ToMissionReport(status), now_s).signals) {
      Mission_Event e;
      e.mission_id = due.mission_id;
      e.event = static_cast<std::uint8_t>(due.kind);
      e.not_before_tick = due.not_before_tick;
      relay_.Add(kDispatcherSender, e);
    }
  }
  // The recorder.
  if (status.state <= Mission_Status::REJECTED && std::isfinite(status.object_position_x) &&
      std::isfinite(status.object_position_y) && std::isfinite(status.distance_to_target)) {
    metrics_->AddStatus(status.mission_id, static_cast<MissionPhase>(status.state), status.tick,
                        {status.object_position_x, status.object_position_y});
    for (const std::string& row : metrics_->TakeMissionRows()) {
      missions_csv_.Line(row);
      recorder_row_ = true;
    }
  }
}

void Run::Tick() {
  // The final state at the final time: a frame, no round.
  if (tick_ == job_.max_ticks) {
    TakeFrame();
    end_ = job_.kind == "flocking" ? "max_ticks" : "TICK_LIMIT";
    over_ = true;
    return;
  }
  if (tick_ == 0 && order_) relay_.AddOrder(kDispatcherSender, *order_);
  // The simulator's PublishRadio: orders due enter the relay and the books, then every round.
  for (const New_Mission& order : relay_.ReleaseOrders(tick_)) {
    sim::RegisterMission(ToMissionSpec(order), *world_, &missions_);
  }
  const double sim_time = static_cast<double>(tick_) * config_.tick_period_s;
  std::vector<Robot_Position> truth;
  truth.reserve(world_->size());
  for (const auto& entry : world_->robots()) {
    truth.push_back(ToRobotPosition(entry.first, entry.second.pose));
  }
  radio_->Begin(*world_, {}, missions_);
  TakeFrame();

  const std::vector<Robot_Position> no_extras;
  std::vector<core::Velocity> commands(robots_.size());
  std::vector<Tick_Answer> answers(robots_.size());
  sim::RadioRound heard;
  std::size_t i = 0;
  for (auto robot = world_->robots().begin(); robot != world_->robots().end(); ++robot, ++i) {
    radio_->Hear(i, &heard);
    Neighbors round = RadioRoundMessage(tick_, sim_time, robot->second, heard, truth, no_extras);
    relay_.Fill(&round);
    RobotTick(robots_[i].get(), round, &answers[i], &commands[i]);
  }
  relay_.Clear();
  // The lock-step session's TakeAnswers, by robot id: the next relay, the simulator's own books
  // (object updates and deletes), then the observers of the statuses (the dispatcher's events
  // join the next tick's relay).
  for (i = 0; i < robots_.size(); ++i) {
    const Tick_Answer& a = answers[i];
    relay_.AddAnswer(robots_[i]->id, a);
    for (const Update_Object& u : a.object_updates) {
      sim::UpdateMissionObject(u.mission_id, {u.object_position_x, u.object_position_y}, *world_,
                               &missions_);
    }
    for (const Delete_Object& d : a.object_deletes) missions_.erase(d.mission_id);
  }
  for (const Tick_Answer& a : answers) {
    for (const Mission_Status& s : a.statuses) Observe(s);
  }
  // All answers apply together, then the world steps one tick.
  i = 0;
  for (const auto& entry : world_->robots()) world_->SetCommand(entry.first, commands[i++], nullptr);
  world_->Step(config_.tick_period_s);
  ++tick_;
  for (const auto& phase : phases_) {
    if (phase.first == Mission_Status::DONE || phase.first == Mission_Status::ABORTED) {
      end_ = phase.first == Mission_Status::DONE ? "DONE" : "ABORTED";
      over_ = true;
    }
  }
}

bool Run::Finish(std::string* error) {
  if (end_ == "DONE" && track_) track_->Arrived(phases_.back().second);
  metrics_->Drain();
  for (const std::string& row : metrics_->TakeMissionRows()) {
    missions_csv_.Line(row);
    recorder_row_ = true;
  }
  bool ok = swarm_csv_.Close() & missions_csv_.Close() & trace_csv_.Close();
  CsvOut run;
  if (!run.Open(record_path_ + "/run.csv", core::RunMetrics::kRunHeader, error)) return false;
  run.Line(metrics_->RunRow(job_.run_name, job_.seed));
  ok = run.Close() && ok;
  if (track_ && !track_->Write(job_.run_dir + "/leader_track.csv")) ok = false;
  if (!ok) *error = "cannot write the files of " + record_path_;
  return ok;
}

void Run::AddResult(double setup_s, double ticking_s, double finish_s, JsonObject* result) const {
  JsonObject& o = *result;
  o.Add("engine", JsonString("batch"));
  o.Add("end", JsonString(end_));
  if (job_.has_mission) {
    std::string phases = "[";
    for (std::size_t k = 0; k < phases_.size(); ++k) {
      phases += (k ? ", [" : "[") + std::to_string(phases_[k].first) + ", " +
                std::to_string(phases_[k].second) + "]";
    }
    o.Add("phases", phases + "]");
    o.Add("end_tick", std::to_string(metrics_->newest_tick()));
    o.Add("gathering_swerves", std::to_string(gathering_swerves_));
    JsonObject last;
    if (last_status_) {
      const Mission_Status& s = *last_status_;
      last.Add("distance_to_target", JsonNumber(s.distance_to_target));
      last.Add("object", "[" + JsonNumber(s.object_position_x) + ", " +
                             JsonNumber(s.object_position_y) + "]");
      last.Add("reason", JsonString(s.reason));
      last.Add("state", std::to_string(s.state));
      last.Add("tick", std::to_string(s.tick));
    }
    o.Add("last_status", last.Text(" "));
    if (end_ == "DONE" || end_ == "ABORTED") o.Add("recorder_row", recorder_row_ ? "true" : "false");
  }
  if (last_sample_) {
    JsonObject stats;
    stats.Add("largest_swarm", std::to_string(last_sample_->largest_swarm));
    stats.Add("robots", std::to_string(last_sample_->robots));
    stats.Add("sim_time", JsonNumber(last_sample_->sim_time_s));
    stats.Add("swarm_count", std::to_string(last_sample_->swarm_count));
    stats.Add("tick", std::to_string(last_sample_->tick));
    o.Add("final_stats", stats.Text(" "));
  } else {
    o.Add("final_stats", "null");
  }
  o.Add("ticks", std::to_string(metrics_->newest_tick()));
  o.Add("startup_s", JsonNumber(setup_s));
  o.Add("ticking_s", JsonNumber(ticking_s));
  o.Add("ticks_per_s",
        JsonNumber(ticking_s > 0.0 ? static_cast<double>(metrics_->newest_tick()) / ticking_s
                                   : 0.0));
  o.Add("shutdown_s", JsonNumber(finish_s));
}

}  // namespace

bool ReadBatchJob(const std::string& path, BatchJob* job, std::string* error) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    *error = path + ": " + e.what();
    return false;
  }
  if (!root.IsMap()) {
    *error = path + ": not a JSON object";
    return false;
  }
  std::string placement = "random";
  long long max_ticks = 0;
  long long seed = 1;
  if (!Get(root, "kind", &job->kind, error) || !Get(root, "setting", &job->setting, error) ||
      !Get(root, "run", &job->run, error) || !Get(root, "seed", &seed, error) ||
      !Get(root, "robots", &job->robots, error) || !Get(root, "max_ticks", &max_ticks, error) ||
      !Get(root, "config_path", &job->config_path, error) ||
      !Get(root, "run_dir", &job->run_dir, error) ||
      !Get(root, "record_dir", &job->record_dir, error) ||
      !Get(root, "run_name", &job->run_name, error) ||
      !Get(root, "placement", &placement, error) ||
      !Get(root, "placement_file", &job->placement_file, error, false) ||
      !Get(root, "trace", &job->trace, error, false) ||
      !Get(root, "leader_id", &job->leader_id, error, false)) {
    *error = path + ": " + *error;
    return false;
  }
  job->seed = seed;
  if (max_ticks <= 0) {
    *error = path + ": 'max_ticks' must be > 0 (a batch run must end)";
    return false;
  }
  job->max_ticks = static_cast<std::uint64_t>(max_ticks);
  if (!core::ParsePlacement(placement, &job->placement)) {
    *error = path + ": 'placement' must be random, corner or file but is '" + placement + "'";
    return false;
  }
  if (job->kind != "flocking" && job->kind != "transport" && job->kind != "leader") {
    *error = path + ": 'kind' must be flocking, transport or leader but is '" + job->kind + "'";
    return false;
  }
  const YAML::Node m = root["mission"];
  job->has_mission = job->kind != "flocking";
  if (!job->has_mission) return true;
  if (!m || !m.IsMap()) {
    *error = path + ": a " + job->kind + " run needs its 'mission'";
    return false;
  }
  try {
    New_Mission& msg = job->mission;
    msg.mission_id = static_cast<std::uint16_t>(m["id"].as<int>());
    msg.target_x = static_cast<float>(m["target"][0].as<double>());
    msg.target_y = static_cast<float>(m["target"][1].as<double>());
    msg.transport_mode = static_cast<std::uint8_t>(m["mode"] ? m["mode"].as<int>() : 0);
    if (job->kind == "leader") {
      if (job->leader_id < 0) {
        *error = path + ": a leader run needs its 'leader_id'";
        return false;
      }
      msg.robot_index_from = static_cast<std::uint16_t>(job->leader_id);
      msg.robot_index_to = static_cast<std::uint16_t>(job->leader_id + 1);
      msg.leader_number = 1;
    } else {
      msg.robot_index_from = 0;
      msg.robot_index_to =
          static_cast<std::uint16_t>(m["group"] ? m["group"].as<int>() : job->robots);
      msg.leader_number = static_cast<std::uint16_t>(m["leaders"].as<int>());
      msg.object_position_x = static_cast<float>(m["object"][0].as<double>());
      msg.object_position_y = static_cast<float>(m["object"][1].as<double>());
      msg.object_size_x = static_cast<float>(m["object"][2].as<double>());
      msg.object_size_y = static_cast<float>(m["object"][3].as<double>());
    }
  } catch (const YAML::Exception& e) {
    *error = path + ": 'mission' is malformed: " + e.what();
    return false;
  }
  return true;
}

void MergeParams(const XmlRpc::XmlRpcValue& over, XmlRpc::XmlRpcValue* base) {
  XmlRpc::XmlRpcValue& b = *base;
  if (over.getType() != XmlRpc::XmlRpcValue::TypeStruct ||
      b.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    b = over;
    return;
  }
  XmlRpc::XmlRpcValue& o = const_cast<XmlRpc::XmlRpcValue&>(over);  // no const iteration
  for (auto it = o.begin(); it != o.end(); ++it) {
    if (it->second.getType() == XmlRpc::XmlRpcValue::TypeStruct && b.hasMember(it->first) &&
        b[it->first].getType() == XmlRpc::XmlRpcValue::TypeStruct) {
      MergeParams(it->second, &b[it->first]);
    } else {
      b[it->first] = it->second;
    }
  }
}

bool RunBatchJob(const BatchJob& job, const XmlRpc::XmlRpcValue& base_config, std::string* error) {
  const Clock::time_point started = Clock::now();
  JsonObject result;
  result.Add("setting", JsonString(job.setting));
  result.Add("run", std::to_string(job.run));
  result.Add("seed", std::to_string(job.seed));
  result.Add("robots", std::to_string(job.robots));
  result.Add("mission_id",
             job.has_mission ? std::to_string(job.mission.mission_id) : std::string("null"));
  bool ok = false;
  {
    Run run(job);
    if (run.SetUp(base_config, error)) {
      const double setup_s = Seconds(started);
      const Clock::time_point ticking = Clock::now();
      while (!run.over()) run.Tick();
      const double ticking_s = Seconds(ticking);
      const Clock::time_point finishing = Clock::now();
      ok = run.Finish(error);
      run.AddResult(setup_s, ticking_s, Seconds(finishing), &result);
    }
  }
  result.Add("status", JsonString(ok ? "ok" : "error"));
  result.Add("error", JsonString(ok ? "" : *error));
  result.Add("wall_s", JsonNumber(Seconds(started)));
  const std::string text = result.Text();
  std::ofstream out(job.run_dir + "/result.json");
  out << text << "\n";
  if (!out) {
    if (ok) *error = "cannot write " + job.run_dir + "/result.json";
    return false;
  }
  return ok;
}

}  // namespace swarm_transport
