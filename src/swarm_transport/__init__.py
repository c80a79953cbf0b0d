"""The project's Python tools (scripts/experiment, bench, scenario, demo and the test helpers).

Built with catkin_python_setup, so that the devel space's swarm_transport package holds these
modules beside the generated swarm_transport.msg and swarm_transport.srv.
"""
