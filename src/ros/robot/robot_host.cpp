#include "swarm_transport/ros/robot/robot_host.h"

#include <std_msgs/String.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <queue>
#include <sstream>
#include <thread>
#include <utility>

#include "swarm_transport/ros/common/names.h"
#include "swarm_transport/ros/simulator/simulator.h"

namespace swarm_transport {
namespace {

// The node name each robot has in robot.launch: its private namespace is robot_<id>/robot.
constexpr char kRobotNodeName[] = "robot";
constexpr int kMaxThreads = 64;
constexpr int kMaxRobots = 65536;

}  // namespace

std::string RobotHostOptions::Validate() const {
  std::ostringstream os;
  if (from < 0 || from >= kMaxRobots) {
    os << "~from must be an id in [0, 65535] but is " << from;
  } else if (to <= from || to > kMaxRobots) {
    os << "~to must be in (~from, 65536] but is " << to << " (~from " << from << ")";
  } else if (threads < 1 || threads > kMaxThreads) {
    os << "~threads must be in [1, " << kMaxThreads << "] but is " << threads;
  } else if (deploy != core::Deploy::kHost && deploy != core::Deploy::kHostSim) {
    os << "~deploy of a robot_host must be 'host' or 'host_sim' but is '"
       << core::DeployName(deploy) << "'";
  }
  return os.str();
}

// Real time: one thread runs a share of the robots - their ticks from one heap of due times,
// their radio rounds (the simulator of this process hands them over once per round) and their
// roscpp callbacks (subscriptions, services) from their callback queue - so one robot's
// callbacks never overlap, and nothing passes through a callback queue per robot and tick.
// Until 2026-11-25 every tick and every round was a callback-queue entry of its own
// (CallbackQueue::addCallback, getIDInfo, their mutexes and wake-ups: ~15 % of the process at
// 2,000 robots). A tick is rescheduled at due + period or, when the robot fell more than a
// period behind, at the first due time of its own timeline after now: no burst of catch-up
// ticks, and the robots' phases stay spread over the period (a worker held up for a moment,
// as by the first /flock/robots of thousands of robots, rescheduling them all to "now" as
// roscpp's timers do, made them tick in one burst of 10-20 ms every period from then on).
class HostWorker {
 public:
  using Clock = TickClock;

