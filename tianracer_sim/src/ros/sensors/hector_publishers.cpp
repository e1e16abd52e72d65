// hector_gazebo_plugins' sensors (sensors/hector/): the IMU (imu and bias topics, calibrate
// service), the GPS (fix and velocity), the magnetometer (Vector3Stamped or MagneticField) and
// the sonar (Range), with upstream's topics and queue sizes (10 for the IMU and GPS, 1 for the
// magnetometer and sonar).
#include <geometry_msgs/Vector3Stamped.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/MagneticField.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/Range.h>
#include <std_srvs/Empty.h>

#include "factories.h"
#include "tianracer_sim/ros/hector_msgs.h"
#include "tianracer_sim/ros/imu_msgs.h"
#include "tianracer_sim/sensors/hector/sim_hector.h"
#include "topic_publisher.h"

namespace tianracer_sim {
namespace {

/// A topic of a sensor with two: advertised when named, heard or not.
template <class Msg>
struct Topic {
  ros::Publisher pub;
  Msg msg;
  void advertise(const PublisherSetup& setup, const std::string& topic, const std::string& who,
                 uint32_t queue) {
    setup.claim_topic(topic, setup.owner() + " " + who);
    ros::NodeHandle root = setup.root;
    pub = root.advertise<Msg>(topic, queue);
  }
  bool heard() const { return pub && pub.getNumSubscribers() > 0; }
};

class HectorImuPublisher : public SensorListener {
 public:
  HectorImuPublisher(SimHectorImu& sensor, const PublisherSetup& setup) : sensor_(sensor) {
    const HectorImuConfig& c = sensor.config();
    const std::string who = "hector IMU '" + c.name + "'";
    if (!c.topic_name.empty()) imu_.advertise(setup, c.topic(), who, 10);
    if (!c.bias_topic_name.empty()) bias_.advertise(setup, c.biasTopic(), who, 10);
    imu_.msg.header.frame_id = bias_.msg.header.frame_id = sensor.frame();
    ros::NodeHandle root = setup.root;
    if (!c.service_name.empty())
      calibrate_ = root.advertiseService(c.service(), &HectorImuPublisher::onCalibrate, this);
    sensor.stat().name = c.topic_name.empty() ? c.biasTopic() : c.topic();
    ROS_INFO("hector IMU '%s' on link %s: %g Hz on %s, bias on %s, calibrate %s (frame %s)",
             c.name.c_str(), c.link.c_str(), c.timer.rate(), c.topic().c_str(),
             c.bias_topic_name.empty() ? "(none)" : c.biasTopic().c_str(),
             c.service_name.empty() ? "(none)" : c.service().c_str(), sensor.frame().c_str());
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return due & ((imu_.heard() ? SimHectorImu::kImu : 0) |
                  (bias_.heard() ? SimHectorImu::kBias : 0));
  }

  void onOutputs(const SimSensor&, SensorOutputs outputs, double t) override {
    const HectorImuReading& r = sensor_.reading();
    if (outputs & SimHectorImu::kImu) {
      toImu(r.imu, ros::Time(t), &imu_.msg);
      imu_.pub.publish(imu_.msg);
    }
    if (outputs & SimHectorImu::kBias) {
      toImu(r.bias, ros::Time(t), &bias_.msg);
      bias_.pub.publish(bias_.msg);
    }
  }

 private:
  // Called between steps, on the node's queue: the rate model's drift set to 0, as upstream.
  bool onCalibrate(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    sensor_.core().calibrate();
    return true;
  }

  SimHectorImu& sensor_;
  Topic<sensor_msgs::Imu> imu_, bias_;
  ros::ServiceServer calibrate_;
};

class HectorGpsPublisher : public SensorListener {
 public:
  HectorGpsPublisher(SimHectorGps& sensor, const PublisherSetup& setup) : sensor_(sensor) {
    const HectorGpsConfig& c = sensor.config();
    const std::string who = "hector GPS '" + c.name + "'";
    fix_.advertise(setup, c.topic(), who, 10);
    velocity_.advertise(setup, c.velocityTopic(), who, 10);
    sensor.stat().name = c.topic();
    ROS_INFO("hector GPS '%s' on link %s: %g Hz on %s and %s (frame %s), reference %.7f, %.7f, "
             "%g m, heading %g rad",
             c.name.c_str(), c.link.c_str(), c.timer.rate(), c.topic().c_str(),
             c.velocityTopic().c_str(), sensor.frame().c_str(), c.reference_latitude,
             c.reference_longitude, c.reference_altitude, c.reference_heading);
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return due & ((fix_.heard() ? SimHectorGps::kFix : 0) |
                  (velocity_.heard() ? SimHectorGps::kVelocity : 0));
  }

