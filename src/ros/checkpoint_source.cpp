#include "mpm_sdem/ros/checkpoint_source.hpp"

#include <mpm_sdem/Checkpoint.h>
#include <rosbag/bag.h>
#include <rosbag/query.h>
#include <rosbag/view.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/ros/conversions.hpp"
#include "mpm_sdem/ros/recorded_commands.hpp"

namespace fs = std::filesystem;

namespace mpm_sdem {

std::string checkpointFileName(Real t) {
  char name[64];
  std::snprintf(name, sizeof name, "t%013.6f.ckpt", t);
  return name;
}

namespace {

std::string seconds(Real t) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g s", t);
  return s;
}

// A bag stamp to the nanosecond, as BAG@TIME takes it back (0.200043977 s).
std::string stampText(const ros::Time& t) {
  char s[48];
  std::snprintf(s, sizeof s, "%u.%09u", t.sec, t.nsec);
  std::string out = s;
  out.erase(out.find_last_not_of('0') + 1);
  if (out.back() == '.') out.pop_back();
  return out + " s";
}

CheckpointSource fromFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the checkpoint " + file.string());
  std::ostringstream bytes;
  bytes << in.rdbuf();
  CheckpointSource s;
  s.bytes = bytes.str();
  s.description = file.string();
  try {
    s.time = readCheckpointHeader(s.bytes).time;
    s.description = "the checkpoint at t = " + seconds(s.time) + " in " + file.string();
  } catch (const CheckpointError&) {
    // restoreCheckpoint reports it with the reason.
  }
  return s;
}

CheckpointSource fromFolder(const fs::path& dir) {
  for (const fs::path& d : {dir / "checkpoints", dir}) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(d, ec))
      if (e.path().extension() == ".ckpt" && e.path().filename().string()[0] == 't')
        files.push_back(e.path());
    if (!files.empty()) return fromFile(*std::max_element(files.begin(), files.end()));
  }
  throw std::runtime_error(dir.string() +
                           " holds no checkpoint (t*.ckpt, written by --checkpoint-every)");
}

CheckpointSource fromBag(const std::string& path, bool at, Real t) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("cannot read the bag " + path + ": " + e.what());
  }
  const std::string type = ros::message_traits::DataType<mpm_sdem::Checkpoint>::value();
  rosbag::View view(bag, rosbag::TypeQuery(type));
  // Chosen by stamp (rounded to ns): no checkpoint is read but the one resumed from.
  const ros::Time limit = conversions::toRosTime(t);
  std::vector<ros::Time> times;
  const rosbag::MessageInstance* chosen = nullptr;
  std::vector<rosbag::MessageInstance> all(view.begin(), view.end());
  for (const rosbag::MessageInstance& m : all) {
    times.push_back(m.getTime());
    if (!at || m.getTime() <= limit) chosen = &m;
  }
  if (all.empty())
    throw std::runtime_error(path + " holds no checkpoint (record with a checkpoint rate > 0)");
  if (!chosen) {
    std::string held;
    for (std::size_t k = 0; k < times.size() && k < 8; ++k)
      held += (k ? ", " : "") + seconds(times[k].toSec());
    if (times.size() > 8) held += ", ...";
    throw std::runtime_error(path + " holds no checkpoint at or before " + seconds(t) +
                             "; it holds checkpoints at " + held);
  }
  const auto msg = chosen->instantiate<mpm_sdem::Checkpoint>();
  if (!msg) throw std::runtime_error(path + ": a checkpoint message cannot be read");
  CheckpointSource s;
  s.bytes.assign(msg->data.begin(), msg->data.end());
  s.bag = path;
  s.time = msg->time;
  s.description = "the checkpoint at t = " + stampText(chosen->getTime()) + " (step " +
                  std::to_string(msg->steps) + ") in " + path;
  if (at) {
    s.asked = t;
    s.recorded_end = rosbag::View(bag).getEndTime().toSec();
    s.commands = readRecordedCommands(path, s.time, std::min(t, s.recorded_end));
  }
  return s;
}

}  // namespace

CatchUp catchUpToAsked(World& world, const CheckpointSource& from, Time end_time,
                       Real step_collapse) {
  if (from.asked < 0) return {};
  // The bag's stamps are rounded to the nanosecond: its last step ends within one of its stamp.
  const Time until = std::min<Time>(from.asked, from.recorded_end + 1e-9);
  CatchUp c = catchUp(world, until, end_time, step_collapse, from.commands);
  if (!c.problem.empty())
    throw std::runtime_error("stepping on from " + from.description +
                             " to t = " + seconds(from.asked) + ": " + c.problem);
  return c;
}

std::string resumeDescription(const CheckpointSource& from, const CatchUp& c, Time reached) {
  std::string out = "resuming from " + from.description;
  if (c.steps == 0) return out;
  char m[256];
  std::snprintf(m, sizeof m,
                "; stepped on to t = %.9g s as the bag's run did (%ld steps, %zu recorded "
                "commands, %.3g s of wall time)",
                reached, c.steps, c.applied, c.wall_seconds);
  out += m;
  if (c.skipped > 0)
    out += "; " + std::to_string(c.skipped) + " commands could not be applied (a changed scene)";
  return out;
}

std::string resumeGapWarning(const CheckpointSource& from, Time reached, Real dt) {
  const Real gap = from.asked - reached;
  if (from.asked < 0 || !(gap > dt)) return "";
  char m[320];
  std::snprintf(m, sizeof m,
                "resuming at t = %.9g s, %.6g s before the t = %.9g s asked for: the bag's "
                "recording ends at t = %.9g s",
                reached, gap, from.asked, from.recorded_end);
  return m;
}

CheckpointSource loadCheckpointSource(const std::string& spec) {
  // BAG@TIME: the @ splits only a .bag's name from a number.
  const std::size_t at = spec.rfind('@');
  if (at != std::string::npos && spec.compare(at >= 4 ? at - 4 : 0, 4, ".bag") == 0) {
    const std::string time = spec.substr(at + 1);
    char* end = nullptr;
    const double t = std::strtod(time.c_str(), &end);
    if (time.empty() || *end != '\0' || !(t >= 0) || t > 1e9)
      throw std::runtime_error("'" + spec + "': the time after @ must be seconds >= 0, got '" +
                               time + "'");
    return fromBag(spec.substr(0, at), true, t);
  }
  std::error_code ec;
  if (!fs::exists(spec, ec)) throw std::runtime_error(spec + ": no such file or folder");
  if (fs::is_directory(spec, ec)) return fromFolder(spec);
  if (fs::path(spec).extension() == ".bag") return fromBag(spec, false, 0);
  return fromFile(spec);
}

}  // namespace mpm_sdem
