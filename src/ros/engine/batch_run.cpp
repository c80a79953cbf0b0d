#include "swarm_transport/ros/engine/batch_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/core/dispatcher_policy.h"
#include "swarm_transport/core/metrics.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/core/robot_session.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/core/run_metrics.h"
#include "swarm_transport/core/run_metrics_gathering.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/dispatcher/dispatcher_options.h"
#include "swarm_transport/ros/engine/batch_files.h"
#include "swarm_transport/ros/recorder/recorder.h"
#include "swarm_transport/ros/simulator/simulator_params.h"
#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/sim/lockstep_barrier.h"
#include "swarm_transport/sim/lockstep_engine.h"
#include "swarm_transport/sim/radio.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace {

using core::MissionPhase;
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point from) {
  return std::chrono::duration<double>(Clock::now() - from).count();
}

// The dispatcher of a batch run: its policy as the dispatcher node has it without private
// parameters; its order is released at tick 0, its LOADED / UNLOADED go into the next relay.
// Its answers go to the dispatcher's side of a lock-step barrier as in a launched run; in one
// process each tick finds them complete (else the run fails).
class BatchDispatcher : public core::DispatcherOutlet {
 public:
  BatchDispatcher(const SwarmConfig& config, std::uint64_t* tick, sim::LockstepEngine* engine)
      : engine_(engine), policy_(ParamsOf(config, tick), this) {}
  core::DispatcherPolicy& policy() { return policy_; }
  // A status the robots said in tick `tick`, taken as MissionDispatcher::OnStatus takes it
  // (booked when its fields are sound, answered either way).
  void TakeStatus(const core::StatusReport& status, std::uint64_t tick) {
    const core::StatusKey key{status.mission_id, status.phase, tick};
    barrier_.StatusRelayed(key);
    if (static_cast<std::size_t>(status.phase) < core::kPhaseCount &&
        std::isfinite(status.object.x) && std::isfinite(status.object.y) &&
        std::isfinite(status.distance_to_target)) {
      policy_.OnStatus(core::ReportOf(status, tick), "robots");
    } else {
      policy_.SkipStatus(key);
    }
  }
  // Before tick `tick`: what the barrier would wait for has come; why not, else empty.
  std::string Missing(std::uint64_t tick) const {
    if (!barrier_.DispatcherPending(tick)) return "";
    return "the dispatcher's answers were incomplete before tick " + std::to_string(tick);
  }
  // The order as the dispatcher publishes it (its message's precision).
  const std::optional<New_Mission>& order() const { return order_; }

  void Order(const core::MissionSpec& spec, std::uint64_t start_tick) override {
    order_ = ToNewMission(spec);
    order_->start_tick = start_tick;
  }
  void Event(const core::Signal& signal, const char* /*why*/) override {
    engine_->relay().Add(names::kDispatcherNode, signal);
    barrier_.EventArrived({signal.mission_id, static_cast<std::uint8_t>(signal.kind)});
  }
  void Answer(const core::DispatcherAnswer& answer) override {
    barrier_.OnDispatcherAnswer(answer);
  }
  void Rejected(const core::MissionSpec&, const std::string&) override {}
  void Aborted(const core::MissionSpec&, const std::string&) override {}
  void Log(bool, const std::string&) override {}

 private:
  static core::DispatcherPolicyParams ParamsOf(const SwarmConfig& config, std::uint64_t* tick) {
    core::DispatcherPolicyParams params =
        DispatcherPolicyParamsOf(config, DispatcherOptionsOf(config), true);
    const double period_s = config.tick_period_s;
    params.clock = [tick, period_s] { return static_cast<double>(*tick) * period_s; };
    return params;
  }

  sim::LockstepEngine* engine_;
  core::DispatcherPolicy policy_;
  std::optional<New_Mission> order_;
  sim::LockstepBarrier barrier_;  // its dispatcher side
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
  // The recorder's frame of the world as /flock/world_poses carries it (`truth`: the physical
  // robots' poses in world order), and the runner's trace.
  void TakeFrame(const std::vector<core::Position>& truth);
  // The robot at world index `i` ticks on its round: its answer joins the tick's answers.
  void RobotTick(std::size_t i, const core::Round& round);
  // A status the robots said in tick `tick`: the runner's, the dispatcher's and the recorder's
  // part.
  void Observe(const core::StatusReport& status, std::uint64_t tick);
  void WriteMissionRows();

