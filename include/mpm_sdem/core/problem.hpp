// The one return type of every check named *Problem: what is wrong with an input and where.
#pragma once

#include <string>
#include <utility>

namespace mpm_sdem {

// What is wrong with an input: the key it belongs to (as a scene file names it) and why. Empty
// when nothing is. Every check named *Problem returns one; a check of a bare value (a range, a
// name, a path) leaves the key to its caller, so it converts from its message alone.
struct Problem {
  Problem() = default;
  Problem(const char* why) : message(why) {}             // NOLINT: a message alone, no key
  Problem(std::string why) : message(std::move(why)) {}  // NOLINT: as above
  Problem(std::string key_, std::string why) : key(std::move(key_)), message(std::move(why)) {}

  std::string key;
  std::string message;
  bool empty() const { return message.empty(); }
  std::string text() const { return key.empty() ? message : key + ": " + message; }
  // The same problem under a key: a bare value's check placed by its caller.
  Problem under(std::string key_) const { return {std::move(key_), message}; }
};

}  // namespace mpm_sdem
