// hector_gazebo_plugins' sensors (plugins/hector/): the IMU (imu and bias topics, calibrate
// service), the GPS (fix and velocity), the magnetometer (Vector3Stamped or MagneticField) and
// the sonar (Range), with upstream's topics and queue sizes (10 for the IMU and GPS, 1 for the
// magnetometer and sonar), and their dynamic_reconfigure servers: the error models'
// (cfg/SensorModel.cfg: gaussian_noise, offset, drift, drift_frequency, scale_error, one value
// each; sensor_model.h dynamicReconfigureCallback: a vector model shows the mean of its three
// components and a change sets all three) and the GPS status (cfg/GNSS.cfg).
#include <geometry_msgs/Vector3Stamped.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/MagneticField.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/Range.h>
#include <std_srvs/Empty.h>

#include "factories.h"
#include "tianracer_sim/ros/hector_msgs.h"
#include "tianracer_sim/ros/imu_msgs.h"
#include "tianracer_sim/plugins/hector/sim_hector.h"
#include "reconfigure_server.h"
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

using Servers = std::vector<std::unique_ptr<ReconfigureServer>>;

// cfg/SensorModel.cfg.
const std::vector<ReconfigureServer::Param>& sensorModelParams() {
  static const std::vector<ReconfigureServer::Param> params = {
      {"gaussian_noise", false, "Standard deviation of the additive white Gaussian noise", 0.0,
       10.0, 0.0},
      {"offset", false, "Zero-offset of the published sensor signal", -10.0, 10.0, 0.0},
      {"drift", false, "Standard deviation of the sensor drift", 0.0, 10.0, 0.0},
      {"drift_frequency", false,
       "Reciprocal of the time constant of the first-order drift model in Hz", 0.0, 1.0, 0.0},
      {"scale_error", false, "Scale error", 0.0, 2.0, 1.0},
  };
  return params;
}

// A SensorModel_'s server on <ns>: it reads the means of the model's components and sets every
// component (SensorModel_::dynamicReconfigureCallback with level 1).
template <int N>
std::unique_ptr<ReconfigureServer> modelServer(const PublisherSetup& setup, const std::string& ns,
                                               HectorErrorModel<N>* m) {
  const auto get = [m] {
    return ReconfigureServer::Values{{"gaussian_noise", m->gaussian_noise.mean()},
                                     {"offset", m->offset.mean()},
                                     {"drift", m->drift.mean()},
                                     {"drift_frequency", m->drift_frequency.mean()},
                                     {"scale_error", m->scale_error.mean()}};
  };
  const auto set = [m](const ReconfigureServer::Values& v) {
    m->gaussian_noise.setConstant(v.at("gaussian_noise"));
    m->offset.setConstant(v.at("offset"));
    m->drift.setConstant(v.at("drift"));
    m->drift_frequency.setConstant(v.at("drift_frequency"));
    m->scale_error.setConstant(v.at("scale_error"));
  };
  return std::make_unique<ReconfigureServer>(setup.root, ns, sensorModelParams(), get, set);
}

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
    if (!c.topic_name.empty()) {  // upstream: <topicName>/accel, /rate, /yaw
      HectorImu& core = sensor.core();
      servers_.push_back(modelServer(setup, c.topic() + "/accel", &core.accelModel()));
      servers_.push_back(modelServer(setup, c.topic() + "/rate", &core.rateModel()));
      servers_.push_back(modelServer(setup, c.topic() + "/yaw", &core.yawModel()));
    }
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
  Servers servers_;
};

// cfg/GNSS.cfg and GazeboRosGps::dynamicReconfigureCallback: the fix status and the services.
std::unique_ptr<ReconfigureServer> statusServer(const PublisherSetup& setup,
                                                const std::string& ns, HectorGps* gps) {
  using sensor_msgs::NavSatStatus;
  static const std::vector<ReconfigureServer::Param> params = {
      {"STATUS_FIX", true, "unaugmented fix", 0, 1, 1},
      {"STATUS_SBAS_FIX", true, "fix with satellite-based augmentation", 0, 1, 0},
      {"STATUS_GBAS_FIX", true, "with ground-based augmentation", 0, 1, 0},
      {"SERVICE_GPS", true, "GPS service", 0, 1, 1},
      {"SERVICE_GLONASS", true, "GLONASS service", 0, 1, 1},
      {"SERVICE_COMPASS", true, "COMPASS service", 0, 1, 1},
      {"SERVICE_GALILEO", true, "GALILEO service", 0, 1, 1},
  };
  const auto get = [gps] {
    const int status = gps->config().status, service = gps->config().service;
    const auto bit = [](int v, int b) { return (v & b) ? 1.0 : 0.0; };
    return ReconfigureServer::Values{
        {"STATUS_FIX", status != NavSatStatus::STATUS_NO_FIX ? 1.0 : 0.0},
        {"STATUS_SBAS_FIX", bit(status, NavSatStatus::STATUS_SBAS_FIX)},
        {"STATUS_GBAS_FIX", bit(status, NavSatStatus::STATUS_GBAS_FIX)},
        {"SERVICE_GPS", bit(service, NavSatStatus::SERVICE_GPS)},
        {"SERVICE_GLONASS", bit(service, NavSatStatus::SERVICE_GLONASS)},
        {"SERVICE_COMPASS", bit(service, NavSatStatus::SERVICE_COMPASS)},
        {"SERVICE_GALILEO", bit(service, NavSatStatus::SERVICE_GALILEO)}};
  };
  const auto set = [gps](const ReconfigureServer::Values& v) {
    const auto on = [&](const char* name) { return v.at(name) != 0.0; };
    const int augmented = (on("STATUS_SBAS_FIX") ? NavSatStatus::STATUS_SBAS_FIX : 0) |
                          (on("STATUS_GBAS_FIX") ? NavSatStatus::STATUS_GBAS_FIX : 0);
    const int status = on("STATUS_FIX") ? augmented : NavSatStatus::STATUS_NO_FIX;
    const int service = (on("SERVICE_GPS") ? NavSatStatus::SERVICE_GPS : 0) |
                        (on("SERVICE_GLONASS") ? NavSatStatus::SERVICE_GLONASS : 0) |
                        (on("SERVICE_COMPASS") ? NavSatStatus::SERVICE_COMPASS : 0) |
                        (on("SERVICE_GALILEO") ? NavSatStatus::SERVICE_GALILEO : 0);
    gps->setStatus(status, service);
  };
  return std::make_unique<ReconfigureServer>(setup.root, ns, params, get, set);
}

