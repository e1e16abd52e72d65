// Camera messages: encodings, sizes, steps, frame ids, CameraInfo, and the cloud's layout and
// byte order read back with sensor_msgs' own iterators (as a subscriber would).
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include "tianracer_sim/scene/materials.h"
#include "tianracer_sim/ros/camera_msgs.h"

namespace tianracer_sim {
namespace {

CameraConfig cameraConfig(int w, int h) {
  CameraConfig c;
  c.name = "cam";
  c.type = "camera";
  c.link = "camera";
  c.frame_name = "camera";
  c.width = w;
  c.height = h;
  c.horizontal_fov = 1.3962634;
  c.near_clip = 0.02;
  c.far_clip = 300;
  c.hack_baseline = 0.07;
  return c;
}

// A wall at x = d: red on the left half of the image (y > 0), blue on the right.
Scene wall(double d) {
  Scene scene;
  scene.lights.push_back(DirectionalLight{});
  scene.lights[0].direction = Eigen::Vector3d(0.6, -0.3, -0.74);
  scene.addBody(SceneBody{"wall::link", "wall", true, Eigen::Isometry3d::Identity()});
  for (int side = 0; side < 2; ++side) {
    SceneItem item;
    item.shape.type = ShapeType::kBox;
    item.shape.size = Eigen::Vector3d(0.2, 50.0, 100.0);
    item.X_BS.translation() = Eigen::Vector3d(d + 0.1, side == 0 ? 25.0 : -25.0, 0);
    item.material = findGazeboMaterial(side == 0 ? "Gazebo/Red" : "Gazebo/Blue")->material;
    scene.items.push_back(item);
  }
  return scene;
}

TEST(CameraMsgs, ImageAndCameraInfo) {
  Renderer renderer;
  CameraSensor camera(cameraConfig(80, 60), renderer);
  camera.render(wall(2.0), Eigen::Isometry3d::Identity());
  const ros::Time stamp(12, 345);
  const sensor_msgs::Image img = toImage(camera, stamp);
  EXPECT_EQ(img.header.stamp, stamp);
  EXPECT_EQ(img.header.frame_id, "camera_optical_frame");
  EXPECT_EQ(img.encoding, "rgb8");
  EXPECT_EQ(img.width, 80u);
  EXPECT_EQ(img.height, 60u);
  EXPECT_EQ(img.step, 240u);
  EXPECT_EQ(img.is_bigendian, 0);
  EXPECT_EQ(img.data, camera.image());
  // Left of the image is red (world +y is the camera's left), right is blue.
  EXPECT_GT(img.data[(30 * 80 + 5) * 3], 150);
  EXPECT_GT(img.data[(30 * 80 + 75) * 3 + 2], 150);

  const sensor_msgs::CameraInfo info = toCameraInfo(camera.info(), stamp);
  EXPECT_EQ(info.header.frame_id, "camera_optical_frame");
  EXPECT_EQ(info.width, 80u);
  EXPECT_EQ(info.height, 60u);
  EXPECT_EQ(info.distortion_model, "plumb_bob");
  ASSERT_EQ(info.D.size(), 5u);
  const double f = 80 / (2 * std::tan(1.3962634 / 2));
  EXPECT_DOUBLE_EQ(info.K[0], f);
  EXPECT_DOUBLE_EQ(info.K[2], 40.5);
  EXPECT_DOUBLE_EQ(info.K[5], 30.5);
  EXPECT_DOUBLE_EQ(info.P[3], -f * 0.07);
  EXPECT_DOUBLE_EQ(info.R[4], 1.0);

  // Into an existing message: same content, buffers reused.
  sensor_msgs::Image reused = img;
  const uint8_t* before = reused.data.data();
  camera.render(wall(2.0), Eigen::Isometry3d::Identity());
  toImage(camera, ros::Time(13, 0), &reused);
  EXPECT_EQ(reused.data.data(), before);
  EXPECT_EQ(reused.header.stamp, ros::Time(13, 0));
}

TEST(CameraMsgs, Mono8) {
  Renderer renderer;
  CameraConfig c = cameraConfig(8, 4);
  c.format = ImageFormat::kL8;
  c.format_name = "L8";
  CameraSensor camera(c, renderer);
  camera.render(wall(2.0), Eigen::Isometry3d::Identity());
  const sensor_msgs::Image img = toImage(camera, ros::Time(1, 0));
  EXPECT_EQ(img.encoding, "mono8");
  EXPECT_EQ(img.step, 8u);
  EXPECT_EQ(img.data.size(), 32u);
}

TEST(CameraMsgs, Bgr8AndMono16EncodingAndStep) {
  Renderer renderer;
  CameraConfig c = cameraConfig(8, 4);
  c.format = ImageFormat::kB8G8R8;
  CameraSensor bgr(c, renderer);
  bgr.render(wall(2.0), Eigen::Isometry3d::Identity());
  sensor_msgs::Image img = toImage(bgr, ros::Time(1, 0));
  EXPECT_EQ(img.encoding, "bgr8");
  EXPECT_EQ(img.step, 24u);
  EXPECT_EQ(img.data, bgr.image());
  c.format = ImageFormat::kL16;
  CameraSensor mono16(c, renderer);
  mono16.render(wall(2.0), Eigen::Isometry3d::Identity());
  img = toImage(mono16, ros::Time(1, 0));
  EXPECT_EQ(img.encoding, "mono16");
  EXPECT_EQ(img.step, 16u);
  EXPECT_EQ(img.is_bigendian, 0);
  EXPECT_EQ(img.data.size(), 64u);
  BorrowedImage borrowed;
  toImage(mono16, ros::Time(1, 0), &borrowed);
  EXPECT_EQ(borrowed.meta.encoding, "mono16");
  EXPECT_EQ(borrowed.meta.step, 16u);
  EXPECT_EQ(borrowed.size, 64u);
}

TEST(CameraMsgs, DepthImageAndCloud) {
  Renderer renderer;
  DepthCameraConfig d;
  d.camera = cameraConfig(64, 48);
  d.camera.type = "depth";
  d.camera.frame_name = "real_sense";
  d.camera.hack_baseline = 0.0;
  DepthCameraSensor camera(d, renderer);
  Scene scene = wall(2.0);
  scene.items[1].X_BS.translation().x() = 6.0;  // the blue half beyond cutoffMax (5 m): NaN
  camera.render(scene, Eigen::Isometry3d::Identity());
  const ros::Time stamp(7, 0);

  const sensor_msgs::Image depth = toDepthImage(camera, stamp);
  EXPECT_EQ(depth.header.frame_id, "real_sense_optical_frame");
  EXPECT_EQ(depth.encoding, "32FC1");
  EXPECT_EQ(depth.step, 64u * 4u);
  ASSERT_EQ(depth.data.size(), 64u * 48u * 4u);
  float left = 0, right = 0;
  std::memcpy(&left, &depth.data[(24 * 64 + 5) * 4], 4);
  std::memcpy(&right, &depth.data[(24 * 64 + 60) * 4], 4);
  EXPECT_NEAR(left, 2.0, 1e-4);
  EXPECT_TRUE(std::isnan(right));

  const sensor_msgs::Image rgb = toImage(camera, stamp);
  EXPECT_EQ(rgb.encoding, "rgb8");
  EXPECT_EQ(rgb.header.frame_id, "real_sense_optical_frame");

  const sensor_msgs::PointCloud2 cloud = toPointCloud2(camera, stamp);
  EXPECT_EQ(cloud.header.frame_id, "real_sense_optical_frame");
  EXPECT_EQ(cloud.header.stamp, stamp);
  EXPECT_EQ(cloud.height, 48u);
  EXPECT_EQ(cloud.width, 64u);
  EXPECT_EQ(cloud.point_step, 32u);
  EXPECT_EQ(cloud.row_step, 32u * 64u);
  EXPECT_FALSE(cloud.is_bigendian);
  EXPECT_FALSE(cloud.is_dense);
  ASSERT_EQ(cloud.fields.size(), 4u);
  const char* names[4] = {"x", "y", "z", "rgb"};
  const uint32_t offsets[4] = {0, 4, 8, 16};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(cloud.fields[i].name, names[i]);
    EXPECT_EQ(cloud.fields[i].offset, offsets[i]);
    EXPECT_EQ(cloud.fields[i].datatype, sensor_msgs::PointField::FLOAT32);
    EXPECT_EQ(cloud.fields[i].count, 1u);
  }
  sensor_msgs::PointCloud2ConstIterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  sensor_msgs::PointCloud2ConstIterator<uint8_t> bgr(cloud, "rgb");
  const double f = camera.info().K[0];
  for (int v = 0; v < 48; ++v) {
    for (int u = 0; u < 64; ++u, ++x, ++y, ++z, ++bgr) {
      if (u >= 28 && u <= 35) continue;  // the seam between the halves
      if (u < 32) {
        EXPECT_NEAR(*z, 2.0, 1e-4);
        // The published K's principal point, (W+1)/2 and (H+1)/2 as gazebo_ros writes it.
        EXPECT_NEAR(*x, 2.0 * (u - 32.5) / f, 1e-5);
        EXPECT_NEAR(*y, 2.0 * (v - 24.5) / f, 1e-5);
        // PCL's byte order: B, G, R in bytes 16, 17, 18 (Gazebo writes R, G, B: its bug).
        const uint8_t* px = &rgb.data[(v * 64 + u) * 3];
        EXPECT_EQ(bgr[0], px[2]);
        EXPECT_EQ(bgr[1], px[1]);
        EXPECT_EQ(bgr[2], px[0]);
        EXPECT_GT(bgr[2], 150);  // red
      } else {
        EXPECT_TRUE(std::isnan(*x) && std::isnan(*y) && std::isnan(*z));
      }
    }
  }
  // A fully visible wall gives a dense cloud.
  camera.render(wall(2.0), Eigen::Isometry3d::Identity());
  EXPECT_TRUE(toPointCloud2(camera, stamp).is_dense);
}

// The serialised bytes of a message (what a subscriber receives).
template <typename M>
std::vector<uint8_t> wireBytes(const M& msg) {
  const ros::SerializedMessage m = ros::serialization::serializeMessage(msg);
  return std::vector<uint8_t>(m.buf.get(), m.buf.get() + m.num_bytes);
}

TEST(CameraMsgs, BorrowedMessagesSerialiseAsTheirSensorMsgs) {
  namespace mt = ros::message_traits;
  EXPECT_STREQ(mt::md5sum<BorrowedImage>(), mt::md5sum<sensor_msgs::Image>());
  EXPECT_STREQ(mt::datatype<BorrowedPointCloud2>(), "sensor_msgs/PointCloud2");
  EXPECT_STREQ(mt::md5sum<BorrowedPointCloud2>(), mt::md5sum<sensor_msgs::PointCloud2>());

  Renderer renderer;
  DepthCameraConfig d;
  d.camera = cameraConfig(64, 48);
  d.camera.type = "depth";
  d.camera.frame_name = "real_sense";
  DepthCameraSensor depth_camera(d, renderer);
  Scene scene = wall(2.0);
  scene.items[1].X_BS.translation().x() = 6.0;  // NaN points too
  depth_camera.render(scene, Eigen::Isometry3d::Identity());
  CameraSensor camera(cameraConfig(80, 60), renderer);
  camera.render(scene, Eigen::Isometry3d::Identity());
  const ros::Time stamp(7, 5);

  BorrowedImage image, rgb, depth;
  BorrowedPointCloud2 cloud;
  toImage(camera, stamp, &image);
  toImage(depth_camera, stamp, &rgb);
  toDepthImage(depth_camera, stamp, &depth);
  toPointCloud2(depth_camera, stamp, &cloud);
  EXPECT_TRUE(image.meta.data.empty());
  EXPECT_EQ(cloud.data, depth_camera.cloud().data());  // borrowed, not copied
  EXPECT_EQ(wireBytes(image), wireBytes(toImage(camera, stamp)));
  EXPECT_EQ(wireBytes(rgb), wireBytes(toImage(depth_camera, stamp)));
  EXPECT_EQ(wireBytes(depth), wireBytes(toDepthImage(depth_camera, stamp)));
  EXPECT_EQ(wireBytes(cloud), wireBytes(toPointCloud2(depth_camera, stamp)));

  // The cloud written into the serialisation buffer, from a render without outputs.cloud.
  const std::vector<uint8_t> rendered_cloud = wireBytes(toPointCloud2(depth_camera, stamp));
  DepthCameraSensor deferred_camera(d, renderer);
  DepthOutputs no_cloud;
  no_cloud.cloud = false;
  deferred_camera.render(scene, Eigen::Isometry3d::Identity(), no_cloud);
  BorrowedPointCloud2 deferred;
  toPointCloud2Deferred(deferred_camera, stamp, &deferred);
  EXPECT_EQ(wireBytes(deferred), rendered_cloud);
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
