// mpm_sdem_sweep: runs a sweep file's runs on this machine (GNU parallel) or on Slurm, and gathers
// what they measured. See usage().
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "backends.hpp"
#include "results.hpp"
#include "sweep_file.hpp"

namespace fs = std::filesystem;
using namespace mpm_sdem::sweep;

namespace {

const char* usage() {
  return "usage: mpm_sdem_sweep SWEEP.yaml [--backend local|slurm] [--jobs N] [--out DIR]\n"
         "                      [--threads-per-run T] [--gather] [--dry-run]\n"
         "                      [--partition P] [--time-limit T] [--no-submit]\n"
         "  --backend local  run here through GNU parallel (default), then gather\n"
         "  --backend slurm  submit a job array (one task per run) and a gather job after it\n"
         "  --jobs N         runs at once (local default: one per core; slurm: array limit %N)\n"
         "  --out DIR        the sweep's folder: runs/<id>/ per run, results.csv, summary.csv,\n"
         "                   plots (default: out/sweeps/<sweep name>)\n"
         "  --threads-per-run T  OpenMP threads of each run (default 1; slurm: cpus-per-task)\n"
         "  --gather         only collect what the finished runs measured (and plot it)\n"
         "  --dry-run        write commands.txt and pending.txt, run nothing\n"
         "  --partition P, --time-limit T  slurm: sbatch's --partition and --time\n"
         "  --no-submit      slurm: write the scripts in DIR/slurm, do not submit them\n"
         "Runs already done (their summary.csv says status 0) are skipped: run the same command\n"
         "again to finish an interrupted sweep.\n"
         "exit status: 0 every run done, 1 bad sweep file, 2 bad command line, 3 runs failed or\n"
         "missing, 4 the backend could not start\n";
}

std::string executable() {
  return fs::read_symlink("/proc/self/exe").string();
}

// The plots (scripts/sweep_plots.py, matplotlib): installed beside this program, or in the
// source tree of a devel build. The CSVs are the result, so a missing matplotlib is a warning.
void plot(const std::string& out_dir) {
  fs::path script = fs::path(executable()).parent_path() / "sweep_plots.py";
  if (!fs::exists(script)) script = fs::path(MPM_SDEM_SOURCE_DIR) / "scripts" / "sweep_plots.py";
  const std::string command = "/usr/bin/python3 '" + script.string() + "' '" + out_dir + "'";
  if (std::system(command.c_str()) != 0)
    std::cerr << "warning: no plots (" << command
              << " failed; it needs python3-matplotlib); the CSVs are complete\n";
}

// A validation sweep's split cases fit across their runs once all are gathered: their combine
// step (mpm_sdem_validate --combine, beside this program) appends those rows to data/.
bool combineValidation(const SweepDef& sweep, const std::string& out_dir) {
  // The cases the sweep ran as separate runs (name.N), each once; a case run whole has combined
  // its own.
  std::string cases;
  for (const std::string& run : sweep.validation->cases) {
    const std::size_t dot = run.find('.');
    if (dot == std::string::npos) continue;
    const std::string name = run.substr(0, dot);
    if (("," + cases + ",").find("," + name + ",") == std::string::npos)
      cases += (cases.empty() ? "" : ",") + name;
  }
  if (cases.empty()) return true;
  const std::string validate =
      (fs::path(executable()).parent_path() / "mpm_sdem_validate").string();
  const std::string log = out_dir + "/combine.log";
  const std::string command = "'" + validate + "'" + (sweep.validation->fast ? " --fast" : "") +
                              " --combine --cases " + cases + " --out '" + out_dir + "/data' > '" +
                              log + "' 2>&1";
  if (std::system(command.c_str()) == 0) return true;
  std::cerr << "the split cases' combine step failed: " << log << "\n";
  return false;
}

int gatherAndReport(const SweepDef& sweep, const std::string& out_dir) {
  const Gathered g = gather(sweep, out_dir);
  bool combined = true;
  if (sweep.validation) {  // the report is scripts/validate's (report.py)
    combined = g.done < g.runs || combineValidation(sweep, out_dir);  // only all runs combine
    std::cerr << g.done << " of " << g.runs << " runs done; their data in " << out_dir << "/data\n";
  } else {
    plot(out_dir);
    std::cerr << g.done << " of " << g.runs << " runs done; " << out_dir << "/results.csv, "
              << out_dir << "/summary.csv\n";
  }
  for (std::size_t k = 0; k < g.problems.size() && k < 20; ++k)
    std::cerr << "  " << g.problems[k] << "\n";
  if (g.problems.size() > 20) std::cerr << "  ... and " << g.problems.size() - 20 << " more\n";
  return g.done == g.runs && combined ? 0 : 3;
}

bool positive(const char* text, int& out) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (*text == '\0' || *end != '\0' || v < 1 || v > 100000) return false;
  out = static_cast<int>(v);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::string file, backend = "local", out;
  bool only_gather = false, dry_run = false;
  Launch launch;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::cerr << "mpm_sdem_sweep: " << a << " needs a value\n" << usage();
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      std::cout << usage();
      return 0;
    } else if (a == "--backend") {
      backend = value();
      if (backend != "local" && backend != "slurm") {
        std::cerr << "mpm_sdem_sweep: --backend takes local or slurm, got '" << backend << "'\n";
        return 2;
      }
    } else if (a == "--jobs" || a == "--threads-per-run") {
      const char* v = value();
      if (!positive(v, a == "--jobs" ? launch.jobs : launch.threads_per_run)) {
        std::cerr << "mpm_sdem_sweep: " << a << " takes a whole number >= 1, got '" << v << "'\n";
        return 2;
      }
    } else if (a == "--out") {
      out = value();
    } else if (a == "--partition") {
      launch.partition = value();
    } else if (a == "--time-limit") {
      launch.time_limit = value();
    } else if (a == "--no-submit") {
      launch.submit = false;
    } else if (a == "--gather") {
      only_gather = true;
    } else if (a == "--dry-run") {
      dry_run = true;
    } else if (!a.empty() && a[0] == '-') {
      std::cerr << "mpm_sdem_sweep: unknown option '" << a << "'\n" << usage();
      return 2;
    } else if (file.empty()) {
      file = a;
    } else {
      std::cerr << "mpm_sdem_sweep: more than one sweep file ('" << file << "', '" << a << "')\n";
      return 2;
    }
  }
  if (file.empty()) {
    std::cerr << "mpm_sdem_sweep: no sweep file given\n" << usage();
    return 2;
  }
  SweepDef sweep;
  try {
    sweep = loadSweep(file);
  } catch (const SweepError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  sweep.source = fs::absolute(file).lexically_normal().string();
  launch.out_dir =
      fs::absolute(out.empty() ? fs::path("out") / "sweeps" / sweep.name : fs::path(out))
          .lexically_normal()
          .string();
  if (only_gather) return gatherAndReport(sweep, launch.out_dir);

  launch.self = executable();
  launch.runner = (fs::path(launch.self).parent_path() / "mpm_sdem_run").string();
  std::vector<Run> pending;
  try {
    pending = prepare(sweep, launch);
  } catch (const SweepError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  const std::size_t total = expandRuns(sweep).size();
  std::cerr << "sweep " << sweep.name << ": " << total << " runs, " << total - pending.size()
            << " already done, " << pending.size() << " to run (" << backend << "); folder "
            << launch.out_dir << "\n";
  if (dry_run) return 0;
  if (backend == "slurm") {
    if (pending.empty()) return gatherAndReport(sweep, launch.out_dir);
    return submitSlurm(sweep, pending, launch) == 0 ? 0 : 4;
  }
  const int failed = runLocal(pending, launch);
  if (failed < 0) {
    std::cerr << "error: cannot run GNU parallel (Debian package 'parallel'); the commands are "
                 "in "
              << launch.out_dir << "/pending.txt\n";
    return 4;
  }
  return gatherAndReport(sweep, launch.out_dir);
}
