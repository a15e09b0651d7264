// A PNG summary of a comparison, drawn with OpenCV: block position error, cloud distance and
// total energy against time, one panel each.
#pragma once

#include <string>

#include "compare.hpp"

namespace mpm_sdem::compare {

// Throws std::runtime_error when the file cannot be written.
void plotComparison(const Comparison& c, const std::string& label_a, const std::string& label_b,
                    const std::string& png_path);

}  // namespace mpm_sdem::compare