  // `stats` (may be null): the host's diagnostics lines, flushed when due at every wake-up.
  HostWorker(ros::CallbackQueue* queue, double period_s, StatsBatch* stats)
      : queue_(queue),
        stats_(stats),
        period_(
            std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_s))),
        slack_(std::min<Clock::duration>(std::chrono::milliseconds(1), period_ / 100)) {}
  ~HostWorker() { Stop(); }

  // Robot `robot` first ticks `phase` after the worker starts, or after now when it runs
  // already (a robot that joins). The returned slot is the robot's for Stage() and Remove().
  void* Add(RobotNode* robot, Clock::duration phase) {
    Slot* slot = nullptr;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      slots_.push_back(std::make_unique<Slot>());
      slot = slots_.back().get();
      slot->robot = robot;
      // Before Start(): due times count from the epoch until Start() moves them to its now.
      heap_.push(Entry{(started_ ? Clock::now() : Clock::time_point()) + phase, slot});
    }
    Wake();
    return slot;
  }

  // The robot ticks and hears no more; returns when none of its ticks or rounds runs (from
  // any thread but this worker's).
  void Remove(void* handle) {
    Slot* slot = static_cast<Slot*>(handle);
    std::unique_lock<std::mutex> lock(mutex_);
    slot->robot = nullptr;
    slot->pending.reset();
    idle_.wait(lock, [&] { return running_ != slot; });
  }

  // The simulator's thread: the robot's round of this radio round (handed over by Flush).
  void Stage(void* handle, Neighbors::ConstPtr round) {
    staged_.emplace_back(static_cast<Slot*>(handle), std::move(round));
  }

  // The simulator's thread: hands the staged rounds over. A robot that has not taken its
  // last round yet gets the latest only, as a neighbors subscription with a short queue drops
  // old rounds (its diagnostics count them as missed).
  void Flush() {
    if (staged_.empty()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& entry : staged_) {
        Slot* slot = entry.first;
        if (slot->robot == nullptr) continue;
        if (!slot->pending) dirty_.push_back(slot);
        slot->pending = std::move(entry.second);
      }
    }
    staged_.clear();
    Wake();
  }

  // The initial robots' phases count from now: they were added while the robots were set up
  // (thousands take seconds).
  void Start() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      std::vector<Entry> entries;
      for (; !heap_.empty(); heap_.pop()) entries.push_back(heap_.top());
      const Clock::time_point now = Clock::now();
      for (Entry& entry : entries) {
        entry.due = now + entry.due.time_since_epoch();
        heap_.push(entry);
      }
      started_ = true;
    }
    thread_ = std::thread(&HostWorker::Run, this);
  }

  void Stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    Wake();
    if (thread_.joinable()) thread_.join();
  }

 private:
  struct Slot {
    RobotNode* robot = nullptr;   // null: removed
    Neighbors::ConstPtr pending;  // its latest round not taken yet
  };
  struct Entry {
    Clock::time_point due;
    Slot* slot;
    bool operator>(const Entry& other) const { return due > other.due; }
  };
  // Does nothing: its arrival ends the worker's wait on the callback queue.
  class WakeCall : public ros::CallbackInterface {
   public:
    CallResult call() override { return Success; }
  };

  void Wake() {
    bool wake = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      wake = !wake_queued_;
      wake_queued_ = true;
    }
    if (wake) queue_->addCallback(boost::make_shared<WakeCall>(), kWakeId);
  }

  // Runs `call` for the slot's robot unless it was removed; Remove() waits for it.
  template <typename F>
  bool RunFor(Slot* slot, F call) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (slot->robot == nullptr) return false;
      running_ = slot;
    }
    call(slot->robot);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      running_ = nullptr;
    }
    idle_.notify_all();
    return true;
  }

  // Runs the ticks due by now, and those due within the slack (1 % of the period, at most 1 ms:
  // a tick that early is no tick late, and thousands of robots cost one wake-up per slack, not
  // one per tick); returns how long until the next one (at most a period).
  Clock::duration RunDueTicks() {
    for (;;) {
      Entry top;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (heap_.empty()) return period_;
        const Clock::time_point now = Clock::now();
        if (heap_.top().due > now + slack_) return std::min(period_, heap_.top().due - now);
        top = heap_.top();
        heap_.pop();
      }
      if (!RunFor(top.slot, [](RobotNode* robot) { robot->TimerTick(); })) continue;
      // More than a period behind: its next due time on its own timeline after now.
      const Clock::time_point next = NextTickDue(top.due, period_, Clock::now());
      std::lock_guard<std::mutex> lock(mutex_);
      heap_.push(Entry{next, top.slot});
    }
  }

  void Run() {
    std::vector<std::pair<Slot*, Neighbors::ConstPtr>> rounds;
    for (;;) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stop_) return;
        wake_queued_ = false;
        for (Slot* slot : dirty_) rounds.emplace_back(slot, std::move(slot->pending));
        dirty_.clear();
      }
      // The rounds in the order they were delivered (ascending id), a few at a time between
      // the ticks that fall due meanwhile: a whole round of thousands of robots at once would
      // hold their ticks back by milliseconds.
      for (std::size_t k = 0; k < rounds.size(); ++k) {
        if (k % kRoundsBetweenTicks == 0) RunDueTicks();
        if (rounds[k].second) {
          RunFor(rounds[k].first, [&](RobotNode* robot) { robot->OnNeighbors(rounds[k].second); });
        }
      }
      rounds.clear();
      const Clock::duration wait = RunDueTicks();
      if (stats_ != nullptr) stats_->FlushIfDue();
      // The robots' roscpp callbacks, and the wait for the next tick or a wake-up.
      queue_->callAvailable(ros::WallDuration(std::chrono::duration<double>(wait).count()));
    }
  }

  static constexpr std::size_t kRoundsBetweenTicks = 32;
  static constexpr std::uint64_t kWakeId = 1;  // no robot's address

  ros::CallbackQueue* queue_;
  StatsBatch* stats_;
  const Clock::duration period_;
  const Clock::duration slack_;
  std::mutex mutex_;
  std::condition_variable idle_;
  std::vector<std::unique_ptr<Slot>> slots_;  // kept until the worker goes (Remove() only marks)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap_;
  std::vector<Slot*> dirty_;  // slots with a pending round
  Slot* running_ = nullptr;
  bool wake_queued_ = false;
  bool started_ = false;
  bool stop_ = false;
  std::vector<std::pair<Slot*, Neighbors::ConstPtr>> staged_;  // the simulator's thread only
  std::thread thread_;
};

