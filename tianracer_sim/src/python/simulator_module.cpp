// Python bindings of the ROS-free simulation (env/sim_env.h): `tianracer_sim.simulator`.
//   Simulation      one robot in one world: step, commands or Ackermann drive, observations as
//                   numpy arrays (only those asked for are computed), reset, reseed
//   SimulationBatch several Simulations stepped on C++ threads, the GIL released
// docs/learning.md describes them; tianracer_gym builds the Gymnasium environments on them.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <mutex>
#include <set>
#include <thread>

#include <tianracer_control/ackermann.h>
#include <tianracer_control/joint_controllers.h>

#include "tianracer_sim/env/centreline.h"
#include "tianracer_sim/common/sdf_pose.h"
#include "tianracer_sim/env/parallel.h"
#include "tianracer_sim/env/sim_env.h"
#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/plugins/camera/camera_config.h"
#include "tianracer_sim/world/world.h"

namespace py = pybind11;
using namespace tianracer_sim;  // NOLINT: a binding file

namespace {

// --- warnings: collected from any thread, handed to Python by drain_warnings() ---------------
struct Warnings {
  std::mutex mutex;
  std::set<std::string> seen;  // each distinct message once per process
  std::vector<std::string> pending;
  void add(const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex);
    if (seen.insert(text).second) pending.push_back(text);
  }
  std::vector<std::string> drain() {
    std::lock_guard<std::mutex> lock(mutex);
    std::vector<std::string> out;
    out.swap(pending);
    return out;
  }
};
Warnings& warnings() {
  static Warnings w;
  return w;
}

