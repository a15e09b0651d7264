#include "backends.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "results.hpp"

namespace mpm_sdem::sweep {

namespace fs = std::filesystem;

namespace {

// One word for sh: single-quoted, a quote inside closed, escaped and reopened.
std::string shellWord(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

void writeLines(const fs::path& path, const std::vector<std::string>& lines) {
  std::ofstream out(path);
  for (const std::string& l : lines) out << l << '\n';
  if (!out) throw SweepError("cannot write " + path.string());
}

// stdout of a shell command, and its exit status.
std::string capture(const std::string& command, int& status) {
  std::string text;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) {
    status = -1;
    return text;
  }
  char buffer[256];
  while (fgets(buffer, sizeof buffer, pipe)) text += buffer;
  status = pclose(pipe);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

}  // namespace

std::string runCommand(const SweepDef& sweep, const Run& run, const Launch& launch) {
  const std::string dir = runDir(launch.out_dir, run);
  if (sweep.validation) {
    // mpm_sdem_validate beside the runner, one case; its threads as a run's.
    const std::string validate =
        (fs::path(launch.runner).parent_path() / "mpm_sdem_validate").string();
    return "OMP_NUM_THREADS=" + std::to_string(launch.threads_per_run) + " " + shellWord(validate) +
           " --cases " + shellWord(run.validation_case) +
           (sweep.validation->fast ? " --fast" : "") + " --out " + shellWord(dir) + " > " +
           shellWord(dir + "/log.txt") + " 2>&1";
  }
  std::string c = shellWord(launch.runner) + " " + shellWord(sweep.scene);
  for (const std::string& o : run.overrides) c += " --set " + shellWord(o);
  if (run.perturbation > 0) {
    char p[64];
    std::snprintf(p, sizeof p, " --perturb %.17g --seed %u", run.perturbation, run.seed);
    c += p;
  }
  c += " --threads " + std::to_string(launch.threads_per_run) + " --quiet --out " + shellWord(dir) +
       " > " + shellWord(dir + "/log.txt") + " 2>&1";
  return c;
}

std::vector<Run> prepare(const SweepDef& sweep, const Launch& launch) {
  std::vector<std::string> all, pending_lines;
  std::vector<Run> pending;
  for (const Run& r : expandRuns(sweep)) {
    const std::string dir = runDir(launch.out_dir, r);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw SweepError("cannot create " + dir + ": " + ec.message());
    const std::string c = runCommand(sweep, r, launch);
    all.push_back(c);
    if (runDone(dir)) continue;
    pending.push_back(r);
    pending_lines.push_back(c);
  }
  writeLines(fs::path(launch.out_dir) / "commands.txt", all);
  writeLines(fs::path(launch.out_dir) / "pending.txt", pending_lines);
  return pending;
}

int runLocal(const std::vector<Run>& pending, const Launch& launch) {
  if (pending.empty()) return 0;
  const std::string list = (fs::path(launch.out_dir) / "pending.txt").string();
  const std::string log = (fs::path(launch.out_dir) / "joblog.txt").string();
  std::vector<std::string> args = {"parallel", "--joblog", log, "--halt", "never"};
  if (launch.jobs > 0) args.insert(args.end(), {"--jobs", std::to_string(launch.jobs)});
  if (isatty(STDERR_FILENO)) args.push_back("--bar");
  args.insert(args.end(), {"::::", list});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child < 0) return -1;
  if (child == 0) {
    execvp("parallel", argv.data());
    _exit(127);
  }
  int status = 0;
  if (waitpid(child, &status, 0) < 0) return -1;
  if (!WIFEXITED(status)) return -1;
  return WEXITSTATUS(status) == 127 ? -1 : WEXITSTATUS(status);
}

int submitSlurm(const SweepDef& sweep, const std::vector<Run>& pending, const Launch& launch) {
  const fs::path dir = fs::path(launch.out_dir) / "slurm";
  fs::create_directories(dir);
  // The array's own copy of the pending commands: a later call rewrites pending.txt while this
  // array may still be running.
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  const std::string list = (dir / ("tasks_" + std::string(stamp) + ".txt")).string();
  fs::copy_file(fs::path(launch.out_dir) / "pending.txt", list,
                fs::copy_options::overwrite_existing);
  const std::string job = "mpm_sdem_" + sweep.name;
  auto header = [&](std::ofstream& f, const std::string& name) {
    f << "#!/bin/bash\n#SBATCH --job-name=" << name << "\n";
    if (!launch.partition.empty()) f << "#SBATCH --partition=" << launch.partition << "\n";
  };
  {
    std::ofstream f(dir / "array.sh");
    header(f, job);
    f << "#SBATCH --array=1-" << pending.size()
      << (launch.jobs > 0 ? "%" + std::to_string(launch.jobs) : "") << "\n"
      << "#SBATCH --cpus-per-task=" << launch.threads_per_run << "\n"
      << "#SBATCH --output=" << (dir / "run_%a.out").string() << "\n";
    if (!launch.time_limit.empty()) f << "#SBATCH --time=" << launch.time_limit << "\n";
    f << "# Task k runs line k of the tasks file (the runs not done when this was written).\n"
      << "set -eu\n"
      << "line=$(sed -n \"${SLURM_ARRAY_TASK_ID}p\" " << shellWord(list) << ")\n"
      << "exec bash -c \"$line\"\n";
  }
  {
    std::ofstream f(dir / "gather.sh");
    header(f, job + "_gather");
    f << "#SBATCH --output=" << (dir / "gather.out").string() << "\n"
      << "exec " << shellWord(launch.self) << " " << shellWord(sweep.source) << " --gather --out "
      << shellWord(launch.out_dir) << "\n";
  }
  if (!launch.submit) {
    std::cerr << "wrote " << (dir / "array.sh").string() << " and " << (dir / "gather.sh").string()
              << "; submit with: jid=$(sbatch --parsable " << (dir / "array.sh").string()
              << ") && sbatch --dependency=afterany:$jid " << (dir / "gather.sh").string() << "\n";
    return 0;
  }
  int status = 0;
  const std::string array_id =
      capture("sbatch --parsable " + shellWord((dir / "array.sh").string()) + " 2>&1", status);
  if (status != 0 || array_id.empty() ||
      array_id.find_first_not_of("0123456789;") != std::string::npos) {
    std::cerr << "error: sbatch refused the array ("
              << (status == -1 ? "cannot run sbatch" : array_id)
              << "). Is this a Slurm login node? The scripts are in " << dir.string() << "\n";
    return 1;
  }
  const std::string id = array_id.substr(0, array_id.find(';'));  // "id;cluster" on federations
  const std::string gather_id = capture("sbatch --parsable --dependency=afterany:" + id + " " +
                                            shellWord((dir / "gather.sh").string()) + " 2>&1",
                                        status);
  if (status != 0) {
    std::cerr << "error: sbatch refused the gather job (" << gather_id << "); the array " << id
              << " runs. Gather later with: " << launch.self << " " << sweep.source
              << " --gather --out " << launch.out_dir << "\n";
    return 1;
  }
  std::ofstream(dir / "jobs.txt") << "array " << id << "\ngather " << gather_id << "\n";
  std::cerr << "submitted " << pending.size() << " runs as array job " << id << ", gather job "
            << gather_id << " after it; watch with: squeue -j " << id << "," << gather_id
            << (sweep.validation ? "\ndata: " + launch.out_dir +
                                       "/data (scripts/validate --gather "
                                       "writes the report)\n"
                                 : "\nresults: " + launch.out_dir + "/results.csv, summary.csv\n");
  return 0;
}

}  // namespace mpm_sdem::sweep
