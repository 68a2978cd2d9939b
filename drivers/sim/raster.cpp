#include "drivers/sim/raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stairs::sim {
namespace {

using V = Eigen::Vector3d;

// Sutherland-Hodgman clip of a convex polygon (camera frame) against z >= near.
int clip_near(const V* in, int n, V* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const V& a = in[i];
    const V& b = in[(i + 1) % n];
    const bool a_in = a.z() >= kNearPlane_m, b_in = b.z() >= kNearPlane_m;
    if (a_in) out[m++] = a;
    if (a_in != b_in) out[m++] = a + (b - a) * ((kNearPlane_m - a.z()) / (b.z() - a.z()));
  }
  return m;
}

// Scan-converts a front-facing planar polygon (camera frame) whose plane is
// n.X = d (d < 0). Pixel centres sit at integer (u, v); a pixel belongs to the
// polygon when its centre lies in [left, right) x [top, bottom), so faces that
// share an edge neither overlap nor leave a gap.
void fill_polygon(const V* poly, int count, const V& n, double d, const Intrinsics& K, int32_t id, ZBuffer& zb) {
  double u[8], v[8];
  double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
  for (int i = 0; i < count; ++i) {
    u[i] = K.fx * poly[i].x() / poly[i].z() + K.cx;
    v[i] = K.fy * poly[i].y() / poly[i].z() + K.cy;
    vmin = std::min(vmin, v[i]);
    vmax = std::max(vmax, v[i]);
  }
  const int r0 = std::max(0, static_cast<int>(std::ceil(vmin)));
  const int r1 = std::min(zb.height - 1, static_cast<int>(std::ceil(vmax)) - 1);
  // 1/z = (n . ray) / d with ray = ((u - cx)/fx, (v - cy)/fy, 1): affine in u and v.
  const double a_u = n.x() / (K.fx * d);
  for (int r = r0; r <= r1; ++r) {
    double xl = std::numeric_limits<double>::infinity(), xr = -xl;
    for (int i = 0; i < count; ++i) {
      const int j = (i + 1) % count;
      if ((v[i] <= r && v[j] > r) || (v[j] <= r && v[i] > r)) {
        const double x = u[i] + (r - v[i]) * (u[j] - u[i]) / (v[j] - v[i]);
        xl = std::min(xl, x);
        xr = std::max(xr, x);
      }
    }
    if (!(xl < xr)) continue;
    const int c0 = std::max(0, static_cast<int>(std::ceil(xl)));
    const int c1 = std::min(zb.width - 1, static_cast<int>(std::ceil(xr)) - 1);
    const double row = (n.y() * (r - K.cy) / K.fy + n.z()) / d - a_u * K.cx;
    float* z = zb.inv_z.data() + static_cast<size_t>(r) * zb.width;
    int32_t* ids = zb.id.data() + static_cast<size_t>(r) * zb.width;
    for (int c = c0; c <= c1; ++c) {
      const float iz = static_cast<float>(a_u * c + row);
      if (iz > z[c]) {
        z[c] = iz;
        ids[c] = id;
      }
    }
  }
}

// Depth (= ray parameter, as the ray's z is 1) of the first hit of ray r with
// a capped cylinder in the camera frame; infinity if none.
double cylinder_hit(const V& r, const V& base, const V& axis, double length, double radius) {
  const V w = -base;
  const double wa = w.dot(axis), ra = r.dot(axis);
  const V wp = w - wa * axis, rp = r - ra * axis;
  double best = std::numeric_limits<double>::infinity();
  const double A = rp.squaredNorm(), B = 2.0 * wp.dot(rp), C = wp.squaredNorm() - radius * radius;
  const double disc = B * B - 4.0 * A * C;
  if (A > 1e-12 && disc >= 0.0) {
    const double t = (-B - std::sqrt(disc)) / (2.0 * A);
    const double h = wa + t * ra;
    if (t > kNearPlane_m && h >= 0.0 && h <= length) best = t;
  }
  if (std::abs(ra) > 1e-12) {
    for (double cap : {0.0, length}) {
      const double t = (cap - wa) / ra;
      if (t > kNearPlane_m && t < best && (wp + t * rp).squaredNorm() <= radius * radius) best = t;
    }
  }
  return best;
}