  const BatchJob& job_;
  SwarmConfig config_;
  RecorderParams recorder_;
  std::unique_ptr<sim::World2D> world_;
  std::unique_ptr<core::Rng> radio_rng_;
  std::unique_ptr<sim::Radio> radio_;
  sim::LiveMissions missions_;  // the simulator's books
  std::unique_ptr<sim::LockstepEngine> engine_;
  std::vector<core::RobotSession> robots_;  // in world order (ascending id)
  std::set<std::uint16_t> known_robots_;
  std::unique_ptr<BatchDispatcher> dispatcher_;  // with a mission; its order released at tick 0
  std::string dispatcher_failure_;               // a tick began without its answers
  std::unique_ptr<core::RunMetrics> metrics_;
  std::unique_ptr<LeaderTrack> track_;
  std::string record_path_;
  CsvFile swarm_csv_;
  CsvFile missions_csv_;
  CsvFile trace_csv_;
  sim::LockstepEngine::Answers answers_;  // of the current tick
  std::vector<core::Velocity> commands_;
  core::Round round_;
  std::uint64_t tick_ = 0;
  bool over_ = false;
  bool files_ok_ = true;
  std::string end_;
  // What the experiment's runner sees of the mission: each new state with its tick, the last
  // status of a tick > 0, the last swarm sample.
  std::vector<std::pair<int, std::uint64_t>> phases_;
  std::optional<std::pair<core::StatusReport, std::uint64_t>> last_status_;  // with its tick
  std::optional<core::SwarmSample> last_sample_;
  bool recorder_row_ = false;
  std::size_t logged_warnings_ = 0;
  // Collisions avoided while gathering: moves of mission robots before their transport (not
  // frozen for loading) that swerved or slowed for a robot in the way (result.json).
  std::uint64_t gathering_swerves_ = 0;
  // Interference while gathering and the plans of a planned gathering (issue 27).
  core::GatheringMetrics gathering_;
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
  // The simulator's parameters as swarm.launch sets them for a lock-step host_sim run: its
  // defaults, /swarm, the run's robots and placement.
  SimulatorParams sim_params;
  sim_params.swarm = config_;
  std::string why;
  if (swarm.hasMember("radio_loss") &&
      !XmlRpcNumber(swarm["radio_loss"], &sim_params.radio_loss, &why)) {
    *error = "/swarm/radio_loss " + why;
    return false;
  }
  sim_params.robots = job_.robots;
  sim_params.placement = job_.placement;
  sim_params.placement_file = job_.placement_file;
  sim_params.clock = core::Clock::kLockstep;
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
  engine_ = std::make_unique<sim::LockstepEngine>(world_.get(), radio_.get(), &missions_);
  robots_.reserve(world_->size());
  for (const auto& entry : world_->robots()) {
    robots_.emplace_back(entry.first, config_);
    known_robots_.insert(entry.first);
  }
  answers_.reserve(robots_.size());
  commands_.resize(robots_.size());

