# The tianracer_gym Python package; installed by catkin_python_setup().
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=['tianracer_gym'], package_dir={'': 'src'}))
