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
#include <vector>

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

namespace tianracer_sim {

/// A `Msg` (a sensor_msgs type with one uint8[] field, `data`): every field in `meta` except
/// data (left empty), which is `size` bytes at `data`, or, when `write` is set, written by
/// write(writer, destination) straight into the serialisation buffer (the depth camera builds
/// its 10 MB cloud there: no copy at all).
template <class Msg>
struct Borrowed {
  Msg meta;
  const uint8_t* data = nullptr;
  uint32_t size = 0;
  void (*write)(const void* writer, uint8_t* out) = nullptr;  // must write all `size` bytes
  const void* writer = nullptr;
};

using BorrowedImage = Borrowed<sensor_msgs::Image>;
using BorrowedPointCloud2 = Borrowed<sensor_msgs::PointCloud2>;

}  // namespace tianracer_sim

namespace ros {
namespace message_traits {

// The wire identity of the sensor_msgs type each one stands for.
template <template <class> class Trait, class Msg>
struct BorrowedTrait {
  static const char* value() { return Trait<Msg>::value(); }
  static const char* value(const tianracer_sim::Borrowed<Msg>&) { return value(); }
};

template <class Msg>
struct IsMessage<tianracer_sim::Borrowed<Msg>> : TrueType {};
template <class Msg>
struct IsMessage<const tianracer_sim::Borrowed<Msg>> : TrueType {};
template <class Msg>
struct MD5Sum<tianracer_sim::Borrowed<Msg>> : BorrowedTrait<MD5Sum, Msg> {};
template <class Msg>
struct DataType<tianracer_sim::Borrowed<Msg>> : BorrowedTrait<DataType, Msg> {};
template <class Msg>
struct Definition<tianracer_sim::Borrowed<Msg>> : BorrowedTrait<Definition, Msg> {};

}  // namespace message_traits

namespace serialization {

namespace borrowed_detail {

/// The stream Msg's own (generated) serializer writes its fields to: each goes on to `out` as
/// it is, except meta.data, whose place the borrowed bytes take. The field order is so the
/// sensor_msgs type's by construction.
template <class Stream, class Msg>
struct BorrowingStream {
  Stream& out;
  const tianracer_sim::Borrowed<Msg>& m;

  template <class Field>
  void next(const Field& field) {
    out.next(field);
  }
  void next(const std::vector<uint8_t>& field) {
    if (&field != &m.meta.data) {
      out.next(field);
    } else if (m.write != nullptr) {
      out.next(m.size);
      m.write(m.writer, out.advance(m.size));
    } else {
      out.next(m.size);
      if (m.size > 0) std::memcpy(out.advance(m.size), m.data, m.size);
    }
  }
};

}  // namespace borrowed_detail

template <class Msg>
struct Serializer<tianracer_sim::Borrowed<Msg>> {
  template <typename Stream>
  inline static void write(Stream& stream, const tianracer_sim::Borrowed<Msg>& m) {
    borrowed_detail::BorrowingStream<Stream, Msg> borrowing{stream, m};
    Serializer<Msg>::template allInOne<borrowed_detail::BorrowingStream<Stream, Msg>, const Msg&>(
        borrowing, m.meta);
  }
  inline static uint32_t serializedLength(const tianracer_sim::Borrowed<Msg>& m) {
    // meta's own data is empty: its 4-byte length prefix is counted there.
    return serializationLength(m.meta) + m.size;
  }
};

}  // namespace serialization
}  // namespace ros

#endif  // TIANRACER_SIM_ROS_BORROWED_MSGS_H
