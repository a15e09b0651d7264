#include "checkpoint_files.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/ros/checkpoint_source.hpp"

namespace fs = std::filesystem;

namespace mpm_sdem::runner {

CheckpointFiles::CheckpointFiles(const std::string& dir, Real interval,
                                 const std::string& state_text)
    : dir_(dir), state_text_(state_text), clock_(1 / interval) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw std::runtime_error("cannot create " + dir_ + ": " + ec.message());
}

void CheckpointFiles::write(World& world, bool force) {
  if (!clock_.due(world.time(), force) || world.time() == last_) return;
  last_ = world.time();
  const std::string bytes = saveCheckpoint(world, state_text_);
  const fs::path file = fs::path(dir_) / checkpointFileName(world.time());
  const fs::path part = file.string() + ".part";
  {
    std::ofstream out(part, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) throw std::runtime_error("cannot write the checkpoint " + part.string());
  }
  std::error_code ec;
  fs::rename(part, file, ec);
  if (ec) throw std::runtime_error("cannot rename " + part.string() + ": " + ec.message());
  // The two latest (names sort by time).
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir_, ec))
    if (e.path().extension() == ".ckpt") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (std::size_t k = 0; k + 2 < files.size(); ++k) fs::remove(files[k], ec);
}

}  // namespace mpm_sdem::runner
