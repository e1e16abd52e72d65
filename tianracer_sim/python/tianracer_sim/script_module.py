"""A script without the .py suffix (scripts/save_frames, spawn_model, ...) as a module, so that
a test can call its functions."""
import importlib.machinery
import importlib.util
import os


def load_script(path, name=None):
    """The script at `path`, run as a module named `name` (default: its file name)."""
    name = name or os.path.basename(path)
    loader = importlib.machinery.SourceFileLoader(name, path)
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(name, loader))
    loader.exec_module(module)
    return module
