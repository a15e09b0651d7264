// mpm_sdem_run --resume and --checkpoint-every: a run killed with SIGKILL and resumed from its
// latest checkpoint file writes the files of a run that never stopped (CSVs, the final
// checkpoint, the ParaView series); a resume from a bag at a time between its checkpoints steps on
// to it as the bag's run did and continues it to the bit; a checkpoint of other scene settings, a
// damaged one or a time the bag does not hold is refused with the reason.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "helpers.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::temp_directory_path() / ("mpm_sdem_resume_" + std::to_string(getpid()));

std::string scene() {
  return mpm_sdem::test::sourcePath("config/scenes/debris_impact.yaml");
}

// Runs the runner with args; its exit status, and its stderr in log.
int runner(const std::string& args, std::string* log = nullptr) {
  const fs::path err = kDir / "stderr.txt";
  const std::string cmd = std::string(MPM_SDEM_RUNNER) + " " + scene() + " " + args +
                          " --quiet --threads 1 2>" + err.string();
  const int status = std::system(cmd.c_str());
  if (log) {
    std::ifstream in(err);
    std::stringstream s;
    s << in.rdbuf();
    *log = s.str();
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The run to 0.4 s with checkpoint files every 0.05 s and ParaView frames every 0.05 s.
const std::string kRun = "--set time.end=0.4 --checkpoint-every 0.05 --vtk-every 0.05";

class RunnerResume : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    fs::create_directories(kDir);
    ASSERT_EQ(runner(kRun + " --bag-checkpoint-rate 10 --bag " + (kDir / "whole.bag").string() +
                     " --out " + (kDir / "whole").string()),
              0);
  }
  static void TearDownTestSuite() {
    if (!std::getenv("KEEP")) fs::remove_all(kDir);
  }
};

}  // namespace