namespace {
constexpr double kStatsBatchS = 0.05;
// Messages, not lines: a subscriber that lags a few seconds still gets every line.
constexpr std::uint32_t kStatsBatchQueue = 100;
}  // namespace

StatsBatch::StatsBatch(ros::NodeHandle nh)
    : pub_(nh.advertise<std_msgs::String>(names::kRobotStats, kStatsBatchQueue)),
      last_(ros::WallTime::now()) {}

void StatsBatch::Add(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!lines_.empty()) lines_ += '\n';
  lines_ += line;
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_).toSec() >= kStatsBatchS) FlushLocked(now);
}

void StatsBatch::FlushIfDue() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (lines_.empty()) return;
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_).toSec() >= kStatsBatchS) FlushLocked(now);
}

void StatsBatch::FlushLocked(const ros::WallTime& now) {
  auto msg = boost::make_shared<std_msgs::String>();
  msg->data.swap(lines_);
  pub_.publish(msg);
  last_ = now;
}

RobotHost::RobotHost(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

RobotHost::~RobotHost() {
  StopCallbacks();
  // Ticks still queued refer to the scheduler, which goes first.
  for (auto& queue : queues_) queue->clear();
}

bool RobotHost::Initialize() {
  std::string error;
  if (ReadPrivate(private_nh_, "from", &options_.from, &error) &&
      ReadPrivate(private_nh_, "to", &options_.to, &error) &&
      ReadPrivate(private_nh_, "clock", &options_.clock, &error) &&
      ReadPrivate(private_nh_, "comm", &options_.comm, &error) &&
      ReadPrivate(private_nh_, "diagnostics", &options_.diagnostics, &error) &&
      ReadPrivate(private_nh_, "threads", &options_.threads, &error) &&
      ReadPrivate(private_nh_, "deploy", &options_.deploy, &error) &&
      ReadPrivate(private_nh_, "adopt", &options_.adopt, &error) &&
      ReadPrivate(private_nh_, "robot_services", &options_.robot_services, &error)) {
    error = options_.Validate();
  }
  if (!error.empty()) {
    ROS_FATAL("robot_host: invalid parameters: %s", error.c_str());
    return false;
  }
  {
    XmlRpc::XmlRpcValue dict;
    SwarmConfig config;
    std::string swarm_error;
    if (nh_.getParam("/swarm", dict) && ConfigFromXmlRpc(dict, &config, &swarm_error)) {
      swarm_ = config;
    }
  }
  // Its robots, before the simulator (linking them directly) asks.
  for (int id = options_.from; id < options_.to; ++id) ids_.insert(static_cast<std::uint16_t>(id));
  if (options_.RunsSimulator()) {
    simulator_ = std::make_unique<Simulator>(nh_, ros::NodeHandle(private_nh_, "simulator"));
    simulator_->AttachDirect(this);
    if (!simulator_->Initialize()) return false;
    // Direct links carry no clock: robots ticking on their own wall timers would answer
    // lock-step rounds out of turn, and lock-step robots would wait for rounds forever.
    const core::Clock sim_clock =
        simulator_->lockstep() ? core::Clock::kLockstep : core::Clock::kRealtime;
    if (sim_clock != options_.clock) {
      ROS_FATAL(
          "robot_host: invalid parameters: ~clock is '%s' but ~simulator/clock is '%s'; "
          "with ~deploy host_sim both must be the same",
          core::ClockName(options_.clock), core::ClockName(sim_clock));
      return false;
    }
  }
  for (int i = 0; i < options_.threads; ++i) {
    queues_.push_back(std::make_unique<ros::CallbackQueue>());
  }
  const bool realtime = options_.clock == core::Clock::kRealtime;
  const ros::WallTime started = ros::WallTime::now();
  for (int id = options_.from; id < options_.to; ++id) {
    if (!StartRobot(static_cast<std::uint16_t>(id))) return false;
  }
  // With the simulator here its thread (the global queue, which it spins) changes hosted_;
  // without, the control queue's.
  if (simulator_) {
    SubscribeSharedTopics(nh_);
  } else {
    ros::NodeHandle control(nh_);
    control.setCallbackQueue(&control_queue_);
    SubscribeSharedTopics(control);
  }
  ROS_INFO("robot_host: robots [%d, %d) up in %.1f s (%s clock, %s comm, %d threads)",
           options_.from, options_.to, (ros::WallTime::now() - started).toSec(),
           core::ClockName(options_.clock), core::CommName(options_.comm), options_.threads);
  // Callbacks start only now: a robot must not hear anything while it is being set up.
  // Real time: a worker thread per queue runs its robots (HostWorker). Lock-step with the
  // simulator here: the simulator runs the queues (SpinRobots), so a tick needs no thread
  // hand-off and callbacks run in the same order every time; without it, a spinner per queue.
  if (realtime) {
    for (auto& worker : workers_) worker->Start();
  } else if (!simulator_) {
    for (auto& queue : queues_) {
      spinners_.push_back(std::make_unique<ros::AsyncSpinner>(1, queue.get()));
      spinners_.back()->start();
    }
  }
  if (!simulator_) {
    // The host's own thread: robots joining and leaving, and its diagnostic status (with the
    // simulator here, the simulator reports for the process).
    ros::NodeHandle control(nh_);
    control.setCallbackQueue(&control_queue_);
    if (options_.adopt) {
      robots_sub_ = control.subscribe(names::kRobots, 2, &RobotHost::OnRobots, this);
    }
    diagnostics_ = std::make_unique<NodeDiagnostics>(
        control, "swarm_transport: " + ros::this_node::getName().substr(1));
    status_timer_ =
        control.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) {
          diagnostics_->PublishIfDue([this](NodeStatus* s) {
            std::uint64_t ticks = 0;
            for (const auto& entry : hosted_) ticks += entry.second.node->ticks();
            s->message = std::to_string(hosted_.size()) + " robots, " +
                         core::ClockName(options_.clock) + " clock";
            s->Add("robots", static_cast<std::uint64_t>(hosted_.size()));
            s->Add("robot_ticks", ticks);
            s->Add("threads", static_cast<std::uint64_t>(options_.threads));
          });
        });
    control_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &control_queue_);
    control_spinner_->start();
  }
  return true;
}

