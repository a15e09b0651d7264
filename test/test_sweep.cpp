// Sweeps (issue 23): the sweep file read strictly (every bad input named with its line), its runs
// expanded as a grid, zipped and with groups, each output read from a run's CSVs as specified,
// the ensemble statistics of summary.csv against hand-computed values, and the local backend for
// real through GNU parallel: four runs, resumed without running a finished one again. Checked:
// it fails with the deviation taken over n (2 failures) or a run never counted done.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "backends.hpp"
#include "results.hpp"
#include "sweep_file.hpp"

namespace fs = std::filesystem;
using namespace mpm_sdem::sweep;
using SweepRun = mpm_sdem::sweep::Run;  // not gtest's Test::Run

namespace {

const std::string kScene = std::string(MPM_SDEM_SOURCE_DIR) + "/config/scenes/debris_impact.yaml";

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("mpm_sdem_test_sweep_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string write(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

std::string sweepText(const std::string& body) {
  return "name: t\nscene: " + kScene + "\n" + body;
}

const char* kOutputs =
    "outputs:\n"
    "  left:\n"
    "    measure: block_left_face\n"
    "    block: block2\n"
    "    reference: 0.346\n";

// The message of the SweepError that loading text throws ("" if it loads).
std::string refusal(const std::string& text) {
  const fs::path d = tempDir("refusal");
  try {
    loadSweep(write(d / "s.yaml", text));
  } catch (const SweepError& e) {
    return e.what();
  }
  return "";
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(SweepFile, GridZipAndGroupsExpandInOrder) {
  const fs::path d = tempDir("expand");
  const SweepDef s = loadSweep(
      write(d / "s.yaml", sweepText("set:\n  time.end: 0.01\n"
                                    "parameters:\n"
                                    "  grid.cell_size: [0.01, 0.005]\n"
                                    "  sand:\n"
                                    "    materials.sand.density: [1300, 1400, 1500]\n"
                                    "    materials.sand.youngs_modulus: [5.0e4, 6.0e4, 7.0e4]\n"
                                    "ensemble: {members: 2, perturbation: 1.0e-6, seed: 7}\n") +
                              kOutputs));
  const std::vector<SweepRun> runs = expandRuns(s);
  ASSERT_EQ(runs.size(), 2u * 3u * 2u);
  EXPECT_EQ(parameterKeys(s), (std::vector<std::string>{"grid.cell_size", "materials.sand.density",
                                                        "materials.sand.youngs_modulus"}));
  // The last parameter varies fastest, then the member; a group's values go together.
  EXPECT_EQ(runs[0].id, "s000_m00");
  EXPECT_EQ(runs[1].id, "s000_m01");
  EXPECT_EQ(runs[1].seed, 8u);
  EXPECT_EQ(runs[2].values, (std::vector<std::string>{"0.01", "1400", "6.0e4"}));
  EXPECT_EQ(runs[11].id, "s005_m01");
  EXPECT_EQ(runs[11].overrides, (std::vector<std::string>{"time.end=0.01", "grid.cell_size=0.005",
                                                          "materials.sand.density=1500",
                                                          "materials.sand.youngs_modulus=7.0e4"}));
  EXPECT_EQ(runs[11].perturbation, 1e-6);

  const SweepDef z = loadSweep(write(d / "z.yaml", sweepText("parameters:\n"
                                                             "  grid.cell_size: [0.01, 0.005]\n"
                                                             "  time.end: [0.02, 0.03]\n"
                                                             "combine: zip\n"
                                                             "ensemble:\n"
                                                             "  members: 3\n"
                                                             "  perturbation_cells: 1.0e-4\n") +
                                                       kOutputs));
  const std::vector<SweepRun> zr = expandRuns(z);
  ASSERT_EQ(zr.size(), 2u * 3u);
  EXPECT_EQ(zr[3].values, (std::vector<std::string>{"0.005", "0.03"}));
  // In cells of each setting's grid.
  EXPECT_DOUBLE_EQ(zr[0].perturbation, 1e-4 * 0.01);
  EXPECT_DOUBLE_EQ(zr[3].perturbation, 1e-4 * 0.005);
  EXPECT_EQ(zr[2].seed, 3u);  // seed 1 by default, member 2
}

TEST(SweepFile, BadInputIsNamedWithItsLine) {
  struct Case {
    std::string body, expected;
  };
  const Case cases[] = {
      {"paramters:\n  time.end: [0.1]\n",
       "s.yaml:3:1: paramters: unknown key; did you mean "
       "'parameters'?"},
      {"parameters:\n  time.end: 0.1\n", "s.yaml:4:13: parameters.time.end: expected a list"},
      {"parameters:\n  time.end: [0.1, 0.2]\n  grid.cell_size: [0.01]\ncombine: zip\n",
       "zip takes the k-th value of each parameter: 'grid.cell_size' has 1 values"},
      {"parameters:\n  g:\n    time.end: [0.1, 0.2]\n    grid.cell_size: [0.01]\n",
       "s.yaml:6:21: parameters.g.grid.cell_size: a group's keys take their k-th values together"},
      {"parameters:\n  grid.cell_size: [0.01, -1]\n", "setting 1 (run s001_m00): "},
      {"ensemble: {members: 2}\n", "ensemble.perturbation: members of an ensemble differ only"},
      {"ensemble: {members: 0, perturbation: 1.0e-6}\n", "ensemble.members: 1 to 10000"},
      {"combine: cross\n", "combine: 'cross' is not valid; use one of: grid | zip"},

  };
  for (const Case& c : cases) {
    const std::string got = refusal(sweepText(c.body) + kOutputs);
    EXPECT_NE(got.find(c.expected), std::string::npos) << c.body << "\ngot: " << got;
  }
  struct OutputCase {
    std::string output, expected;
  };
  const OutputCase outputs[] = {
      {"    file: blocks.csv\n    column: x\n", "blocks.csv has a row per block: give block"},
      {"    file: particles.csv\n    column: x\n",
       "particles.csv has a row per point: give reduce"},
      {"    file: timeseries.csv\n    column: kinetic_energy\n    reduce: max\n",
       "reduce applies to particles.csv only"},
      {"    measure: block_left_face\n", "'block_left_face' needs block"},
      {"    measure: speed\n", "'speed' is not a measurement; use one of: block_left_face"},
      {"    file: summary.csv\n    column: steps\n    at: 0.5\n",
       "only timeseries.csv and blocks.csv have rows in time"},
      {"    file: summary.csv\n    column: steps\n    reference: 0\n", "must not be 0"},
      {"    file: timeseries.csv\n    column: com_x\n    rate_between: [2, 1]\n",
       "low must be below high"},
      {"    file: blocks.csv\n    column: x\n    block: a\n    rate_between: [1, 2]\n",
       "a slope over timeseries.csv rows"},
  };
  for (const OutputCase& c : outputs) {
    const std::string got = refusal(sweepText("outputs:\n  o:\n" + c.output));
    EXPECT_NE(got.find(c.expected), std::string::npos) << c.output << "\ngot: " << got;
  }
  EXPECT_NE(refusal(sweepText("parameters:\n  time.end: [0.1, 0.2, 0.3]\noutputs:\n  o:\n"
                              "    file: summary.csv\n    column: steps\n    reference: [1, 2]\n"))
                .find("outputs.o.reference: 2 values for 3 settings; give one, or one per setting"),
            std::string::npos);
  EXPECT_NE(refusal("name: t\nscene: nowhere.yaml\noutputs: {}\n").find("no such scene file"),
            std::string::npos);
  EXPECT_NE(refusal(sweepText("outputs: {}\n")).find("outputs: expected a map of named outputs"),
            std::string::npos);
}

// Outputs read from hand-written files of the runner's formats.
TEST(SweepResults, OutputsReadTheirRowAndColumn) {
  const fs::path d = tempDir("outputs");
  write(d / "timeseries.csv", "time,step,kinetic_energy\n0,0,1\n0.1,10,2\n0.2,20,4\n0.3,30,8\n");
  write(d / "blocks.csv",
        "time,block,name,x,min_x\n0,0,a,1,0.5\n0,1,b,2,1.5\n0.3,0,a,3,2.5\n0.3,1,b,4,3.5\n");
  write(d / "particles.csv", "id,x\n0,1\n1,4\n2,-2\n");
  write(d / "summary.csv", "status,time,steps,points,wall_s\n0,0.3,30,3,1.5\n");
  auto out = [](const char* file, const char* column) {
    Output o;
    o.file = file;
    o.column = column;
    return o;
  };
  Output o = out("timeseries.csv", "kinetic_energy");
  EXPECT_EQ(measureOutput(d.string(), o), 8);  // the last row
  o.at = 0.15;
  EXPECT_EQ(measureOutput(d.string(), o), 4);  // the first row at or after 0.15 s
  o.at = 0.1;
  EXPECT_EQ(measureOutput(d.string(), o), 2);  // a row exactly at the time
  o = out("blocks.csv", "min_x");
  o.block = "b";
  EXPECT_EQ(measureOutput(d.string(), o), 3.5);
  o.at = 0;
  EXPECT_EQ(measureOutput(d.string(), o), 1.5);
  o = out("particles.csv", "x");
  for (auto [reduce, value] : {std::pair{"max", 4.0}, {"min", -2.0}, {"mean", 1.0}, {"sum", 3.0}}) {
    o.reduce = reduce;
    EXPECT_EQ(measureOutput(d.string(), o), value) << reduce;
  }
  EXPECT_EQ(measureOutput(d.string(), out("summary.csv", "wall_s")), 1.5);
  EXPECT_TRUE(runDone(d.string()));
  try {
    measureOutput(d.string(), out("summary.csv", "speed"));
    ADD_FAILURE() << "a missing column was read";
  } catch (const SweepError& e) {
    EXPECT_NE(std::string(e.what()).find("no column 'speed'; its columns: status, time, steps"),
              std::string::npos)
        << e.what();
  }
  o = out("blocks.csv", "min_x");
  o.block = "c";
  EXPECT_THROW(measureOutput(d.string(), o), SweepError);
}

// A rate: the least-squares slope over the rows whose value lies in the band, here a line of
// slope 10 kg/(s m) through the band with rows outside it that would bend a fit of all rows.
TEST(SweepResults, RateIsTheSlopeInsideTheBand) {
  const fs::path d = tempDir("rate");
  std::string rows = "time,outlet_mass\n";
  for (int k = 0; k <= 20; ++k) {
    const double t = 0.1 * k;
    const double m = t < 0.5 ? 0 : t > 1.5 ? 10 + 2 * (t - 1.5) : 10 * (t - 0.5);
    rows += std::to_string(t) + "," + std::to_string(m) + "\n";
  }
  write(d / "timeseries.csv", rows);
  Output o;
  o.file = "timeseries.csv";
  o.column = "outlet_mass";
  o.rate_between = std::make_pair(1.0, 9.0);
  EXPECT_NEAR(measureOutput(d.string(), o), 10, 1e-9);
  o.rate_between = std::make_pair(1.0, 3.5);  // three rows: 1, 2, 3
  try {
    measureOutput(d.string(), o);
    ADD_FAILURE() << "a rate from three rows";
  } catch (const SweepError& e) {
    EXPECT_NE(std::string(e.what()).find("3 rows with outlet_mass in [1, 3.5]; a rate needs 5"),
              std::string::npos)
        << e.what();
  }
}

// summary.csv's statistics over members written by hand: two settings of three members, one
// member of the second missing.
TEST(SweepResults, SummaryHoldsEachSettingsStatistics) {
  const fs::path d = tempDir("gather");
  const SweepDef s = loadSweep(
      write(d / "s.yaml", sweepText("parameters:\n  time.end: [0.1, 0.2]\n"
                                    "ensemble: {members: 3, perturbation: 1.0e-6}\n"
                                    "outputs:\n"
                                    "  ke:\n    file: timeseries.csv\n    column: kinetic_energy\n"
                                    "    reference: 2\n")));
  const double ke[2][3] = {{1, 2, 6}, {4, 4, 0}};
  for (const SweepRun& r : expandRuns(s)) {
    if (r.setting == 1 && r.member == 2) continue;  // never ran
    const fs::path run = runDir(d.string(), r);
    fs::create_directories(run);
    write(run / "timeseries.csv",
          "time,kinetic_energy\n0.1," + std::to_string(ke[r.setting][r.member]) + "\n");
    write(run / "summary.csv",
          "status,time,steps,points,wall_s\n0,0.1,100,10," + std::to_string(r.member + 1) + "\n");
  }
  const Gathered g = gather(s, d.string());
  EXPECT_EQ(g.runs, 6);
  EXPECT_EQ(g.done, 5);
  ASSERT_EQ(g.problems.size(), 1u);
  EXPECT_NE(g.problems[0].find("s001_m02: not done"), std::string::npos);
  std::stringstream summary(read(d / "summary.csv"));
  std::string header, row0, row1;
  std::getline(summary, header);
  std::getline(summary, row0);
  std::getline(summary, row1);
  EXPECT_EQ(header,
            "setting,time.end,runs,steps_mean,wall_s_mean,ke_mean,ke_std,ke_min,ke_max,"
            "ke_reference,ke_error");
  // Setting 0: 1, 2, 6: mean 3, sample deviation sqrt(7) = 2.645751311, error |3 - 2| / 2.
  EXPECT_EQ(row0, "0,0.1,3,100,2,3,2.645751311,1,6,2,0.5");
  // Setting 1: 4, 4 (the third missing): mean 4, deviation 0, error 1.
  EXPECT_EQ(row1, "1,0.2,2,100,1.5,4,0,4,4,2,1");
  EXPECT_NE(read(d / "results.csv").find("s000_m02,0,2,3,0.1,100,3,6,2\n"), std::string::npos)
      << read(d / "results.csv");
}

// The local backend for real: GNU parallel runs four short runs of the default scene (two cell
// sizes, two members each); the same command again runs nothing; a run whose summary is gone
// runs again and gives the same numbers (the runs are deterministic).
TEST(SweepLocal, RunsGathersAndResumes) {
  const fs::path d = tempDir("local");
  const std::string file = write(
      d / "s.yaml", sweepText("set:\n  time.end: 0.02\n  output.particles: true\n"
                              "  output.gauges: {ahead: {right_of: 0.05}}\n"
                              "parameters:\n  grid.cell_size: [0.01, 0.005]\n"
                              "ensemble: {members: 2, perturbation_cells: 1.0e-3}\n"
                              "outputs:\n"
                              "  front:\n    measure: flow_front\n"
                              "  left:\n    measure: block_left_face\n    block: block2\n"
                              "  ke:\n    file: timeseries.csv\n    column: kinetic_energy\n"
                              "    at: 0.01\n"
                              "  ahead:\n    file: timeseries.csv\n    column: ahead_mass\n"));
  const std::string sweep = std::string(MPM_SDEM_SWEEP) + " " + file + " --jobs 2 --out " +
                            (d / "out").string() + " 2>" + (d / "err.txt").string();
  ASSERT_EQ(std::system(sweep.c_str()), 0) << read(d / "err.txt");
  EXPECT_NE(read(d / "err.txt").find("4 runs, 0 already done, 4 to run"), std::string::npos);
  EXPECT_NE(read(d / "err.txt").find("4 of 4 runs done"), std::string::npos) << read(d / "err.txt");
  // Results without the wall times, which differ from run to run.
  auto results = [&] {
    std::stringstream in(read(d / "out" / "results.csv"));
    std::string out, line;
    while (std::getline(in, line)) {
      std::stringstream cells(line);
      std::string c;
      for (int k = 0; std::getline(cells, c, ','); ++k)
        if (k != 6) out += c + ",";  // run,setting,member,seed,grid.cell_size,steps,wall_s
      out += "\n";
    }
    return out;
  };
  const std::string first = results();
  EXPECT_EQ(std::count(first.begin(), first.end(), '\n'), 5) << first;
  // The members differ (the perturbation acts), the settings too.
  std::stringstream rows(first);
  std::string header, r0, r1;
  std::getline(rows, header);
  std::getline(rows, r0);
  std::getline(rows, r1);
  EXPECT_NE(r0.substr(r0.find(",0.01,")), r1.substr(r1.find(",0.01,"))) << first;
  // The gauge's last row is the mass of the final points right of x = 5 cm.
  {
    std::stringstream points(read(d / "out" / "runs" / "s000_m00" / "particles.csv"));
    std::string line;
    std::getline(points, line);  // id,body,material,kind,x,y,vx,vy,mass,...
    double ahead = 0;
    int counted = 0;
    while (std::getline(points, line)) {
      std::vector<std::string> c;
      std::stringstream cells(line);
      for (std::string v; std::getline(cells, v, ',');) c.push_back(v);
      if (std::stod(c[4]) > 0.05) ahead += std::stod(c[8]), ++counted;
    }
    EXPECT_GT(counted, 100);
    std::stringstream res(read(d / "out" / "results.csv"));
    std::string header, row;
    std::getline(res, header);
    std::getline(res, row);
    EXPECT_EQ(header.substr(header.rfind(',') + 1), "ahead");
    EXPECT_NEAR(std::stod(row.substr(row.rfind(',') + 1)), ahead, 1e-9 * ahead) << row;
  }
  ASSERT_EQ(std::system(sweep.c_str()), 0);
  EXPECT_NE(read(d / "err.txt").find("4 runs, 4 already done, 0 to run"), std::string::npos);
  fs::remove(d / "out" / "runs" / "s001_m01" / "summary.csv");
  ASSERT_EQ(std::system(sweep.c_str()), 0);
  EXPECT_NE(read(d / "err.txt").find("4 runs, 3 already done, 1 to run"), std::string::npos);
  EXPECT_EQ(results(), first);
}

namespace {

// A CSV line's fields (quotes around a field that holds commas).
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

// A CSV text without one column (a wall time, which differs per run).
std::string withoutColumn(const std::string& text, std::size_t column) {
  std::stringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> f = fields(line);
    for (std::size_t k = 0; k < f.size(); ++k)
      if (k != column) out += f[k] + "|";
    out += "\n";
  }
  return out;
}

// results.csv of the validation report without its wall_s column (8th).
std::string withoutWallTimes(const std::string& text) {
  return withoutColumn(text, 7);
}

}  // namespace

// A validation sweep (the report's cases, scripts/validate): one run per case, in order, each
// mpm_sdem_validate with that case; a sweep file that mixes in a scene's keys or names a case
// badly is refused at its line.
TEST(SweepFile, ValidationSweepRunsOneCaseEach) {
  const fs::path d = tempDir("validation_file");
  const SweepDef s = loadSweep(
      write(d / "v.yaml", "name: v\nvalidation:\n  fast: true\n  cases: [bar, drop, wheel.1]\n"));
  ASSERT_TRUE(s.validation.has_value());
  const std::vector<SweepRun> runs = expandRuns(s);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].id, "bar");
  EXPECT_EQ(runs[1].validation_case, "drop");
  EXPECT_EQ(runs[2].id, "wheel.1");  // one run of a case split into runs
  Launch launch;
  launch.out_dir = "/o";
  launch.runner = "/b/mpm_sdem_run";
  const std::string c = runCommand(s, runs[1], launch);
  EXPECT_NE(c.find("'/b/mpm_sdem_validate' --cases 'drop' --fast --out '/o/runs/drop'"),
            std::string::npos)
      << c;
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {"name: v\nscene: x.yaml\nvalidation:\n  cases: [bar]\n",
       "s.yaml:2:8: scene: a validation sweep runs mpm_sdem_validate's cases; remove scene"},
      {"name: v\nvalidation:\n  cases: []\n", "validation.cases: expected a list of case names"},
      {"name: v\nvalidation:\n  cases: [Bar]\n", "'Bar' is not a case name"},
      {"name: v\nvalidation:\n  cases: [bar, bar]\n", "'bar' is listed twice"},
      {"name: v\nvalidation:\n  cases: [wheel.]\n", "'wheel.' is not a case name"},
      {"name: v\nvalidation:\n  cases: [wheel.x]\n", "or one of its runs (name.N)"},
      {"name: v\nvalidation:\n  cases: [.3]\n", "'.3' is not a case name"},
      {"name: v\nvalidation:\n  fast: maybe\n  cases: [bar]\n", "validation.fast"},
  };
  for (const Case& k : cases) {
    const std::string got = refusal(k.text);
    EXPECT_NE(got.find(k.expected), std::string::npos) << k.text << "\ngot: " << got;
  }
}

