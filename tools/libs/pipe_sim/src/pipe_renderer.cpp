#include "bowg_pipe_sim/pipe_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "bowg_pipe_sim/random.h"

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
inline V3 madd(const V3& a, const V3& b, float t) { return {a.x + b.x * t, a.y + b.y * t, a.z + b.z * t}; }

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

void CameraModel::validate() const {
  if (width < 16 || height < 16) throw std::invalid_argument("CameraModel: width/height must be >= 16");
  if (!(fx > 0) || !(fy > 0)) throw std::invalid_argument("CameraModel: fx/fy must be > 0");
}
void LightModel::validate() const {
  if (!(power > 0)) throw std::invalid_argument("LightModel.power must be > 0");
  if (!(core_m >= 0)) throw std::invalid_argument("LightModel.core_m must be >= 0");
  if (!(falloff_m > 0)) throw std::invalid_argument("LightModel.falloff_m must be > 0");
  if (!(beam_exponent >= 0)) throw std::invalid_argument("LightModel.beam_exponent must be >= 0");
}
void SensorModel::validate() const {
  if (!(read_noise >= 0) || !(shot_noise >= 0)) {
    throw std::invalid_argument("SensorModel: read_noise/shot_noise must be >= 0");
  }
  if (!(gamma > 0)) throw std::invalid_argument("SensorModel.gamma must be > 0");
  if (!(blur_sigma_px >= 0)) throw std::invalid_argument("SensorModel.blur_sigma_px must be >= 0");
  if (!(max_distance_m > 0)) throw std::invalid_argument("SensorModel.max_distance_m must be > 0");
}

PipeRenderer::PipeRenderer(const PipeNetwork& network, const Route& route,
                           const WallTexture& texture, const CameraModel& camera,
                           const LightModel& light, const SensorModel& sensor)
    : network_(network), route_(route), texture_(texture), camera_(camera), light_(light),
      sensor_(sensor) {
  camera_.validate();
  light_.validate();
  sensor_.validate();
  rays_optical_.resize(static_cast<std::size_t>(camera_.width) * camera_.height);
  for (int v = 0; v < camera_.height; ++v) {
    for (int u = 0; u < camera_.width; ++u) {
      rays_optical_[static_cast<std::size_t>(v) * camera_.width + u] = cv::normalize(
          cv::Vec3f(static_cast<float>((u - camera_.cx) / camera_.fx),
                    static_cast<float>((v - camera_.cy) / camera_.fy), 1.f));
    }
  }
  beam_.resize(rays_optical_.size());
  for (std::size_t i = 0; i < rays_optical_.size(); ++i) {
    beam_[i] = static_cast<float>(std::pow(rays_optical_[i][2], light_.beam_exponent));
  }
  // Sensor response as a table over sqrt(linear): fine steps in the darks,
  // where the gamma curve is steep.
  response_.resize(kResponseSize);
  for (int i = 0; i < kResponseSize; ++i) {
    const double root = static_cast<double>(i) / (kResponseSize - 1);
    response_[i] = static_cast<float>(255.0 * std::pow(root * root, sensor_.gamma) + 0.5);
  }
  Random rng(0x6e6f697365ULL);  // fixed: the table is part of the renderer
  noise_table_.resize(1 << 20);
  for (float& n : noise_table_) n = static_cast<float>(rng.normal());
  node_edges_.resize(network_.nodes.size());
  for (std::size_t e = 0; e < network_.edges.size(); ++e) {
    node_edges_[network_.edges[e].from].push_back(static_cast<int>(e));
    node_edges_[network_.edges[e].to].push_back(static_cast<int>(e));
  }
}

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

