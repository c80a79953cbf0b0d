# The Python package src/swarm_transport (catkin_python_setup; not to be run by hand).
from setuptools import setup

from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=['swarm_transport'], package_dir={'': 'src'}))
