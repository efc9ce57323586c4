// Named node sequences through the default network (PipeNetwork::figureEight),
// so that a robustness suite can vary how much of a mission is a revisit:
// everything twice, only part, or nothing at all. See docs/pipe_sequence.md
// ("The network and the route") for the programs and why they look so.
#pragma once

#include <string>
#include <vector>

namespace bowg {
namespace pipe_sim {

/// The names routeProgramNodes accepts, the default first.
const std::vector<std::string>& routeProgramNames();

/// The node sequence of program `name` driven `laps` times:
///  - figure-eight: defaultRouteNodes(laps);
///  - circuit: the outer rectangle 0 1 2 3 4 5 0, `laps` times (the second
///    lap revisits every place of the first);
///  - partial: the outer circuit, then its right half again through the
///    cross pipe (0 1 2 3 4 5 0 1 2 3 4 1): half the places are revisited;
///  - no-revisit: 0 1 2 3 4 5, every pipe once and no place twice.
/// partial and no-revisit are one mission each: laps must be 1.
/// Throws std::invalid_argument naming the bad name or laps.
std::vector<int> routeProgramNodes(const std::string& name, int laps);

/// Parses a custom node list "0,1,2,...": non-negative integers separated by
/// commas, at least two. Whether consecutive nodes are joined and turn
/// without a U-turn is the Route's check. Throws std::invalid_argument
/// naming `option` (the CLI flag) and the bad token.
std::vector<int> parseRouteNodes(const std::string& text, const std::string& option);

}  // namespace pipe_sim
}  // namespace bowg
