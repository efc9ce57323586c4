#include "bowg_pipe_sim/route_programs.h"

#include <cctype>
#include <sstream>
#include <stdexcept>

#include "bowg_pipe_sim/pipe_sequence.h"

namespace bowg {
namespace pipe_sim {

const std::vector<std::string>& routeProgramNames() {
  static const std::vector<std::string> names{"figure-eight", "circuit", "partial", "no-revisit"};
  return names;
}

std::vector<int> routeProgramNodes(const std::string& name, int laps) {
  if (laps < 1) throw std::invalid_argument("route program " + name + ": laps must be >= 1");
  if (name == "figure-eight") return defaultRouteNodes(laps);
  if (name == "circuit") {
    // Counter-clockwise round the rectangle; 5 -> 0 -> 1 turns left, so the
    // laps chain without a U-turn.
    std::vector<int> nodes{0};
    for (int l = 0; l < laps; ++l) nodes.insert(nodes.end(), {1, 2, 3, 4, 5, 0});
    return nodes;
  }
  if (name == "partial" || name == "no-revisit") {
    if (laps != 1) {
      throw std::invalid_argument("route program " + name + " is one mission: laps must be 1");
    }
    // partial: after the outer circuit the robot drives the bottom, the
    // right side and the top-right pipe again and comes back down the cross
    // pipe (a left turn at 4), so the top-left pipe, the left side and the
    // cross pipe are seen once only.
    if (name == "partial") return {0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 1};
    return {0, 1, 2, 3, 4, 5};
  }
  std::string known;
  for (const std::string& n : routeProgramNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown route program '" + name + "' (known: " + known + ")");
}

std::vector<int> parseRouteNodes(const std::string& text, const std::string& option) {
  std::vector<int> nodes;
  std::istringstream in(text);
  std::string token;
  while (std::getline(in, token, ',')) {
    bool digits = !token.empty() && token.size() <= 6;
    for (char c : token) digits = digits && std::isdigit(static_cast<unsigned char>(c));
    if (!digits) {
      throw std::invalid_argument(option + ": '" + token +
                                  "' is not a node index (a non-negative integer; nodes are "
                                  "separated by commas without spaces)");
    }
    nodes.push_back(std::stoi(token));
  }
  if (!text.empty() && text.back() == ',') throw std::invalid_argument(option + ": trailing comma");
  if (nodes.size() < 2) throw std::invalid_argument(option + ": a route needs at least two nodes");
  return nodes;
}

}  // namespace pipe_sim
}  // namespace bowg
