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
  // The initial robots share one reading of /swarm; a robot that joins later reads it itself,
  // as a process of its own would.
  const SwarmConfig* swarm =
      swarm_ && k < static_cast<std::size_t>(options_.to - options_.from) ? &*swarm_ : nullptr;
  StatsSink sink;
  if (options_.diagnostics) {
    if (!stats_) stats_ = std::make_unique<StatsBatch>(nh_);
    StatsBatch* stats = stats_.get();
    sink = [stats](const std::string& line) { stats->Add(line); };
  }
  // Its transport: linked directly to the simulator of this process, or its own per-robot
  // topics; the swarm-wide topics come from the host's shared subscriptions either way.
  std::unique_ptr<RobotTransport> transport;
  if (simulator_) {
    transport = std::make_unique<DirectTransport>(simulator_.get(), sink, options_.robot_services);
  } else {
    transport = std::make_unique<HostTransport>(sink, options_.robot_services);
  }
  Hosted hosted;
  hosted.node = std::make_unique<RobotNode>(nh, private_nh);
  hosted.queue = queue;
  if (!hosted.node->Initialize(robot, std::move(transport), swarm)) return false;
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
    const Robot_Positions::ConstPtr list = last_robots_;
    queue->addCallback(boost::make_shared<QueuedCall>([node, list]() { node->HearRobots(*list); }),
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

template <typename F>
void RobotHost::FanOut(const F& hear) {
  for (auto& entry : hosted_) {
    RobotNode* robot = entry.second.node.get();
    entry.second.queue->addCallback(
        boost::make_shared<QueuedCall>([robot, hear]() { hear(robot); }),
        reinterpret_cast<std::uint64_t>(robot));
  }
}

void RobotHost::SubscribeSharedTopics(ros::NodeHandle nh) {
  // The queue size of a robot's own subscription (own_topics_transport.cpp).
  robots_shared_sub_ = nh.subscribe<Robot_Positions>(
      names::kRobots, 2,
      boost::function<void(const Robot_Positions::ConstPtr&)>(
          [this](const Robot_Positions::ConstPtr& list) {
            last_robots_ = list;
            FanOut([list](RobotNode* robot) { robot->HearRobots(*list); });
          }));
  // Lock-step: mission messages come relayed inside each round.
  if (options_.clock == core::Clock::kLockstep) return;
  mission_topics_.Subscribe(
      nh, [this](const core::MissionMessage& message, const core::Sender& from) {
        const auto shared = std::make_shared<const core::MissionMessage>(message);
        FanOut([shared, from](RobotNode* robot) { robot->Hand(*shared, from); });
      });
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
    queue->addCallback(boost::make_shared<QueuedCall>([robot, round]() {
                         robot->TakeRound(round, ros::WallTime::now().toSec());
                       }),
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
  robots_shared_sub_.shutdown();
  mission_topics_.Shutdown();
  if (control_spinner_) control_spinner_->stop();
  for (auto& worker : workers_) worker->Stop();
  for (auto& spinner : spinners_) spinner->stop();
}

}  // namespace swarm_transport
