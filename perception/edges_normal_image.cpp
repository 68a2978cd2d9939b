#include "perception/edges_normal_image.hpp"

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>

namespace stairs {

namespace {

const float kDeg = static_cast<float>(M_PI) / 180.0f;

// Lengths are configured in px at 640x480; the grid has 640 / grid_cell_px
// columns at every resolution.
int to_cells(float px_640, int grid_cell_px_640) {
  return std::max(1, static_cast<int>(std::lround(px_640 / grid_cell_px_640)));
}

// Thesis eq. 3.7: each component of the gravity-aligned normal, [-1, 1] ->
// [0, 255], so that treads, risers and walls keep their colours whatever the
// camera pose. `unmeasured` marks the cells without a normal.
void draw_normal_image(const NormalGrid& g, const Eigen::Matrix3f& R, cv::Mat& colour, cv::Mat& unmeasured) {
  colour.create(g.height, g.width, CV_8UC3);
  unmeasured.create(g.height, g.width, CV_8U);
  for (int gy = 0; gy < g.height; ++gy) {
    cv::Vec3b* c = colour.ptr<cv::Vec3b>(gy);
    uint8_t* u = unmeasured.ptr<uint8_t>(gy);
    for (int gx = 0; gx < g.width; ++gx) {
      const int i = g.index(gx, gy);
      u[gx] = g.has_normal[i] ? 0 : 255;
      const Eigen::Vector3f n = g.has_normal[i] ? Eigen::Vector3f(R * g.normals[i]) : -Eigen::Vector3f::Ones();
      for (int k = 0; k < 3; ++k) c[gx][k] = cv::saturate_cast<uint8_t>((n[k] + 1.0f) * 127.5f);
    }
  }
}

// Canny edges of the normal image that outline bends: those within a cell of
// an unmeasured cell outline holes and depth jumps and are dropped. Only edge
// curves (contours) spanning normal_edge_min_contour_px are kept: the thesis
// cleans the Hough input of short noise edges this way.
cv::Mat bend_edges(const cv::Mat& colour, const cv::Mat& unmeasured, const NormalImageEdgesConfig& cfg,
                   int grid_cell_px_640) {
  cv::Mat blurred, edges, near_hole;
  const int blur = 2 * cfg.blur_cells + 1;
  cv::GaussianBlur(colour, blurred, cv::Size(blur, blur), 0);
  cv::Canny(blurred, edges, cfg.canny_low, cfg.canny_high);
  cv::dilate(unmeasured, near_hole, cv::Mat());
  edges.setTo(0, near_hole);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(edges, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
  const int min_span = to_cells(cfg.min_contour_px, grid_cell_px_640);
  cv::Mat kept = cv::Mat::zeros(edges.size(), CV_8U);
  for (size_t i = 0; i < contours.size(); ++i) {
    const cv::Rect box = cv::boundingRect(contours[i]);
    if (std::max(box.width, box.height) >= min_span) cv::drawContours(kept, contours, static_cast<int>(i), 255);
  }
  return kept;
}

bool horizontal_across(const Eigen::Vector3f& dir, const Eigen::Vector3f& axis, const NormalImageEdgesConfig& cfg) {
  return std::abs(dir.z()) <= std::sin(cfg.max_tilt_deg * kDeg) &&
         std::abs(dir.dot(axis)) <= std::sin(cfg.max_axis_deg * kDeg);
}

// The cells under one or more Hough segments and where their two surfaces meet.
struct Line {
  EdgeType type = EdgeType::Unknown;
  std::vector<Eigen::Vector3f> points;  // of the cells under the segments, gravity-aligned frame
  std::vector<Eigen::Vector2f> px;      // their image positions
  Eigen::Vector3f meet_sum = Eigen::Vector3f::Zero();  // a point on both surfaces, times points.size()
  Edge edge;                                           // fitted
  float theta_deg = 0, s = 0, z = 0;  // merge keys: direction from the lateral axis (deg), horizontal
                                      // distance of the line from the camera, height of its middle (m)
};

// The edge: along the cells (their principal direction), through the point
// where the surfaces meet, spanning the cells' projections.
void fit(Line& l, const Eigen::Vector3f& axis, int cell_px) {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  for (const Eigen::Vector3f& p : l.points) centre += p;
  centre /= static_cast<float>(l.points.size());
  Eigen::Matrix3f scatter = Eigen::Matrix3f::Zero();
  for (const Eigen::Vector3f& p : l.points) scatter += (p - centre) * (p - centre).transpose();
  const Eigen::Vector3f lateral(-axis.y(), axis.x(), 0.0f);
  Eigen::Vector3f dir = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f>(scatter).eigenvectors().col(2);
  if (dir.dot(lateral) < 0) dir = -dir;
  const Eigen::Vector3f meet = l.meet_sum / static_cast<float>(l.points.size());
  size_t lo = 0, hi = 0;
  std::vector<float> t(l.points.size());
  for (size_t i = 0; i < t.size(); ++i) {
    t[i] = (l.points[i] - meet).dot(dir);
    if (t[i] < t[lo]) lo = i;
    if (t[i] > t[hi]) hi = i;
  }
  l.edge.type = l.type;
  l.edge.source = EdgeSource::NormalImage;
  l.edge.start = meet + t[lo] * dir;
  l.edge.end = meet + t[hi] * dir;
  l.edge.start_px = l.px[lo];
  l.edge.end_px = l.px[hi];
  l.edge.support = static_cast<int>(l.points.size()) * cell_px;
  const Eigen::Vector3f mid = 0.5f * (l.edge.start + l.edge.end);
  l.theta_deg = std::atan2(dir.dot(axis), dir.dot(lateral)) / kDeg;
  l.s = (mid.x() * dir.y() - mid.y() * dir.x()) / dir.head<2>().norm();
  l.z = mid.z();
}

// The step edge under a Hough segment: the meet of the surfaces in the strips on either side, its
// extent from the cells under it. Nothing unless both sides are measured, bend, and the edge is level.
std::optional<Line> back_project(const NormalGrid& g, const Eigen::Matrix3f& R, const cv::Vec4i& seg,
                                 const Eigen::Vector3f& axis, const NormalImageEdgesConfig& cfg) {
  const Eigen::Vector2f a(seg[0], seg[1]), b(seg[2], seg[3]);
  const float len = (b - a).norm();
  if (!(len > 0)) return std::nullopt;
  const Eigen::Vector2f across = Eigen::Vector2f(a.y() - b.y(), b.x() - a.x()) / len;
  auto cell_at = [&](const Eigen::Vector2f& q) {
    const int gx = static_cast<int>(std::lround(q.x())), gy = static_cast<int>(std::lround(q.y()));
    return gx < 0 || gy < 0 || gx >= g.width || gy >= g.height ? -1 : g.index(gx, gy);
  };
  Line l;
  std::array<std::vector<int>, 2> side_cells;
  const float cell = static_cast<float>(g.cell_px);
  const int samples = static_cast<int>(std::ceil(len)) + 1;
  for (int i = 0; i < samples; ++i) {
    const Eigen::Vector2f q = a + (b - a) * (static_cast<float>(i) / static_cast<float>(samples - 1));
    const int c = cell_at(q);
    if (c >= 0 && g.has_point[c]) {
      l.points.push_back(R * g.points[c]);
      l.px.push_back(q * cell + Eigen::Vector2f::Constant(0.5f * cell));
    }
    for (int side = 0; side < 2; ++side)
      for (int k = 1; k <= cfg.side_cells; ++k) {
        const int n = cell_at(q + static_cast<float>(side ? -k : k) * across);
        if (n >= 0 && g.has_normal[n]) side_cells[side].push_back(n);
      }
  }
  if (side_cells[0].empty() || side_cells[1].empty() || l.points.size() < 2) return std::nullopt;
  // Mean normal and point of each side; then again without the cells closer
  // to the other side's normal: where the segment strays from the edge by a
  // cell, or a surface is thin, a strip reaches across.
  std::array<Eigen::Vector3f, 2> normal, point;
  for (int pass = 0; pass < 2; ++pass) {
    std::array<Eigen::Vector3f, 2> n_sum{Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()};
    std::array<Eigen::Vector3f, 2> p_sum = n_sum;
    std::array<int, 2> count{0, 0};
    for (int side = 0; side < 2; ++side)
      for (int c : side_cells[side]) {
        const Eigen::Vector3f n = R * g.normals[c];
        if (pass == 1 && n.dot(normal[side]) < n.dot(normal[1 - side])) continue;
        n_sum[side] += n;
        p_sum[side] += R * g.points[c];
        ++count[side];
      }
    if (count[0] == 0 || count[1] == 0) return std::nullopt;
    for (int side = 0; side < 2; ++side) {
      normal[side] = n_sum[side].normalized();
      point[side] = p_sum[side] / static_cast<float>(count[side]);
    }
  }
  const Eigen::Vector3f &n0 = normal[0], &n1 = normal[1], &p0 = point[0], &p1 = point[1];
  const float cos_bend = n0.dot(n1);
  if (cos_bend > std::cos(cfg.min_bend_deg * kDeg) ||
      !horizontal_across(n0.cross(n1).normalized(), axis, cfg))
    return std::nullopt;
  // Convex when each side lies behind the other's surface (normals face the
  // camera, i.e. free space): tread above a riser; concave at a riser's foot.
  l.type = (p0 - p1).dot(n1 - n0) < 0 ? EdgeType::Convex : EdgeType::Concave;
  // The point on both planes nearest the cells' centre: centre + u n0 + v n1.
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  for (const Eigen::Vector3f& p : l.points) centre += p;
  centre /= static_cast<float>(l.points.size());
  const float r0 = n0.dot(p0 - centre), r1 = n1.dot(p1 - centre), det = 1 - cos_bend * cos_bend;
  const Eigen::Vector3f meet = centre + (r0 - cos_bend * r1) / det * n0 + (r1 - cos_bend * r0) / det * n1;
  l.meet_sum = meet * static_cast<float>(l.points.size());
  fit(l, axis, g.cell_px);
  const Eigen::Vector3f dir = (l.edge.end - l.edge.start).normalized();
  if (!horizontal_across(dir, axis, cfg) || meet.norm() > cfg.max_range_m) return std::nullopt;
  return l;
}

void absorb(Line& into, const Line& other) {
  into.points.insert(into.points.end(), other.points.begin(), other.points.end());
  into.px.insert(into.px.end(), other.px.begin(), other.px.end());
  into.meet_sum += other.meet_sum;
}

// Thesis 3.4.1 "merge lines that are close and with similar orientation": strongest first, a line joins
// a kept line within a bin in type, direction, distance and height; keys stay the kept line's (no chaining).
std::vector<Line> merge_lines(std::vector<Line> lines, const Eigen::Vector3f& axis, int cell_px,
                              const NormalImageEdgesConfig& cfg) {
  auto by_support = [](const Line& a, const Line& b) { return a.edge.support > b.edge.support; };
  std::sort(lines.begin(), lines.end(), by_support);
  const float bin_deg = cfg.merge_bin_deg, bin_m = cfg.merge_bin_m;
  auto bin = [](float v, float size) { return static_cast<int>(std::floor(v / size)); };
  std::map<std::array<int, 4>, std::vector<size_t>> bins;  // kept lines by bin
  std::vector<Line> kept;
  for (Line& l : lines) {
    const std::array<int, 4> key{static_cast<int>(l.type), bin(l.theta_deg, bin_deg), bin(l.s, bin_m),
                                 bin(l.z, bin_m)};
    size_t into = kept.size();
    for (int dt = -1; dt <= 1; ++dt)
      for (int ds = -1; ds <= 1; ++ds)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = bins.find({key[0], key[1] + dt, key[2] + ds, key[3] + dz});
          if (it == bins.end()) continue;
          for (size_t k : it->second)
            if (k < into && std::abs(kept[k].theta_deg - l.theta_deg) < bin_deg &&
                std::abs(kept[k].s - l.s) < bin_m && std::abs(kept[k].z - l.z) < bin_m)
              into = k;
        }
    if (into < kept.size()) {
      absorb(kept[into], l);
    } else {
      bins[key].push_back(kept.size());
      kept.push_back(std::move(l));
    }
  }
  for (Line& l : kept) fit(l, axis, cell_px);
  std::sort(kept.begin(), kept.end(), by_support);
  return kept;
}

}  // namespace

std::vector<Edge> normal_image_edges(const NormalGrid& g, const Eigen::Matrix3f& R, float yaw_rad,
                                     const NormalImageEdgesConfig& cfg, int grid_cell_px_640, float min_length_m) {
  if (g.width < 3 || g.height < 3) return {};
  cv::Mat colour, unmeasured;
  draw_normal_image(g, R, colour, unmeasured);
  const cv::Mat edges = bend_edges(colour, unmeasured, cfg, grid_cell_px_640);
  std::vector<cv::Vec4i> segments;
  // rho resolution: one cell, the normal image's resolution.
  cv::HoughLinesP(edges, segments, 1.0, cfg.hough_theta_deg * kDeg,
                  to_cells(cfg.hough_votes_px, grid_cell_px_640), to_cells(cfg.hough_min_length_px, grid_cell_px_640),
                  to_cells(cfg.hough_max_gap_px, grid_cell_px_640));
  const Eigen::Vector3f axis(std::cos(yaw_rad), std::sin(yaw_rad), 0.0f);
  std::vector<Line> lines;
  for (const cv::Vec4i& seg : segments)
    if (std::optional<Line> l = back_project(g, R, seg, axis, cfg)) lines.push_back(std::move(*l));
  std::vector<Edge> out;
  for (const Line& l : merge_lines(std::move(lines), axis, g.cell_px, cfg))
    if ((l.edge.end - l.edge.start).norm() >= min_length_m) out.push_back(l.edge);
  return out;
}

}  // namespace stairs