class HectorGpsPublisher : public SensorListener {
 public:
  HectorGpsPublisher(SimHectorGps& sensor, const PublisherSetup& setup) : sensor_(sensor) {
    const HectorGpsConfig& c = sensor.config();
    const std::string who = "hector GPS '" + c.name + "'";
    fix_.advertise(setup, c.topic(), who, 10);
    velocity_.advertise(setup, c.velocityTopic(), who, 10);
    // upstream: <topicName>/position, /velocity and /status.
    HectorGps& core = sensor.core();
    servers_.push_back(modelServer(setup, c.topic() + "/position", &core.positionModel()));
    servers_.push_back(modelServer(setup, c.topic() + "/velocity", &core.velocityModel()));
    servers_.push_back(statusServer(setup, c.topic() + "/status", &core));
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
  Servers servers_;
};

/// A sensor's TopicPublisher and its model's reconfigure server on <topicName> (magnetometer,
/// sonar).
class WithServer : public SensorListener {
 public:
  WithServer(std::unique_ptr<SensorListener> publisher, std::unique_ptr<ReconfigureServer> server)
      : publisher_(std::move(publisher)), server_(std::move(server)) {}
  SensorOutputs wanted(const SimSensor& s, SensorOutputs due) override {
    return publisher_->wanted(s, due);
  }
  void onOutputs(const SimSensor& s, SensorOutputs outputs, double t) override {
    publisher_->onOutputs(s, outputs, t);
  }

 private:
  std::unique_ptr<SensorListener> publisher_;
  std::unique_ptr<ReconfigureServer> server_;
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
  std::unique_ptr<SensorListener> publisher;
  if (c.use_magnetic_field_msgs) {
    publisher = std::make_unique<TopicPublisher<SimHectorMagnetic, sensor_msgs::MagneticField>>(
        sensor, setup, spec, &toFieldMsg);
  } else {
    publisher = std::make_unique<TopicPublisher<SimHectorMagnetic, geometry_msgs::Vector3Stamped>>(
        sensor, setup, spec, &toFieldVector);
  }
  return std::make_unique<WithServer>(std::move(publisher),
                                      modelServer(setup, c.topic(), &sensor.core().model()));
}

std::unique_ptr<SensorListener> makeHectorSonarPublisher(SimSensor& s,
                                                         const PublisherSetup& setup) {
  auto& sensor = static_cast<SimHectorSonar&>(s);
  const HectorSonarConfig& c = sensor.config();
  ROS_INFO("hector sonar '%s' on link %s: %d x %d rays, %.4g..%.4g m, %g Hz on %s (frame %s)",
           c.ray.name.c_str(), c.ray.link.c_str(), c.ray.vertical_samples, c.ray.samples,
           c.ray.range_min, c.ray.range_max, c.timer.rate(), c.topic().c_str(),
           c.frame_id.c_str());
  return std::make_unique<WithServer>(
      std::make_unique<TopicPublisher<SimHectorSonar, sensor_msgs::Range>>(
          sensor, setup, TopicSpec{c.topic(), "hector sonar '" + c.ray.name + "'", 1},
          &toSonarMsg),
      modelServer(setup, c.topic(), &sensor.model()));
}

TIANRACER_SENSOR_PUBLISHER(hectorImuKind, makeHectorImuPublisher);
TIANRACER_SENSOR_PUBLISHER(hectorGpsKind, makeHectorGpsPublisher);
TIANRACER_SENSOR_PUBLISHER(hectorMagneticKind, makeHectorMagneticPublisher);
TIANRACER_SENSOR_PUBLISHER(hectorSonarKind, makeHectorSonarPublisher);

}  // namespace tianracer_sim
