# The tianracer_sim Python module (waiting on a running sim in sim time, for rostests and
# scripts); installed by catkin_python_setup(). In python/, not src/: src/ holds the C++
# sources, whose folders would otherwise land on sys.path.
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=['tianracer_sim'], package_dir={'': 'python'}))
