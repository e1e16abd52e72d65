# The tianracer_bringup Python module (scenario batches); installed by catkin_python_setup().
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=['tianracer_bringup'], package_dir={'': 'src'}))