cv::Mat PipeRenderer::renderLinear(const CameraPose& pose) const {
  std::vector<Region> regions;
  int current = 0;
  buildRegions(pose.leg, regions, current);
  // R_world_optical = R_world_body * R_body_optical; the optical x, y, z axes
  // are the body's -y, -z, +x.
  const cv::Matx33d Rb_o(0, 0, 1, -1, 0, 0, 0, -1, 0);
  const cv::Matx33d R = pose.R_world_body * Rb_o;
  float M[9];
  for (int i = 0; i < 9; ++i) M[i] = static_cast<float>(R.val[i]);
  const V3 o = v3(pose.position);
  const float radius = static_cast<float>(network_.radius);
  const float power = static_cast<float>(light_.power);
  const float core2 = static_cast<float>(light_.core_m * light_.core_m);
  const float inv_falloff = static_cast<float>(1.0 / light_.falloff_m);
  const float max_t = static_cast<float>(sensor_.max_distance_m);
  const float inv_fx = static_cast<float>(1.0 / camera_.fx);
  const float texel = static_cast<float>(texture_.options().texel_m);
  const float margin = static_cast<float>(texture_.options().margin_m);
  const int nreg = static_cast<int>(regions.size());

  cv::Mat out(camera_.height, camera_.width, CV_32F);
  for (int v = 0; v < camera_.height; ++v) {
    float* row = out.ptr<float>(v);
    for (int u = 0; u < camera_.width; ++u) {
      const cv::Vec3f& ro = rays_optical_[static_cast<std::size_t>(v) * camera_.width + u];
      const V3 d{M[0] * ro[0] + M[1] * ro[1] + M[2] * ro[2],
                 M[3] * ro[0] + M[4] * ro[1] + M[5] * ro[2],
                 M[6] * ro[0] + M[7] * ro[1] + M[8] * ro[2]};
      // Walk the mitred regions until the ray leaves through a wall.
      int ri = current;
      float t_in = 0, t_hit = kInf;
      for (int step = 0; step < 6 && ri >= 0 && ri < nreg; ++step) {
        const Region& r = regions[ri];
        const float tc = cylinderExit(o, d, r.axis_origin, r.axis, radius);
        float tn = kInf, tp = kInf;
        if (r.has_next) {
          const float dn = dot(d, r.next_normal);
          if (dn > 1e-6f) tn = dot(sub(r.next_point, o), r.next_normal) / dn;
        }
        if (r.has_prev) {
          const float dp = dot(d, r.prev_normal);
          if (dp < -1e-6f) tp = dot(sub(r.prev_point, o), r.prev_normal) / dp;
        }
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
        if (t_in > max_t) break;
      }
      if (!(t_hit < max_t) || ri < 0 || ri >= nreg) {
        row[u] = 0.f;
        continue;
      }
      const Region& r = regions[ri];
      V3 p = madd(o, d, t_hit);
      // A hole in the wall where a side branch joins: follow the ray into it.
      V3 eo = r.edge_origin, eu = r.edge_axis, up = r.up, side = r.side;
      int edge = r.edge;
      V3 axis_point = r.axis_origin, axis = r.axis;
      for (const Region::Branch& b : r.branches) {
        const V3 w = sub(p, b.origin);
        const float along = dot(w, b.axis);
        if (along <= 0) continue;
        const V3 wp = madd(w, b.axis, -along);
        if (dot(wp, wp) >= radius * radius * 0.998f) continue;
        const float tb = cylinderExit(o, d, b.origin, b.axis, radius);
        if (!(tb > t_hit) || tb > max_t) continue;
        t_hit = tb;
        p = madd(o, d, t_hit);
        eo = b.edge_origin;
        eu = b.edge_axis;
        up = b.up;
        side = b.side;
        edge = b.edge;
        axis_point = b.origin;
        axis = b.axis;
        break;
      }
      if (!(t_hit < max_t)) {
        row[u] = 0.f;
        continue;
      }
      // Wall coordinates on the edge: s along, theta about the axis.
      const V3 we = sub(p, eo);
      const float s = dot(we, eu);
      const float theta = fastAtan2(dot(we, side), dot(we, up));
      // Incidence: the light sits at the camera, so cos = |d . normal|.
      const V3 wa = sub(p, axis_point);
      const V3 radial = madd(wa, axis, -dot(wa, axis));
      const float cos_inc = std::min(1.f, std::abs(dot(d, radial)) / radius);
      // Mip level from the texel footprint of one pixel.
      const float footprint = t_hit * inv_fx / std::max(cos_inc, 0.05f) / texel;
      const int level = footprint > 4.f ? 2 : footprint > 2.f ? 1 : 0;
      const float albedo = lookup(texture_.texture(edge, level), (s + margin) / (texel * (1 << level)),
                                  (theta < 0 ? theta + kTwoPiF : theta) * (1.f / kTwoPiF));
      const float off_axis = beam_[static_cast<std::size_t>(v) * camera_.width + u];
      row[u] = power * albedo * cos_inc / (t_hit * t_hit + core2) * std::exp(-t_hit * inv_falloff) *
               off_axis;
    }
  }
  return out;
}

