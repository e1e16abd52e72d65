// Ackermann geometry from a URDF (urdfdom), and its resolution against explicit parameters.
// ROS-free: the nodes read the parameters and robot_description, this decides and explains.
#ifndef TIANRACER_CONTROL_URDF_GEOMETRY_H
#define TIANRACER_CONTROL_URDF_GEOMETRY_H

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "tianracer_control/ackermann.h"

namespace tianracer_control {

/// The joints that carry the geometry (defaults: the seed's names).
struct AckermannJointNames {
  std::string left_hinge = "left_steering_hinge_joint";
  std::string right_hinge = "right_steering_hinge_joint";
  std::string left_rear_wheel = "left_rear_wheel_joint";
  std::string right_rear_wheel = "right_rear_wheel_joint";
};

/// The model's own names for the Ackermann joints and its base link, and how they were found.
struct ModelNames {
  AckermannJointNames joints;
  std::string base_link;
  std::string prefix;                 // the prefix the names share ("car1/", "car1_"), or ""
  std::vector<std::string> found;     // one line per name found under another name than asked
  std::vector<std::string> warnings;  // names not found or ambiguous: what was looked for
};

/// Finds each of `wanted`'s joints and `base_link` in the URDF: the exact name if the URDF has
/// it, else the one name ending in "/<name>" or "_<name>" (how prefix:=car1 xacros write
/// `car1/left_rear_wheel_joint` or `car1_base_link`). A base link not found by either rule is
/// looked for with the joints' common prefix; failing that it stays as asked (geometryFromUrdf
/// then falls back to the root link). A joint not found or matched more than once keeps the
/// asked name, with a warning naming the parameter (~<default joint name>, e.g.
/// ~left_rear_wheel_joint) and every name it looked for. Throws AckermannError when the XML
/// does not parse as URDF.
ModelNames findModelNames(const std::string& urdf_xml, const AckermannJointNames& wanted,
                          const std::string& base_link = "base_link");

/// Keys of the geometry values, in logging order: wheelbase, hinge_separation, wheel_radius,
/// rear_track, max_steering_angle, rear_axle_x, rear_axle_y, hinge_skew_x, hinge_offset_y
/// (also the parameter names of the nodes).
const std::vector<std::string>& geometryKeys();

/// A value and where it came from, e.g. "parameter ~wheelbase" or "robot_description: ...".
struct GeometryValue {
  double value = 0.0;
  std::string source;
};

/// What a URDF says about the geometry. Values it cannot give are absent, with a warning.
struct UrdfGeometry {
  std::map<std::string, GeometryValue> values;
  std::vector<std::string> warnings;
};

/// Derives from the URDF, all positions expressed in `base_link` (the root link if empty or
/// absent), composing the fixed/joint origins along the tree:
///   rear_axle_x, _y    = mean x, y of the two rear wheel joint origins
///   wheelbase          = mean x of the two hinge joint origins - rear_axle_x
///   hinge_separation   = |y_left_hinge - y_right_hinge|
///   hinge_skew_x       = (x_right_hinge - x_left_hinge) / 2
///   hinge_offset_y     = mean y of the two hinge joint origins - rear_axle_y
///   rear_track         = |y_left_rear - y_right_rear|
///   wheel_radius       = radius of the rear wheel links' collision cylinder or sphere; for a
///                        collision mesh, the largest distance of its (scaled, posed) vertices
///                        from the wheel joint's axis: tianracer_assets' mesh loader and wheel
///                        fit, the ones the simulator sizes the wheel with (needs `mesh_path`
///                        to find the file; else absent, with a warning)
///   max_steering_angle = min(|lower|, |upper|) over both hinges' limits
/// `mesh_path` maps a mesh URI (package://, model://, file:// or a path) to a file; it returns
/// "" or throws (the message is passed on in the warning) when it cannot, e.g.
/// tianracer_assets::UriResolver. Throws AckermannError when the XML does not parse as URDF.
using MeshPathResolver = std::function<std::string(const std::string& uri)>;
UrdfGeometry geometryFromUrdf(const std::string& urdf_xml, const AckermannJointNames& joints,
                              const std::string& base_link = "base_link",
                              const MeshPathResolver& mesh_path = MeshPathResolver());

/// The geometry in use and, per key (geometryKeys() order), its value and source.
struct ResolvedGeometry {
  AckermannGeometry geometry;
  std::vector<std::pair<std::string, GeometryValue>> values;
  std::vector<std::string> warnings;
};

/// Per key: the explicit parameter if given, else the URDF's value, else the default of
/// AckermannGeometry (warned). Throws AckermannError if the result does not validate().
ResolvedGeometry resolveGeometry(const std::map<std::string, double>& parameters,
                                 const UrdfGeometry* urdf);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_URDF_GEOMETRY_H
