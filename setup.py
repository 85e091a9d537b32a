# The package's Python modules (python/marble_maze), beside the generated marble_maze.msg and
# marble_maze.srv: catkin_python_setup() in CMakeLists.txt puts them on the workspace's path.
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["marble_maze"], package_dir={"": "python"}))