  void onOutputs(const SimSensor&, SensorOutputs outputs, double t) override {
    const HectorGpsReading& r = sensor_.reading();
    if (outputs & SimHectorGps::kFix) {
      toNavSatFix(r, sensor_.frame(), ros::Time(t), &fix_.msg);
      fix_.pub.publish(fix_.msg);
    }
    if (outputs & SimHectorGps::kVelocity) {
      toGpsVelocity(r, sensor_.frame(), ros::Time(t), &velocity_.msg);
      velocity_.pub.publish(velocity_.msg);
    }
  }

 private:
  SimHectorGps& sensor_;
  Topic<sensor_msgs::NavSatFix> fix_;
  Topic<geometry_msgs::Vector3Stamped> velocity_;
};

void toFieldVector(const SimHectorMagnetic& s, const ros::Time& stamp,
                   geometry_msgs::Vector3Stamped* msg) {
  toVector3Stamped(s.field(), s.frame(), stamp, msg);
}

void toFieldMsg(const SimHectorMagnetic& s, const ros::Time& stamp,
                sensor_msgs::MagneticField* msg) {
  toMagneticField(s.field(), s.frame(), stamp, msg);
}

void toSonarMsg(const SimHectorSonar& s, const ros::Time& stamp, sensor_msgs::Range* msg) {
  toSonarRange(s.reading(), s.config().frame_id, stamp, msg);
}

}  // namespace

std::unique_ptr<SensorListener> makeHectorImuPublisher(SimSensor& sensor,
                                                       const PublisherSetup& setup) {
  return std::make_unique<HectorImuPublisher>(static_cast<SimHectorImu&>(sensor), setup);
}

std::unique_ptr<SensorListener> makeHectorGpsPublisher(SimSensor& sensor,
                                                       const PublisherSetup& setup) {
  return std::make_unique<HectorGpsPublisher>(static_cast<SimHectorGps&>(sensor), setup);
}

std::unique_ptr<SensorListener> makeHectorMagneticPublisher(SimSensor& s,
                                                            const PublisherSetup& setup) {
  auto& sensor = static_cast<SimHectorMagnetic&>(s);
  const HectorMagneticConfig& c = sensor.config();
  const TopicSpec spec{c.topic(), "hector magnetic '" + c.name + "'", 1};
  ROS_INFO("hector magnetic '%s' on link %s: %g Hz on %s (%s, frame %s), |B| %g",
           c.name.c_str(), c.link.c_str(), c.timer.rate(), c.topic().c_str(),
           c.use_magnetic_field_msgs ? "MagneticField" : "Vector3Stamped",
           sensor.frame().c_str(), c.magnitude);
  if (c.use_magnetic_field_msgs)
    return std::make_unique<TopicPublisher<SimHectorMagnetic, sensor_msgs::MagneticField>>(
        sensor, setup, spec, &toFieldMsg);
  return std::make_unique<TopicPublisher<SimHectorMagnetic, geometry_msgs::Vector3Stamped>>(
      sensor, setup, spec, &toFieldVector);
}

std::unique_ptr<SensorListener> makeHectorSonarPublisher(SimSensor& s,
                                                         const PublisherSetup& setup) {
  auto& sensor = static_cast<SimHectorSonar&>(s);
  const HectorSonarConfig& c = sensor.config();
  ROS_INFO("hector sonar '%s' on link %s: %d x %d rays, %.4g..%.4g m, %g Hz on %s (frame %s)",
           c.ray.name.c_str(), c.ray.link.c_str(), c.ray.vertical_samples, c.ray.samples,
           c.ray.range_min, c.ray.range_max, c.timer.rate(), c.topic().c_str(),
           c.frame_id.c_str());
  return std::make_unique<TopicPublisher<SimHectorSonar, sensor_msgs::Range>>(
      sensor, setup, TopicSpec{c.topic(), "hector sonar '" + c.ray.name + "'", 1}, &toSonarMsg);
}

}  // namespace tianracer_sim