bool RobotHost::StartRobot(std::uint16_t id) {
  const std::size_t k = started_++;
  ros::CallbackQueue* queue = queues_[k % queues_.size()].get();
  ros::NodeHandle nh(nh_, names::RobotNamespace(id));
  nh.setCallbackQueue(queue);
  ros::NodeHandle private_nh(nh, kRobotNodeName);
  private_nh.setCallbackQueue(queue);
  RobotNodeOptions robot;
  robot.id = id;
  robot.clock = options_.clock;
  robot.comm = options_.comm;
  robot.diagnostics = options_.diagnostics;
  robot.external_timer = options_.clock == core::Clock::kRealtime;
  robot.shared_topics = true;
  robot.services = options_.robot_services;
  // The initial robots share one reading of /swarm; a robot that joins later reads it itself,
  // as a process of its own would.
  if (swarm_ && k < static_cast<std::size_t>(options_.to - options_.from)) {
    robot.swarm = &*swarm_;
  }
  if (options_.diagnostics) {
    if (!stats_) stats_ = std::make_unique<StatsBatch>(nh_);
    StatsBatch* stats = stats_.get();
    robot.stats_sink = [stats](const std::string& line) { stats->Add(line); };
  }
  if (simulator_) robot.direct = simulator_.get();
  Hosted hosted;
  hosted.node = std::make_unique<RobotNode>(nh, private_nh);
  hosted.queue = queue;
  if (!hosted.node->Initialize(robot)) return false;
  RobotNode* node = hosted.node.get();
  if (options_.clock == core::Clock::kRealtime) {
    const double period_s = node->tick_period_s();
    if (workers_.empty()) {
      for (auto& q : queues_) {
        workers_.push_back(std::make_unique<HostWorker>(q.get(), period_s, stats_.get()));
      }
    }
    // Each robot on its own timeline, as separate processes would be: the initial robots'
    // phases are spread over one period so that their ticks do not all fall due at once; a
    // robot that joins later ticks from now.
    const std::size_t initial = static_cast<std::size_t>(options_.to - options_.from);
    const double phase_s =
        k < initial ? period_s * static_cast<double>(k) / static_cast<double>(initial) : 0.0;
    hosted.worker = workers_[k % workers_.size()].get();
    hosted.slot = hosted.worker->Add(node, std::chrono::duration_cast<HostWorker::Clock::duration>(
                                               std::chrono::duration<double>(phase_s)));
  }
  ids_.insert(id);
  // A robot that starts while the swarm runs hears the current robot list (latched), as its
  // own subscription would have.
  if (last_robots_) {
    const ros::MessageEvent<Robot_Positions const> event = *last_robots_;
    queue->addCallback(boost::make_shared<QueuedCall>([node, event]() { node->Hear(event); }),
                       reinterpret_cast<std::uint64_t>(node));
  }
  hosted_.emplace(id, std::move(hosted));
  return true;
}

