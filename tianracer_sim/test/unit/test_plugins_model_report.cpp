// The start-up table: every plugin and sensor of a model, simulated, simulated with named
// differences, or left out with the reason (golden text for test/data/urdf/report.urdf).
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tianracer_sim/plugins/model_report.h"

namespace tianracer_sim {
namespace {

// Loaded from its text under a short source name, so that the messages in the golden text
// do not depend on where the repository lives.
RobotModel reportModel() {
  std::ifstream file(std::string(TEST_DATA_DIR) + "/urdf/report.urdf");
  std::stringstream xml;
  xml << file.rdbuf();
  return loadRobotModel(xml.str(), "report.urdf", LoadOptions());
}

const ReportRow& rowOf(const std::vector<ReportRow>& rows, const std::string& name) {
  for (const ReportRow& r : rows) {
    if (r.name == name) return r;
  }
  throw std::runtime_error("no row " + name);
}

TEST(SensorsModelReport, ACameraInItsOwnOpticalFrameHasNoFrameDifference) {
  // test/data/urdf/camera_frames.urdf: frameName the URDF's optical link, the plain link, a
  // link turned another way.
  const RobotModel model =
      loadRobotModelFile(std::string(TEST_DATA_DIR) + "/urdf/camera_frames.urdf", LoadOptions());
  const std::vector<ReportRow> rows = modelReport(model, "camera_frames");
  EXPECT_EQ(rowOf(rows, "optical").status, ReportRow::Status::kSimulated);
  // No <update_rate>: Gazebo's 0, as often as it can, which is every step here.
  EXPECT_EQ(rowOf(rows, "optical").topics.at(0), "/optical/image_raw sensor_msgs/Image every step");
  EXPECT_EQ(rowOf(rows, "depth").status, ReportRow::Status::kSimulated);
  for (const char* name : {"plain", "turned"}) {
    const ReportRow& row = rowOf(rows, name);
    EXPECT_EQ(row.status, ReportRow::Status::kDifferences) << name;
    ASSERT_EQ(row.notes.size(), 1u) << name;
    EXPECT_NE(row.notes[0].find("<frameName>_optical_frame"), std::string::npos) << row.notes[0];
  }
}

TEST(SensorsModelReport, GoldenTable) {
  const RobotModel model = reportModel();
  const std::string table = formatModelReport("report", modelReport(model, "report"));
  const std::string golden = R"(robot 'report': 11 plugins and sensors: 4 simulated, 2 with differences, 5 left out
  KIND    NAME                TYPE                          LINK          STATUS
  plugin  gazebo_ros_control  libgazebo_ros_control.so      -             simulated
          runs the controllers of the YAML under /report
  plugin  ground_truth        libgazebo_ros_p3d.so          base_link     simulated
          /report/p3d/odom nav_msgs/Odometry @ 50 Hz
  plugin  imu                 libgazebo_ros_imu.so          base_link     simulated
          /report/imu sensor_msgs/Imu @ 100 Hz
  plugin  imu_nowhere         libgazebo_ros_imu.so          no_such_link  left out
          why: link 'no_such_link' is not a link of the model
  plugin  planar_move         libgazebo_ros_planar_move.so  -             simulated
          /odom nav_msgs/Odometry @ 20 Hz
          /cmd_vel geometry_msgs/Twist (subscribed)
  plugin  pusher              libgazebo_ros_force.so        base_link     left out
          why: libgazebo_ros_force (a geometry_msgs/Wrench topic pushing a link) is not simulated: /gazebo/apply_body_wrench applies the same force and torque to a link
  sensor  front               camera                        base_link     simulated, with differences
          /front/image_raw sensor_msgs/Image @ 15 Hz
          /front/camera_info sensor_msgs/CameraInfo @ 15 Hz
          difference: images are stamped in <frameName>_optical_frame (z forward), not the plain frame
  sensor  bayer               camera                        base_link     left out
          why: report.urdf:58: camera sensor 'bayer' on link 'base_link': <image><format> 'R_FLOAT32' is a Gazebo format that is not simulated (supported: R8G8B8, B8G8R8, L8, L16, R16G16B16, BAYER_RGGB8, BAYER_BGGR8, BAYER_GBRG8, BAYER_GRBG8); the camera is left out
  sensor  lidar               gpu_ray                       base_link     simulated, with differences
          /scan sensor_msgs/LaserScan @ 10 Hz
          difference: ray-cast on the CPU (Embree), exactly as type ray
  sensor  sonar               sonar                         base_link     left out
          why: sensor type 'sonar' is not simulated
  sensor  imu_bad_rate        imu                           base_link     left out
          why: report.urdf:80: sensor 'imu_bad_rate' on link 'base_link': <update_rate> value '-5' must be finite and >= 0
)";
  EXPECT_EQ(table, golden) << table;
}

TEST(SensorsModelReport, TheNodesReasonsWin) {
  const RobotModel model = reportModel();
  const std::vector<ReportRow> rows =
      modelReport(model, "report", {{"front", "disabled by ~disable_sensors"},
                                    {"imu", "link 'base_link' has no body"}});
  EXPECT_EQ(rowOf(rows, "front").status, ReportRow::Status::kLeftOut);
  EXPECT_EQ(rowOf(rows, "front").notes, std::vector<std::string>{"disabled by ~disable_sensors"});
  EXPECT_TRUE(rowOf(rows, "front").topics.empty());
  EXPECT_EQ(rowOf(rows, "imu").status, ReportRow::Status::kLeftOut);
  EXPECT_EQ(rowOf(rows, "lidar").status, ReportRow::Status::kDifferences);
}

// The node logs the table as a warning only when the model does less than in Gazebo for a
// reason the user did not choose.
TEST(SensorsModelReport, WarnsOnlyForWhatTheUserDidNotLeaveOut) {
  LoadOptions options;
  const RobotModel minimal =
      loadRobotModelFile(std::string(TEST_DATA_DIR) + "/urdf/minimal.urdf", options);
  EXPECT_FALSE(leavesOutUnasked(modelReport(minimal, "minimal")));
  // report.urdf leaves out an unknown plugin, an unknown sensor type, a Bayer camera, ...
  const RobotModel model = reportModel();
  EXPECT_TRUE(leavesOutUnasked(modelReport(model, "report")));
  // Only what the user switched off: no warning.
  ReportRow off;
  off.kind = "sensor";
  off.name = "front";
  off.status = ReportRow::Status::kLeftOut;
  off.notes = {kDisabledBySensorList};
  ReportRow simulated;
  simulated.name = "lidar";
  EXPECT_FALSE(leavesOutUnasked({simulated, off}));
  ReportRow failed = off;
  failed.notes = {"link 'base_link' has no body"};
  EXPECT_TRUE(leavesOutUnasked({simulated, off, failed}));
}

TEST(SensorsModelReport, EmptyModel) {
  LoadOptions options;
  const RobotModel model =
      loadRobotModelFile(std::string(TEST_DATA_DIR) + "/urdf/minimal.urdf", options);
  EXPECT_EQ(formatModelReport("minimal", modelReport(model, "minimal")),
            "robot 'minimal': 0 plugins and sensors: 0 simulated, 0 with differences, 0 left out\n");
}

}  // namespace
}  // namespace tianracer_sim
