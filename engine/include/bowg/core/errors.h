// Exceptions thrown by the engine. Every message names what was wrong and,
// for files, the path, so that a user can act on it without a debugger.
#pragma once

#include <stdexcept>
#include <string>

namespace bowg {

/// A file could not be read or written (missing, permissions, disk full).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file was read but its content is corrupt, truncated, of the wrong
/// format or version, or does not belong to the loaded vocabulary.
class FormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An options struct failed validate(); the message names the parameter.
class InvalidParameter : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A number for a message, as a person reads it: at most 6 significant
/// digits ("%g"), so that a corrupt value such as -1e300 does not print as
/// 300 digits and -1e-9 does not print as "-0.000000".
std::string formatNumber(double value);

}  // namespace bowg
