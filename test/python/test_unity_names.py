#!/usr/bin/env python3
"""A fresh build compiles each library in unity batches (the top-level CMakeLists.txt,
docs/performance.md): several of a library's sources in one translation unit. Two sources that
define the same name in an anonymous namespace (or as a file-static function) then clash, but
only in a fresh build or CI: a developer's ccache build compiles them one by one. This test
finds such pairs from the sources, so that the clash shows in every build."""
import os
import re
import unittest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))

# Names defined at the top of an anonymous namespace: functions, constants, types, aliases.
DEFINITION = re.compile(
    r'^(?=[^\s}/#])(?:(?:static|inline|constexpr|const|template\s*<[^>]*>)\s+)*'
    r'(?:(?P<type>struct|class|enum(?:\s+class)?)\s+(?P<tname>\w+)\s*[:{]'
    r'|using\s+(?P<alias>\w+)\s*='
    r'|[\w:<>,\s\*&]+?[\s\*&](?P<var>\w+)\s*(?:=|\{)'
    r'|[\w:<>,\s\*&]+?[\s\*&](?P<func>\w+)\((?P<params>[^)]*)\)\s*(?:const\s*)?\{)',
    re.M)


def library_sources():
    """{library: [source paths]} for every library tianracer_unity_build() batches."""
    libs = {}
    sim_src = os.path.join(REPO, 'tianracer_sim', 'src')
    for area in sorted(os.listdir(sim_src)):
        folder = os.path.join(sim_src, area)
        if not os.path.isdir(folder) or area in ('python', 'tools'):
            continue  # one-source modules and executables, not libraries
        libs['tianracer_sim_' + area] = [os.path.join(d, f) for d, _, files in os.walk(folder)
                                         for f in sorted(files) if f.endswith('.cpp')]
    control = os.path.join(REPO, 'tianracer_control', 'CMakeLists.txt')
    text = open(control).read()
    for name in ('tianracer_control', 'tianracer_control_ros'):
        m = re.search(r'add_library\(%s\s+([^)]*)\)' % name, text)
        libs[name] = [os.path.join(REPO, 'tianracer_control', s) for s in m.group(1).split()]
    assets = os.path.join(REPO, 'tianracer_assets', 'CMakeLists.txt')
    m = re.search(r'add_library\(tianracer_assets_mesh\s+([^)]*)\)', open(assets).read())
    libs['tianracer_assets_mesh'] = [os.path.join(REPO, 'tianracer_assets', s)
                                     for s in m.group(1).split()]
    return libs


def file_local_names(path):
    """(name, signature) of what `path` defines in its anonymous namespaces and as statics."""
    text = open(path, encoding='utf-8').read()
    names = set()
    blocks = []
    for m in re.finditer(r'^namespace \{\n(.*?)^\}  // namespace\n', text, re.S | re.M):
        blocks.append(m.group(1))
    statics = '\n'.join(line for line in text.splitlines() if line.startswith('static '))
    for block in blocks + [statics]:
        for d in DEFINITION.finditer(block):
            if d.group('func'):
                params = re.sub(r'\s+', ' ', d.group('params')).strip()
                names.add((d.group('func'), '(' + params + ')'))
            else:
                name = d.group('tname') or d.group('alias') or d.group('var')
                if name not in ('return', 'else'):
                    names.add((name, ''))
    return names


class UnityNames(unittest.TestCase):
    def test_the_parser_sees_a_file_local_function(self):
        names = file_local_names(os.path.join(REPO, 'tianracer_sim', 'src', 'plugins',
                                              'hector', 'sim_hector.cpp'))
        self.assertTrue(any(n == 'makeHectorImu' for n, _ in names), sorted(names))

    def test_no_library_defines_a_file_local_name_twice(self):
        clashes = []
        for lib, sources in sorted(library_sources().items()):
            self.assertTrue(sources, lib)
            seen = {}
            for path in sources:
                for name in file_local_names(path):
                    seen.setdefault(name, []).append(os.path.relpath(path, REPO))
            for (name, sig), paths in sorted(seen.items()):
                if len(paths) > 1:
                    clashes.append('%s: %s%s in %s' % (lib, name, sig, ', '.join(paths)))
        self.assertEqual(clashes, [], 'these would clash in one unity batch (define them once, '
                         'in a header both include, or give them distinct names):\n' +
                         '\n'.join(clashes))


if __name__ == '__main__':
    unittest.main()
