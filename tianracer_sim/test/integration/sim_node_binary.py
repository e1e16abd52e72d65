"""Where the built tianracer_sim_node is, for rostests that start it themselves (with arguments
or an environment a launch file cannot give)."""
import os


def node_binary():
    for d in os.environ.get('CMAKE_PREFIX_PATH', '').split(':'):
        path = os.path.join(d, 'lib', 'tianracer_sim', 'tianracer_sim_node')
        if os.path.exists(path):
            return path
    raise RuntimeError('tianracer_sim_node not found on CMAKE_PREFIX_PATH')
