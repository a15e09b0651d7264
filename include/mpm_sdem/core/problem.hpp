/// \file
/// The one return type of every check named *Problem: what is wrong with an input and where.
#pragma once

#include <string>
#include <utility>

namespace mpm_sdem {

/// What is wrong with an input: the key it belongs to (as a scene file names it) and why. Empty
/// when nothing is. Every check named *Problem returns one; a check of a bare value (a range, a
/// name, a path) leaves the key to its caller, so it converts from its message alone.
struct Problem {
  /// Nothing is wrong.
  Problem() = default;
  ///@{
  /// A message alone, no key (a bare value's check).
  Problem(const char* why) : message(why) {}             // NOLINT: implicit on purpose
  Problem(std::string why) : message(std::move(why)) {}  // NOLINT: implicit on purpose
  ///@}
  /// A message under a key.
  Problem(std::string key_, std::string why) : key(std::move(key_)), message(std::move(why)) {}

  std::string key;      ///< as a scene file names it (e.g. "coupling.scheme"); may be empty
  std::string message;  ///< why, in words; empty when nothing is wrong
  /// Whether nothing is wrong.
  bool empty() const { return message.empty(); }
  /// "key: message", or the message alone without a key.
  std::string text() const { return key.empty() ? message : key + ": " + message; }
  /// The same problem under a key: a bare value's check placed by its caller.
  Problem under(std::string key_) const { return {std::move(key_), message}; }
};

}  // namespace mpm_sdem
