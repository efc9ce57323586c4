#include "bowg_pipe_sim/pipe_network.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bowg {
namespace pipe_sim {

PipeNetwork PipeNetwork::figureEight(double width, double height) {
  if (!(width > 0) || !(height > 0)) {
    throw std::invalid_argument("PipeNetwork::figureEight: width and height must be > 0");
  }
  PipeNetwork n;
  n.nodes = {{0, 0, 0},          {width / 2, 0, 0},      {width, 0, 0},
             {width, height, 0}, {width / 2, height, 0}, {0, height, 0}};
  n.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {5, 0}, {1, 4}};
  return n;
}

double PipeNetwork::edgeLength(int edge) const {
  return cv::norm(nodes[edges[edge].to] - nodes[edges[edge].from]);
}

cv::Vec3d PipeNetwork::edgeDirection(int edge) const {
  return cv::normalize(nodes[edges[edge].to] - nodes[edges[edge].from]);
}

int PipeNetwork::findEdge(int a, int b) const {
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if ((edges[e].from == a && edges[e].to == b) || (edges[e].from == b && edges[e].to == a)) {
      return static_cast<int>(e);
    }
  }
  return -1;
}

void PipeNetwork::validate() const {
  if (!(radius > 0)) throw std::invalid_argument("PipeNetwork: radius must be > 0");
  const int n = static_cast<int>(nodes.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (edges[e].from < 0 || edges[e].from >= n || edges[e].to < 0 || edges[e].to >= n) {
      throw std::invalid_argument("PipeNetwork: edge " + std::to_string(e) +
                                  " refers to a node that does not exist");
    }
    if (edgeLength(static_cast<int>(e)) < 4 * radius) {
      throw std::invalid_argument("PipeNetwork: edge " + std::to_string(e) +
                                  " is shorter than two pipe diameters");
    }
  }
}

RouteLeg Route::makeLeg(const PipeNetwork& network, int edge, bool forward) const {
  RouteLeg leg;
  leg.edge = edge;
  leg.forward = forward;
  const PipeEdge& e = network.edges[edge];
  leg.start = network.nodes[forward ? e.from : e.to];
  leg.end = network.nodes[forward ? e.to : e.from];
  leg.direction = cv::normalize(leg.end - leg.start);
  return leg;
}

namespace {

// The straightest edge at `node` to continue `dir` through it (leaving the node when outward,
// else entering it), or -1: a render leg beyond an end of the route.
int continuation(const PipeNetwork& network, int node, int exclude_edge, const cv::Vec3d& dir,
                 bool outward) {
  int best = -1;
  double best_cos = -0.5;  // reject continuations sharper than 120 degrees
  for (std::size_t e = 0; e < network.edges.size(); ++e) {
    if (static_cast<int>(e) == exclude_edge) continue;
    const PipeEdge& pe = network.edges[e];
    if (pe.from != node && pe.to != node) continue;
    // Direction of travel along e when leaving (outward) or entering node.
    cv::Vec3d d = network.edgeDirection(static_cast<int>(e)) * (pe.from == node ? 1.0 : -1.0);
    if (!outward) d = -d;
    const double c = d.dot(dir);
    if (c > best_cos) {
      best_cos = c;
      best = static_cast<int>(e);
    }
  }
  return best;
}

}  // namespace

Route::Route(const PipeNetwork& network, const std::vector<int>& nodes, double bend_radius) {
  network.validate();
  if (nodes.size() < 2) throw std::invalid_argument("Route: needs at least two nodes");
  if (!(bend_radius >= 0)) throw std::invalid_argument("Route: bend_radius must be >= 0");
  buildLegs(network, nodes);
  buildPieces(nodes, bend_radius);
  buildRenderLegs(network, nodes);
}

// One leg per pair of consecutive nodes; throws when the pair is not joined by a pipe.
void Route::buildLegs(const PipeNetwork& network, const std::vector<int>& nodes) {
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    const int e = network.findEdge(nodes[i], nodes[i + 1]);
    if (e < 0) {
      throw std::invalid_argument("Route: nodes " + std::to_string(nodes[i]) + " and " +
                                  std::to_string(nodes[i + 1]) + " are not joined by a pipe");
    }
    legs_.push_back(makeLeg(network, e, network.edges[e].from == nodes[i]));
  }
}

// The filleted centreline as pieces with their start distances, and its total length.
void Route::buildPieces(const std::vector<int>& nodes, double bend_radius) {
  // Straight pieces shortened by the fillet tangent lengths T = R tan(theta/2)
  // at both ends, arcs in between.
  std::vector<double> tangent_length(legs_.size() + 1, 0.0);
  std::vector<double> turn_angle(legs_.size() + 1, 0.0);
  computeTurns(nodes, bend_radius, turn_angle, tangent_length);
  double s = 0;
  for (std::size_t i = 0; i < legs_.size(); ++i) {
    const Piece straight = straightPiece(i, s, tangent_length[i], tangent_length[i + 1]);
    pieces_.push_back(straight);
    s += straight.length;
    if (i + 1 < legs_.size() && turn_angle[i + 1] > 1e-9) {
      const Piece arc = arcPiece(i, s, bend_radius, turn_angle[i + 1], tangent_length[i + 1]);
      pieces_.push_back(arc);
      s += arc.length;
    }
  }
  total_length_ = s;
}

