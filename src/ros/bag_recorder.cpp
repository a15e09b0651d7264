#include "mpm_sdem/ros/bag_recorder.hpp"

#include <geometry_msgs/WrenchStamped.h>
#include <mpm_sdem/Checkpoint.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <cstdio>
#include <stdexcept>

#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/limits.hpp"

namespace mpm_sdem {

namespace {

// rosbag refuses times before ros::TIME_MIN (1 ns); simulation time starts at 0.
ros::Time bagTime(Real t) {
  return std::max(conversions::toRosTime(t), ros::TIME_MIN);
}

}  // namespace

BagRecorder::BagRecorder(const std::string& path, const RecordDef& def,
                         const std::string& scene_text, const std::string& state_text)
    : bag_(std::make_unique<rosbag::Bag>()),
      def_(def),
      path_(path),
      state_text_(state_text),
      clouds_(def.cloud_rate),
      states_(def.state_rate),
      checkpoints_(def.checkpoint_rate) {
  if (const Problem problem = bagPathProblem(path); !problem.empty())
    throw std::runtime_error("cannot record the bag: " + problem.message);
  try {
    bag_->open(path_ + ".active", rosbag::bagmode::Write);
    // LZ4 chunks, on the writer thread: the default scene's bag 1.9x smaller, the clouds' zeros
    // and repeated fields most of it; rosbag's readers and `rosbag reindex` take them as they are.
    bag_->setCompression(rosbag::compression::LZ4);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("cannot write the bag " + path_ + ".active: " + e.what());
  }
  writer_ = std::make_unique<BoundedWorker<std::function<void(rosbag::Bag&)>>>(
      kQueued, [this](std::function<void(rosbag::Bag&)>& write) { write(*bag_); });
  open_ = true;
  std_msgs::String scene;
  scene.data = scene_text;
  write(def_.ns + "/scene", 0, scene, true);
}

Problem bagPathProblem(const std::string& path) {
  return limits::outputFileProblem(path, {".bag"});
}

BagRecorder::~BagRecorder() {
  close();
}

template <class M>
void BagRecorder::write(const std::string& topic, Real t, M msg, bool latched) {
  boost::shared_ptr<ros::M_string> header;
  if (latched) {
    // A connection header given to rosbag replaces the one it would build: it needs the type,
    // checksum and definition as well, or `rosbag info` calls the bag unindexed.
    namespace mt = ros::message_traits;
    header = boost::make_shared<ros::M_string>();
    (*header)["type"] = mt::DataType<M>::value();
    (*header)["md5sum"] = mt::MD5Sum<M>::value();
    (*header)["message_definition"] = mt::Definition<M>::value();
    (*header)["latching"] = "1";
    (*header)["callerid"] = def_.ns;
  }
  auto owned = std::make_shared<const M>(std::move(msg));
  enqueue([topic, time = bagTime(t), owned, header](rosbag::Bag& bag) {
    if (header)
      bag.write(topic, time, *owned, header);
    else
      bag.write(topic, time, *owned);
  });
  ++messages_;
}

void BagRecorder::enqueue(std::function<void(rosbag::Bag&)> write) {
  if (!writer_->push(std::move(write))) throwWriteFailure();
}

void BagRecorder::drain() {
  if (!writer_->drain()) throwWriteFailure();
}

void BagRecorder::throwWriteFailure() const {
  throw std::runtime_error("cannot write the bag " + path_ + ": " + writer_->failure());
}

void BagRecorder::blocksChanged(const World& world) {
  if (!open_) return;
  // The domain's frame and the static blocks, as the node sends them on /tf_static.
  std_msgs::Header header;
  header.stamp = conversions::toRosTime(world.time());
  header.frame_id = def_.fixed_frame;
  tf2_msgs::TFMessage tf;
  tf.transforms = conversions::toTransforms(conversions::toBlockStates(world, header),
                                            def_.tf_prefix, conversions::Frames::kStatic);
  tf.transforms.push_back(conversions::domainTransform(world, header, def_.tf_prefix));
  write("/tf_static", world.time(), tf, true);
}

void BagRecorder::record(World& world, const conversions::StatsInput& stats) {
  if (!open_) return;
  if (!started_) {
    started_ = true;
    blocksChanged(world);
  }
  const Real t = world.time();
  std_msgs::Header header;
  header.stamp = conversions::toRosTime(t);
  header.frame_id = def_.fixed_frame;
  if (clouds_.due(t)) {
    conversions::toPointCloud(world, def_.cloud_decimation, header, cloud_);
    write(def_.ns + "/particles", t, cloud_);
    if (world.femBodies()) {
      conversions::toFemCloud(world, header, fem_cloud_);
      write(def_.ns + "/fem_nodes", t, fem_cloud_);
      write(def_.ns + "/fem_mesh", t, conversions::toFemMarker(world, header));
    }
  }
  if (states_.due(t)) {
    const mpm_sdem::BlockStates blocks = conversions::toBlockStates(world, header);
    write(def_.ns + "/blocks", t, blocks);
    write(def_.ns + "/block_poses", t, conversions::toPoseArray(blocks));
    write(def_.ns + "/markers", t, conversions::toMarkers(world, header), true);
    tf2_msgs::TFMessage tf;
    tf.transforms = conversions::toTransforms(blocks, def_.tf_prefix, conversions::Frames::kMoving);
    if (!tf.transforms.empty()) write("/tf", t, tf);
    for (const mpm_sdem::RigidBlockState& b : blocks.blocks) {
      geometry_msgs::WrenchStamped w;
      w.header.stamp = header.stamp;
      w.header.frame_id = conversions::blockFrame(def_.tf_prefix, b.name);
      w.wrench = conversions::toWrench(b);
      write(def_.ns + "/obstacles/" + b.name + "/wrench", t, w);
    }
    write(def_.ns + "/stats", t, conversions::toStats(world, measure(world), stats, header));
  }
  if (checkpoints_.due(t)) checkpoint(world);
}

void BagRecorder::checkpoint(World& world) {
  if (!open_ || world.time() == last_checkpoint_) return;
  last_checkpoint_ = world.time();
  mpm_sdem::Checkpoint msg;
  const std::string bytes = saveCheckpoint(world, state_text_);
  msg.header.stamp = conversions::toRosTime(world.time());
  msg.header.frame_id = def_.fixed_frame;
  msg.time = world.time();
  msg.steps = world.stepCount();
  msg.build = buildId();
  msg.scene_hash = sceneHash(state_text_);
  msg.data.assign(bytes.begin(), bytes.end());
  write(def_.ns + "/checkpoint", world.time(), msg);
}

void BagRecorder::command(const WorldCommand& c) {
  if (!open_) return;
  write(def_.ns + "/commands", c.time, conversions::toMsg(c, def_.fixed_frame));
}

void BagRecorder::continueFrom(const std::string& path, Real t) {
  drain();  // the writer idle: the old run's messages go in here, in order
  rosbag::Bag source;
  try {
    source.open(path, rosbag::bagmode::Read);
    const ros::Time end = bagTime(t);
    rosbag::View view(source, ros::TIME_MIN, end);
    for (const rosbag::MessageInstance& m : view) {
      if (m.getTopic() == def_.ns + "/scene") continue;  // this run wrote its own
      if (m.getDataType() == ros::message_traits::DataType<mpm_sdem::RecordedCommand>::value() &&
          m.instantiate<mpm_sdem::RecordedCommand>()->time >= t)
        continue;
      bag_->write(m.getTopic(), m.getTime(), m, m.getConnectionHeader());
      ++messages_;
    }
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("cannot copy the run so far from " + path + ": " + e.what());
  }
  // This run's samples continue the schedule of the one it resumes.
  started_ = true;
  last_checkpoint_ = t;
  clouds_.due(t, true);
  states_.due(t, true);
  checkpoints_.due(t, true);
}

void BagRecorder::close() {
  if (!open_) return;
  open_ = false;
  writer_->finish();  // every message queued is written (or the first error stopped it)
  if (const std::string failure = writer_->failure(); !failure.empty())
    std::fprintf(stderr, "mpm_sdem: bag %s: %s\n", path_.c_str(), failure.c_str());
  bag_->close();
  if (std::rename((path_ + ".active").c_str(), path_.c_str()) != 0) {
    std::perror(("mpm_sdem: cannot rename " + path_ + ".active").c_str());
  }
}

}  // namespace mpm_sdem
