#!/usr/bin/env python3
"""xacro.py: the legacy name of xacro (older launch files call `$(find xacro)/xacro.py`).
Runs the same as ./xacro."""
import os
import runpy
import sys

if __name__ == '__main__':
    here = os.path.dirname(os.path.realpath(__file__))
    runpy.run_path(os.path.join(here, 'xacro'), run_name='__main__')
