#include "results.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace mpm_sdem::sweep {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// The runner's CSVs: a header, then plain numbers and names (no quoting).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name, const std::string& path) const {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) {
      std::string valid;
      for (const std::string& h : header) valid += (valid.empty() ? "" : ", ") + h;
      throw SweepError(path + ": no column '" + name + "'; its columns: " + valid);
    }
    return static_cast<int>(it - header.begin());
  }
};

Csv readCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SweepError(path + ": missing (did the run write it? see log.txt beside it)");
  Csv c;
  std::string line;
  if (!std::getline(in, line)) throw SweepError(path + ": empty");
  c.header = splitCsv(line);
  while (std::getline(in, line)) {
    if (!line.empty()) c.rows.push_back(splitCsv(line));
  }
  return c;
}

double number(const std::string& text, const std::string& path, const std::string& column) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0')
    throw SweepError(path + ": column '" + column + "' holds '" + text + "', not a number");
  return v;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

// Sample standard deviation (n - 1); 0 for one member.
double deviation(const std::vector<double>& v) {
  if (v.size() < 2) return 0;
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

std::string cell(double v) {
  if (std::isnan(v)) return "";
  std::ostringstream o;
  o << std::setprecision(10) << v;
  return o.str();
}

// A value for a CSV cell: --set text with commas (a vector) quoted.
std::string quoted(const std::string& v) {
  return v.find_first_of(",\"") == std::string::npos ? v : "\"" + v + "\"";
}

}  // namespace

std::string runDir(const std::string& out_dir, const Run& r) {
  return (fs::path(out_dir) / "runs" / r.id).string();
}

bool runDone(const std::string& run_dir) {
  std::ifstream in(fs::path(run_dir) / "summary.csv");
  std::string header, row;
  return std::getline(in, header) && std::getline(in, row) && row.rfind("0,", 0) == 0;
}

double measureOutput(const std::string& run_dir, const Output& o) {
  const std::string path = (fs::path(run_dir) / o.file).string();
  const Csv csv = readCsv(path);
  const int col = csv.column(o.column, path);
  if (o.file == "particles.csv") {
    std::vector<double> v;
    for (const auto& row : csv.rows) v.push_back(number(row.at(col), path, o.column));
    if (v.empty()) throw SweepError(path + ": no points");
    if (o.reduce == "max") return *std::max_element(v.begin(), v.end());
    if (o.reduce == "min") return *std::min_element(v.begin(), v.end());
    if (o.reduce == "mean") return mean(v);
    return mean(v) * static_cast<double>(v.size());
  }
  const int time_col = o.file == "summary.csv" ? -1 : csv.column("time", path);
  if (o.rate_between) {
    // Least-squares slope of the value against time over the rows in the band.
    double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
    for (const auto& row : csv.rows) {
      const double v = number(row.at(col), path, o.column);
      if (v < o.rate_between->first || v > o.rate_between->second) continue;
      const double t = number(row.at(time_col), path, "time");
      n += 1;
      st += t;
      sv += v;
      stt += t * t;
      stv += t * v;
    }
    if (n < 5)
      throw SweepError(path + ": " + std::to_string(static_cast<int>(n)) + " rows with " +
                       o.column + " in [" + cell(o.rate_between->first) + ", " +
                       cell(o.rate_between->second) +
                       "]; a rate needs 5: run longer (time.end) or sample more often "
                       "(output.interval)");
    return (n * stv - st * sv) / (n * stt - st * st);
  }
  const int name_col = o.block.empty() ? -1 : csv.column("name", path);
  const std::string* found = nullptr;
  for (const auto& row : csv.rows) {
    if (name_col >= 0 && row.at(name_col) != o.block) continue;
    if (o.at >= 0 && time_col >= 0 &&
        number(row.at(time_col), path, "time") < o.at * (1 - 1e-9) - 1e-12)
      continue;
    found = &row.at(col);
    if (o.at >= 0) break;  // the first row at or after the time; else the last
  }
  if (!found)
    throw SweepError(path + ": no row" + (o.block.empty() ? "" : " of block '" + o.block + "'") +
                     (o.at >= 0 ? " at or after " + cell(o.at) + " s" : ""));
  return number(*found, path, o.column);
}

namespace {

// A run's series file onto the gathered one: a copy, or its rows below the same header.
void appendSeries(const fs::path& from, const fs::path& to) {
  std::ifstream in(from);
  std::string header, line;
  const bool exists = fs::exists(to);
  if (!std::getline(in, header)) {  // an empty file stays one
    if (!exists) std::ofstream(to).flush();
    return;
  }
  if (exists) {
    std::ifstream gathered(to);
    std::string first;
    std::getline(gathered, first);
    if (first != header)
      throw SweepError(from.string() + ": its header differs from " + to.string() +
                       "'s, written by another run (two cases writing one file?)");
  }
  std::ofstream out(to, exists ? std::ios::app : std::ios::trunc);
  if (!exists) out << header << '\n';
  while (std::getline(in, line)) out << line << '\n';
  if (!out) throw SweepError("cannot write " + to.string());
}

// A validation sweep's runs into DIR/data: every run's results.csv rows under one header, in the
// cases' order, and their series files beside it (each case writes files of its own names; the
// runs of a split case, name.0, name.1, ..., each write theirs with its rows alone, joined here
// under their one header), as one mpm_sdem_validate run over all the cases would have written
// them, but for a split case's combined rows (mpm_sdem_validate --combine adds them).
Gathered gatherValidation(const SweepDef& sweep, const std::string& out_dir) {
  const std::vector<Run> runs = expandRuns(sweep);
  Gathered g;
  g.runs = static_cast<int>(runs.size());
  const fs::path data = fs::path(out_dir) / "data";
  fs::remove_all(data);
  fs::create_directories(data);
  std::ofstream results(data / "results.csv");
  bool header = false;
  for (const Run& r : runs) {
    const fs::path dir = runDir(out_dir, r);
    if (!runDone(dir.string())) {
      g.problems.push_back(r.id + ": not done (" + (dir / "log.txt").string() + ")");
      continue;
    }
    std::ifstream in(dir / "results.csv");
    std::string line;
    for (bool first = true; std::getline(in, line); first = false) {
      if (first && header) continue;
      results << line << '\n';
      header = true;
    }
    std::vector<fs::path> series;  // in name order: the same on every file system
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (e.is_regular_file() && e.path().extension() == ".csv" && name != "results.csv" &&
          name != "summary.csv")
        series.push_back(e.path());
    }
    std::sort(series.begin(), series.end());
    for (const fs::path& file : series) appendSeries(file, data / file.filename());
    ++g.done;
  }
  if (!results) throw SweepError("cannot write " + (data / "results.csv").string());
  return g;
}

}  // namespace

