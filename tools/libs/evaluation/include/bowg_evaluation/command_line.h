// Reading numbers from the tools' command lines, with one error wording for
// every tool: "<flag>: '<text>' is not a number".
#pragma once

#include <string>

namespace bowg {
namespace eval {

/// The finite number `value` spells, all of it; throws std::invalid_argument
/// naming `flag` otherwise (empty text, trailing characters, inf, nan).
double numberArgument(const std::string& flag, const std::string& value);

}  // namespace eval
}  // namespace bowg
