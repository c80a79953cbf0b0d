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
  libgeometry-msgs-dev libnav-msgs-dev python3-nav-msgs libros-rosgraph-msgs-dev python3-rosgraph-msgs libeigen3-dev googletest libgtest-dev
  libyaml-cpp-dev python3-numpy python3-matplotlib libdiagnostic-msgs-dev python3-diagnostic-msgs
  iproute2 python3-rosbag python3-nose
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
)
# scripts/fuzz's compiler (scripts/test installs them before it leaves the network).
ST_APT_FUZZ_PACKAGES=(clang-14 libclang-rt-14-dev)
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

# Puts the devel space's Python packages on PYTHONPATH (and nothing else of the workspace's
# environment): its swarm_transport package holds the tools' modules (src/swarm_transport, by
# catkin_python_setup) and the generated messages together. Then `python3 -m swarm_transport.X`.
st_python_path() {
  export PYTHONPATH="$ST_WS/devel/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}"
}

# Prints a free TCP port on loopback.
st_free_port() {
  /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1]); s.close()'
}

# Re-runs the calling script (its path and arguments given) inside a network namespace of its
# own that has only loopback, so that nothing of the run can be reached from another host:
# roscpp's XML-RPC and TCPROS servers listen on every interface whatever ROS_IP says (issue
# 11). Call it after apt and the build, which need the network. Where a namespace cannot be
# made (no root and no user namespaces, a restricted container) the run goes on in the
# machine's network with one line saying so. ST_SHARED_NETWORK=1 skips it on purpose.
st_private_network() {
  [ "${ST_IN_PRIVATE_NETWORK:-}" = 1 ] && return 0
  if [ "${ST_SHARED_NETWORK:-}" = 1 ]; then
    echo "[swarm_transport] network: the machine's (ST_SHARED_NETWORK=1)" >&2
    return 0
  fi
  local unshare_args=(--net)
  [ "$(id -u)" -ne 0 ] && unshare_args=(--net --map-root-user)
  if ! unshare "${unshare_args[@]}" -- ip link set lo up 2>/dev/null; then
    echo "[swarm_transport] network: the machine's (a private network namespace is not" \
      "permitted here; ROS stays on loopback addresses, but its servers listen on every" \
      "interface)" >&2
    return 0
  fi
  exec unshare "${unshare_args[@]}" -- env ST_IN_PRIVATE_NETWORK=1 /bin/bash -c \
    'ip link set lo up && echo "[swarm_transport] network: a namespace of its own (loopback" \
       "only: no other host can reach the run)" >&2 && exec "$@"' st_private_network "$@"
}
