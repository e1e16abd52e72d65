// The SDF world parser's pieces shared by world.cpp (worlds, models, links, geometry) and
// world_include.cpp (<include>, model files and model:// search, <state>). Private to src/world.
#ifndef TIANRACER_SIM_SRC_WORLD_WORLD_PARSER_H
#define TIANRACER_SIM_SRC_WORLD_WORLD_PARSER_H

#include <optional>
#include <set>
#include <string>
#include <vector>

#include <tinyxml2.h>
#include <tianracer_assets/paths.h>

#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace world_internal {

using tinyxml2::XMLElement;

bool isFile(const std::string& path);
bool isDir(const std::string& path);
std::string join(const std::string& dir, const std::string& rest);
/// "." for a bare file name.
std::string dirName(const std::string& path);
bool startsWith(const std::string& s, const std::string& prefix);

/// State shared by the parse functions of one file.
class Parser : public XmlReader {
 public:
  Parser(std::string source, std::string base_dir, const WorldLoadOptions& options)
      : XmlReader(source, options.warn),
        source_(std::move(source)), base_dir_(std::move(base_dir)), options_(options) {}

  WorldDescription parse(const std::string& xml);
  /// A model file (<sdf><model>) of an <include>.
  ModelDescription parseModelFile(const std::string& xml);

  /// Model files being included, outermost first (an <include> loop is an error).
  std::vector<std::string> include_stack_;
  /// Folders an enclosing <include> found its model in (searched for model:// URIs too).
  std::vector<std::string> model_roots_;

 private:
  void parsePhysics(const XMLElement* e, PhysicsSettings& physics);
  void parsePhysicsOde(const XMLElement* e, PhysicsSettings& physics);
  void parseScene(const XMLElement* e, WorldDescription& world);
  /// A <gravity> vector within limits::kGravity.
  Eigen::Vector3d gravity(const XMLElement* e, const std::string& what);
  /// Fails "<what> x 1e+308 is out of range (|x| <= 1e+06 m)" beyond limits::kSize.
  void checkSize(const XMLElement* e, const Eigen::Vector3d& size, const std::string& what);
  /// A joint's damping, friction or spring stiffness: >= 0 and within limits::kJointCoefficient.
  double coefficient(const XMLElement* e, const std::string& what);
  /// Fails when the world holds more than limits::kModelsPerWorld models.
  void checkModelCount(const XMLElement* e, const WorldDescription& world);
  void parseInclude(const XMLElement* e, WorldDescription& world);
  void parseLight(const XMLElement* e, WorldDescription& world);
  ModelDescription parseModel(const XMLElement* e);
  /// <actor> (world_actor.cpp); throws WorldError at a broken element.
  ActorDescription parseActor(const XMLElement* e);
  LinkDescription parseLink(const XMLElement* e, const std::string& model);
  InertialDescription parseInertial(const XMLElement* e, const std::string& what);
  /// The shape, or nullopt when it is left out (leftOut() has reported why).
  std::optional<Shape> parseGeometry(const XMLElement* e, const std::string& what,
                                     const std::string& kind);
  Friction parseSurface(const XMLElement* e, const std::string& what, ContactDescription* contact);
  struct IncludeSpec {
    std::string uri, name;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    bool has_pose = false;
    std::optional<bool> is_static;
  };
  // Nothing when the include has no <uri> (left out, reported).
  std::optional<IncludeSpec> parseIncludeSpec(const XMLElement* e);
  /// Resolves and parses the model an <include> names, with its <name>/<pose>/<static>;
  /// nullopt when its model is not found (left out, leftOut()).
  std::optional<ModelDescription> includeModel(const XMLElement* e, const IncludeSpec& spec);
  /// Folders searched for model://NAME: Gazebo's model path (tianracer_assets::modelSearchPath:
  /// ~/.gazebo/models, GAZEBO_MODEL_PATH, ROS packages' exported gazebo_model_path), then the
  /// load options' model_paths, the folders of enclosing includes, the world file's folder and
  /// its models/ subfolder.
  std::vector<std::string> modelDirs() const;
  /// The one resolver (tianracer_assets/paths.h) with this file's folder and the folders above.
  tianracer_assets::UriResolver uriResolver() const;
  void applyState(const XMLElement* e, WorldDescription& world, std::set<std::string>& names);
  static void mergeSubModel(ModelDescription* m, const ModelDescription& sub,
                            const Eigen::Isometry3d& X_MS);
  /// *axis_in_model_frame: the <axis> is given in the model frame (parseModel turns it).
  JointDescription parseJoint(const XMLElement* e, const std::string& model,
                              bool* axis_in_model_frame);
  /// The file of a mesh URI; nullopt when it is not found (left out, leftOut()).
  std::optional<std::string> resolveMesh(const XMLElement* e, const std::string& uri,
                                         const std::string& what, const std::string& kind);
  /// A part of the world that cannot be used: `problem` goes to the options' error sink with
  /// `consequence` ("the collision is left out") and parsing goes on, as in Gazebo; with
  /// strict options it is a WorldError.
  void leftOut(const XMLElement* e, const std::string& problem, const std::string& consequence);
  /// As leftOut, for an error whose message names its place already (the robot loader's
  /// <sensor> and <plugin> parsers).
  void leftOutError(const InputError& error, const std::string& consequence);
  // A second model (or actor) of a name the world already has: left out, as Gazebo's
  // World::LoadModel does ("Model with name [...] already exists. Not inserting model.").
  void duplicate(const XMLElement* e, const std::string& name, const std::string& kind = "model");

  std::string source_;
  std::string base_dir_;
  const WorldLoadOptions& options_;
};

}  // namespace world_internal
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_WORLD_WORLD_PARSER_H
