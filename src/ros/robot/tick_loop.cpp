#include "swarm_transport/ros/robot/tick_loop.h"

#include <poll.h>
#include <ros/callback_queue.h>
#include <ros/poll_manager.h>
#include <ros/ros.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include <boost/make_shared.hpp>
#include <cerrno>
#include <cstring>

namespace swarm_transport {

struct PollThreadTicker::State {
  int fd = -1;
  std::mutex mutex;  // held while a tick runs; guards the rest
  bool stopped = false;
  TickClock::duration period{};
  TickClock::time_point due;
  std::function<void()> tick;

  ~State() {
    if (fd >= 0) ::close(fd);
  }

  // Arms the timer for `due` (absolute, CLOCK_MONOTONIC: steady_clock's clock).
  void Arm() {
    const auto since = std::chrono::duration_cast<std::chrono::nanoseconds>(due.time_since_epoch());
    itimerspec spec{};
    spec.it_value.tv_sec = static_cast<time_t>(since.count() / 1000000000);
    spec.it_value.tv_nsec = static_cast<long>(since.count() % 1000000000);
    if (spec.it_value.tv_sec == 0 && spec.it_value.tv_nsec == 0) spec.it_value.tv_nsec = 1;
    ::timerfd_settime(fd, TFD_TIMER_ABSTIME, &spec, nullptr);
  }

  // The poll thread: the timer expired (or a spurious wake-up).
  void OnEvents(int events) {
    if ((events & POLLIN) == 0) return;
    std::lock_guard<std::mutex> lock(mutex);
    if (stopped) return;
    std::uint64_t expirations = 0;
    if (::read(fd, &expirations, sizeof(expirations)) < 0 && errno != EAGAIN) return;
    if (TickClock::now() < due) {
      Arm();
      return;
    }
    tick();
    due = NextTickDue(due, period, TickClock::now());
    Arm();
  }
};

bool PollThreadTicker::Start(TickClock::duration period, std::function<void()> tick,
                             std::string* error) {
  Stop();
  auto state = std::make_shared<State>();
  state->fd = ::timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
  if (state->fd < 0) {
    *error = std::string("timerfd_create failed: ") + std::strerror(errno);
    return false;
  }
  state->period = period;
  state->tick = std::move(tick);
  state->due = TickClock::now() + period;
  state->Arm();
  ros::PollSet& poll_set = ros::PollManager::instance()->getPollSet();
  // The poll set keeps a copy of this function until delSocket, and may call a copy it took
  // just before: it holds the state, whose destructor closes the timer only after that.
  if (!poll_set.addSocket(state->fd, [state](int events) { state->OnEvents(events); }) ||
      !poll_set.addEvents(state->fd, POLLIN)) {
    poll_set.delSocket(state->fd);
    *error = "roscpp's poll set did not take the tick timer";
    return false;
  }
  state_ = std::move(state);
  return true;
}

void PollThreadTicker::Stop() {
  if (!state_) return;
  {
    std::lock_guard<std::mutex> lock(state_->mutex);  // waits for a tick that runs
    state_->stopped = true;
    state_->tick = nullptr;
    itimerspec off{};
    ::timerfd_settime(state_->fd, 0, &off, nullptr);
  }
  ros::PollManager::instance()->getPollSet().delSocket(state_->fd);
  state_.reset();
}

namespace {

// A callback run under a lock.
class LockedCallback : public ros::CallbackInterface {
 public:
  LockedCallback(ros::CallbackInterfacePtr inner, std::mutex* mutex)
      : inner_(std::move(inner)), mutex_(mutex) {}
  CallResult call() override {
    std::lock_guard<std::mutex> lock(*mutex_);
    return inner_->call();
  }
  bool ready() override { return inner_->ready(); }

 private:
  ros::CallbackInterfacePtr inner_;
  std::mutex* mutex_;
};

}  // namespace

void LockedCallbackQueue::addCallback(const ros::CallbackInterfacePtr& callback,
                                      uint64_t owner_id) {
  target_->addCallback(boost::make_shared<LockedCallback>(callback, mutex_), owner_id);
}

namespace {
// The longest wait between two looks at ros::ok() (ros::shutdown ends a wait at once; ros::spin
// looks every 0.1 s, a wake-up per tick at 10 Hz).
constexpr double kMaxWaitS = 1.0;
}  // namespace

bool SpinWithOwnTicks(PollThreadTicker* ticker, double period_s, std::function<void()> tick,
                      unsigned id) {
  std::string error;
  const TickClock::duration period =
      std::chrono::duration_cast<TickClock::duration>(std::chrono::duration<double>(period_s));
  if (!ticker->Start(period, std::move(tick), &error)) {
    ROS_FATAL("robot %u: cannot tick: %s", id, error.c_str());
    return false;
  }
  while (ros::ok()) ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(kMaxWaitS));
  ticker->Stop();
  return true;
}

}  // namespace swarm_transport