bool RobotHost::Adopt(std::uint16_t id) {
  if (!options_.adopt || hosted_.count(id) > 0) return hosted_.count(id) > 0;
  ids_.insert(id);  // Hosts(id) from now on: the simulator links it directly
  if (!StartRobot(id)) {
    ids_.erase(id);
    ROS_ERROR("robot_host: robot %u could not be started", id);
    return false;
  }
  ROS_INFO("robot_host: robot %u joined", id);
  return true;
}

void RobotHost::Release(std::uint16_t id) {
  auto it = hosted_.find(id);
  if (it == hosted_.end()) return;
  RobotNode* robot = it->second.node.get();
  // Real time: it ticks and hears no more (a tick or round in progress ends first).
  if (it->second.worker != nullptr) it->second.worker->Remove(it->second.slot);
  // Lock-step: its queued rounds go, and one in progress ends first.
  it->second.queue->removeByID(reinterpret_cast<std::uint64_t>(robot));
  // Its callbacks end before it goes (the queue thread runs the other robots meanwhile).
  robot->Disconnect();
  robot->Shutdown();
  hosted_.erase(it);  // unsubscribes (waiting for a callback in progress)
  ids_.erase(id);
  ROS_INFO("robot_host: robot %u left", id);
}

template <typename M>
void RobotHost::FanOut(const ros::MessageEvent<M const>& event) {
  for (auto& entry : hosted_) {
    RobotNode* robot = entry.second.node.get();
    entry.second.queue->addCallback(
        boost::make_shared<QueuedCall>([robot, event]() { robot->Hear(event); }),
        reinterpret_cast<std::uint64_t>(robot));
  }
}

template <typename M>
void RobotHost::SubscribeShared(ros::NodeHandle& nh, const char* topic, std::uint32_t queue_size) {
  shared_subs_.push_back(
      nh.subscribe<M>(topic, queue_size,
                      boost::function<void(const ros::MessageEvent<M const>&)>(
                          [this](const ros::MessageEvent<M const>& event) { FanOut(event); })));
}

