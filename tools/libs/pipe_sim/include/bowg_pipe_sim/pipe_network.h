// A pipe network (nodes joined by straight pipes of one bore) and a route of
// the robot through it, with the bends filleted so that the camera pose is
// smooth. Units: metres, world frame `map` (REP-103: x east, y north, z up);
// the default network lies in the horizontal plane z = 0.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace bowg {
namespace pipe_sim {

struct PipeEdge {
  int from = 0;  ///< node index; the edge's own coordinate s runs from `from`
  int to = 0;    ///< to `to`, whatever the direction the robot drives it in
};

struct PipeNetwork {
  /// Inner radius of every pipe (6-inch bore: 152 mm / 2).
  double radius = 0.076;
  std::vector<cv::Vec3d> nodes;
  std::vector<PipeEdge> edges;

  /// The default network: a `width` x `height` rectangle of straight pipes
  /// with a cross pipe at mid-width, i.e. three closed circuits (left, right,
  /// outer) and T-junctions where the cross pipe branches off. Nodes:
  ///   5 --- 4 --- 3        0 = (0, 0), 1 = (w/2, 0), 2 = (w, 0),
  ///   |     |     |        3 = (w, h), 4 = (w/2, h), 5 = (0, h).
  ///   0 --- 1 --- 2        Edges: 0-1, 1-2, 2-3, 3-4, 4-5, 5-0, 1-4.
  static PipeNetwork figureEight(double width = 4.0, double height = 3.0);

  double edgeLength(int edge) const;
  /// Unit vector from edge.from to edge.to.
  cv::Vec3d edgeDirection(int edge) const;
  /// The edge joining nodes a and b (either way round), or -1.
  int findEdge(int a, int b) const;
  /// Throws std::invalid_argument naming the problem (bad node index,
  /// zero-length edge, non-positive radius).
  void validate() const;
};

/// One traversal of one edge.
struct RouteLeg {
  int edge = 0;
  bool forward = true;              ///< driven from edge.from to edge.to
  cv::Vec3d start, end, direction;  ///< direction of travel (unit)
};

/// A point of the filleted centreline.
struct CentrelinePoint {
  cv::Vec3d position;
  cv::Vec3d tangent;  ///< unit direction of travel
  /// Index of the leg whose render region (the leg's cylinder cut by the
  /// mitre planes at both ends) contains the position.
  int leg = 0;
};

/// The robot's route: a node sequence driven along the pipe centrelines;
/// at every node the path is a circular fillet of radius `bend_radius`
/// tangent to both pipes (the camera stays inside the mitred elbow for
/// bend_radius < radius / (1 - 1/sqrt(2)), about 3.4 radii at 90 degrees).
class Route {
 public:
  /// Throws std::invalid_argument when two consecutive nodes are not joined
  /// by an edge, the route turns back on itself (U-turn) or has < 2 nodes.
  Route(const PipeNetwork& network, const std::vector<int>& node_sequence, double bend_radius);

  double length() const { return total_length_; }
  CentrelinePoint at(double distance) const;  ///< distance clamped to [0, length]
  const std::vector<RouteLeg>& legs() const { return legs_; }
  /// The route's legs plus, for rendering only, one leg before the first
  /// and one after the last (the straightest continuation in the network,
  /// when there is one): index i of legs() is index i + 1 here.
  const std::vector<RouteLeg>& renderLegs() const { return render_legs_; }
  /// Unit normal of the mitre plane between render legs i and i+1
  /// (normalised sum of their directions), through their common node.
  cv::Vec3d mitreNormal(int render_leg) const;

 private:
  struct Piece {
    bool arc = false;
    double start_distance = 0, length = 0;
    cv::Vec3d p0, d0;                  ///< straight: start and direction; arc: fillet start, d1
    cv::Vec3d n1, corner, d1_plus_d2;  ///< arc only
    double radius = 0;
    int leg = 0;  ///< straight: its leg; arc: the incoming leg
  };
  RouteLeg makeLeg(const PipeNetwork& network, int edge, bool forward) const;
  // The steps of the constructor (pipe_network.cpp).
  void buildLegs(const PipeNetwork& network, const std::vector<int>& nodes);
  void buildPieces(const std::vector<int>& nodes, double bend_radius);
  void computeTurns(const std::vector<int>& nodes, double bend_radius,
                    std::vector<double>& turn_angle, std::vector<double>& tangent_length) const;
  Piece straightPiece(std::size_t i, double s, double tangent_start, double tangent_end) const;
  Piece arcPiece(std::size_t i, double s, double bend_radius, double turn_angle,
                 double tangent_length) const;
  void buildRenderLegs(const PipeNetwork& network, const std::vector<int>& nodes);

  std::vector<RouteLeg> legs_, render_legs_;
  std::vector<Piece> pieces_;
  double total_length_ = 0;
};

}  // namespace pipe_sim
}  // namespace bowg
