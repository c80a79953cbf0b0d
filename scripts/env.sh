# Shared environment of the project's scripts (sourced, not run): Debian's ROS under /usr,
# Debian's python first on PATH, ROS kept on loopback.
# shellcheck shell=bash
ST_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ST_WS="$ST_ROOT/.catkin_ws"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"
export ROS_IP=127.0.0.1
export ROS_HOSTNAME=127.0.0.1
unset ROS_MASTER_URI_SET_BY_USER
export PYTHONDONTWRITEBYTECODE=1

# Debian packages the project needs to build, test and run headless.
ST_APT_PACKAGES=(
  build-essential cmake ros-core-dev catkin python3-catkin-pkg python3-rospy python3-rostest
  python3-roslaunch python3-rosnode python3-rostopic python3-rosservice python3-yaml
  rosbash libtf2-ros-dev libtf2-geometry-msgs-dev libstd-srvs-dev libvisualization-msgs-dev
  libgeometry-msgs-dev libros-rosgraph-msgs-dev python3-rosgraph-msgs libeigen3-dev googletest libgtest-dev
  libyaml-cpp-dev python3-numpy python3-matplotlib libdiagnostic-msgs-dev python3-diagnostic-msgs
  iproute2 python3-rosbag
)
# Only for --rviz.
ST_APT_VIEW_PACKAGES=(rviz xvfb x11-apps imagemagick)

# Installs the named Debian packages that are missing; quiet when all are there.
st_apt_ensure() {
  local missing=()
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "[swarm_transport] installing: ${missing[*]}" >&2
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  if ! $sudo apt-get install -y -qq "${missing[@]}" >/tmp/st_apt.log 2>&1; then
    $sudo apt-get update -qq >>/tmp/st_apt.log 2>&1
    $sudo apt-get install -y -qq "${missing[@]}" >>/tmp/st_apt.log 2>&1 || {
      echo "[swarm_transport] apt-get install failed, see /tmp/st_apt.log" >&2; tail -20 /tmp/st_apt.log >&2; return 1; }
  fi
}

# Sources the built workspace.
st_source_ws() {
  # shellcheck disable=SC1091
  set +u; source "$ST_WS/devel/setup.bash"; set -u
}

# Prints a free TCP port on loopback.
st_free_port() {
  /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1]); s.close()'
}