void RobotHost::SubscribeSharedTopics(ros::NodeHandle nh) {
  // The queue sizes of a robot's own subscriptions (robot_node.cpp).
  shared_subs_.push_back(nh.subscribe<Robot_Positions>(
      names::kRobots, 2,
      boost::function<void(const ros::MessageEvent<Robot_Positions const>&)>(
          [this](const ros::MessageEvent<Robot_Positions const>& event) {
            last_robots_ = event;
            FanOut(event);
          })));
  // Lock-step: mission messages come relayed inside each round.
  if (options_.clock == core::Clock::kLockstep) return;
  SubscribeShared<Robot_Freeze>(nh, names::kFreeze, 20);
  SubscribeShared<Robot_Continue>(nh, names::kContinue, 20);
  SubscribeShared<New_Mission>(nh, names::kMissionNew, 256);
  SubscribeShared<Update_Object>(nh, names::kObjectUpdate, 20);
  SubscribeShared<Delete_Object>(nh, names::kObjectDelete, 20);
  SubscribeShared<Mission_Event>(nh, names::kMissionEvent, 20);
  SubscribeShared<Mission_Status>(nh, names::kMissionStatus, 50);
}

void RobotHost::OnRobots(const Robot_Positions::ConstPtr& msg) {
  std::set<std::uint16_t> listed;
  for (const Robot_Position& r : msg->robots) {
    if (r.type == Robot_Position::TYPE_PHYSICAL) listed.insert(r.robot_id);
  }
  std::vector<std::uint16_t> gone;
  for (const auto& entry : hosted_) {
    if (listed.count(entry.first) == 0) gone.push_back(entry.first);
  }
  for (std::uint16_t id : gone) Release(id);
  // Every robot of the world is this host's (swarm.launch deploy:=host); ~adopt false leaves
  // the robots it did not start with to processes of their own.
  for (std::uint16_t id : listed) {
    if (hosted_.count(id) == 0) Adopt(id);
  }
}

bool RobotHost::Hosts(std::uint16_t id) const {
  return options_.RunsSimulator() && ids_.count(id) > 0;
}

void RobotHost::Deliver(std::uint16_t id, const Neighbors::ConstPtr& round) {
  auto it = hosted_.find(id);
  if (it == hosted_.end()) return;  // not set up (yet)
  RobotNode* robot = it->second.node.get();
  ros::CallbackQueue* queue = it->second.queue;
  // On the robot's queue, like a neighbors message: never concurrently with its other
  // callbacks, and in real time on its own thread, not the simulator's.
  if (options_.clock == core::Clock::kLockstep) {
    // Every round is a tick and is answered (the simulator sends the next one only then).
    queue->addCallback(
        boost::make_shared<QueuedCall>([robot, round]() { robot->OnNeighbors(round); }),
        reinterpret_cast<std::uint64_t>(robot));
    return;
  }
  // Real time: staged for the robot's worker, handed over with the whole round (EndRound).
  it->second.worker->Stage(it->second.slot, round);
}

void RobotHost::EndRound() {
  for (auto& worker : workers_) worker->Flush();
}

void RobotHost::SpinRobots() {
  // Real time: the spinner threads run the queues.
  if (options_.clock != core::Clock::kLockstep || !spinners_.empty()) return;
  // Queue by queue: robot k's callbacks in arrival order, the robots of a queue in the order
  // their rounds were delivered (ascending id), so a run is the same every time.
  for (auto& queue : queues_) queue->callAvailable(ros::WallDuration());
  if (stats_) stats_->FlushIfDue();
}

void RobotHost::Spin() {
  if (simulator_) {
    simulator_->Run();
  } else {
    ros::waitForShutdown();
  }
}

void RobotHost::Shutdown() {
  StopCallbacks();
  for (auto& entry : hosted_) entry.second.node->Shutdown();
  if (simulator_) simulator_->Shutdown();
}

void RobotHost::StopCallbacks() {
  status_timer_.stop();
  for (auto& sub : shared_subs_) sub.shutdown();
  if (control_spinner_) control_spinner_->stop();
  for (auto& worker : workers_) worker->Stop();
  for (auto& spinner : spinners_) spinner->stop();
}

}  // namespace swarm_transport