// Two fast cases through GNU parallel: the gathered data/results.csv holds what one
// mpm_sdem_validate run of both cases writes (but the wall times; the sweep's order is its
// list's, here that of mpm_sdem_validate --list as scripts/validate writes it), and a second
// call runs neither again; a case whose run did not finish is run again.
TEST(SweepLocal, ValidationCasesGatherAsOneRunAndResume) {
  const fs::path d = tempDir("validation_local");
  const std::string file =
      write(d / "v.yaml", "name: v\nvalidation:\n  fast: true\n  cases: [drop, bar]\n");
  const std::string sweep = std::string(MPM_SDEM_SWEEP) + " " + file + " --jobs 2 --out " +
                            (d / "out").string() + " 2>" + (d / "err.txt").string();
  ASSERT_EQ(std::system(sweep.c_str()), 0) << read(d / "err.txt");
  EXPECT_NE(read(d / "err.txt").find("2 of 2 runs done"), std::string::npos) << read(d / "err.txt");
  const fs::path validate = fs::path(MPM_SDEM_SWEEP).parent_path() / "mpm_sdem_validate";
  const std::string whole = validate.string() + " --fast --cases drop,bar --out " +
                            (d / "whole").string() + " > /dev/null";
  ASSERT_EQ(std::system(whole.c_str()), 0);
  const std::string gathered = withoutWallTimes(read(d / "out" / "data" / "results.csv"));
  EXPECT_EQ(gathered, withoutWallTimes(read(d / "whole" / "results.csv")));
  EXPECT_GT(std::count(gathered.begin(), gathered.end(), '\n'), 5);
  // Each case's series files beside it, as one run writes them.
  for (const auto& e : fs::directory_iterator(d / "whole")) {
    if (e.path().filename() != "summary.csv") {
      EXPECT_TRUE(fs::exists(d / "out" / "data" / e.path().filename())) << e.path();
    }
  }
  ASSERT_EQ(std::system(sweep.c_str()), 0);
  EXPECT_NE(read(d / "err.txt").find("2 runs, 2 already done, 0 to run"), std::string::npos);
  fs::remove(d / "out" / "runs" / "drop" / "summary.csv");
  ASSERT_EQ(std::system(sweep.c_str()), 0);
  EXPECT_NE(read(d / "err.txt").find("2 runs, 1 already done, 1 to run"), std::string::npos);
  EXPECT_EQ(withoutWallTimes(read(d / "out" / "data" / "results.csv")), gathered);
}

