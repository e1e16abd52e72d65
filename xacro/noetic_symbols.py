"""The expression symbols of ROS Noetic's xacro (1.14) that PyPI's xacro 1.13.3 lacks, added to
1.13.3's global symbols before it runs (ros/xacro noetic-devel, src/xacro/__init__.py,
create_global_symbols, load_yaml, YamlDictWrapper, ConstructUnits, describe them).

Noetic robots' xacros call them: ur_description's `${xacro.load_yaml(file)}` with `!degrees`
values in its YAML. And 1.13.3's own `load_yaml` calls `yaml.load(f)` without a Loader, which
PyYAML 6 (Debian 12) refuses; here both names load with yaml's safe loader, as 1.14 does.

- `xacro.load_yaml`, `xacro.abs_filename`, `xacro.dotify`, `xacro.arg`, `xacro.tokenize`,
  `xacro.message`, `xacro.warning`, `xacro.error`, `xacro.print_location`, `xacro.fatal`;
- a YAML file's maps allow dotted access (`limits.shoulder_pan.max_position`), its values may
  carry the unit tags !radians, !degrees, !meters, !millimeters, !foot, !inches (the value, an
  expression over math's symbols, times the unit's factor);
- `math.<name>` for math's functions and constants, `python.<name>` for the builtins 1.14 puts
  there; `len`, `sorted` and `range` directly.
"""
import math
import re
import types

UNITS = {'!radians': 1.0, '!degrees': math.pi / 180.0, '!meters': 1.0, '!millimeters': 0.001,
         '!foot': 0.3048, '!inches': 0.0254}
PYTHON = ('list', 'dict', 'map', 'len', 'str', 'float', 'int', 'True', 'False', 'min', 'max',
          'round', 'abs', 'all', 'any', 'complex', 'divmod', 'enumerate', 'filter', 'frozenset',
          'hash', 'isinstance', 'issubclass', 'ord', 'repr', 'reversed', 'slice', 'set', 'sum',
          'tuple', 'type', 'zip', 'sorted', 'range')
MATH = {k: v for k, v in math.__dict__.items() if not k.startswith('_')}


def wrap(item):
    if isinstance(item, dict) and not isinstance(item, YamlDict):
        return YamlDict(item)
    if isinstance(item, list) and not isinstance(item, YamlList):
        return YamlList(item)
    return item


class YamlList(list):
    def __getitem__(self, index):
        return wrap(list.__getitem__(self, index))

    def __iter__(self):
        for item in list.__iter__(self):
            yield wrap(item)


class YamlDict(dict):
    """A YAML map with dotted access to its keys."""

    def __getattr__(self, key):
        try:
            return wrap(dict.__getitem__(self, key))
        except KeyError:  # AttributeError, so that hasattr() works
            raise AttributeError("The yaml dictionary has no key '{}'".format(key))

    def __getitem__(self, key):
        return wrap(dict.__getitem__(self, key))


def unit_value(text, factor):
    """A unit-tagged YAML scalar: an expression over math's symbols, times the unit's factor."""
    if re.search(r'__', text):
        raise ValueError('invalid expression in a unit-tagged YAML value: %s' % text)
    return float(eval(compile(text.strip(), '<yaml unit>', 'eval'), {'__builtins__': {}}, MATH)) \
        * factor


def install(xacro):
    """Adds the symbols to the imported xacro 1.13.3 module's global symbols."""
    import yaml

    class Loader(yaml.SafeLoader):
        pass

    for tag, factor in UNITS.items():
        Loader.add_constructor(
            tag, lambda loader, node, f=factor: unit_value(loader.construct_scalar(node), f))

    def load_yaml(filename):
        filename = xacro.abs_filename_spec(filename)
        oldstack = xacro.push_file(filename)
        try:
            with open(filename) as f:
                return wrap(yaml.load(f, Loader=Loader))
        finally:
            xacro.restore_filestack(oldstack)
            xacro.all_includes.append(filename)

    def fatal(*args):
        raise xacro.XacroException(' '.join(map(str, args)))

    def message_adapter(f, location_default):
        def wrapper(*args, **kwargs):
            location = kwargs.pop('print_location', location_default)
            kwargs.pop('file', None)
            f(*args, **kwargs)
            if location:
                xacro.print_location(xacro.filestack)
            return ''
        return wrapper

    def tokenize(s, sep=',; ', skip_empty=True):
        parts = re.split('[{}]'.format(sep), s)
        return [p for p in parts if p] if skip_empty else parts

    builtins = __builtins__ if isinstance(__builtins__, dict) else __builtins__.__dict__
    g = xacro.global_symbols
    g['load_yaml'] = load_yaml
    g['xacro'] = types.SimpleNamespace(
        load_yaml=load_yaml, abs_filename=xacro.abs_filename_spec, dotify=YamlDict,
        arg=lambda name: xacro.substitution_args_context['arg'][name], tokenize=tokenize,
        fatal=fatal, message=message_adapter(xacro.message, False),
        warning=message_adapter(xacro.warning, True), error=message_adapter(xacro.error, True),
        print_location=message_adapter(lambda *a, **k: None, True))
    g['math'] = types.SimpleNamespace(**MATH)
    g['python'] = types.SimpleNamespace(**{k: builtins[k] for k in PYTHON})
    for name in ('len', 'sorted', 'range'):
        g['__builtins__'][name] = builtins[name]