  // The recorder as recorder.launch starts it: its defaults, /swarm, the run's name and seed.
  recorder_.swarm = config_;
  recorder_.run_name = job_.run_name;
  recorder_.seed = job_.seed;
  *error = recorder_.Validate();
  if (!error->empty()) return false;
  metrics_ = std::make_unique<core::RunMetrics>(
      RunMetricsParamsOf(recorder_),
      [this](core::RunMetrics::Level level, const std::string& text) {
        if (level == core::RunMetrics::Level::kWarn && logged_warnings_++ < 20) {
          std::fprintf(stderr, "%s/%s: recorder: %s\n", job_.setting.c_str(), job_.run_name.c_str(),
                       text.c_str());
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
  if (job_.trace && !trace_csv_.Open(job_.run_dir + "/trace.csv", "tick,robot_id,x,y,heading_deg",
                                     error, /*flush_each_row=*/false)) {
    return false;
  }

  if (job_.has_mission) {
    // The dispatcher's ~submit (a dispatcher without private parameters): validated against
    // the swarm, then published as its order.
    dispatcher_ = std::make_unique<BatchDispatcher>(config_, &tick_, engine_.get());
    std::vector<Robot_Position> swarm;  // as /flock/world_poses carries it
    for (const auto& entry : world_->robots()) {
      swarm.push_back(ToRobotPosition(entry.first, entry.second.pose));
    }
    dispatcher_->policy().SetSwarm(0, SwarmOf(swarm));
    const core::MissionBook::Verdict verdict =
        dispatcher_->policy().Submit(ToMissionSpec(job_.mission), "service", true, true, 0);
    if (!verdict.accepted) {
      *error = "the dispatcher rejected the mission: " + verdict.message;
      return false;
    }
    const New_Mission& order = *dispatcher_->order();
    // The recorder follows it from the tick it enters (tick 0).
    RecordOrder(order, config_, metrics_.get());
    if (job_.kind == "leader") {
      track_ = std::make_unique<LeaderTrack>(static_cast<std::uint16_t>(job_.leader_id),
                                             core::Vec2{order.target_x, order.target_y},
                                             config_.flocking.local_range_m);
    }
  }
  return true;
}

void Run::WriteMissionRows() {
  for (const std::string& row : metrics_->TakeMissionRows()) {
    files_ok_ = missions_csv_.Append(row) && files_ok_;
    recorder_row_ = true;
  }
}

void Run::TakeFrame(const std::vector<core::Position>& truth) {
  if (job_.trace) {
    char row[96];
    for (const core::Position& p : truth) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      std::snprintf(row, sizeof(row), "%llu,%u,%.4f,%.4f,%.2f",
                    static_cast<unsigned long long>(tick_), static_cast<unsigned>(p.robot_id),
                    static_cast<double>(p.x), static_cast<double>(p.y),
                    static_cast<double>(p.angle_deg));
      files_ok_ = trace_csv_.Append(row) && files_ok_;
    }
  }
  // As the recorder takes /flock/world_poses.
  std::size_t bad = 0;
  core::MetricsFrame frame =
      core::FrameOf(tick_, static_cast<double>(tick_) * config_.tick_period_s, truth, &bad);
  if (track_) track_->Add(frame);
  std::optional<core::SwarmSample> sample;
  metrics_->AddFrame(std::move(frame), &sample);
  if (sample) {
    files_ok_ = swarm_csv_.Append(core::RunMetrics::SwarmRow(*sample)) && files_ok_;
    last_sample_ = sample;
  }
  WriteMissionRows();
}

void Run::RobotTick(std::size_t i, const core::Round& round) {
  core::RobotSession& robot = robots_[i];
  robot.TakeRelayed(round, known_robots_, nullptr);
  core::RobotSession::Step step =
      robot.Tick(core::PerceptionOf(robot.id(), round), round.tick, round.sim_time, true);
  const core::RobotBrain& brain = robot.brain();
  const std::optional<core::Carry>& carry = brain.last_plan().carry;
  if (carry && !carry->transport && !carry->loading && !brain.frozen() &&
      (step.brain.move.outcome == core::MoveOutcome::kSwerved ||
       step.brain.move.outcome == core::MoveOutcome::kSlowed)) {
    ++gathering_swerves_;
  }
  gathering_.AddMove(carry, brain.frozen(), core::Pose2Of(round.pose).position,
                     step.brain.move.outcome);
  if (brain.missions().last_gather_plan()) {
    gathering_.AddPlan(robot.id(), *brain.missions().last_gather_plan());
  }
  gathering_.AddPosition(robot.id(), round.tick, carry, core::Pose2Of(round.pose).position);
  commands_[i] = core::CommandOf(step.answer);
  answers_.emplace_back(robot.id(), std::move(step.answer));
}

void Run::Observe(const core::StatusReport& status, std::uint64_t tick) {
  const int state = static_cast<int>(status.phase);
  // The runner: each new state with its tick; the last status of a tick > 0.
  if (job_.has_mission && status.mission_id == job_.mission.mission_id) {
    if (phases_.empty() || phases_.back().first != state) phases_.emplace_back(state, tick);
    if (tick > 0) last_status_.emplace(status, tick);
  }
  // The dispatcher: LOADED / UNLOADED at their stamped ticks, into the next tick's relay.
  if (dispatcher_) dispatcher_->TakeStatus(status, tick);
  // The recorder.
  RecordStatus(status, tick, metrics_.get());
  WriteMissionRows();
}

void Run::Tick() {
  // The final state at the final time: a frame, no round.
  if (tick_ == job_.max_ticks) {
    std::vector<core::Position> truth;
    truth.reserve(world_->size());
    for (const auto& entry : world_->robots()) {
      truth.push_back(core::PositionOf(entry.first, entry.second.pose));
    }
    TakeFrame(truth);
    end_ = job_.kind == "flocking" ? "max_ticks" : "TICK_LIMIT";
    over_ = true;
    return;
  }
  if (dispatcher_ && dispatcher_failure_.empty()) dispatcher_failure_ = dispatcher_->Missing(tick_);
  if (tick_ == 0 && dispatcher_) {
    const New_Mission& order = *dispatcher_->order();
    engine_->relay().AddOrder(names::kDispatcherNode, ToMissionSpec(order), order.start_tick);
  }
  engine_->ReleaseOrders(tick_);  // one the books refuse, the robots refuse too
  engine_->BeginRound(tick_, static_cast<double>(tick_) * config_.tick_period_s, nullptr, {});
  TakeFrame(engine_->truth());
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    engine_->Round(i, false, &round_);
    RobotTick(i, round_);
  }
  engine_->EndRound();
  engine_->TakeAnswers(&answers_, [this](std::uint16_t, const core::Answer& a) {
    for (const core::StatusReport& s : a.statuses) Observe(s, a.tick);
  });
  // All answers apply together, then the world steps one tick.
  for (std::size_t i = 0; i < commands_.size(); ++i) world_->SetCommandAt(i, commands_[i], nullptr);
  world_->Step(config_.tick_period_s);
  ++tick_;
  for (const auto& phase : phases_) {
    const auto phase_is = [&phase](MissionPhase p) { return phase.first == static_cast<int>(p); };
    if (phase_is(MissionPhase::kDone) || phase_is(MissionPhase::kAborted)) {
      end_ = phase_is(MissionPhase::kDone) ? "DONE" : "ABORTED";
      over_ = true;
    }
  }
}

bool Run::Finish(std::string* error) {
  if (end_ == "DONE" && track_) track_->Arrived(phases_.back().second);
  metrics_->Drain();
  WriteMissionRows();
  bool ok = swarm_csv_.Close() & missions_csv_.Close() & trace_csv_.Close() & files_ok_;
  std::string why;
  if (!WriteRunFile(record_path_, metrics_->RunRow(job_.run_name, job_.seed), &why)) ok = false;
  if (track_ && !track_->Write(job_.run_dir + "/leader_track.csv")) ok = false;
  if (!ok) *error = "cannot write the files of " + record_path_ + (why.empty() ? "" : ": " + why);
  if (!dispatcher_failure_.empty()) *error = dispatcher_failure_;
  return ok && dispatcher_failure_.empty();
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
    o.Add("gathering_interference", std::to_string(gathering_.interference()));
    if (gathering_.plans() > 0) {
      const std::vector<double>& ratios = gathering_.cost_ratios();
      o.Add("plans", std::to_string(gathering_.plans()));
      o.Add("plan_unstable_pct",
            JsonNumber(100.0 * static_cast<double>(gathering_.unstable_plans()) /
                       static_cast<double>(gathering_.plans())));
      o.Add("plan_cost_ratio", JsonNumber(core::Median(ratios)));
      o.Add("plan_cost_ratio_max", JsonNumber(*std::max_element(ratios.begin(), ratios.end())));
    }
    for (const auto& field : gathering_.ResultFields())
      o.Add(field.first, JsonNumber(field.second));
    JsonObject last;
    if (last_status_) {
      const core::StatusReport& s = last_status_->first;
      last.Add("distance_to_target", JsonNumber(s.distance_to_target));
      last.Add("object", "[" + JsonNumber(s.object.x) + ", " + JsonNumber(s.object.y) + "]");
      last.Add("reason", JsonString(s.reason));
      last.Add("state", std::to_string(static_cast<int>(s.phase)));
      last.Add("tick", std::to_string(last_status_->second));
    }
    o.Add("last_status", last.Text(" "));
    if (end_ == "DONE" || end_ == "ABORTED")
      o.Add("recorder_row", recorder_row_ ? "true" : "false");
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
  o.Add(
      "ticks_per_s",
      JsonNumber(ticking_s > 0.0 ? static_cast<double>(metrics_->newest_tick()) / ticking_s : 0.0));
  o.Add("shutdown_s", JsonNumber(finish_s));
}

}  // namespace

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
