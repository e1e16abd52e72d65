#include "tianracer_sim/ros/camera_msgs.h"

#include <algorithm>
#include <cstring>

#include <sensor_msgs/image_encodings.h>

namespace tianracer_sim {
namespace {

// Every field but data.
void fillImageMeta(int width, int height, int bytes_per_pixel, const char* encoding,
                   const std::string& frame_id, const ros::Time& stamp, sensor_msgs::Image* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame_id;
  msg->width = static_cast<uint32_t>(width);
  msg->height = static_cast<uint32_t>(height);
  msg->encoding = encoding;
  msg->is_bigendian = 0;  // mono16 is little-endian
  msg->step = static_cast<uint32_t>(width * bytes_per_pixel);
}

void fillImage(const std::vector<uint8_t>& data, int width, int height, int bytes_per_pixel,
               const char* encoding, const std::string& frame_id, const ros::Time& stamp,
               sensor_msgs::Image* msg) {
  fillImageMeta(width, height, bytes_per_pixel, encoding, frame_id, stamp, msg);
  msg->data.resize(data.size());
  std::memcpy(msg->data.data(), data.data(), data.size());
}

void fillDepthImageMeta(const DepthCameraSensor& camera, const ros::Time& stamp,
                        sensor_msgs::Image* msg) {
  const CameraConfig& c = camera.config().camera;
  fillImageMeta(c.width, c.height, sizeof(float), sensor_msgs::image_encodings::TYPE_32FC1.c_str(),
                c.opticalFrame(), stamp, msg);
}

// Every field but data.
void fillPointCloud2Meta(const DepthCameraSensor& camera, const ros::Time& stamp,
                         sensor_msgs::PointCloud2* msg) {
  const CameraConfig& c = camera.config().camera;
  msg->header.stamp = stamp;
  msg->header.frame_id = c.opticalFrame();
  msg->height = static_cast<uint32_t>(c.height);
  msg->width = static_cast<uint32_t>(c.width);
  if (msg->fields.size() != 4) {
    msg->fields.resize(4);
    const char* names[4] = {"x", "y", "z", "rgb"};
    const uint32_t offsets[4] = {CloudLayout::kOffsetX, CloudLayout::kOffsetY, CloudLayout::kOffsetZ,
                                 CloudLayout::kOffsetRgb};
    for (int i = 0; i < 4; ++i) {
      msg->fields[i].name = names[i];
      msg->fields[i].offset = offsets[i];
      msg->fields[i].datatype = sensor_msgs::PointField::FLOAT32;
      msg->fields[i].count = 1;
    }
  }
  msg->is_bigendian = false;
  msg->point_step = CloudLayout::kPointStep;
  msg->row_step = CloudLayout::kPointStep * msg->width;
  msg->is_dense = camera.cloudIsDense();
}

void borrow(const void* data, std::size_t size, const uint8_t** out, uint32_t* out_size) {
  *out = static_cast<const uint8_t*>(data);
  *out_size = static_cast<uint32_t>(size);
}

}  // namespace

void toImage(const CameraSensor& camera, const ros::Time& stamp, sensor_msgs::Image* msg) {
  fillImage(camera.image(), camera.config().width, camera.config().height,
            camera.bytesPerPixel(), camera.encoding(), camera.config().opticalFrame(), stamp, msg);
}

void toImage(const DepthCameraSensor& camera, const ros::Time& stamp, sensor_msgs::Image* msg) {
  const CameraConfig& c = camera.config().camera;
  fillImage(camera.image(), c.width, c.height, camera.bytesPerPixel(), camera.encoding(),
            c.opticalFrame(), stamp, msg);
}

void toDepthImage(const DepthCameraSensor& camera, const ros::Time& stamp, sensor_msgs::Image* msg) {
  fillDepthImageMeta(camera, stamp, msg);
  const std::vector<float>& depth = camera.depth();
  msg->data.resize(depth.size() * sizeof(float));
  std::memcpy(msg->data.data(), depth.data(), msg->data.size());
}

void toCameraInfo(const CameraInfo& info, const ros::Time& stamp, sensor_msgs::CameraInfo* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = info.frame_id;
  msg->width = static_cast<uint32_t>(info.width);
  msg->height = static_cast<uint32_t>(info.height);
  msg->distortion_model = info.distortion_model;
  msg->D.assign(info.D.begin(), info.D.end());
  std::copy(info.K.begin(), info.K.end(), msg->K.begin());
  std::copy(info.R.begin(), info.R.end(), msg->R.begin());
  std::copy(info.P.begin(), info.P.end(), msg->P.begin());
  msg->binning_x = 0;
  msg->binning_y = 0;
  msg->roi = sensor_msgs::RegionOfInterest();
}

void toPointCloud2(const DepthCameraSensor& camera, const ros::Time& stamp,
                   sensor_msgs::PointCloud2* msg) {
  fillPointCloud2Meta(camera, stamp, msg);
  const std::vector<uint8_t>& cloud = camera.cloud();
  msg->data.resize(cloud.size());
  std::memcpy(msg->data.data(), cloud.data(), cloud.size());
}

void toImage(const CameraSensor& camera, const ros::Time& stamp, BorrowedImage* msg) {
  fillImageMeta(camera.config().width, camera.config().height, camera.bytesPerPixel(),
                camera.encoding(), camera.config().opticalFrame(), stamp, &msg->meta);
  borrow(camera.image().data(), camera.image().size(), &msg->data, &msg->size);
}

void toImage(const DepthCameraSensor& camera, const ros::Time& stamp, BorrowedImage* msg) {
  const CameraConfig& c = camera.config().camera;
  fillImageMeta(c.width, c.height, camera.bytesPerPixel(), camera.encoding(), c.opticalFrame(),
                stamp, &msg->meta);
  borrow(camera.image().data(), camera.image().size(), &msg->data, &msg->size);
}

void toDepthImage(const DepthCameraSensor& camera, const ros::Time& stamp, BorrowedImage* msg) {
  fillDepthImageMeta(camera, stamp, &msg->meta);
  borrow(camera.depth().data(), camera.depth().size() * sizeof(float), &msg->data, &msg->size);
}

void toPointCloud2(const DepthCameraSensor& camera, const ros::Time& stamp,
                   BorrowedPointCloud2* msg) {
  fillPointCloud2Meta(camera, stamp, &msg->meta);
  borrow(camera.cloud().data(), camera.cloud().size(), &msg->data, &msg->size);
  msg->write = nullptr;
  msg->writer = nullptr;
}

void toPointCloud2Deferred(const DepthCameraSensor& camera, const ros::Time& stamp,
                           BorrowedPointCloud2* msg) {
  fillPointCloud2Meta(camera, stamp, &msg->meta);
  const CameraConfig& c = camera.config().camera;
  msg->data = nullptr;
  msg->size = static_cast<uint32_t>(static_cast<std::size_t>(c.width) * c.height * CloudLayout::kPointStep);
  msg->write = [](const void* writer, uint8_t* out) {
    static_cast<const DepthCameraSensor*>(writer)->writeCloud(out);
  };
  msg->writer = &camera;
}

namespace {

/// A conversion into an existing message, as one returning a new message.
template <class Msg, class Source>
Msg newMsg(void (*fill)(const Source&, const ros::Time&, Msg*), const Source& source,
           const ros::Time& stamp) {
  Msg msg;
  fill(source, stamp, &msg);
  return msg;
}

}  // namespace

sensor_msgs::Image toImage(const CameraSensor& camera, const ros::Time& stamp) {
  return newMsg<sensor_msgs::Image>(toImage, camera, stamp);
}
sensor_msgs::Image toImage(const DepthCameraSensor& camera, const ros::Time& stamp) {
  return newMsg<sensor_msgs::Image>(toImage, camera, stamp);
}
sensor_msgs::Image toDepthImage(const DepthCameraSensor& camera, const ros::Time& stamp) {
  return newMsg<sensor_msgs::Image>(toDepthImage, camera, stamp);
}
sensor_msgs::CameraInfo toCameraInfo(const CameraInfo& info, const ros::Time& stamp) {
  return newMsg<sensor_msgs::CameraInfo>(toCameraInfo, info, stamp);
}
sensor_msgs::PointCloud2 toPointCloud2(const DepthCameraSensor& camera, const ros::Time& stamp) {
  return newMsg<sensor_msgs::PointCloud2>(toPointCloud2, camera, stamp);
}

}  // namespace tianracer_sim