// Messages quote names and values from the user's files, which need not be UTF-8: decoded
// with backslashreplace, a stray byte reads \xe9 and nothing is lost (pybind11's strict
// decoding left the exception's message empty and made drain_warnings() raise).
py::str text(const std::string& s) {
  PyObject* o = PyUnicode_DecodeUTF8(s.data(), static_cast<Py_ssize_t>(s.size()), "backslashreplace");
  if (!o) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

// Gazebo's pose convention, as SDF's <pose> (common/sdf_pose.h).
Eigen::Isometry3d poseFrom(const std::vector<double>& p, const char* what) {
  double x = 0, y = 0, z = 0, roll = 0, pitch = 0, yaw = 0;
  if (p.size() == 3) {
    x = p[0], y = p[1], yaw = p[2];
  } else if (p.size() == 6) {
    x = p[0], y = p[1], z = p[2], roll = p[3], pitch = p[4], yaw = p[5];
  } else {
    throw EnvError(std::string(what) + " must be (x, y, yaw) or (x, y, z, roll, pitch, yaw), got " +
                   std::to_string(p.size()) + " values");
  }
  return sdfPose(x, y, z, roll, pitch, yaw);
}

std::string dtypeName(char c) {
  switch (c) {
    case 'f': return "float32";
    case 'd': return "float64";
    case 'B': return "uint8";
    case 'H': return "uint16";
  }
  return "?";
}

const char* kindName(Observation::Kind k) {
  switch (k) {
    case Observation::Kind::kScan: return "scan";
    case Observation::Kind::kImage: return "image";
    case Observation::Kind::kDepth: return "depth";
    case Observation::Kind::kImu: return "imu";
    case Observation::Kind::kGroundTruth: return "ground_truth";
    case Observation::Kind::kOdom: return "odom";
    case Observation::Kind::kJoints: return "joints";
  }
  return "?";
}

py::dtype dtypeOf(const Observation& o) { return py::dtype(dtypeName(o.dtype)); }

py::array newArray(const Observation& o, const std::vector<std::size_t>& prefix = {}) {
  std::vector<py::ssize_t> shape(prefix.begin(), prefix.end());
  for (std::size_t d : o.shape) shape.push_back(static_cast<py::ssize_t>(d));
  return py::array(dtypeOf(o), shape);
}

std::size_t observationIndex(const SimEnv& env, const std::string& key) {
  const auto& obs = env.observations();
  for (std::size_t i = 0; i < obs.size(); ++i) {
    if (obs[i].key == key) return i;
  }
  std::string keys;
  for (const auto& o : obs) keys += (keys.empty() ? "" : ", ") + o.key;
  throw py::key_error("no observation '" + key + "' (observed: " + (keys.empty() ? "none" : keys) + ")");
}

/// A numpy array the C++ side may write into from other threads: checked here, written there.
struct Destination {
  char* data = nullptr;
  std::size_t row_bytes = 0;  // bytes of one env's value
};

Destination destination(const py::handle& array, const Observation& o, std::size_t n) {
  if (!py::isinstance<py::array>(array)) throw py::type_error("out['" + o.key + "'] is not a numpy array");
  py::array a = py::reinterpret_borrow<py::array>(array);
  if (!a.dtype().is(dtypeOf(o))) {
    throw py::type_error("out['" + o.key + "'] must be " + dtypeName(o.dtype));
  }
  if (!(a.flags() & py::array::c_style) || !a.writeable()) {
    throw py::value_error("out['" + o.key + "'] must be a writeable C-contiguous array");
  }
  std::vector<std::size_t> want = {n};
  want.insert(want.end(), o.shape.begin(), o.shape.end());
  bool ok = static_cast<std::size_t>(a.ndim()) == want.size();
  for (std::size_t d = 0; ok && d < want.size(); ++d) ok = static_cast<std::size_t>(a.shape(d)) == want[d];
  if (!ok) throw py::value_error("out['" + o.key + "'] has the wrong shape");
  return {static_cast<char*>(a.mutable_data()), o.bytes()};
}

py::dict commandDict(const CommandSpec& c) {
  py::dict d;
  d["controller"] = c.controller;
  d["joint"] = c.joint;
  d["type"] = c.type;
  d["lower"] = c.lower;
  d["upper"] = c.upper;
  return d;
}

/// Several simulations stepped together on C++ threads.
class Batch {
 public:
  Batch(std::vector<SimEnv*> envs, int threads)
      : envs_(std::move(envs)),
        pool_(threads > 0 ? threads
                          : std::max(1, std::min<int>(static_cast<int>(envs_.size()),
                                                      static_cast<int>(std::thread::hardware_concurrency())))) {
    if (envs_.empty()) throw EnvError("SimulationBatch needs at least one Simulation");
    for (SimEnv* e : envs_) {
      if (e->observations().size() != envs_[0]->observations().size()) {
        throw EnvError("the Simulations of a batch must observe the same outputs");
      }
      for (std::size_t i = 0; i < e->observations().size(); ++i) {
        const Observation& a = e->observations()[i];
        const Observation& b = envs_[0]->observations()[i];
        if (a.key != b.key || a.shape != b.shape || a.dtype != b.dtype) {
          throw EnvError("the Simulations of a batch must observe the same outputs (" + a.key + ")");
        }
      }
    }
  }

  int threads() const { return pool_.threads(); }
  std::size_t size() const { return envs_.size(); }

  /// Per env i with active[i]: its action (Ackermann speed and steering, or the controller
  /// commands), `steps` physics steps, its observations into out[key][i]; contacts begun into
  /// contacts[i]. Inputs are checked first, then the GIL is released while the envs step.
  void step(py::array_t<double, py::array::c_style | py::array::forcecast> actions,
            const std::string& mode, int steps, py::dict out,
            py::array_t<bool, py::array::c_style | py::array::forcecast> active,
            py::array_t<std::int64_t, py::array::c_style> contacts) {
    const std::size_t n = envs_.size();
    const bool ackermann = mode == "ackermann";
    if (!ackermann && mode != "commands") throw EnvError("mode must be 'ackermann' or 'commands'");
    if (steps < 1) throw EnvError("steps must be >= 1");
    const std::size_t width = ackermann ? 2 : envs_[0]->commands().size();
    if (actions.ndim() != 2 || static_cast<std::size_t>(actions.shape(0)) != n ||
        static_cast<std::size_t>(actions.shape(1)) != width) {
      throw EnvError("actions must have shape (" + std::to_string(n) + ", " + std::to_string(width) + ")");
    }
    if (active.size() != static_cast<py::ssize_t>(n) || contacts.size() != static_cast<py::ssize_t>(n)) {
      throw EnvError("active and contacts need one entry per Simulation");
    }
    const auto& obs = envs_[0]->observations();
    std::vector<Destination> dest;
    for (const Observation& o : obs) {
      if (!out.contains(o.key)) throw py::key_error("out has no array for '" + o.key + "'");
      dest.push_back(destination(out[py::str(o.key)], o, n));
    }
    const double* a = actions.data();
    const bool* on = active.data();
    std::int64_t* hits = contacts.mutable_data();
    py::gil_scoped_release release;
    pool_.run(static_cast<int>(n), [&](int i) {
      if (!on[i]) return;
      SimEnv& env = *envs_[i];
      const double* row = a + static_cast<std::size_t>(i) * width;
      if (ackermann) {
        env.setAckermann(row[0], row[1]);
      } else {
        env.setCommands(row, width);
      }
      hits[i] = static_cast<std::int64_t>(env.step(steps));
      for (std::size_t k = 0; k < dest.size(); ++k) {
        env.read(k, dest[k].data + static_cast<std::size_t>(i) * dest[k].row_bytes);
      }
    });
  }

  /// Env i's current observations into out[key][i] (after a reset).
  void read(std::size_t i, py::dict out) {
    SimEnv& env = *envs_.at(i);
    for (std::size_t k = 0; k < env.observations().size(); ++k) {
      const Observation& o = env.observations()[k];
      const Destination d = destination(out[py::str(o.key)], o, envs_.size());
      env.read(k, d.data + i * d.row_bytes);
    }
  }

 private:
  std::vector<SimEnv*> envs_;
  ParallelFor pool_;
};

}  // namespace

