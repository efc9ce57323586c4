// PipeRenderer's ray caster (renderLinear): the pipe geometry in float, the
// mitred regions of the route around the camera and the walk of every pixel's
// ray through them to the wall. The camera, light and sensor models are in
// pipe_renderer.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bowg_pipe_sim/pipe_renderer.h"

namespace bowg {
namespace pipe_sim {
namespace {

constexpr float kTwoPiF = 6.2831853f;
constexpr float kInf = std::numeric_limits<float>::infinity();

struct V3 {
  float x, y, z;
};
inline V3 v3(const cv::Vec3d& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}
inline float dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 sub(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 madd(const V3& a, const V3& b, float t) {
  return {a.x + b.x * t, a.y + b.y * t, a.z + b.z * t};
}

/// Exit distance of the ray o + t d (|d| = 1) from the infinite cylinder of
/// radius r around the axis through a with unit direction u, for a ray
/// origin inside it: the larger root of |w_perp + t d_perp|^2 = r^2.
inline float cylinderExit(const V3& o, const V3& d, const V3& a, const V3& u, float r) {
  const V3 w = sub(o, a);
  const float wu = dot(w, u), du = dot(d, u);
  const V3 wp = madd(w, u, -wu), dp = madd(d, u, -du);
  const float A = dot(dp, dp);
  if (A < 1e-12f) return kInf;  // ray along the axis
  const float B = dot(wp, dp), C = dot(wp, wp) - r * r;
  const float disc = B * B - A * C;
  if (disc < 0) return kInf;
  return (-B + std::sqrt(disc)) / A;
}

/// atan2 to ~1e-5 rad (a minimax polynomial on [0, 1] plus octant
/// folding): std::atan2 costs a third of the frame time and the texture has
/// 512 columns, i.e. 0.012 rad per column.
inline float fastAtan2(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  const float mx = std::max(ax, ay), mn = std::min(ax, ay);
  if (mx == 0.f) return 0.f;
  const float a = mn / mx, s = a * a;
  float r = ((-0.0464964749f * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
  if (ay > ax) r = 1.57079637f - r;
  if (x < 0) r = 3.14159274f - r;
  return y < 0 ? -r : r;
}

/// Bilinear lookup of an 8-bit texture: row coordinate clamped, column
/// coordinate `c01` in [0, 1) wraps around the circumference.
inline float lookup(const cv::Mat& tex, float r, float c01) {
  r = std::max(0.f, std::min(static_cast<float>(tex.rows) - 1.001f, r));
  const float c = c01 * tex.cols;
  const int r0 = static_cast<int>(r);
  int c0 = static_cast<int>(c);
  const float fr = r - r0, fc = c - c0;
  if (c0 >= tex.cols) c0 -= tex.cols;
  const int c1 = c0 + 1 == tex.cols ? 0 : c0 + 1;
  const uchar* a = tex.ptr<uchar>(r0);
  const uchar* b = a + tex.step[0];
  const float top = a[c0] + (a[c1] - a[c0]) * fc, bottom = b[c0] + (b[c1] - b[c0]) * fc;
  return (top + (bottom - top) * fr) * (1.f / 255.f);
}

cv::Vec3d upFor(const cv::Vec3d& u) {
  cv::Vec3d ref(0, 0, 1);
  if (std::abs(u.dot(ref)) > 0.9) ref = cv::Vec3d(1, 0, 0);
  return cv::normalize(ref - u * u.dot(ref));
}

}  // namespace

struct PipeRenderer::Region {
  V3 axis_origin, axis;                 // the leg's centreline
  int edge;                             // texture of this pipe
  V3 edge_origin, edge_axis, up, side;  // canonical edge frame
  bool has_next = false, has_prev = false;
  V3 next_point, next_normal, prev_point, prev_normal;  // mitre planes
  struct Branch {
    V3 origin, axis, edge_origin, edge_axis, up, side;
    int edge;
  };
  std::vector<Branch> branches;
};

void PipeRenderer::buildRegions(int leg, std::vector<Region>& regions, int& current) const {
  const std::vector<RouteLeg>& legs = route_.renderLegs();
  const int n = static_cast<int>(legs.size());
  const int c = leg + 1;  // render index of the route leg
  const int first = std::max(0, c - 1), last = std::min(n - 1, c + 3);
  current = c - first;
  auto nodeOf = [&](const cv::Vec3d& p) {
    for (std::size_t i = 0; i < network_.nodes.size(); ++i) {
      if (cv::norm(network_.nodes[i] - p) < 1e-9) return static_cast<int>(i);
    }
    return -1;
  };
  for (int i = first; i <= last; ++i) {
    const RouteLeg& L = legs[i];
    Region r;
    r.axis_origin = v3(L.start);
    r.axis = v3(L.direction);
    r.edge = L.edge;
    const cv::Vec3d eu = network_.edgeDirection(L.edge), up = upFor(eu);
    r.edge_origin = v3(network_.nodes[network_.edges[L.edge].from]);
    r.edge_axis = v3(eu);
    r.up = v3(up);
    r.side = v3(eu.cross(up));
    if (i + 1 < n) {
      r.has_next = true;
      r.next_point = v3(L.end);
      r.next_normal = v3(route_.mitreNormal(i));
    }
    if (i > 0) {
      r.has_prev = true;
      r.prev_point = v3(L.start);
      r.prev_normal = v3(route_.mitreNormal(i - 1));
    }
    // Side branches at both ends: every other pipe meeting at the node.
    for (int end = 0; end < 2; ++end) {
      const int node = nodeOf(end == 0 ? L.start : L.end);
      if (node < 0) continue;
      const int neighbour = end == 0 ? i - 1 : i + 1;
      for (int e : node_edges_[node]) {
        if (e == L.edge || (neighbour >= 0 && neighbour < n && legs[neighbour].edge == e)) continue;
        const PipeEdge& pe = network_.edges[e];
        const cv::Vec3d bu = network_.edgeDirection(e) * (pe.from == node ? 1.0 : -1.0);
        Region::Branch b;
        b.origin = v3(network_.nodes[node]);
        b.axis = v3(bu);
        b.edge = e;
        const cv::Vec3d ceu = network_.edgeDirection(e), cup = upFor(ceu);
        b.edge_origin = v3(network_.nodes[pe.from]);
        b.edge_axis = v3(ceu);
        b.up = v3(cup);
        b.side = v3(ceu.cross(cup));
        r.branches.push_back(b);
      }
    }
    regions.push_back(r);
  }
}

/// Follows the pixel rays of one frame through the regions around the camera
/// (renderLinear's per-frame constants, in float, and its per-pixel steps).
class PipeRenderer::RayCaster {
 public:
  RayCaster(const PipeRenderer& renderer, const CameraPose& pose);
  float pixel(std::size_t index) const;

 private:
  /// The wall a ray ends on: its pipe's texture frame and centreline.
  struct Surface {
    V3 edge_origin, edge_axis, up, side;  // canonical edge frame
    int edge;                             // texture of this pipe
    V3 axis_point, axis;                  // the pipe's centreline
  };
  V3 worldRay(std::size_t index) const;
  int walkRegions(const V3& d, float& t_hit) const;
  void mitreDistances(const Region& r, const V3& d, float& tn, float& tp) const;
  void enterSideBranch(const V3& d, const Region& r, float& t_hit, V3& p, Surface& wall) const;
  float shade(const V3& d, float t_hit, const V3& p, const Surface& wall, std::size_t index) const;

  const PipeRenderer& renderer_;
  std::vector<Region> regions_;
  int current_ = 0;
  int nreg_;
  float M_[9];  // R_world_optical, row-major
  V3 o_;        // the camera centre
  float radius_, power_, core2_, inv_falloff_, max_t_, inv_fx_, texel_, margin_;
};

// The frame's regions and its constants in float, so that no pixel converts them again.
PipeRenderer::RayCaster::RayCaster(const PipeRenderer& renderer, const CameraPose& pose)
    : renderer_(renderer) {
  renderer.buildRegions(pose.leg, regions_, current_);
  // R_world_optical = R_world_body * R_body_optical; the optical x, y, z axes
  // are the body's -y, -z, +x.
  const cv::Matx33d Rb_o(0, 0, 1, -1, 0, 0, 0, -1, 0);
  const cv::Matx33d R = pose.R_world_body * Rb_o;
  for (int i = 0; i < 9; ++i) M_[i] = static_cast<float>(R.val[i]);
  o_ = v3(pose.position);
  radius_ = static_cast<float>(renderer.network_.radius);
  power_ = static_cast<float>(renderer.light_.power);
  core2_ = static_cast<float>(renderer.light_.core_m * renderer.light_.core_m);
  inv_falloff_ = static_cast<float>(1.0 / renderer.light_.falloff_m);
  max_t_ = static_cast<float>(renderer.sensor_.max_distance_m);
  inv_fx_ = static_cast<float>(1.0 / renderer.camera_.fx);
  texel_ = static_cast<float>(renderer.texture_.options().texel_m);
  margin_ = static_cast<float>(renderer.texture_.options().margin_m);
  nreg_ = static_cast<int>(regions_.size());
}

// Linear irradiance of pixel `index` (row-major), 0 where no wall lies within max_distance_m.
float PipeRenderer::RayCaster::pixel(std::size_t index) const {
  const V3 d = worldRay(index);
  float t_hit = kInf;
  const int ri = walkRegions(d, t_hit);
  if (!(t_hit < max_t_) || ri < 0 || ri >= nreg_) return 0.f;
  const Region& r = regions_[ri];
  V3 p = madd(o_, d, t_hit);
  // A hole in the wall where a side branch joins: follow the ray into it.
  Surface wall{r.edge_origin, r.edge_axis, r.up, r.side, r.edge, r.axis_origin, r.axis};
  enterSideBranch(d, r, t_hit, p, wall);
  if (!(t_hit < max_t_)) return 0.f;
  return shade(d, t_hit, p, wall, index);
}

// The pixel's unit ray in the world frame: R_world_optical times its optical-frame ray.
V3 PipeRenderer::RayCaster::worldRay(std::size_t index) const {
  const cv::Vec3f& ro = renderer_.rays_optical_[index];
  return V3{M_[0] * ro[0] + M_[1] * ro[1] + M_[2] * ro[2],
            M_[3] * ro[0] + M_[4] * ro[1] + M_[5] * ro[2],
            M_[6] * ro[0] + M_[7] * ro[1] + M_[8] * ro[2]};
}

// The region whose wall the ray hits (t_hit; out of range or t_hit = kInf when none in reach).
int PipeRenderer::RayCaster::walkRegions(const V3& d, float& t_hit) const {
  // Walk the mitred regions until the ray leaves through a wall.
  int ri = current_;
  float t_in = 0;
  for (int step = 0; step < 6 && ri >= 0 && ri < nreg_; ++step) {
    const Region& r = regions_[ri];
    const float tc = cylinderExit(o_, d, r.axis_origin, r.axis, radius_);
    float tn, tp;
    mitreDistances(r, d, tn, tp);
    if (tc <= tn && tc <= tp) {
      t_hit = tc;
      break;
    }
    if (tn < tp) {
      ++ri;
      t_in = tn;
    } else {
      --ri;
      t_in = tp;
    }
    if (t_in > max_t_) break;
  }
  return ri;
}

// Where the ray crosses region r's next (tn) and previous (tp) mitre plane outwards, else kInf.
void PipeRenderer::RayCaster::mitreDistances(const Region& r, const V3& d, float& tn,
                                             float& tp) const {
  tn = kInf;
  tp = kInf;
  if (r.has_next) {
    const float dn = dot(d, r.next_normal);
    if (dn > 1e-6f) tn = dot(sub(r.next_point, o_), r.next_normal) / dn;
  }
  if (r.has_prev) {
    const float dp = dot(d, r.prev_normal);
    if (dp < -1e-6f) tp = dot(sub(r.prev_point, o_), r.prev_normal) / dp;
  }
}

// If p lies in a side branch's hole, moves t_hit, p and the wall to where the ray meets that pipe.
void PipeRenderer::RayCaster::enterSideBranch(const V3& d, const Region& r, float& t_hit, V3& p,
                                              Surface& wall) const {
  for (const Region::Branch& b : r.branches) {
    const V3 w = sub(p, b.origin);
    const float along = dot(w, b.axis);
    if (along <= 0) continue;
    const V3 wp = madd(w, b.axis, -along);
    if (dot(wp, wp) >= radius_ * radius_ * 0.998f) continue;
    const float tb = cylinderExit(o_, d, b.origin, b.axis, radius_);
    if (!(tb > t_hit) || tb > max_t_) continue;
    t_hit = tb;
    p = madd(o_, d, t_hit);
    wall = Surface{b.edge_origin, b.edge_axis, b.up, b.side, b.edge, b.origin, b.axis};
    break;
  }
}

// Ring-light irradiance of wall point p: texture albedo x incidence x distance falloff x beam.
float PipeRenderer::RayCaster::shade(const V3& d, float t_hit, const V3& p, const Surface& wall,
                                     std::size_t index) const {
  // Wall coordinates on the edge: s along, theta about the axis.
  const V3 we = sub(p, wall.edge_origin);
  const float s = dot(we, wall.edge_axis);
  const float theta = fastAtan2(dot(we, wall.side), dot(we, wall.up));
  // Incidence: the light sits at the camera, so cos = |d . normal|.
  const V3 wa = sub(p, wall.axis_point);
  const V3 radial = madd(wa, wall.axis, -dot(wa, wall.axis));
  const float cos_inc = std::min(1.f, std::abs(dot(d, radial)) / radius_);
  // Mip level from the texel footprint of one pixel.
  const float footprint = t_hit * inv_fx_ / std::max(cos_inc, 0.05f) / texel_;
  const int level = footprint > 4.f ? 2 : footprint > 2.f ? 1 : 0;
  const float albedo =
      lookup(renderer_.texture_.texture(wall.edge, level), (s + margin_) / (texel_ * (1 << level)),
             (theta < 0 ? theta + kTwoPiF : theta) * (1.f / kTwoPiF));
  const float off_axis = renderer_.beam_[index];
  return power_ * albedo * cos_inc / (t_hit * t_hit + core2_) * std::exp(-t_hit * inv_falloff_) *
         off_axis;
}

cv::Mat PipeRenderer::renderLinear(const CameraPose& pose) const {
  const RayCaster caster(*this, pose);
  cv::Mat out(camera_.height, camera_.width, CV_32F);
  for (int v = 0; v < camera_.height; ++v) {
    float* row = out.ptr<float>(v);
    for (int u = 0; u < camera_.width; ++u) {
      row[u] = caster.pixel(static_cast<std::size_t>(v) * camera_.width + u);
    }
  }
  return out;
}

}  // namespace pipe_sim
}  // namespace bowg
