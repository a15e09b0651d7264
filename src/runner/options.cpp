#include "options.hpp"

#include <cmath>
#include <cstdlib>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/ros/bag_recorder.hpp"

namespace mpm_sdem::runner {

const char* usage() {
  return "usage: mpm_sdem_run <scene.yaml> [--out DIR] [--set key=value ...] [--threads N] "
         "[--quiet]\n"
         "  --out DIR        write timeseries.csv, particles.csv and profile.csv to DIR\n"
         "                   (default: out/<scene file name without .yaml>)\n"
         "  --set key=value  override a scene value, e.g. --set time.end=0.5 or\n"
         "                   --set materials.sand.density=1500 (repeatable)\n"
         "  --threads N      OpenMP threads, 1 to the cores (default 0: chosen while running,\n"
         "                   up to OMP_NUM_THREADS or all cores, from measured step times)\n"
         "  --quiet          no progress line\n"
         "  --bag FILE       also record a rosbag as the node does (no ROS master needed)\n"
         "  --bag-cloud-rate HZ, --bag-state-rate HZ, --bag-checkpoint-rate HZ\n"
         "                   particle clouds / block states / checkpoints per simulated second\n"
         "                   (10, 100, 1; a last checkpoint is written at the end)\n"
         "  --checkpoint-every S\n"
         "                   also write the whole state to DIR/checkpoints/t<time>.ckpt every S\n"
         "                   simulated seconds and at the end (the latest two are kept)\n"
         "  --resume FROM    continue a run, bit for bit, from a checkpoint: a .ckpt file, a\n"
         "                   folder (its latest), or BAG[@TIME] (the bag's state at TIME s: its\n"
         "                   last checkpoint before, stepped on under its commands). Same scene\n"
         "                   and --set values (time.end, output and view may change), same\n"
         "                   build; with --bag, the new bag starts with the old one's messages\n"
         "                   up to there\n"
         "  --replay-commands BAG\n"
         "                   apply the obstacle commands recorded in BAG (the node's ~commands)\n"
         "                   at their times: the run again, or with a changed scene (--set)\n"
         "  --vtk-every S    ParaView files in DIR/vtk (points.pvd, ...) every S seconds of\n"
         "                   simulated time, from the start, and at the end\n"
         "  --perturb M      move every material point at the start by a uniform draw in\n"
         "                   [-M, M] m along x and y (an ensemble member; not with --resume)\n"
         "  --seed N         the perturbation's seed (default 1): the same N, the same run\n"
         "exit status: 0 done, 1 bad scene or checkpoint, 2 bad command line, 3 unstable state, "
         "130 "
         "interrupted\n";
}

bool parseOptions(int argc, char** argv, Options& out, std::string& error, bool& help) {
  help = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* flag) -> const char* {
      if (i + 1 >= argc) {
        error = std::string(flag) + " needs a value";
        return nullptr;
      }
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      help = true;
      return true;
    } else if (a == "--out") {
      const char* v = value("--out");
      if (!v) return false;
      out.out_dir = v;
    } else if (a == "--set") {
      const char* v = value("--set");
      if (!v) return false;
      out.overrides.push_back(v);
    } else if (a == "--threads") {
      const char* v = value("--threads");
      if (!v) return false;
      char* end = nullptr;
      const long n = std::strtol(v, &end, 10);
      const Problem p = limits::threadsProblem(n);
      if (*end != '\0' || *v == '\0' || !p.empty()) {
        error = std::string("--threads ") +
                (*end != '\0' || *v == '\0' ? "takes a whole number, got '" + std::string(v) + "'"
                                            : p.message);
        return false;
      }
      out.threads = static_cast<int>(n);
    } else if (a == "--bag") {
      const char* v = value("--bag");
      if (!v) return false;
      out.bag = v;
    } else if (a == "--bag-cloud-rate" || a == "--bag-state-rate" || a == "--bag-checkpoint-rate") {
      const char* v = value(a.c_str());
      if (!v) return false;
      char* end = nullptr;
      const double r = std::strtod(v, &end);
      if (*end != '\0' || !(r >= 0) || r > 1e6) {
        error = a + " takes a rate >= 0 Hz (0: off), got '" + v + "'";
        return false;
      }
      (a == "--bag-cloud-rate"   ? out.bag_cloud_rate
       : a == "--bag-state-rate" ? out.bag_state_rate
                                 : out.bag_checkpoint_rate) = r;
    } else if (a == "--checkpoint-every") {
      const char* v = value(a.c_str());
      if (!v) return false;
      char* end = nullptr;
      const double s = std::strtod(v, &end);
      if (*end != '\0' || *v == '\0' || !(s > 0) || s > 1e9) {
        error = "--checkpoint-every takes simulated seconds > 0, got '" + std::string(v) + "'";
        return false;
      }
      out.checkpoint_every = s;
    } else if (a == "--resume" || a == "--replay-commands") {
      const char* v = value(a.c_str());
      if (!v) return false;
      if (*v == '\0') {
        error = a + " needs a value";
        return false;
      }
      (a == "--resume" ? out.resume : out.replay) = v;
    } else if (a == "--vtk-every") {
      const char* v = value("--vtk-every");
      if (!v) return false;
      char* end = nullptr;
      const double s = std::strtod(v, &end);
      if (*end != '\0' || *v == '\0' || !(s > 0) || !std::isfinite(s)) {
        error =
            "--vtk-every takes an interval > 0 s of simulated time, got '" + std::string(v) + "'";
        return false;
      }
      out.vtk_every = s;
    } else if (a == "--perturb") {
      const char* v = value("--perturb");
      if (!v) return false;
      char* end = nullptr;
      const double m = std::strtod(v, &end);
      if (*end != '\0' || *v == '\0' || !(m >= 0) || m > 1) {
        error = "--perturb takes a distance in [0, 1] m, got '" + std::string(v) + "'";
        return false;
      }
      out.perturb = m;
    } else if (a == "--seed") {
      const char* v = value("--seed");
      if (!v) return false;
      char* end = nullptr;
      const long long n = std::strtoll(v, &end, 10);
      if (*end != '\0' || *v == '\0' || n < 0 || n > 4294967295LL) {
        error = "--seed takes a whole number from 0 to 4294967295, got '" + std::string(v) + "'";
        return false;
      }
      out.seed = static_cast<unsigned>(n);
    } else if (a == "--quiet") {
      out.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      error = "unknown option '" + a + "'";
      return false;
    } else if (out.scene.empty()) {
      out.scene = a;
    } else {
      error = "more than one scene file given ('" + out.scene + "', '" + a + "')";
      return false;
    }
  }
  if (out.scene.empty()) {
    error = "no scene file given";
    return false;
  }
  if (out.perturb > 0 && !out.resume.empty()) {
    error =
        "--perturb applies to a fresh start, not to --resume (the checkpoint has the positions)";
    return false;
  }
  if (!out.bag.empty()) {
    if (const Problem p = bagPathProblem(out.bag); !p.empty()) {
      error = "--bag: " + p.message;
      return false;
    }
  }
  return true;
}

}  // namespace mpm_sdem::runner
