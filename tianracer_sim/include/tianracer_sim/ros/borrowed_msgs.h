// sensor_msgs/Image and sensor_msgs/PointCloud2 whose data bytes stay in the sensor's buffer:
// roscpp serialises them into exactly the bytes of the sensor_msgs type (same MD5 sum, same
// field order), reading the data straight from the sensor. A publisher advertised with the
// sensor_msgs type publishes them as they are (Publisher::publish(const M&)), and every
// subscriber receives an ordinary sensor_msgs message.
//
// Why: a frame is otherwise copied twice in the node (sensor -> message, message -> roscpp's
// serialisation buffer); the depth camera's cloud alone is 10 MB at 20 Hz. Borrowing skips
// the first copy. The sensor's buffer must stay unchanged until publish() returns (it does:
// roscpp serialises inside publish()).
#ifndef TIANRACER_SIM_ROS_BORROWED_MSGS_H
#define TIANRACER_SIM_ROS_BORROWED_MSGS_H

#include <cstdint>
#include <cstring>

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

namespace tianracer_sim {

/// An Image: every field in `meta` except data (left empty), which is `size` bytes at `data`.
struct BorrowedImage {
  sensor_msgs::Image meta;
  const uint8_t* data = nullptr;
  uint32_t size = 0;
};

/// A PointCloud2: every field in `meta` except data (left empty), `size` bytes at `data`, or,
/// when `write` is set, written by write(writer, destination) straight into the serialisation
/// buffer (the depth camera builds its 10 MB cloud there: no copy at all).
struct BorrowedPointCloud2 {
  sensor_msgs::PointCloud2 meta;
  const uint8_t* data = nullptr;
  uint32_t size = 0;
  void (*write)(const void* writer, uint8_t* out) = nullptr;  // must write all `size` bytes
  const void* writer = nullptr;
};

}  // namespace tianracer_sim

namespace ros {
namespace message_traits {

// The wire identity of the sensor_msgs type each one stands for.
#define TIANRACER_SIM_BORROWED_TRAITS(Borrowed, Msg)                                        \
  template <>                                                                             \
  struct IsMessage<Borrowed> : TrueType {};                                               \
  template <>                                                                             \
  struct IsMessage<const Borrowed> : TrueType {};                                         \
  template <>                                                                             \
  struct MD5Sum<Borrowed> {                                                               \
    static const char* value() { return MD5Sum<Msg>::value(); }                          \
    static const char* value(const Borrowed&) { return value(); }                        \
  };                                                                                      \
  template <>                                                                             \
  struct DataType<Borrowed> {                                                             \
    static const char* value() { return DataType<Msg>::value(); }                        \
    static const char* value(const Borrowed&) { return value(); }                        \
  };                                                                                      \
  template <>                                                                             \
  struct Definition<Borrowed> {                                                           \
    static const char* value() { return Definition<Msg>::value(); }                      \
    static const char* value(const Borrowed&) { return value(); }                        \
  };

TIANRACER_SIM_BORROWED_TRAITS(tianracer_sim::BorrowedImage, sensor_msgs::Image)
TIANRACER_SIM_BORROWED_TRAITS(tianracer_sim::BorrowedPointCloud2, sensor_msgs::PointCloud2)
#undef TIANRACER_SIM_BORROWED_TRAITS

}  // namespace message_traits

namespace serialization {

namespace borrowed_detail {
// A uint8[] field: its length, then the bytes.
template <typename Stream>
void writeBytes(Stream& stream, const uint8_t* data, uint32_t size) {
  stream.next(size);
  if (size > 0) std::memcpy(stream.advance(size), data, size);
}
}  // namespace borrowed_detail

// Field order as in sensor_msgs/Image.h's serializer.
template <>
struct Serializer<tianracer_sim::BorrowedImage> {
  template <typename Stream>
  inline static void write(Stream& stream, const tianracer_sim::BorrowedImage& m) {
    stream.next(m.meta.header);
    stream.next(m.meta.height);
    stream.next(m.meta.width);
    stream.next(m.meta.encoding);
    stream.next(m.meta.is_bigendian);
    stream.next(m.meta.step);
    borrowed_detail::writeBytes(stream, m.data, m.size);
  }
  inline static uint32_t serializedLength(const tianracer_sim::BorrowedImage& m) {
    // meta's own data is empty: its 4-byte length prefix is counted there.
    return serializationLength(m.meta) + m.size;
  }
};

// Field order as in sensor_msgs/PointCloud2.h's serializer.
template <>
struct Serializer<tianracer_sim::BorrowedPointCloud2> {
  template <typename Stream>
  inline static void write(Stream& stream, const tianracer_sim::BorrowedPointCloud2& m) {
    stream.next(m.meta.header);
    stream.next(m.meta.height);
    stream.next(m.meta.width);
    stream.next(m.meta.fields);
    stream.next(m.meta.is_bigendian);
    stream.next(m.meta.point_step);
    stream.next(m.meta.row_step);
    if (m.write != nullptr) {
      stream.next(m.size);
      m.write(m.writer, stream.advance(m.size));
    } else {
      borrowed_detail::writeBytes(stream, m.data, m.size);
    }
    stream.next(m.meta.is_dense);
  }
  inline static uint32_t serializedLength(const tianracer_sim::BorrowedPointCloud2& m) {
    return serializationLength(m.meta) + m.size;
  }
};

}  // namespace serialization
}  // namespace ros

#endif  // TIANRACER_SIM_ROS_BORROWED_MSGS_H