PYBIND11_MODULE(simulator, m) {
  m.doc() = "The tianracer simulation without ROS (docs/learning.md).";

  // Bad input (a model, world, controller YAML, sensor or physics setting that cannot be used:
  // the one InputError of diagnostic.h, message with file and line) is a ValueError in Python.
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetObject(input_error.ptr(), text(e.what()).ptr());
    }
  });

  m.def("drain_warnings",
        [] {
          py::list out;
          for (const std::string& w : warnings().drain()) out.append(text(w));
          return out;
        },
        "Warnings of the loaders and sensors since the last call (each distinct one once).");

  py::class_<SimEnv>(m, "Simulation")
      .def(py::init([](const std::string& model, const std::vector<std::string>& model_args,
                       const std::string& urdf, const std::string& model_dir,
                       const std::string& robot_name, const std::string& control_config,
                       const std::string& control_namespace,
                       const std::vector<std::string>& controllers, const std::string& world,
                       const std::string& worlds_dir, std::optional<std::vector<double>> pose,
                       std::uint64_t seed, double max_step_size,
                       const std::vector<std::string>& disable_sensors,
                       const std::vector<std::string>& observe, py::object find_package,
                       bool timing) {
             EnvConfig c;
             c.model = model;
             c.model_args = model_args;
             c.urdf = urdf;
             c.model_dir = model_dir;
             c.robot_name = robot_name;
             c.control_config = control_config;
             c.control_namespace = control_namespace;
             c.controllers = controllers;
             c.world = world;
             c.worlds_dir = worlds_dir;
             if (pose) {
               c.X_WB = poseFrom(*pose, "pose");
               c.drop_to_ground = pose->size() == 3;
             }
             c.seed = seed;
             c.max_step_size = max_step_size;
             c.disabled_sensors = disable_sensors;
             c.observe = observe;
             if (find_package.is_none()) {
               // ROS's own lookup (ROS_PACKAGE_PATH, as xacro's $(find)); no master needed.
               py::object rospack = py::module_::import("rospkg").attr("RosPack")();
               find_package = py::cpp_function([rospack](const std::string& pkg) -> py::object {
                 try {
                   return rospack.attr("get_path")(pkg);
                 } catch (const py::error_already_set&) {
                   return py::none();
                 }
               });
             }
             // Called while loading (GIL held); the GIL is taken anyway, in case.
             auto holder = std::make_shared<py::object>(find_package);
             c.find_package = [holder](const std::string& pkg) -> std::string {
               py::gil_scoped_acquire gil;
               py::object r = (*holder)(pkg);
               return r.is_none() ? std::string() : r.cast<std::string>();
             };
             c.warn = [](const std::string& w) { warnings().add(w); };
             c.timing = timing;
             return std::make_unique<SimEnv>(std::move(c));
           }),
           py::arg("model") = "", py::arg("model_args") = std::vector<std::string>(),
           py::arg("urdf") = "", py::arg("model_dir") = "", py::arg("robot_name") = "",
           py::arg("control_config") = "", py::arg("control_namespace") = "",
           py::arg("controllers") = std::vector<std::string>(), py::arg("world") = "empty",
           py::arg("worlds_dir") = "", py::arg("pose") = py::none(), py::arg("seed") = 0,
           py::arg("max_step_size") = 0.0,
           py::arg("disable_sensors") = std::vector<std::string>(),
           py::arg("observe") = std::vector<std::string>{"odom"},
           py::arg("find_package") = py::none(), py::arg("timing") = false,
           "Loads the model (xacro with model_args, URDF file or URDF text), its controllers "
           "(control_config YAML under control_namespace) and the world (a shipped name, .world "
           "or map .yaml); pose (x, y, yaw) rests the robot on the ground there, (x, y, z, roll, "
           "pitch, yaw) puts it there. Only the outputs named in `observe` are computed.")
      .def("step",
           [](SimEnv& e, int n) {
             if (n < 1) throw EnvError("step(n): n must be >= 1, got " + std::to_string(n));
             py::gil_scoped_release release;
             return e.step(n);
           },
           py::arg("n") = 1, "n physics steps; returns the contacts begun during them.")
      .def("set_commands",
           [](SimEnv& e, py::array_t<double, py::array::c_style | py::array::forcecast> v) {
             e.setCommands(v.data(), static_cast<std::size_t>(v.size()));
           },
           py::arg("values"), "One command per entry of `commands`, in that order.")
      .def("set_ackermann", &SimEnv::setAckermann, py::arg("speed"), py::arg("steering"),
           "The cmd_vel node's Ackermann drive command: speed (m/s), steering angle (rad).")
      .def("reset",
           [](SimEnv& e, std::optional<std::vector<double>> pose) {
             py::gil_scoped_release release;
             if (pose) {
               e.reset(poseFrom(*pose, "pose"), pose->size() == 3);
             } else {
               e.reset();
             }
           },
           py::arg("pose") = py::none(),
           "Time 0, the robot at `pose` ((x, y, yaw) on the ground, or (x, y, z, roll, pitch, "
           "yaw)) or its spawn pose; the initial observation is taken.")
      .def("reseed",
           [](SimEnv& e, std::uint64_t seed) {
             py::gil_scoped_release release;
             e.reseed(seed);
           },
           py::arg("seed"), "A new simulation whose sensors' noise has this seed.")
      .def_property_readonly("time", &SimEnv::time)
      .def_property_readonly("dt", &SimEnv::dt)
      .def_property_readonly("urdf", &SimEnv::urdf)
      .def_property_readonly("robot_name", &SimEnv::robotName)
      .def_property_readonly("robot_namespace", &SimEnv::robotNamespace,
                             "its ros_control namespace, as the node has it")
      .def_property_readonly("control_namespace", &SimEnv::controlNamespace,
                             "where its controllers were read, as the node reads them")
      .def_property_readonly("controllers", &SimEnv::controllers,
                             "(name, type) of every controller, in load order")
      .def_property_readonly("sensors", &SimEnv::sensors, "(name, kind) of every sensor")
      .def_property_readonly("commands",
                             [](const SimEnv& e) {
                               py::list l;
                               for (const CommandSpec& c : e.commands()) l.append(commandDict(c));
                               return l;
                             })
      .def_property_readonly(
          "ackermann",
          [](const SimEnv& e) -> py::object {
            const AckermannDrive* d = e.ackermann();
            if (!d) return py::none();
            py::dict r;
            r["max_speed"] = d->limits().max_speed;
            r["max_steering_left"] = d->maxSteeringLeft();
            r["max_steering_right"] = d->maxSteeringRight();
            r["wheelbase"] = d->geometry().wheelbase;
            r["wheel_radius"] = d->geometry().wheel_radius;
            r["controllers"] = std::vector<std::string>(d->controllers().begin(), d->controllers().end());
            return std::move(r);
          },
          "The Ackermann drive's limits, or None (ackermann_problem says why).")
      .def_property_readonly("ackermann_problem", &SimEnv::ackermannProblem)
      .def_property_readonly(
          "observation_specs",
          [](const SimEnv& e) {
            py::list l;
            for (const Observation& o : e.observations()) {
              std::vector<py::ssize_t> shape(o.shape.begin(), o.shape.end());
              l.append(py::make_tuple(o.key, py::tuple(py::cast(shape)), dtypeOf(o)));
            }
            return l;
          },
          "(key, shape, dtype) of each observation")
      .def_property_readonly(
          "observation_kinds",
          [](const SimEnv& e) {
            py::dict d;
            for (const Observation& o : e.observations()) d[py::str(o.key)] = kindName(o.kind);
            return d;
          },
          "key -> scan, image, depth, imu, ground_truth, odom or joints")
      .def("observation",
           [](const SimEnv& e) {
             py::dict d;
             for (std::size_t i = 0; i < e.observations().size(); ++i) {
               py::array a = newArray(e.observations()[i]);
               e.read(i, a.mutable_data());
               d[py::str(e.observations()[i].key)] = a;
             }
             return d;
           },
           "Every observation, as new numpy arrays.")
      .def("read",
           [](const SimEnv& e, const std::string& key) {
             const std::size_t i = observationIndex(e, key);
             py::array a = newArray(e.observations()[i]);
             e.read(i, a.mutable_data());
             return a;
           },
           py::arg("key"))
      .def("stamps",
           [](const SimEnv& e) {
             py::dict d;
             for (const Observation& o : e.observations()) d[py::str(o.key)] = o.stamp;
             return d;
           },
           "Sim time each observation was sampled at (NaN before the first sample).")
      .def("odom",
           [](const SimEnv& e) {
             py::array_t<double> a(13);
             e.odom(a.mutable_data());
             return a;
           },
           "Ground truth as <ns>/ground_truth/odom: x y z, qx qy qz qw (world), vx vy vz, wx wy "
           "wz (base_link).")
      .def("joint_states",
           [](const SimEnv& e) {
             JointStates js;
             e.jointStates(&js);
             py::dict d;
             d["name"] = js.name;
             d["position"] = py::array(py::cast(js.position));
             d["velocity"] = py::array(py::cast(js.velocity));
             d["effort"] = py::array(py::cast(js.effort));
             return d;
           })
      .def("sensor_samples",
           [](const SimEnv& e) {
             py::dict d;
             for (const auto& s : e.simulator().sensors()) {
               if (s->link().model == e.robot()) d[py::str(s->name())] = s->stat().renders;
             }
             return d;
           },
           "Samples computed so far per sensor (scans cast, frames rendered): nothing is "
           "computed for a sensor that is not observed.")
      .def_property_readonly("contact_count", &SimEnv::contactCount,
                             "Contacts begun since the start (a wheel on the ground is none).")
      .def("contacts",
           [](SimEnv& e) {
             py::list l;
             for (const LinkContact& c : e.contacts()) {
               py::dict d;
               d["own"] = c.own;
               d["other"] = c.other;
               d["position"] = std::vector<double>{c.position_W.x(), c.position_W.y(), c.position_W.z()};
               d["normal"] = std::vector<double>{c.normal_W.x(), c.normal_W.y(), c.normal_W.z()};
               d["depth"] = c.depth;
               d["impulse"] = c.impulse;
               l.append(d);
             }
             return l;
           },
           "The robot's contacts in the last physics step.")
      .def("timing",
           [](const SimEnv& e) {
             py::dict d;
             d["physics"] = e.timing().physics;
             d["sensors"] = e.timing().sensors;
             d["frames_wait"] = e.timing().frames_wait;
             d["steps"] = e.timing().steps;
             return d;
           },
           "With timing=True: CPU s of the stepping thread in physics and in sensors, wall s "
           "waiting for camera frames, physics steps.")
      .def("clear_timing", &SimEnv::clearTiming);

  py::class_<Centreline>(m, "Centreline")
      .def(py::init([](const std::vector<std::pair<double, double>>& points, bool closed) {
             std::vector<Eigen::Vector2d> p;
             for (const auto& [x, y] : points) p.emplace_back(x, y);
             return std::make_unique<Centreline>(std::move(p), closed);
           }),
           py::arg("points"), py::arg("closed") = true,
           "A track's centreline through `points` ((x, y) pairs); closed: a lap.")
      .def_property_readonly("length", &Centreline::length)
      .def_property_readonly("closed", &Centreline::closed)
      .def("project",
           [](const Centreline& c, double x, double y, int hint) {
             const Centreline::Projection p = c.project(Eigen::Vector2d(x, y), hint);
             return py::make_tuple(p.s, p.lateral, p.segment);
           },
           py::arg("x"), py::arg("y"), py::arg("hint") = -1,
           "(s, lateral, segment) of the nearest point: arc length, signed distance (+ left), "
           "and the segment (the hint of the next call, which then searches near it only).")
      .def("advance", &Centreline::advance, py::arg("s0"), py::arg("s1"),
           "s1 - s0, the shorter way round a closed line.")
      .def("pose",
           [](const Centreline& c, double s) {
             const Eigen::Vector3d p = c.pose(s);
             return py::make_tuple(p.x(), p.y(), p.z());
           },
           py::arg("s"), "(x, y, heading) at arc length s.");

  py::class_<Batch>(m, "SimulationBatch")
      .def(py::init([](py::list sims, int threads) {
             std::vector<SimEnv*> envs;
             for (py::handle h : sims) envs.push_back(h.cast<SimEnv*>());
             return std::make_unique<Batch>(std::move(envs), threads);
           }),
           py::arg("simulations"), py::arg("threads") = 0, py::keep_alive<1, 2>(),
           "Simulations stepped together on `threads` C++ threads (0: one per simulation, at "
           "most one per core).")
      .def_property_readonly("threads", &Batch::threads)
      .def("__len__", &Batch::size)
      .def("step", &Batch::step, py::arg("actions"), py::arg("mode"), py::arg("steps"),
           py::arg("out"), py::arg("active"), py::arg("contacts"),
           "Each active simulation applies its row of `actions` ('ackermann': speed, steering; "
           "'commands': one per controller), steps `steps` times and writes its observations "
           "into out[key][i] and the contacts begun into contacts[i]; the GIL is released.")
      .def("read", &Batch::read, py::arg("index"), py::arg("out"));
}
