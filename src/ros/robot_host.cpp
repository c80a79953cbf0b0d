#include "swarm_transport/ros/robot_host.h"

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

#include "swarm_transport/ros/simulator.h"
#include "swarm_transport/ros/names.h"

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

// Real-time ticks of many robots from one thread and one heap of due times. A due tick is
// queued on its robot's callback queue (so it never overlaps the robot's other callbacks)
// and the next one is scheduled when it has run, as roscpp's timers do: due + period, or
// now when the robot fell more than a period behind (no burst of catch-up ticks).
class TickScheduler {
 public:
  using Clock = std::chrono::steady_clock;

  explicit TickScheduler(double period_s)
      : period_(
            std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_s))) {}
  ~TickScheduler() { Stop(); }

  // Robot `robot`, served by `queue`, first ticks at `first_due` (also while running: a robot
  // that joins).
  void Add(RobotNode* robot, ros::CallbackQueue* queue, Clock::time_point first_due) {
    bool earliest = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      robots_.emplace_back(robot, queue);
      earliest = heap_.empty() || first_due < heap_.top().due;
      heap_.push(Entry{first_due, robots_.size() - 1});
    }
    if (earliest) wake_.notify_one();
  }

  // Robot `robot` ticks no more. A tick already queued still runs unless the caller removes
  // it from the robot's queue (removeByID with the robot's address, which also waits for one
  // in progress).
  void Remove(RobotNode* robot) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& entry : robots_) {
      if (entry.first == robot) entry.first = nullptr;
    }
  }

  void Start() { thread_ = std::thread(&TickScheduler::Run, this); }

  void Stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

 private:
  struct Entry {
    Clock::time_point due;
    std::size_t index;
    bool operator>(const Entry& other) const { return due > other.due; }
  };

  // Runs one robot's tick on its queue's thread, then schedules the next.
  class TickCallback : public ros::CallbackInterface {
   public:
    TickCallback(TickScheduler* scheduler, RobotNode* robot, std::size_t index,
                 Clock::time_point due)
        : scheduler_(scheduler), robot_(robot), index_(index), due_(due) {}
    CallResult call() override {
      robot_->TimerTick();
      scheduler_->Reschedule(index_, due_);
      return Success;
    }

   private:
    TickScheduler* scheduler_;
    RobotNode* robot_;
    std::size_t index_;
    Clock::time_point due_;
  };

  void Reschedule(std::size_t index, Clock::time_point due) {
    Clock::time_point next = due + period_;
    const Clock::time_point now = Clock::now();
    if (next + period_ < now) next = now;
    bool earliest = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (robots_[index].first == nullptr) return;  // removed
      earliest = heap_.empty() || next < heap_.top().due;
      heap_.push(Entry{next, index});
    }
    if (earliest) wake_.notify_one();
  }

  void Run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      if (heap_.empty()) {
        wake_.wait(lock);
        continue;
      }
      const Entry top = heap_.top();
      if (Clock::now() < top.due) {
        wake_.wait_until(lock, top.due);
        continue;
      }
      heap_.pop();
      const std::pair<RobotNode*, ros::CallbackQueue*> robot = robots_[top.index];
      if (robot.first == nullptr) continue;  // removed
      lock.unlock();
      robot.second->addCallback(
          boost::make_shared<TickCallback>(this, robot.first, top.index, top.due),
          reinterpret_cast<std::uint64_t>(robot.first));
      lock.lock();
    }
  }

  const Clock::duration period_;
  std::vector<std::pair<RobotNode*, ros::CallbackQueue*>> robots_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap_;
  bool stop_ = false;
  std::thread thread_;
};

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
      ReadPrivate(private_nh_, "adopt", &options_.adopt, &error)) {
    error = options_.Validate();
  }
  if (!error.empty()) {
    ROS_FATAL("robot_host: invalid parameters: %s", error.c_str());
    return false;
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
  ROS_INFO("robot_host: robots [%d, %d) up in %.1f s (%s clock, %s comm, %d threads)",
           options_.from, options_.to, (ros::WallTime::now() - started).toSec(),
           core::ClockName(options_.clock), core::CommName(options_.comm), options_.threads);
  // Callbacks start only now: a robot must not hear anything while it is being set up.
  // Lock-step with the simulator here: the simulator runs the queues (SpinRobots), so a tick
  // needs no thread hand-off and callbacks run in the same order every time.
  if (!(simulator_ && !realtime)) {
    for (auto& queue : queues_) {
      spinners_.push_back(std::make_unique<ros::AsyncSpinner>(1, queue.get()));
      spinners_.back()->start();
    }
  }
  if (scheduler_) scheduler_->Start();
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
    status_timer_ = control.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) {
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
  if (simulator_) robot.direct = simulator_.get();
  Hosted hosted;
  hosted.node = std::make_unique<RobotNode>(nh, private_nh);
  hosted.queue = queue;
  if (simulator_) hosted.inbox = std::make_unique<Inbox>();
  if (!hosted.node->Initialize(robot)) return false;
  RobotNode* node = hosted.node.get();
  ids_.insert(id);
  hosted_.emplace(id, std::move(hosted));
  if (options_.clock == core::Clock::kRealtime) {
    if (!scheduler_) scheduler_ = std::make_unique<TickScheduler>(node->tick_period_s());
    // Each robot on its own timeline, as separate processes would be: the initial robots'
    // phases are spread over one period so that their ticks do not all fall due at once; a
    // robot that joins later ticks from now.
    const double period_s = node->tick_period_s();
    const std::size_t initial = static_cast<std::size_t>(options_.to - options_.from);
    const double phase_s =
        k < initial ? period_s * static_cast<double>(k) / static_cast<double>(initial) : 0.0;
    scheduler_->Add(node, queue,
                    TickScheduler::Clock::now() +
                        std::chrono::duration_cast<TickScheduler::Clock::duration>(
                            std::chrono::duration<double>(phase_s)));
  }
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
  if (scheduler_) scheduler_->Remove(robot);
  // Its queued ticks and rounds go, and one in progress ends first.
  it->second.queue->removeByID(reinterpret_cast<std::uint64_t>(robot));
  // Its callbacks end before it goes (the queue thread runs the other robots meanwhile).
  robot->Disconnect();
  robot->Shutdown();
  hosted_.erase(it);  // unsubscribes (waiting for a callback in progress)
  ids_.erase(id);
  ROS_INFO("robot_host: robot %u left", id);
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
  // Real time: a robot that fell behind gets the latest round only, as a neighbors
  // subscription with a short queue drops old rounds (its diagnostics count them as missed);
  // an unbounded queue would grow while the robot can not keep up.
  Inbox& inbox = *it->second.inbox;
  bool pending = false;
  {
    std::lock_guard<std::mutex> lock(inbox.mutex);
    pending = inbox.round != nullptr;
    inbox.round = round;
  }
  if (pending) return;  // the queued callback will take this one
  queue->addCallback(boost::make_shared<QueuedCall>([robot, &inbox]() {
                       Neighbors::ConstPtr latest;
                       {
                         std::lock_guard<std::mutex> lock(inbox.mutex);
                         latest.swap(inbox.round);
                       }
                       if (latest) robot->OnNeighbors(latest);
                     }),
                     reinterpret_cast<std::uint64_t>(robot));
}

void RobotHost::SpinRobots() {
  // Real time: the spinner threads run the queues.
  if (options_.clock != core::Clock::kLockstep || !spinners_.empty()) return;
  // Queue by queue: robot k's callbacks in arrival order, the robots of a queue in the order
  // their rounds were delivered (ascending id), so a run is the same every time.
  for (auto& queue : queues_) queue->callAvailable(ros::WallDuration());
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
  if (control_spinner_) control_spinner_->stop();
  if (scheduler_) scheduler_->Stop();
  for (auto& spinner : spinners_) spinner->stop();
}

}  // namespace swarm_transport