// Turn angle and fillet tangent length at every inner node i (between legs i - 1 and i).
void Route::computeTurns(const std::vector<int>& nodes, double bend_radius,
                         std::vector<double>& turn_angle,
                         std::vector<double>& tangent_length) const {
  for (std::size_t i = 1; i < legs_.size(); ++i) {
    const double c = legs_[i - 1].direction.dot(legs_[i].direction);
    if (c < -0.999) {
      throw std::invalid_argument("Route: U-turn at node " + std::to_string(nodes[i]));
    }
    turn_angle[i] = std::acos(std::max(-1.0, std::min(1.0, c)));
    tangent_length[i] = bend_radius * std::tan(turn_angle[i] / 2);
  }
}

// Leg i's straight piece from distance s: the leg less the fillet tangents at its two ends.
Route::Piece Route::straightPiece(std::size_t i, double s, double tangent_start,
                                  double tangent_end) const {
  const RouteLeg& leg = legs_[i];
  const double leg_length = cv::norm(leg.end - leg.start);
  Piece straight;
  straight.start_distance = s;
  straight.length = leg_length - tangent_start - tangent_end;
  if (straight.length < 0) {
    throw std::invalid_argument("Route: pipe " + std::to_string(leg.edge) +
                                " is too short for the bend radius");
  }
  straight.p0 = leg.start + leg.direction * tangent_start;
  straight.d0 = leg.direction;
  straight.leg = static_cast<int>(i);
  return straight;
}

// The fillet arc from leg i into leg i + 1, from distance s, tangent to both pipes.
Route::Piece Route::arcPiece(std::size_t i, double s, double bend_radius, double turn_angle,
                             double tangent_length) const {
  const RouteLeg& leg = legs_[i];
  const cv::Vec3d d1 = leg.direction, d2 = legs_[i + 1].direction;
  Piece arc;
  arc.arc = true;
  arc.start_distance = s;
  arc.radius = bend_radius;
  arc.length = bend_radius * turn_angle;
  arc.corner = leg.end;
  arc.p0 = leg.end - d1 * tangent_length;
  arc.d0 = d1;
  arc.n1 = cv::normalize(d2 - d1 * d2.dot(d1));
  arc.d1_plus_d2 = d1 + d2;
  arc.leg = static_cast<int>(i);
  return arc;
}

// The legs plus a render leg before and after them, so the camera's regions never run out.
void Route::buildRenderLegs(const PipeNetwork& network, const std::vector<int>& nodes) {
  // Render legs: the straightest continuation before the first and after the
  // last node, so that the camera sees the elbow and not a blind end.
  const int before =
      continuation(network, nodes.front(), legs_.front().edge, legs_.front().direction, false);
  const int after =
      continuation(network, nodes.back(), legs_.back().edge, legs_.back().direction, true);
  render_legs_.push_back(before >= 0
                             ? makeLeg(network, before, network.edges[before].to == nodes.front())
                             : RouteLeg());
  if (before < 0) {  // no continuation: a straight virtual extension
    render_legs_.back().edge = legs_.front().edge;
    render_legs_.back().forward = legs_.front().forward;
    render_legs_.back().direction = legs_.front().direction;
    render_legs_.back().end = legs_.front().start;
    render_legs_.back().start = legs_.front().start - legs_.front().direction * 10.0;
  }
  for (const RouteLeg& leg : legs_) render_legs_.push_back(leg);
  if (after >= 0) {
    render_legs_.push_back(makeLeg(network, after, network.edges[after].from == nodes.back()));
  } else {
    RouteLeg leg = legs_.back();
    leg.start = leg.end;
    leg.end = leg.start + leg.direction * 10.0;
    render_legs_.push_back(leg);
  }
}

cv::Vec3d Route::mitreNormal(int i) const {
  return cv::normalize(render_legs_[i].direction + render_legs_[i + 1].direction);
}

CentrelinePoint Route::at(double distance) const {
  distance = std::max(0.0, std::min(total_length_, distance));
  auto it = std::upper_bound(pieces_.begin(), pieces_.end(), distance,
                             [](double d, const Piece& p) { return d < p.start_distance; });
  const Piece& p = *(it == pieces_.begin() ? it : it - 1);
  const double u = distance - p.start_distance;
  CentrelinePoint c;
  c.leg = p.leg;
  if (!p.arc) {
    c.position = p.p0 + p.d0 * u;
    c.tangent = p.d0;
    return c;
  }
  // p = C - R n1 cos(phi) + R d1 sin(phi), C = fillet start + R n1.
  const double phi = u / p.radius;
  c.position = p.p0 + p.n1 * (p.radius * (1 - std::cos(phi))) + p.d0 * (p.radius * std::sin(phi));
  c.tangent = cv::normalize(p.d0 * std::cos(phi) + p.n1 * std::sin(phi));
  // Past the mitre plane the camera is in the next leg's region.
  if ((c.position - p.corner).dot(p.d1_plus_d2) > 0) c.leg = p.leg + 1;
  return c;
}

}  // namespace pipe_sim
}  // namespace bowg