// A case split into runs (mpm_sdem_validate --list --runs: one per resolution or member) as
// separate runs of the sweep: its runs' tables joined under one header, and the ensembles' means
// and spreads (debris_granular's combine step, run at the gather) equal to one run of the whole
// cases but for the wall times; a run the case does not have is refused with the ones it has.
TEST(SweepLocal, SplitCaseRunsGatherAndCombineAsOneRun) {
  const fs::path d = tempDir("validation_split");
  const fs::path validate = fs::path(MPM_SDEM_SWEEP).parent_path() / "mpm_sdem_validate";
  const std::string list = validate.string() + " --fast --cases debris_granular,wheel,bar " +
                           "--list --runs > " + (d / "runs.txt").string();
  ASSERT_EQ(std::system(list.c_str()), 0);
  EXPECT_EQ(read(d / "runs.txt"), "debris_granular.0\ndebris_granular.1\nwheel.0\nwheel.1\nbar\n");
  const std::string file =
      write(d / "v.yaml",
            "name: v\nvalidation:\n  fast: true\n  cases: [debris_granular.0, debris_granular.1, "
            "wheel.0, wheel.1]\n");
  const std::string sweep = std::string(MPM_SDEM_SWEEP) + " " + file + " --jobs 2 --out " +
                            (d / "out").string() + " 2>" + (d / "err.txt").string();
  ASSERT_EQ(std::system(sweep.c_str()), 0) << read(d / "err.txt");
  const std::string whole = validate.string() + " --fast --cases debris_granular,wheel --out " +
                            (d / "whole").string() + " > /dev/null";
  ASSERT_EQ(std::system(whole.c_str()), 0);
  const std::string gathered = withoutWallTimes(read(d / "out" / "data" / "results.csv"));
  EXPECT_EQ(gathered, withoutWallTimes(read(d / "whole" / "results.csv")));
  EXPECT_EQ(std::count(gathered.begin(), gathered.end(), '\n'), 1 + 16 + 6);
  EXPECT_EQ(read(d / "out" / "data" / "wheel_sweep.csv"), read(d / "whole" / "wheel_sweep.csv"));
  // debris_granular.csv: one header, both members (its wall_s, 6th, differs per run).
  const std::string table = withoutColumn(read(d / "out" / "data" / "debris_granular.csv"), 5);
  EXPECT_EQ(table, withoutColumn(read(d / "whole" / "debris_granular.csv"), 5));
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 3);
  const std::string refused = validate.string() + " --fast --cases wheel.2 --out " +
                              (d / "no").string() + " 2> " + (d / "refused.txt").string();
  EXPECT_NE(std::system(refused.c_str()), 0);
  EXPECT_NE(read(d / "refused.txt").find("wheel has runs wheel.0 to wheel.1 with --fast"),
            std::string::npos)
      << read(d / "refused.txt");
}
