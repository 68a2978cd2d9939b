#include "drivers/sim/geometry.hpp"

#include <algorithm>

namespace stairs::sim {
namespace {

using V = Eigen::Vector3d;

// Half the stair width and the room's lateral bounds: a side wall stands at the
// stair's edge, an open side leaves floor out to the room wall.
struct Sides {
  double w, y_left, y_right;
  bool left_wall, right_wall;
};

Sides sides(const Scene& s) {
  const double w = 0.5 * s.width_m;
  const bool left_wall = s.walls == Walls::Left || s.walls == Walls::Both;
  const bool right_wall = s.walls == Walls::Right || s.walls == Walls::Both;
  return {w, left_wall ? w : 0.5 * s.room_width_m, right_wall ? -w : -0.5 * s.room_width_m, left_wall, right_wall};
}

struct Builder {
  std::vector<Face>& faces;

  void add(V a, V b, V c, V d, V normal, int step = -1, FacePart part = FacePart::Other) {
    faces.push_back({{a, b, c, d}, normal, step, part});
  }
  // Rectangles in an axis plane; sign = direction of the outward normal. Empty ones are skipped.
  void x_face(double x, double y0, double y1, double z0, double z1, double sign, int step = -1,
              FacePart part = FacePart::Other) {
    if (y1 - y0 <= 1e-9 || z1 - z0 <= 1e-9) return;
    add({x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}, {sign, 0, 0}, step, part);
  }
  void y_face(double y, double x0, double x1, double z0, double z1, double sign) {
    if (x1 - x0 <= 1e-9 || z1 - z0 <= 1e-9) return;
    add({x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}, {0, sign, 0});
  }
  void z_face(double z, double x0, double x1, double y0, double y1, double sign, int step = -1,
              FacePart part = FacePart::Other) {
    if (x1 - x0 <= 1e-9 || y1 - y0 <= 1e-9) return;
    add({x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}, {0, 0, sign}, step, part);
  }
  void box(const Box& b) {
    const V& lo = b.min_m;
    const V& hi = b.max_m;
    x_face(lo.x(), lo.y(), hi.y(), lo.z(), hi.z(), -1);
    x_face(hi.x(), lo.y(), hi.y(), lo.z(), hi.z(), +1);
    y_face(lo.y(), lo.x(), hi.x(), lo.z(), hi.z(), -1);
    y_face(hi.y(), lo.x(), hi.x(), lo.z(), hi.z(), +1);
    z_face(lo.z(), lo.x(), hi.x(), lo.y(), hi.y(), -1);
    z_face(hi.z(), lo.x(), hi.x(), lo.y(), hi.y(), +1);
  }
  // The room around a flight or ramp that ends at x = end_x, top_z high: the
  // floor before it and beside it where a side is open, the end and side walls,
  // and the back wall above the top when there is one.
  void flight_room(const Scene& s, const Sides& sd, double end_x, double top_z, double wall_top) {
    z_face(0.0, -s.floor_length_m, 0.0, sd.y_right, sd.y_left, +1);
    z_face(0.0, 0.0, end_x, sd.w, sd.y_left, +1);
    z_face(0.0, 0.0, end_x, sd.y_right, -sd.w, +1);
    x_face(-s.floor_length_m, sd.y_right, sd.y_left, 0.0, wall_top, +1);
    y_face(sd.y_left, -s.floor_length_m, end_x, 0.0, wall_top, -1);
    y_face(sd.y_right, -s.floor_length_m, end_x, 0.0, wall_top, +1);
    if (s.back_wall) x_face(end_x, sd.y_right, sd.y_left, top_z, wall_top, -1);
  }
  // The room around everything: floor from x0 to x1 (z = 0), walls at its ends
  // and sides, all facing inwards.
  void room(double x0, double x1, double y_right, double y_left, double z_top, bool far_wall) {
    z_face(0.0, x0, x1, y_right, y_left, +1);
    x_face(x0, y_right, y_left, 0.0, z_top, +1);
    if (far_wall) x_face(x1, y_right, y_left, 0.0, z_top, -1);
    y_face(y_left, x0, x1, 0.0, z_top, -1);
    y_face(y_right, x0, x1, 0.0, z_top, +1);
  }
};

void build_stairs(const Scene& s, Builder& b) {
  const std::vector<StepGeometry> steps = step_geometry(s);
  const Sides sd = sides(s);
  const double w = sd.w;
  const bool left_wall = sd.left_wall, right_wall = sd.right_wall;
  const double end_x = steps.back().end_x_m;
  const double top_z = steps.back().top_z_m;
  const double wall_top = top_z + s.wall_height_m;

  b.flight_room(s, sd, end_x, top_z, wall_top);

  const double n = s.nosing_m;
  for (size_t i = 0; i < steps.size(); ++i) {
    const StepGeometry& g = steps[i];
    const int k = static_cast<int>(i);
    if (s.open_risers && g.landing) {  // solid, its front and back faces down to the floor under the slabs
      b.x_face(g.riser_x_m, -w, w, 0.0, g.bottom_z_m, -1);
      if (i + 1 < steps.size()) b.x_face(g.end_x_m, -w, w, 0.0, g.top_z_m, +1);
    }
    // An open step is its tread slab alone, on nothing: no riser below it, the floor beneath it.
    const bool open = s.open_risers && !g.landing;
    const double t =
        n > 0.0 || open ? std::min(s.nosing_thickness_m, 0.5 * (g.top_z_m - g.bottom_z_m)) : 0.0;
    if (!open) b.x_face(g.riser_x_m, -w, w, g.bottom_z_m, g.top_z_m - t, -1, k, FacePart::Riser);
    b.z_face(g.top_z_m, g.riser_x_m - n, g.end_x_m, -w, w, +1, k, FacePart::Tread);
    if (t > 0.0) {  // the tread slab's front (the step's edge), underside and sides where it stands free:
                    // the overhang before the riser, or the whole slab of an open step
      const double slab_end = open ? g.end_x_m : g.riser_x_m;
      b.x_face(g.riser_x_m - n, -w, w, g.top_z_m - t, g.top_z_m, -1, k, FacePart::Riser);
      b.z_face(g.top_z_m - t, g.riser_x_m - n, slab_end, -w, w, -1);
      if (!left_wall) b.y_face(w, g.riser_x_m - n, slab_end, g.top_z_m - t, g.top_z_m, +1);
      if (!right_wall) b.y_face(-w, g.riser_x_m - n, slab_end, g.top_z_m - t, g.top_z_m, -1);
    }
    if (open) {
      b.z_face(0.0, g.riser_x_m, g.end_x_m, -w, w, +1);  // the floor beneath it
    } else {  // the stair is solid down to the floor: its sides show where a side is open
      if (!left_wall) b.y_face(w, g.riser_x_m, g.end_x_m, 0.0, g.top_z_m, +1);
      if (!right_wall) b.y_face(-w, g.riser_x_m, g.end_x_m, 0.0, g.top_z_m, -1);
    }
  }
  if (!s.back_wall) b.x_face(end_x, -w, w, 0.0, top_z, +1);
}

void build_ramp(const Scene& s, Builder& b) {
  const Sides sd = sides(s);
  const double w = sd.w;
  const bool left_wall = sd.left_wall, right_wall = sd.right_wall;
  const double L = s.ramp_length_m, H = s.ramp_height_m;
  const double end_x = L + s.ramp_landing_m;
  const double wall_top = H + s.wall_height_m;
  b.flight_room(s, sd, end_x, H, wall_top);
  if (!s.back_wall) b.x_face(end_x, -w, w, 0.0, H, +1);
  b.add({0, -w, 0}, {L, -w, H}, {L, w, H}, {0, w, 0}, V(-H, 0, L).normalized());
  b.z_face(H, L, end_x, -w, w, +1);
  for (double side : {+1.0, -1.0}) {
    if ((side > 0 && left_wall) || (side < 0 && right_wall)) continue;
    const double y = side * w;
    b.add({0, y, 0}, {L, y, 0}, {L, y, H}, {L, y, H}, {0, side, 0});  // a triangle
    b.y_face(y, L, end_x, 0.0, H, side);
  }
}

}  // namespace

Geometry build_geometry(const Scene& s) {
  Geometry g;
  Builder b{g.faces};
  switch (s.kind) {
    case SceneKind::Stairs: build_stairs(s, b); break;
    case SceneKind::Ramp: build_ramp(s, b); break;
    case SceneKind::FlatRoom:
      b.room(-s.floor_length_m, s.flat_length_m, -0.5 * s.room_width_m, 0.5 * s.room_width_m, s.wall_height_m, true);
      break;
  }
  for (const Box& box : s.boxes) b.box(box);
  g.cylinders = s.cylinders;
  return g;
}

}  // namespace stairs::sim