void fill_cylinder(const Cylinder& c, const Eigen::Isometry3d& stair_to_cam, const Intrinsics& K, int32_t id,
                   ZBuffer& zb) {
  const V base = stair_to_cam * c.base_m;
  const V axis = stair_to_cam.linear() * c.axis;
  // Screen bounding box of the cylinder's bounding box; the whole image when
  // part of it is behind the near plane.
  const V e1 = axis.unitOrthogonal() * c.radius_m, e2 = axis.cross(e1);
  int u0 = 0, u1 = zb.width - 1, v0 = 0, v1 = zb.height - 1;
  double umin = 1e18, umax = -1e18, vmin = 1e18, vmax = -1e18;
  bool behind = false;
  for (double h : {0.0, c.length_m})
    for (double s1 : {-1.0, 1.0})
      for (double s2 : {-1.0, 1.0}) {
        const V p = base + h * axis + s1 * e1 + s2 * e2;
        if (p.z() < kNearPlane_m) {
          behind = true;
          continue;
        }
        const double u = K.fx * p.x() / p.z() + K.cx, v = K.fy * p.y() / p.z() + K.cy;
        umin = std::min(umin, u), umax = std::max(umax, u), vmin = std::min(vmin, v), vmax = std::max(vmax, v);
      }
  if (!behind) {
    u0 = std::max(u0, static_cast<int>(std::floor(umin)));
    u1 = std::min(u1, static_cast<int>(std::ceil(umax)));
    v0 = std::max(v0, static_cast<int>(std::floor(vmin)));
    v1 = std::min(v1, static_cast<int>(std::ceil(vmax)));
  }
  for (int v = v0; v <= v1; ++v) {
    for (int u = u0; u <= u1; ++u) {
      const V r((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      const double t = cylinder_hit(r, base, axis, c.length_m, c.radius_m);
      if (!std::isfinite(t)) continue;
      const size_t i = static_cast<size_t>(v) * zb.width + u;
      const float iz = static_cast<float>(1.0 / t);
      if (iz > zb.inv_z[i]) {
        zb.inv_z[i] = iz;
        zb.id[i] = id;
      }
    }
  }
}

}  // namespace

void ZBuffer::reset(int w, int h) {
  width = w;
  height = h;
  inv_z.assign(static_cast<size_t>(w) * h, 0.0f);
  id.assign(static_cast<size_t>(w) * h, -1);
}

void rasterise(const Geometry& g, const Eigen::Isometry3d& camera_in_stair, const Intrinsics& K, ZBuffer& zb) {
  zb.reset(K.width, K.height);
  const Eigen::Isometry3d stair_to_cam = camera_in_stair.inverse();
  V cam[4], clipped[8];
  for (size_t f = 0; f < g.faces.size(); ++f) {
    const Face& face = g.faces[f];
    for (int i = 0; i < 4; ++i) cam[i] = stair_to_cam * face.corners_m[i];
    const V n = stair_to_cam.linear() * face.normal;
    const double d = n.dot(cam[0]);
    if (d >= 0.0) continue;  // back-facing (or seen edge-on)
    const int count = clip_near(cam, 4, clipped);
    if (count >= 3) fill_polygon(clipped, count, n, d, K, static_cast<int32_t>(f), zb);
  }
  for (size_t c = 0; c < g.cylinders.size(); ++c)
    fill_cylinder(g.cylinders[c], stair_to_cam, K, static_cast<int32_t>(g.faces.size() + c), zb);
}

Eigen::Vector3d primitive_normal(const Geometry& g, int32_t id, const Eigen::Vector3d& p) {
  if (id < static_cast<int32_t>(g.faces.size())) return g.faces[static_cast<size_t>(id)].normal;
  const Cylinder& c = g.cylinders[static_cast<size_t>(id) - g.faces.size()];
  const V q = p - c.base_m;
  const double h = q.dot(c.axis);
  const V radial = q - h * c.axis;
  if (radial.norm() < c.radius_m * 0.999) return h < 0.5 * c.length_m ? V(-c.axis) : V(c.axis);
  return radial.normalized();
}

}  // namespace stairs::sim
