"""A scenario file from text, for the batch tests that need no ROS running."""
import os
import shutil
import tempfile
import textwrap

from tianracer_bringup import scenario


def load_text(text, name='s.yaml'):
    """scenario.load() of `text` (dedented) written to a file `name`; (scenario, its path)."""
    d = tempfile.mkdtemp()
    path = os.path.join(d, name)
    with open(path, 'w') as f:
        f.write(textwrap.dedent(text))
    try:
        return scenario.load(path), path
    finally:
        shutil.rmtree(d)