Gathered gather(const SweepDef& sweep, const std::string& out_dir) {
  if (sweep.validation) return gatherValidation(sweep, out_dir);
  const std::vector<Run> runs = expandRuns(sweep);
  const std::size_t n_out = sweep.outputs.size();
  Gathered g;
  g.runs = static_cast<int>(runs.size());
  // values[setting][output] over the members that finished; cost per setting.
  const int settings = runs.empty() ? 0 : runs.back().setting + 1;
  std::vector<std::vector<std::vector<double>>> values(settings,
                                                       std::vector<std::vector<double>>(n_out));
  std::vector<std::vector<double>> steps(settings), wall(settings);

  std::ofstream res(fs::path(out_dir) / "results.csv");
  res << "run,setting,member,seed";
  for (const std::string& key : parameterKeys(sweep)) res << ',' << key;
  res << ",steps,wall_s";
  for (const Output& o : sweep.outputs) res << ',' << o.name;
  for (const Output& o : sweep.outputs)
    if (o.hasReference()) res << ',' << o.name << "_error";
  res << '\n';
  for (const Run& r : runs) {
    const std::string dir = runDir(out_dir, r);
    if (!runDone(dir)) {
      g.problems.push_back(r.id + ": not done (" + dir + "/log.txt)");
      continue;
    }
    std::vector<double> v(n_out);
    double run_steps = 0, run_wall = 0;
    try {
      Output cost;
      cost.file = "summary.csv";
      cost.column = "steps";
      run_steps = measureOutput(dir, cost);
      cost.column = "wall_s";
      run_wall = measureOutput(dir, cost);
      for (std::size_t k = 0; k < n_out; ++k) v[k] = measureOutput(dir, sweep.outputs[k]);
    } catch (const SweepError& e) {
      g.problems.push_back(r.id + ": " + e.what());
      continue;
    }
    ++g.done;
    res << r.id << ',' << r.setting << ',' << r.member << ',' << r.seed;
    for (const std::string& value : r.values) res << ',' << quoted(value);
    res << ',' << cell(run_steps) << ',' << cell(run_wall);
    for (double x : v) res << ',' << cell(x);
    for (std::size_t k = 0; k < n_out; ++k) {
      const Output& o = sweep.outputs[k];
      if (!o.hasReference()) continue;
      const double ref = o.referenceAt(r.setting);
      res << ',' << cell(std::abs(v[k] - ref) / std::abs(ref));
    }
    res << '\n';
    for (std::size_t k = 0; k < n_out; ++k) values[r.setting][k].push_back(v[k]);
    steps[r.setting].push_back(run_steps);
    wall[r.setting].push_back(run_wall);
  }

  std::ofstream sum(fs::path(out_dir) / "summary.csv");
  sum << "setting";
  for (const std::string& key : parameterKeys(sweep)) sum << ',' << key;
  sum << ",runs,steps_mean,wall_s_mean";
  for (const Output& o : sweep.outputs) {
    sum << ',' << o.name << "_mean," << o.name << "_std," << o.name << "_min," << o.name << "_max";
    if (o.hasReference()) sum << ',' << o.name << "_reference," << o.name << "_error";
  }
  sum << '\n';
  for (const Run& r : runs) {
    if (r.member != 0) continue;  // one row per setting
    const int k = r.setting;
    sum << k;
    for (const std::string& value : r.values) sum << ',' << quoted(value);
    const bool any = !steps[k].empty();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    sum << ',' << steps[k].size() << ',' << cell(any ? mean(steps[k]) : nan) << ','
        << cell(any ? mean(wall[k]) : nan);
    for (std::size_t o = 0; o < n_out; ++o) {
      const std::vector<double>& v = values[k][o];
      sum << ',' << cell(any ? mean(v) : nan) << ',' << cell(any ? deviation(v) : nan) << ','
          << cell(any ? *std::min_element(v.begin(), v.end()) : nan) << ','
          << cell(any ? *std::max_element(v.begin(), v.end()) : nan);
      if (sweep.outputs[o].hasReference()) {
        const double ref = sweep.outputs[o].referenceAt(k);
        sum << ',' << cell(ref) << ',' << cell(any ? std::abs(mean(v) - ref) / std::abs(ref) : nan);
      }
    }
    sum << '\n';
  }
  return g;
}

}  // namespace mpm_sdem::sweep