cv::Mat PipeRenderer::render(const CameraPose& pose, double exposure, std::uint64_t noise_seed) const {
  cv::Mat linear = renderLinear(pose);
  if (sensor_.blur_sigma_px > 0) {
    cv::GaussianBlur(linear, linear, cv::Size(0, 0), sensor_.blur_sigma_px);
  }
  const std::size_t mask = noise_table_.size() - 1;
  std::size_t k = splitMix64(noise_seed) & mask;
  const std::size_t stride = (splitMix64(noise_seed + 1) & 0xffff) * 2 + 1;  // odd: full cycle
  const float read = static_cast<float>(sensor_.read_noise);
  const float shot = static_cast<float>(sensor_.shot_noise);
  const std::size_t second = noise_table_.size() / 2;  // an unrelated second sample
  const float gain = static_cast<float>(exposure);
  cv::Mat image(linear.size(), CV_8U);
  for (int v = 0; v < linear.rows; ++v) {
    const float* in = linear.ptr<float>(v);
    uchar* px = image.ptr<uchar>(v);
    for (int u = 0; u < linear.cols; ++u) {
      const float s = gain * in[u];
      // Photon noise before the response curve, read-out noise after it (it
      // is what stays visible in the dark centre of the pipe).
      const float noisy = s + std::sqrt(shot * s) * noise_table_[k];
      const float root = noisy > 0 ? std::sqrt(std::min(noisy, 1.f)) : 0.f;
      const float dn = response_[static_cast<int>(root * (kResponseSize - 1))] +
                       read * noise_table_[(k + second) & mask];
      k = (k + stride) & mask;
      px[u] = static_cast<uchar>(std::max(0.f, std::min(255.f, dn)));
    }
  }
  return image;
}

cv::Vec4d rotationToQuaternion(const cv::Matx33d& R) {
  // Shepperd's method: pick the largest of w, x, y, z for stability.
  const double tr = R(0, 0) + R(1, 1) + R(2, 2);
  double x, y, z, w;
  if (tr > 0) {
    const double s = std::sqrt(tr + 1.0) * 2;
    w = 0.25 * s;
    x = (R(2, 1) - R(1, 2)) / s;
    y = (R(0, 2) - R(2, 0)) / s;
    z = (R(1, 0) - R(0, 1)) / s;
  } else if (R(0, 0) > R(1, 1) && R(0, 0) > R(2, 2)) {
    const double s = std::sqrt(1.0 + R(0, 0) - R(1, 1) - R(2, 2)) * 2;
    w = (R(2, 1) - R(1, 2)) / s;
    x = 0.25 * s;
    y = (R(0, 1) + R(1, 0)) / s;
    z = (R(0, 2) + R(2, 0)) / s;
  } else if (R(1, 1) > R(2, 2)) {
    const double s = std::sqrt(1.0 + R(1, 1) - R(0, 0) - R(2, 2)) * 2;
    w = (R(0, 2) - R(2, 0)) / s;
    x = (R(0, 1) + R(1, 0)) / s;
    y = 0.25 * s;
    z = (R(1, 2) + R(2, 1)) / s;
  } else {
    const double s = std::sqrt(1.0 + R(2, 2) - R(0, 0) - R(1, 1)) * 2;
    w = (R(1, 0) - R(0, 1)) / s;
    x = (R(0, 2) + R(2, 0)) / s;
    y = (R(1, 2) + R(2, 1)) / s;
    z = 0.25 * s;
  }
  cv::Vec4d q(x, y, z, w);
  q /= cv::norm(q);
  if (q[3] < 0) q = -q;
  return q;
}

}  // namespace pipe_sim
}  // namespace bowg
