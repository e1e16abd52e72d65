// Tests every shipped file of tianracer_description: the xacro expands (with and
// without the Gazebo laser), the URDF matches the seed literally, every mesh it references loads
// and fits the joint layout, and the committed meshes are exactly the generator's output.
// No roscore needed; xacro and the generator run as child processes.

#include <gtest/gtest.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace tianracer_description
{
namespace
{
namespace fs = std::filesystem;

const std::string kSourceDir = TIANRACER_DESCRIPTION_SOURCE_DIR;
const std::string kXacroPath = kSourceDir + "/urdf/tianracer_description.xacro";
const std::string kMeshPrefix = "package://tianracer_description/";

// Layout constants the meshes are built against (docs/bringup.md, The model).
constexpr double kWheelRadius = 0.032;
constexpr double kGroundZ = 0.0225 - kWheelRadius;  // rear wheel centre z minus radius
constexpr double kNonWheelMinZ = kGroundZ + 0.003;  // clearance kept by everything but wheels
constexpr double kLidarScanPlaneZ = 0.0124;          // in the lidar frame (gazebo sensor pose)

const std::vector<std::string> kWheelLinks = {"left_front_wheel", "right_front_wheel",
                                              "left_rear_wheel", "right_rear_wheel"};

std::string shellQuote(const std::string& s)
{
  std::string out = "'";
  for (char c : s)
    out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct CommandResult
{
  int status = -1;
  std::string output;  // stdout only; stderr goes to the test log
};

CommandResult runCommand(const std::string& command)
{
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
    return result;
  std::array<char, 4096> buffer;
  size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  result.status = pclose(pipe);
  return result;
}

CommandResult expandXacro(bool disable_gazebo_laser)
{
  const std::string env = disable_gazebo_laser ? "env DISABLE_GAZEBO_LASER=true "
                                               : "env -u DISABLE_GAZEBO_LASER ";
  return runCommand(env + "xacro " + shellQuote(kXacroPath));
}

// Expanded once per process: xacro takes about a second.
const CommandResult& defaultExpansion()
{
  static const CommandResult result = expandXacro(false);
  return result;
}

urdf::ModelInterfaceSharedPtr parsedModel()
{
  static const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(defaultExpansion().output);
  return model;
}

Eigen::Isometry3d toEigen(const urdf::Pose& pose)
{
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  X.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y,
                                  pose.rotation.z)
                   .toRotationMatrix();
  return X;
}

// X_BL: pose of link L in base_link with every joint at zero.
Eigen::Isometry3d poseInBaseLink(const urdf::ModelInterface& model, const std::string& link)
{
  Eigen::Isometry3d X_BL = Eigen::Isometry3d::Identity();
  urdf::LinkConstSharedPtr l = model.getLink(link);
  while (l && l->parent_joint)
  {
    X_BL = toEigen(l->parent_joint->parent_to_joint_origin_transform) * X_BL;
    l = model.getLink(l->parent_joint->parent_link_name);
  }
  return X_BL;
}

using Triangle = std::array<Eigen::Vector3d, 3>;

struct LoadedMesh
{
  bool ok = false;
  std::string error;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Triangle> triangles;
};

void collectNode(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent,
                 LoadedMesh& out)
{
  const aiMatrix4x4 X = parent * node->mTransformation;
  for (unsigned m = 0; m < node->mNumMeshes; ++m)
  {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
    std::vector<Eigen::Vector3d> v(mesh->mNumVertices);
    for (unsigned i = 0; i < mesh->mNumVertices; ++i)
    {
      const aiVector3D p = X * mesh->mVertices[i];
      v[i] = Eigen::Vector3d(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f)
    {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 3)
        out.triangles.push_back({v[face.mIndices[0]], v[face.mIndices[1]], v[face.mIndices[2]]});
    }
    out.vertices.insert(out.vertices.end(), v.begin(), v.end());
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    collectNode(scene, node->mChildren[c], X, out);
}

LoadedMesh loadMesh(const std::string& path)
{
  LoadedMesh out;
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (!scene || !scene->mRootNode)
  {
    out.error = importer.GetErrorString();
    return out;
  }
  collectNode(scene, scene->mRootNode, aiMatrix4x4(), out);
  out.ok = true;
  return out;
}

std::string meshPathFromUri(const std::string& uri)
{
  if (uri.rfind(kMeshPrefix, 0) != 0)
    return "";
  return kSourceDir + "/" + uri.substr(kMeshPrefix.size());
}

// link name -> mesh file, from every visual and collision of the model.
std::map<std::string, std::set<std::string>> referencedMeshes(const urdf::ModelInterface& model)
{
  std::map<std::string, std::set<std::string>> out;
  for (const auto& [name, link] : model.links_)
  {
    auto add = [&, name = name](const urdf::GeometrySharedPtr& g) {
      if (g && g->type == urdf::Geometry::MESH)
        out[name].insert(std::static_pointer_cast<urdf::Mesh>(g)->filename);
    };
    for (const auto& v : link->visual_array)
      add(v->geometry);
    for (const auto& c : link->collision_array)
      add(c->geometry);
  }
  return out;
}

std::string readFile(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// xacro re-serialises attributes (name before type), so match the element, not a literal.
bool hasSensorOfType(const std::string& urdf_xml, const std::string& type)
{
  const std::regex sensor("<sensor\\b[^>]*\\btype=\"" + type + "\"");
  return std::regex_search(urdf_xml, sensor);
}

bool isWheel(const std::string& link)
{
  return std::find(kWheelLinks.begin(), kWheelLinks.end(), link) != kWheelLinks.end();
}

// ----------------------------------------------------------------------------------------------
// Xacro

TEST(Xacro, ExpandsWithRaySensorWhenGazeboLaserEnabled)
{
  const CommandResult& r = defaultExpansion();
  ASSERT_EQ(0, r.status) << "xacro failed on " << kXacroPath;
  EXPECT_NE(std::string::npos, r.output.find("<robot")) << r.output.substr(0, 400);
  EXPECT_TRUE(hasSensorOfType(r.output, "ray"));
  EXPECT_NE(std::string::npos, r.output.find("<link name=\"lidar\""));
}

TEST(Xacro, DisableGazeboLaserDropsRaySensorButKeepsLidarLink)
{
  const CommandResult r = expandXacro(true);
  ASSERT_EQ(0, r.status) << "xacro failed on " << kXacroPath;
  EXPECT_FALSE(hasSensorOfType(r.output, "ray"));
  EXPECT_NE(std::string::npos, r.output.find("<link name=\"lidar\""));
  EXPECT_TRUE(hasSensorOfType(r.output, "camera"));
  EXPECT_TRUE(hasSensorOfType(r.output, "depth"));
}

// ----------------------------------------------------------------------------------------------
// URDF against the seed (values copied literally from the xacro).

TEST(Urdf, ParsesWithExactlyTheSeedLinksAndJoints)
{
  const auto model = parsedModel();
  ASSERT_TRUE(model) << "urdf::parseURDF failed";
  EXPECT_EQ("tianracer", model->getName());
  EXPECT_EQ("base_link", model->getRoot()->name);
  std::set<std::string> links, joints;
  for (const auto& kv : model->links_)
    links.insert(kv.first);
  for (const auto& kv : model->joints_)
    joints.insert(kv.first);
  EXPECT_EQ((std::set<std::string>{"base_link", "chassis", "left_steering_hinge",
                                   "right_steering_hinge", "left_front_wheel", "right_front_wheel",
                                   "left_rear_wheel", "right_rear_wheel", "lidar", "camera",
                                   "real_sense"}),
            links);
  EXPECT_EQ((std::set<std::string>{"base_link_joint", "left_steering_hinge_joint",
                                   "right_steering_hinge_joint", "left_front_wheel_joint",
                                   "right_front_wheel_joint", "left_rear_wheel_joint",
                                   "right_rear_wheel_joint", "lidar_joint", "camera_joint",
                                   "real_sense_joint"}),
            joints);
}

struct SeedJoint
{
  std::string name;
  int type;
  std::string parent, child;
  Eigen::Vector3d xyz;
  Eigen::Vector3d axis;   // checked for movable joints only
  bool has_limit;
  double lower, upper, effort, velocity;
};

TEST(Urdf, JointTypesParentsChildrenOriginsAxesAndLimitsMatchSeed)
{
  const auto model = parsedModel();
  ASSERT_TRUE(model);
  const Eigen::Vector3d z(0, 0, 1), y(0, 1, 0), none(0, 0, 0);
  const std::vector<SeedJoint> seed = {
      {"base_link_joint", urdf::Joint::FIXED, "base_link", "chassis", {0, 0, 0}, none, false, 0, 0,
       0, 0},
      {"left_steering_hinge_joint", urdf::Joint::REVOLUTE, "base_link", "left_steering_hinge",
       {0.1237, 0.070647, 0.0235}, z, true, -0.6, 0.6, 10, 1000},
      {"right_steering_hinge_joint", urdf::Joint::REVOLUTE, "base_link", "right_steering_hinge",
       {0.12626, -0.065953, 0.0235}, z, true, -0.6, 0.6, 10, 1000},
      {"left_front_wheel_joint", urdf::Joint::CONTINUOUS, "left_steering_hinge",
       "left_front_wheel", {0, 0.015649, 0}, y, false, 0, 0, 0, 0},
      {"right_front_wheel_joint", urdf::Joint::CONTINUOUS, "right_steering_hinge",
       "right_front_wheel", {0, -0.015649, 0}, y, false, 0, 0, 0, 0},
      {"left_rear_wheel_joint", urdf::Joint::CONTINUOUS, "base_link", "left_rear_wheel",
       {-0.12626, 0.081602, 0.0225}, y, false, 0, 0, 0, 0},
      {"right_rear_wheel_joint", urdf::Joint::CONTINUOUS, "base_link", "right_rear_wheel",
       {-0.1237, -0.086296, 0.0225}, y, false, 0, 0, 0, 0},
      {"lidar_joint", urdf::Joint::FIXED, "base_link", "lidar", {0.093603, -8.284E-05, 0.12377},
       none, false, 0, 0, 0, 0},
      {"camera_joint", urdf::Joint::FIXED, "base_link", "camera", {0.14851, 0.0022137, 0.0975},
       none, false, 0, 0, 0, 0},
      {"real_sense_joint", urdf::Joint::FIXED, "base_link", "real_sense",
       {0.19864, 0.0038046, 0.052021}, none, false, 0, 0, 0, 0},
  };
  for (const SeedJoint& s : seed)
  {
    SCOPED_TRACE(s.name);
    const auto j = model->getJoint(s.name);
    ASSERT_TRUE(j);
    EXPECT_EQ(s.type, j->type);
    EXPECT_EQ(s.parent, j->parent_link_name);
    EXPECT_EQ(s.child, j->child_link_name);
    const Eigen::Isometry3d X = toEigen(j->parent_to_joint_origin_transform);
    EXPECT_LT((X.translation() - s.xyz).norm(), 1e-12) << X.translation().transpose();
    EXPECT_TRUE(X.linear().isIdentity(1e-12)) << "all seed joints have rpy 0 0 0";
    if (s.type != urdf::Joint::FIXED)
    {
      EXPECT_DOUBLE_EQ(s.axis.x(), j->axis.x);
      EXPECT_DOUBLE_EQ(s.axis.y(), j->axis.y);
      EXPECT_DOUBLE_EQ(s.axis.z(), j->axis.z);
    }
    ASSERT_EQ(s.has_limit, static_cast<bool>(j->limits));
    if (s.has_limit)
    {
      EXPECT_DOUBLE_EQ(s.lower, j->limits->lower);
      EXPECT_DOUBLE_EQ(s.upper, j->limits->upper);
      EXPECT_DOUBLE_EQ(s.effort, j->limits->effort);
      EXPECT_DOUBLE_EQ(s.velocity, j->limits->velocity);
    }
  }
}

struct SeedInertial
{
  std::string link;
  Eigen::Vector3d com;
  double mass, ixx, ixy, ixz, iyy, iyz, izz;
};

TEST(Urdf, LinkMassesCentresOfMassAndInertiasMatchSeed)
{
  const auto model = parsedModel();
  ASSERT_TRUE(model);
  const double kWheelI = 0.00026046, kWheelIzz = 0.00041226;
  const std::vector<SeedInertial> seed = {
      {"chassis", {0.0623235722457065, 0.0014584636628485, 0.0350371599032402}, 5, 0.010609, 0,
       0, 0.050409, 0, 0.05865},
      {"left_steering_hinge", {0.00160901052986848, 0.00421500740928921, 0.000999991873067492},
       0.34, 4E-06, 0, 0, 4E-06, 0, 4E-06},
      {"right_steering_hinge",
       {0.00160901052986852, -0.00421500740928916, 0.00100000812693248}, 0.34, 4E-06, 0, 0,
       4E-06, 0, 4E-06},
      {"left_front_wheel", {-1.16652756898539E-10, 0.000722301233977055, -0.000982991824011559},
       0.7, kWheelI, 0, 0, kWheelI, 0, kWheelIzz},
      {"right_front_wheel", {1.16652479342783E-10, -0.000722301233976874, -0.000982991824011684},
       0.7, kWheelI, 0, 0, kWheelI, 0, kWheelIzz},
      {"left_rear_wheel", {-6.22009417952651E-06, 0.000722301233977513, 1.58299866985546E-05},
       0.7, kWheelI, 0, 0, kWheelI, 0, kWheelIzz},
      {"right_rear_wheel", {5.49312575473526E-06, -0.000722301233977277, 1.60966959317256E-05},
       0.7, kWheelI, 0, 0, kWheelI, 0, kWheelIzz},
      {"lidar", {-0.0120919804823413, 0.0023160815953297, -0.0191850779635995},
       0.0792224121739075, 2.10579541640659E-05, -1.189626176555E-07, 4.23690141563745E-07,
       2.51190032657276E-05, -7.86831091483644E-09, 4.38241306407012E-05},
      {"camera", {-0.00831465204525364, 0.000297862545499916, -0.000809694900417546},
       0.0203878842392581, 4.0787812214101E-06, -1.28709200468823E-08, -1.65865223773842E-08,
       3.17565570823081E-06, -1.52713816393124E-08, 2.98536150732633E-06},
      {"real_sense", {-0.00975078931607951, 0.00306064913353049, -7.04374991291334E-05},
       0.103311749598955, 7.35323632954531E-05, 3.0437488683846E-06, 2.08538534427428E-08,
       7.40427481540393E-06, -1.93018760531168E-08, 7.2832884533889E-05},
  };
  for (const SeedInertial& s : seed)
  {
    SCOPED_TRACE(s.link);
    const auto link = model->getLink(s.link);
    ASSERT_TRUE(link);
    ASSERT_TRUE(link->inertial);
    const auto& in = *link->inertial;
    const Eigen::Isometry3d X = toEigen(in.origin);
    EXPECT_LT((X.translation() - s.com).norm(), 1e-15) << X.translation().transpose();
    EXPECT_TRUE(X.linear().isIdentity(1e-12));
    EXPECT_DOUBLE_EQ(s.mass, in.mass);
    EXPECT_DOUBLE_EQ(s.ixx, in.ixx);
    EXPECT_DOUBLE_EQ(s.ixy, in.ixy);
    EXPECT_DOUBLE_EQ(s.ixz, in.ixz);
    EXPECT_DOUBLE_EQ(s.iyy, in.iyy);
    EXPECT_DOUBLE_EQ(s.iyz, in.iyz);
    EXPECT_DOUBLE_EQ(s.izz, in.izz);
  }
  const auto base = model->getLink("base_link");
  ASSERT_TRUE(base);
  EXPECT_FALSE(base->inertial) << "base_link is empty in the seed";
  EXPECT_TRUE(base->visual_array.empty());
}

// ----------------------------------------------------------------------------------------------
// Meshes

TEST(Meshes, EveryReferencedMeshExistsLoadsAndHasSaneBounds)
{
  const auto model = parsedModel();
  ASSERT_TRUE(model);
  const auto refs = referencedMeshes(*model);
  EXPECT_EQ(10u, refs.size()) << "every link but base_link has a mesh";
  for (const auto& [link, uris] : refs)
  {
    SCOPED_TRACE(link);
    ASSERT_EQ(1u, uris.size()) << "visual and collision share one mesh";
    const std::string uri = *uris.begin();
    EXPECT_EQ(kMeshPrefix + "meshes/" + (link == "chassis" ? "base_link" : link) + ".STL", uri);
    const std::string path = meshPathFromUri(uri);
    ASSERT_TRUE(fs::exists(path)) << uri;
    const LoadedMesh mesh = loadMesh(path);
    ASSERT_TRUE(mesh.ok) << path << ": " << mesh.error;
    EXPECT_GT(mesh.triangles.size(), 0u);
    Eigen::AlignedBox3d bounds;
    for (const auto& v : mesh.vertices)
      bounds.extend(v);
    const Eigen::Vector3d size = bounds.sizes();
    for (int i = 0; i < 3; ++i)
    {
      EXPECT_GE(size[i], 0.001) << "axis " << i;
      EXPECT_LE(size[i], 0.5) << "axis " << i;
    }
  }
}

TEST(Meshes, WheelsHaveRadius32mmAboutTheirYAxisAndAreCentred)
{
  const auto model = parsedModel();
  ASSERT_TRUE(model);
  const auto refs = referencedMeshes(*model);
  for (const std::string& link : kWheelLinks)
  {
    SCOPED_TRACE(link);
    ASSERT_EQ(1u, refs.count(link));
    const LoadedMesh mesh = loadMesh(meshPathFromUri(*refs.at(link).begin()));
    ASSERT_TRUE(mesh.ok) << mesh.error;
    ASSERT_FALSE(mesh.vertices.empty());
    double max_radius = 0, sum_y = 0, min_y = 1e9, max_y = -1e9;
    for (const auto& v : mesh.vertices)
    {
      max_radius = std::max(max_radius, std::hypot(v.x(), v.z()));
      sum_y += v.y();
      min_y = std::min(min_y, v.y());
      max_y = std::max(max_y, v.y());
    }
    EXPECT_NEAR(kWheelRadius, max_radius, 0.001);
    EXPECT_NEAR(0.0, sum_y / mesh.vertices.size(), 0.001);
    EXPECT_NEAR(0.0, 0.5 * (min_y + max_y), 0.001);
    EXPECT_NEAR(0.025, max_y - min_y, 0.005) << "wheel width";
  }
}

TEST(Meshes, NoNonWheelGeometryBelowWheelContactPlaneInBaseLink)
{
  const auto model = parsedModel();
  ASSERT_TRUE(model);
  const auto refs = referencedMeshes(*model);
  // Sanity of the ground plane itself: every wheel's lowest point is on it.
  for (const std::string& link : kWheelLinks)
  {
    const double centre_z = poseInBaseLink(*model, link).translation().z();
    EXPECT_NEAR(kGroundZ, centre_z - kWheelRadius, 0.0011) << link;
  }
  for (const auto& [link, uris] : refs)
  {
    if (isWheel(link))
      continue;
    const Eigen::Isometry3d X_BL = poseInBaseLink(*model, link);
    const LoadedMesh mesh = loadMesh(meshPathFromUri(*uris.begin()));
    ASSERT_TRUE(mesh.ok) << link << ": " << mesh.error;
    double min_z = 1e9;
    for (const auto& v : mesh.vertices)
      min_z = std::min(min_z, (X_BL * v).z());
    EXPECT_GE(min_z, kNonWheelMinZ) << link;
  }
}

// Point p (base_link) inside the solid cylinder of a wheel? X_WB: base_link in the wheel frame.
bool insideWheel(const Eigen::Isometry3d& X_WB, const Eigen::Vector3d& p_B)
{
  const Eigen::Vector3d p_W = X_WB * p_B;
  return std::abs(p_W.y()) < 0.0125 && std::hypot(p_W.x(), p_W.z()) < kWheelRadius;
}

TEST(Meshes, ChassisStaysOutOfWheelsSweptOverFullSteeringRange)
{
  const auto model = parsedModel();
  ASSERT_TRUE(model);
  const LoadedMesh chassis = loadMesh(kSourceDir + "/meshes/base_link.STL");
  ASSERT_TRUE(chassis.ok) << chassis.error;
  // Wheel poses: rear fixed; front swept over the hinge limits.
  std::vector<Eigen::Isometry3d> wheel_poses;  // X_BW
  for (const char* link : {"left_rear_wheel", "right_rear_wheel"})
    wheel_poses.push_back(poseInBaseLink(*model, link));
  for (const std::string side : {"left", "right"})
  {
    const auto hinge = model->getJoint(side + "_steering_hinge_joint");
    const auto wheel = model->getJoint(side + "_front_wheel_joint");
    ASSERT_TRUE(hinge && hinge->limits && wheel);
    const Eigen::Isometry3d X_BH = toEigen(hinge->parent_to_joint_origin_transform);
    const Eigen::Isometry3d X_HW = toEigen(wheel->parent_to_joint_origin_transform);
    const Eigen::Vector3d axis(hinge->axis.x, hinge->axis.y, hinge->axis.z);
    for (int i = 0; i <= 48; ++i)
    {
      const double q = hinge->limits->lower + (hinge->limits->upper - hinge->limits->lower) * i / 48;
      wheel_poses.push_back(X_BH * Eigen::AngleAxisd(q, axis) * X_HW);
    }
  }
  std::vector<Eigen::Isometry3d> wheel_inverses;  // X_WB
  for (const auto& X_BW : wheel_poses)
    wheel_inverses.push_back(X_BW.inverse());
  // Sample each chassis triangle on a barycentric grid (vertices, edges and interior); skip
  // triangles whose bounding sphere misses every wheel's bounding sphere.
  constexpr int kGrid = 8;
  const double wheel_bound = std::hypot(kWheelRadius, 0.0125);
  int inside = 0;
  for (const Triangle& t : chassis.triangles)
  {
    const Eigen::Vector3d centre = (t[0] + t[1] + t[2]) / 3.0;
    const double radius = std::max({(t[0] - centre).norm(), (t[1] - centre).norm(),
                                    (t[2] - centre).norm()});
    std::vector<const Eigen::Isometry3d*> near;
    for (size_t w = 0; w < wheel_poses.size(); ++w)
      if ((wheel_poses[w].translation() - centre).norm() < radius + wheel_bound)
        near.push_back(&wheel_inverses[w]);
    if (near.empty())
      continue;
    for (int a = 0; a <= kGrid; ++a)
      for (int b = 0; a + b <= kGrid; ++b)
      {
        const Eigen::Vector3d p =
            (a * t[0] + b * t[1] + (kGrid - a - b) * t[2]) / static_cast<double>(kGrid);
        for (const Eigen::Isometry3d* X_WB : near)
          inside += insideWheel(*X_WB, p) ? 1 : 0;
      }
  }
  EXPECT_EQ(0, inside) << "chassis sample points inside a wheel's (swept) volume";
}

TEST(Meshes, LidarHeadEnclosesScanPlaneAndRestOfCarBelowLidar)
{
  const auto model = parsedModel();
  ASSERT_TRUE(model);
  const auto refs = referencedMeshes(*model);
  const Eigen::Isometry3d X_BLidar = poseInBaseLink(*model, "lidar");
  const double scan_plane_z = X_BLidar.translation().z() + kLidarScanPlaneZ;
  for (const auto& [link, uris] : refs)
  {
    const Eigen::Isometry3d X_BL = poseInBaseLink(*model, link);
    const LoadedMesh mesh = loadMesh(meshPathFromUri(*uris.begin()));
    ASSERT_TRUE(mesh.ok) << link << ": " << mesh.error;
    double max_z = -1e9;
    for (const auto& v : mesh.vertices)
      max_z = std::max(max_z, (X_BL * v).z());
    // The lidar's scanning head reaches 12.6 mm above its scan plane, so that other cars' lidars
    // see it (its own rays start at range min, 0.1 m, past it); the rest of the car stays clear
    // by 11 mm.
    if (link == "lidar")
      EXPECT_NEAR(max_z, scan_plane_z + 0.0126, 1e-6) << link;
    else
      EXPECT_LE(max_z, 0.125 + 1e-6) << link;
  }
}

// ----------------------------------------------------------------------------------------------
// Generator

TEST(Generator, ReproducesCommittedMeshesByteForByte)
{
  char tmpl[] = "/tmp/tianracer_meshes_XXXXXX";
  ASSERT_NE(nullptr, mkdtemp(tmpl));
  const fs::path out = tmpl;
  const std::string cmd = std::string(TIANRACER_PYTHON3) + " " +
                          shellQuote(kSourceDir + "/scripts/generate_meshes.py") + " " +
                          shellQuote(out.string());
  const CommandResult r = runCommand(cmd);
  EXPECT_EQ(0, r.status) << cmd << "\n" << r.output;
  std::set<std::string> generated, committed;
  for (const auto& e : fs::directory_iterator(out))
    generated.insert(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(kSourceDir + "/meshes"))
    if (e.path().extension() == ".STL")
      committed.insert(e.path().filename().string());
  EXPECT_EQ(10u, generated.size());
  EXPECT_EQ(committed, generated);
  for (const std::string& name : generated)
  {
    const std::string fresh = readFile(out / name);
    const std::string shipped = readFile(fs::path(kSourceDir) / "meshes" / name);
    EXPECT_FALSE(fresh.empty()) << name;
    EXPECT_TRUE(fresh == shipped) << name << " differs from the generator's output ("
                                  << fresh.size() << " vs " << shipped.size()
                                  << " bytes); rerun scripts/generate_meshes.py";
  }
  fs::remove_all(out);
}

// $(find tianracer_description) in the xacro needs ROS_PACKAGE_PATH; the catkin devel space
// provides it, a bare ctest run does not.
void ensurePackagePath()
{
  const std::string package_parent = fs::path(kSourceDir).parent_path().string();
  const char* current = std::getenv("ROS_PACKAGE_PATH");
  std::string value = current ? current : "";
  if (value.find(package_parent) != std::string::npos)
    return;
  value = value.empty() ? package_parent : package_parent + ":" + value;
  setenv("ROS_PACKAGE_PATH", value.c_str(), 1);
}

}  // namespace
}  // namespace tianracer_description

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  tianracer_description::ensurePackagePath();
  return RUN_ALL_TESTS();
}
