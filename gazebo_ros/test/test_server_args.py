"""gzserver's command line (Gazebo's options, as empty_world.launch and users pass them) to
what the node gets, without ROS: options taken, noted, refused; world lookup; node name."""
import os
import tempfile
import unittest

from gazebo_ros import server


class ParseTest(unittest.TestCase):
    def test_empty_world_launch_arguments(self):
        # What empty_world.launch passes with paused:=true, plus roslaunch's own arguments.
        a = server.parse(['-u', '-e', 'ode', '/w/track.world', '__name:=gazebo',
                          '__log:=/tmp/gazebo-1.log'])
        self.assertTrue(a.paused)
        self.assertEqual(a.world, '/w/track.world')
        self.assertEqual(a.remaps, ['__name:=gazebo', '__log:=/tmp/gazebo-1.log'])
        self.assertIsNone(a.error)
        self.assertEqual(len(a.notes), 1)
        self.assertIn('-e ode: tianracer_sim simulates with Bullet', a.notes[0])

    def test_long_forms_and_values(self):
        a = server.parse(['--pause', '--physics=bullet', '--seed', '42.0', '--verbose', 'w.world'])
        self.assertTrue(a.paused and a.verbose)
        self.assertEqual((a.physics, a.seed, a.world), ('bullet', 42, 'w.world'))

    def test_builtin_plugins_are_silent_others_noted(self):
        a = server.parse(['-s', '/opt/x/libgazebo_ros_api_plugin.so',
                          '--server-plugin=libgazebo_ros_paths_plugin.so', '-s', 'libmine.so'])
        self.assertEqual(len(a.plugins), 3)
        self.assertEqual(len(a.notes), 1)
        self.assertIn('-s libmine.so: system plugin not loaded', a.notes[0])

    def test_options_we_do_not_take_are_named(self):
        a = server.parse(['-r', '--record_path', '/tmp/r', '--iters', '100', '--minimal_comms',
                          '--lockstep', '-o', 'fast', '--bogus', 'w.world', 'extra'])
        text = '\n'.join(a.notes)
        for expected in ('--record: recording is not supported',
                         '--record_path /tmp/r: recording is not supported',
                         '--iters 100: not supported', '--minimal_comms: accepted',
                         '--lockstep: accepted', '-o fast: physics profiles are not supported',
                         '--bogus is not a gzserver option', 'arguments after the world file'):
            self.assertIn(expected, text)
        self.assertIsNone(a.error)

    def test_play_is_refused(self):
        self.assertIn('log playback is not supported', server.parse(['-p', 'x.log']).error)
        self.assertEqual(server.parse(['--seed']).error, 'option --seed needs a value')

    def test_help_and_version(self):
        self.assertTrue(server.parse(['-h']).help)
        self.assertTrue(server.parse(['--version']).version)
        self.assertEqual(server.main(['gzserver', '--help'], 'gzserver'), 0)
        self.assertEqual(server.main(['gzserver', '-p', 'x.log'], 'gzserver'), 2)


class WorldTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        self.shipped = os.path.join(self.tmp, 'shipped')
        self.resources = os.path.join(self.tmp, 'res')
        os.makedirs(os.path.join(self.resources, 'worlds'))
        os.makedirs(self.shipped)
        for path in (os.path.join(self.shipped, 'empty.world'),
                     os.path.join(self.resources, 'worlds', 'cafe.world')):
            open(path, 'w').close()

    def test_lookup_order(self):
        own = os.path.join(self.tmp, 'own.world')
        open(own, 'w').close()
        self.assertEqual(server.resolve_world(own, self.resources, self.shipped), own)
        self.assertEqual(server.resolve_world('worlds/cafe.world', self.resources, self.shipped),
                         os.path.join(self.resources, 'worlds', 'cafe.world'))
        empty = os.path.join(self.shipped, 'empty.world')
        self.assertEqual(server.resolve_world('worlds/empty.world', '', self.shipped), empty)
        self.assertEqual(server.resolve_world(None, '', self.shipped), empty)
        self.assertEqual(server.resolve_world('empty', '', self.shipped), empty)

    def test_missing_world_names_the_folders(self):
        with self.assertRaises(LookupError) as e:
            server.resolve_world('worlds/nowhere.world', self.resources, self.shipped)
        self.assertIn('world file worlds/nowhere.world not found', str(e.exception))
        self.assertIn(self.resources, str(e.exception))
        self.assertIn(self.shipped, str(e.exception))

    def test_missing_world_falls_back_on_empty_world_as_gazebo(self):
        # Gazebo's Server::ParseArgs loads worlds/empty.world when the world file cannot be
        # loaded (steer_bot_sim.launch passes 'worlds/empty_world'; jackal_gazebo's
        # empty_world.launch a gazebo_ros/worlds/empty_world.world Noetic does not ship).
        world, warning = server.world_or_fallback('worlds/empty_world', self.resources,
                                                  self.shipped)
        self.assertEqual(world, os.path.join(self.shipped, 'empty.world'))
        self.assertIn('world file worlds/empty_world not found', warning)
        self.assertIn('falling back on worlds/empty.world, as Gazebo does', warning)
        world, warning = server.world_or_fallback('worlds/cafe.world', self.resources,
                                                  self.shipped)
        self.assertEqual(world, os.path.join(self.resources, 'worlds', 'cafe.world'))
        self.assertIsNone(warning)
        os.remove(os.path.join(self.shipped, 'empty.world'))
        with self.assertRaises(LookupError) as e:
            server.world_or_fallback('worlds/nowhere.world', self.resources, self.shipped)
        self.assertIn('world file worlds/empty.world not found', str(e.exception))


class NamesAndPathsTest(unittest.TestCase):
    def test_node_name(self):
        self.assertEqual(server.node_name([], {}), '/gazebo')
        self.assertEqual(server.node_name(['__name:=sim'], {'ROS_NAMESPACE': '/a'}), '/a/sim')
        self.assertEqual(server.node_name(['__ns:=/b/', '__name:=g'], {}), '/b/g')

    def test_exported_media_paths(self):
        class Out(object):
            stdout = 'my_robot /src/my_robot/media\nother /x/a:/x/b\n'
        paths = server.exported_paths('gazebo_media_path', run=lambda *a, **k: Out())
        self.assertEqual(paths, ['/src/my_robot/media', '/x/a', '/x/b'])
        env = {'GAZEBO_RESOURCE_PATH': '/x/a'}
        server.extend_env_path(env, 'GAZEBO_RESOURCE_PATH', paths)
        self.assertEqual(env['GAZEBO_RESOURCE_PATH'], '/x/a:/src/my_robot/media:/x/b')


if __name__ == '__main__':
    unittest.main()
