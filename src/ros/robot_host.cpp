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

  // Before Start(): robot `robot`, served by `queue`, first ticks at `first_due`.
  void Add(RobotNode* robot, ros::CallbackQueue* queue, Clock::time_point first_due) {
    robots_.emplace_back(robot, queue);
    heap_.push(Entry{first_due, robots_.size() - 1});
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
    TickCallback(TickScheduler* scheduler, std::size_t index, Clock::time_point due)
        : scheduler_(scheduler), index_(index), due_(due) {}
    CallResult call() override {
      scheduler_->robots_[index_].first->TimerTick();
      scheduler_->Reschedule(index_, due_);
      return Success;
    }

   private:
    TickScheduler* scheduler_;
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
      lock.unlock();
      robots_[top.index].second->addCallback(
          boost::make_shared<TickCallback>(this, top.index, top.due),
          reinterpret_cast<std::uint64_t>(robots_[top.index].first));
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
      ReadPrivate(private_nh_, "run_simulator", &options_.run_simulator, &error)) {
    error = options_.Validate();
  }
  if (!error.empty()) {
    ROS_FATAL("robot_host: invalid parameters: %s", error.c_str());
    return false;
  }
  if (options_.run_simulator) {
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
          "with ~run_simulator both must be the same",
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
    ros::CallbackQueue* queue = queues_[robots_.size() % queues_.size()].get();
    ros::NodeHandle nh(nh_, names::RobotNamespace(static_cast<std::uint16_t>(id)));
    nh.setCallbackQueue(queue);
    ros::NodeHandle private_nh(nh, kRobotNodeName);
    private_nh.setCallbackQueue(queue);
    RobotNodeOptions robot;
    robot.id = id;
    robot.clock = options_.clock;
    robot.comm = options_.comm;
    robot.diagnostics = options_.diagnostics;
    robot.external_timer = realtime;
    if (simulator_) robot.direct = simulator_.get();
    robots_.push_back(std::make_unique<RobotNode>(nh, private_nh));
    if (!robots_.back()->Initialize(robot)) return false;
  }
  if (simulator_) inboxes_ = std::make_unique<Inbox[]>(robots_.size());
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
  if (realtime) {
    // Each robot on its own timeline, as separate processes would be; the phases are spread
    // over one period so that the ticks do not all fall due at once.
    const double period_s = robots_.front()->tick_period_s();
    scheduler_ = std::make_unique<TickScheduler>(period_s);
    const TickScheduler::Clock::time_point start = TickScheduler::Clock::now();
    for (std::size_t i = 0; i < robots_.size(); ++i) {
      const std::chrono::duration<double> phase(period_s * static_cast<double>(i) /
                                                static_cast<double>(robots_.size()));
      scheduler_->Add(robots_[i].get(), queues_[i % queues_.size()].get(),
                      start + std::chrono::duration_cast<TickScheduler::Clock::duration>(phase));
    }
    scheduler_->Start();
  }
  return true;
}

bool RobotHost::Hosts(std::uint16_t id) const {
  return options_.run_simulator && options_.from <= id && id < options_.to;
}

void RobotHost::Deliver(std::uint16_t id, const Neighbors::ConstPtr& round) {
  const std::size_t index = static_cast<std::size_t>(id - options_.from);
  if (index >= robots_.size()) return;  // not set up (yet)
  RobotNode* robot = robots_[index].get();
  ros::CallbackQueue* queue = queues_[index % queues_.size()].get();
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
  Inbox& inbox = inboxes_[index];
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
  for (auto& robot : robots_) robot->Shutdown();
  if (simulator_) simulator_->Shutdown();
}

void RobotHost::StopCallbacks() {
  if (scheduler_) scheduler_->Stop();
  for (auto& spinner : spinners_) spinner->stop();
}

}  // namespace swarm_transport
