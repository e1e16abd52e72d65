// The magnitudes a model or world file may give, checked where the input enters (URDF loader,
// SDF world reader, physics build) so that no NaN and no value that overflows later reaches the
// physics or the ray caster (issue 43). sdformat, urdfdom and Drake check only that a number
// parses (urdfdom: Vector3::init, Link/Joint parsers; sdformat: Param::Set; Drake:
// detail_urdf_parser ParseVectorAttribute), so a box of 1e308 or an origin of 1e30 passes them;
// the bounds here are ours, each far above any real robot or world (docs/bad_input.md).
#ifndef TIANRACER_SIM_COMMON_INPUT_LIMITS_H
#define TIANRACER_SIM_COMMON_INPUT_LIMITS_H

#include <cmath>
#include <cstddef>
#include <optional>
#include <sstream>
#include <string>

#include <Eigen/Core>

namespace tianracer_sim {
namespace limits {

/// Positions (origins, poses), each coordinate, m: the bound of spawn and set_model_state
/// (sim/simulation.h kMaxModelPosition). At 1e6 m a float (Embree, OpenGL) still resolves
/// 6 cm; Embree aborts near 2e9 m.
constexpr double kPosition = 1e6;
/// Shape sizes (box sides, radii, lengths, mesh scale times nothing), m.
constexpr double kSize = 1e6;
/// Mass of a link that moves, kg: a loaded container ship is 2e8 kg.
constexpr double kMass = 1e9;
/// Each inertia tensor component, kg m^2: 1e9 kg at a radius of gyration of 30 m.
constexpr double kInertia = 1e12;
/// Joint damping (N m s/rad, N s/m), friction (N m, N) and spring stiffness, as the 1e6 N
/// bound of apply_body_wrench.
constexpr double kJointCoefficient = 1e6;
/// Gravity, each component, m/s^2 (as set_physics_properties, physics/world.h kMaxGravity).
constexpr double kGravity = 1e3;
/// Physics step, s (as set_physics_properties and ~max_step_size, physics/world.h).
constexpr double kTimeStep = 0.1;

/// Rays per lidar scan (horizontal x vertical samples): a 128-beam lidar at 0.1 degree has
/// 460,800; 1e9 would allocate 4 GB per scan and hang for minutes.
constexpr double kRaysPerScan = 1e6;
/// Pixels per camera image: 8K UHD (7680 x 4320 = 33.2 M) fits; each side stays <= 8192.
constexpr double kImagePixels = 33554432.0;  // 2^25
/// Links of one model (URDF robot or SDF model): the largest robots in use (humanoids, arms
/// with hands) have under 100; a chain of 20,000 hung the loader.
constexpr std::size_t kLinksPerModel = 1000;
/// Models in one world: a city-block world has a few thousand.
constexpr std::size_t kModelsPerWorld = 10000;

/// "1e+06" style text of a number (6 significant digits), as the messages print bounds.
inline std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// "" when v is finite and |v| <= bound, else "<v> is not finite" or
/// "<v> is out of range (|<name>| <= <bound> <unit>)".
inline std::string checkMagnitude(double v, double bound, const std::string& name,
                                  const std::string& unit = "") {
  if (!std::isfinite(v)) return formatNumber(v) + " is not finite";
  if (std::abs(v) > bound)
    return formatNumber(v) + " is out of range (|" + name + "| <= " + formatNumber(bound) +
           (unit.empty() ? "" : " " + unit) + ")";
  return "";
}

/// As checkMagnitude for each component, the first bad one named:
/// "x 1e+30 is out of range (|x| <= 1e+06 m)".
inline std::string checkVector(const Eigen::Vector3d& v, double bound,
                               const std::string& unit = "") {
  static const char* kAxes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    const std::string e = checkMagnitude(v[i], bound, kAxes[i], unit);
    if (!e.empty()) return std::string(kAxes[i]) + " " + e;
  }
  return "";
}

/// The unit vector along `v`, computed so that it cannot overflow (scaled by its largest
/// component first, its norm is then in [1, sqrt(3)]): nullopt when v is not finite or zero.
inline std::optional<Eigen::Vector3d> unitAxis(const Eigen::Vector3d& v) {
  if (!v.allFinite()) return std::nullopt;
  const double m = v.cwiseAbs().maxCoeff();
  if (!(m > 0.0)) return std::nullopt;
  const Eigen::Vector3d s = v / m;
  return Eigen::Vector3d(s / s.norm());
}

}  // namespace limits
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_INPUT_LIMITS_H