TEST_F(RunnerResume, AKilledRunResumedFromItsFolderEndsAsTheWholeRun) {
  const fs::path out = kDir / "killed";
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string o = out.string();
    execl(MPM_SDEM_RUNNER, MPM_SDEM_RUNNER, scene().c_str(), "--set", "time.end=0.4",
          "--checkpoint-every", "0.05", "--vtk-every", "0.05", "--quiet", "--threads", "1", "--out",
          o.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Killed a little after its checkpoint at 0.1 s (a quarter of the way): it has written
  // rows and frames past its latest checkpoint, which the resumed run writes again.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  auto past = [&](const std::string& name) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(out / "checkpoints", ec))
      if (e.path().extension() == ".ckpt" && e.path().filename().string() >= name) return true;
    return false;
  };
  while (!past("t000000.100000") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before it was killed";
  std::string log;
  ASSERT_EQ(runner(kRun + " --resume " + out.string() + " --out " + out.string(), &log), 0) << log;
  EXPECT_NE(log.find("resuming from the checkpoint at t = "), std::string::npos) << log;
  std::printf("%s", log.substr(0, log.find('\n') + 1).c_str());
  for (const char* f : {"timeseries.csv", "blocks.csv", "particles.csv", "vtk/points.pvd",
                        "vtk/blocks.pvd", "checkpoints/t000000.400000.ckpt"})
    EXPECT_TRUE(text(out / f) == text(kDir / "whole" / f)) << f << " differs from the whole run's";
}

TEST_F(RunnerResume, FromABagAtATime) {
  const fs::path out = kDir / "from_bag";
  fs::copy(kDir / "whole", out, fs::copy_options::recursive);
  std::string log;
  // Recorded at 1 checkpoint per simulated second (the default), the bag holds one at t = 0
  // and one at the end: @0.25 restores the first and steps on to 0.25 s as the run did.
  ASSERT_EQ(runner("--set time.end=0.4 --vtk-every 0.05 --bag " + (kDir / "sparse.bag").string() +
                   " --out " + (kDir / "sparse").string()),
            0);
  ASSERT_EQ(
      runner(kRun + " --resume " + (kDir / "sparse.bag").string() + "@0.25 --out " + out.string(),
             &log),
      0)
      << log;
  EXPECT_NE(log.find("(step 0) in " + (kDir / "sparse.bag").string()), std::string::npos) << log;
  // Within a step (0.3 ms) of the time asked for, and no warning.
  auto number = [&log](const std::string& after) {
    const std::size_t at = log.find(after);
    return at == std::string::npos ? -1.0 : std::atof(log.c_str() + at + after.size());
  };
  const double reached = number("stepped on to t = ");
  EXPECT_LE(reached, 0.25) << log;
  EXPECT_GT(reached, 0.25 - 3e-4) << log;
  EXPECT_EQ(log.find("warning"), std::string::npos) << log;
  // The files go on as the whole run's to the bit: the steps and commands were the same.
  for (const char* f : {"timeseries.csv", "blocks.csv", "particles.csv", "vtk/points.pvd",
                        "checkpoints/t000000.400000.ckpt"})
    EXPECT_TRUE(text(out / f) == text(kDir / "whole" / f)) << f << " differs from the whole run's";
  // At a checkpoint's own time: nothing to step.
  ASSERT_EQ(runner(kRun + " --resume " + (kDir / "whole.bag").string() + "@0.25 --out " +
                       (kDir / "at_0.25").string(),
                   &log),
            0)
      << log;
  const std::size_t at = log.find("the checkpoint at t = ") + 22;
  const std::string t = log.substr(at, log.find(' ', at) - at);
  ASSERT_EQ(runner(kRun + " --resume " + (kDir / "whole.bag").string() + "@" + t + " --out " +
                       (kDir / "at_checkpoint").string(),
                   &log),
            0)
      << log;
  EXPECT_NE(log.find("the checkpoint at t = " + t), std::string::npos) << log;
  EXPECT_EQ(log.find("stepped on"), std::string::npos) << log;
  // Past the bag's end: its end, with a warning that says so.
  ASSERT_EQ(runner("--set time.end=0.45 --resume " + (kDir / "whole.bag").string() +
                       "@0.45 --out " + (kDir / "past_end").string(),
                   &log),
            0)
      << log;
  EXPECT_NE(log.find("the bag's recording ends at t = 0.4"), std::string::npos) << log;
}

TEST_F(RunnerResume, ALongerEndIsAllowed) {
  std::string log;
  EXPECT_EQ(runner("--set time.end=0.45 --resume " + (kDir / "whole.bag").string() + " --out " +
                       (kDir / "longer").string(),
                   &log),
            0)
      << log;
  EXPECT_NE(log.find("resuming from the checkpoint at t = 0.4 s"), std::string::npos) << log;
}

TEST_F(RunnerResume, OtherSettingsDamageAndMissingTimesAreRefused) {
  const std::string bag = (kDir / "whole.bag").string();
  std::string log;
  EXPECT_EQ(runner(kRun + " --set materials.sand.density=1500 --resume " + bag + " --out " +
                       (kDir / "refused").string(),
                   &log),
            1);
  EXPECT_NE(log.find("materials.sand.density: 1300 in the checkpoint, 1500 here"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("Resume with the scene file and --set values it was written with"),
            std::string::npos)
      << log;

  // A byte changed in the middle of a checkpoint file.
  const fs::path bad = kDir / "bad.ckpt";
  std::string bytes = text(kDir / "whole/checkpoints/t000000.400000.ckpt");
  bytes[bytes.size() / 2] ^= 1;
  std::ofstream(bad, std::ios::binary) << bytes;
  EXPECT_EQ(
      runner(kRun + " --resume " + bad.string() + " --out " + (kDir / "refused").string(), &log),
      1);
  EXPECT_NE(log.find("damaged: the checksum"), std::string::npos) << log;

  EXPECT_EQ(runner(kRun + " --resume " + bag + "@-1 --out " + (kDir / "refused").string(), &log),
            1);
  EXPECT_NE(log.find("the time after @ must be seconds >= 0"), std::string::npos) << log;
  EXPECT_EQ(runner(kRun + " --resume " + (kDir / "none.bag").string() + " --out " +
                       (kDir / "refused").string(),
                   &log),
            1);
  EXPECT_NE(log.find("no such file"), std::string::npos) << log;
  EXPECT_EQ(runner(kRun + " --resume " + (kDir / "whole").string() + "/particles.csv --out " +
                       (kDir / "refused").string(),
                   &log),
            1);
  EXPECT_NE(log.find("not an mpm_sdem checkpoint"), std::string::npos) << log;
}
