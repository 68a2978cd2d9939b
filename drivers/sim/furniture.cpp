#include "drivers/sim/furniture.hpp"

#include "drivers/sim/rng.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <stdexcept>

namespace stairs::sim {

namespace {

constexpr double kNear_m = 3.5;  // x of the furniture's nearest face; the walk runs from 0 to kNear_m - 0.8

// Sizes drawn uniformly from [lo, hi]; seed 0 gives the middle of each range.
class Sizes {
 public:
  explicit Sizes(uint64_t seed) : rng_(seed * 0x2545f4914f6cdd1dULL + 1), nominal_(seed == 0) {}
  double operator()(double lo, double hi) { return nominal_ ? 0.5 * (lo + hi) : lo + (hi - lo) * rng_.uniform(); }

 private:
  Rng rng_;
  bool nominal_;
};

struct Builder {
  Scene& s;
  void box(double x0, double y0, double z0, double x1, double y1, double z1) {
    s.boxes.push_back({{x0, y0, z0}, {x1, y1, z1}});
  }
  // Four legs of side `leg` under a top spanning [x0, x1] x [y0, y1] up to z.
  void legs(double x0, double y0, double x1, double y1, double z, double leg) {
    for (double x : {x0, x1 - leg})
      for (double y : {y0, y1 - leg}) box(x, y, 0.0, x + leg, y + leg, z);
  }
  // Table or stool top of thickness 0.03 m at height h, with legs.
  void table(double x0, double y0, double x1, double y1, double h, double leg = 0.05) {
    box(x0, y0, h - 0.03, x1, y1, h);
    legs(x0 + 0.02, y0 + 0.02, x1 - 0.02, y1 - 0.02, h - 0.03, leg);
  }
  // Chair with an open seat at height h; the back on the side `back` (+x far, -x near, +y/-y sides).
  void chair(double cx, double cy, double seat, double h, char back) {
    const double x0 = cx - 0.5 * seat, x1 = cx + 0.5 * seat, y0 = cy - 0.5 * seat, y1 = cy + 0.5 * seat;
    table(x0, y0, x1, y1, h, 0.035);
    const double t = 0.03, top = h + 0.45;
    switch (back) {
      case 'f': box(x1 - t, y0, h, x1, y1, top); break;
      case 'n': box(x0, y0, h, x0 + t, y1, top); break;
      case 'l': box(x0, y1 - t, h, x1, y1, top); break;
      default: box(x0, y0, h, x1, y0 + t, top); break;
    }
  }
};

Scene room(const std::string& name, double depth_m) {
  Scene s;
  s.name = name;
  s.kind = SceneKind::FlatRoom;
  s.walls = Walls::None;
  s.floor_length_m = 0.3;
  s.flat_length_m = kNear_m + depth_m + 1.2;
  s.room_width_m = 6.0;
  s.walk_end_m = kNear_m - 0.8;
  return s;
}

using Make = std::function<Scene(Sizes&)>;

// The table in two halves, each a function a reader can hold in their head.
void add_families_first(std::map<std::string, Make>& m) {
  m.insert({
      {"kitchen_table",  // table with chairs on every side, pulled out by different amounts
       [](Sizes& r) {
         const double d = r(0.7, 0.95), w = r(0.9, 1.6), h = r(0.70, 0.78), seat = r(0.38, 0.46), sh = r(0.42, 0.48);
         Scene s = room("kitchen_table", d + 0.6);
         Builder b{s};
         const double x0 = kNear_m + 0.5;
         b.table(x0, -0.5 * w, x0 + d, 0.5 * w, h);
         b.chair(x0 - r(0.05, 0.35), r(-0.25, 0.25) * w, seat, sh, 'n');  // near side, back to the camera
         b.chair(x0 + d + r(-0.1, 0.25), r(-0.25, 0.25) * w, seat, sh, 'f');
         b.chair(x0 + 0.5 * d, 0.5 * w + r(0.0, 0.25), seat, sh, 'l');
         b.chair(x0 + 0.5 * d, -0.5 * w - r(0.0, 0.25), seat, sh, 'r');
         // A second chair seen from its front, beside the table.
         b.chair(kNear_m + 0.2, 0.5 * w + r(0.5, 0.8), seat, sh, 'f');
         return s;
       }},
      {"sofa",  // sofa (seat, arms, back) behind a coffee table
       [](Sizes& r) {
         const double w = r(1.6, 2.4), seat = r(0.38, 0.46), arm = r(0.55, 0.68), back = r(0.75, 0.95), d = r(0.8, 1.0);
         Scene s = room("sofa", 1.0 + d);
         Builder b{s};
         const double ct = r(0.35, 0.48);
         b.table(kNear_m, -0.5, kNear_m + r(0.45, 0.6), 0.5, ct);
         const double x0 = kNear_m + 1.0;
         b.box(x0, -0.5 * w, 0.0, x0 + d, 0.5 * w, seat);
         b.box(x0 + d - 0.2, -0.5 * w, 0.0, x0 + d, 0.5 * w, back);
         b.box(x0, -0.5 * w - 0.2, 0.0, x0 + d, -0.5 * w, arm);
         b.box(x0, 0.5 * w, 0.0, x0 + d, 0.5 * w + 0.2, arm);
         return s;
       }},
      {"armchair",
       [](Sizes& r) {
         const double w = r(0.7, 0.95), seat = r(0.38, 0.46), arm = r(0.55, 0.68), back = r(0.8, 1.0), d = r(0.75, 0.9);
         Scene s = room("armchair", d);
         Builder b{s};
         const double x0 = kNear_m;
         b.box(x0, -0.5 * w + 0.15, 0.0, x0 + d, 0.5 * w - 0.15, seat);
         b.box(x0 + d - 0.2, -0.5 * w, 0.0, x0 + d, 0.5 * w, back);
         b.box(x0, -0.5 * w, 0.0, x0 + d, -0.5 * w + 0.15, arm);
         b.box(x0, 0.5 * w - 0.15, 0.0, x0 + d, 0.5 * w, arm);
         return s;
       }},
      {"bed",  // bed with a headboard and a nightstand beside it
       [](Sizes& r) {
         const double w = r(1.0, 1.8), h = r(0.42, 0.6), len = r(1.9, 2.1), ns = r(0.45, 0.65);
         Scene s = room("bed", len);
         Builder b{s};
         b.box(kNear_m, -0.5 * w, 0.0, kNear_m + len, 0.5 * w, h);
         b.box(kNear_m + len - 0.06, -0.5 * w, 0.0, kNear_m + len, 0.5 * w, h + r(0.3, 0.6));
         b.box(kNear_m + len - 0.45, 0.5 * w + 0.05, 0.0, kNear_m + len, 0.5 * w + 0.5, ns);
         return s;
       }},
      {"desk",  // desk on legs with an office chair (seat on a post) in front
       [](Sizes& r) {
         const double w = r(1.1, 1.6), d = r(0.6, 0.8), h = r(0.72, 0.76), sh = r(0.44, 0.55);
         Scene s = room("desk", d + 0.5);
         Builder b{s};
         const double x0 = kNear_m + 0.45;
         b.table(x0, -0.5 * w, x0 + d, 0.5 * w, h);
         const double cy = r(-0.3, 0.3) * w, cx = x0 - r(0.05, 0.3);
         b.box(cx - 0.23, cy - 0.23, sh - 0.06, cx + 0.23, cy + 0.23, sh);
         b.box(cx - 0.25, cy - 0.23, sh, cx - 0.21, cy + 0.23, sh + 0.5);  // back to the camera
         s.cylinders.push_back({{cx, cy, 0.05}, Eigen::Vector3d::UnitZ(), sh - 0.11, 0.03});
         b.box(cx - 0.3, cy - 0.3, 0.0, cx + 0.3, cy + 0.3, 0.05);  // base
         return s;
       }}});
}

void add_families_second(std::map<std::string, Make>& m) {
  m.insert({
      {"bookshelf",  // open shelves: boards every 0.3-0.4 m between two sides
       [](Sizes& r) {
         const double w = r(0.6, 1.0), d = r(0.25, 0.4), gap = r(0.28, 0.4), h = r(1.6, 2.0);
         Scene s = room("bookshelf", d);
         Builder b{s};
         const double x0 = kNear_m;
         b.box(x0, -0.5 * w, 0.0, x0 + d, -0.5 * w + 0.02, h);
         b.box(x0, 0.5 * w - 0.02, 0.0, x0 + d, 0.5 * w, h);
         b.box(x0 + d - 0.01, -0.5 * w, 0.0, x0 + d, 0.5 * w, h);
         for (double z = 0.08; z < h; z += gap) b.box(x0, -0.5 * w, z - 0.02, x0 + d, 0.5 * w, z);
         return s;
       }},
      {"boxes",  // stacked boxes, each smaller and set back on the one below
       [](Sizes& r) {
         const double h1 = r(0.3, 0.45), h2 = r(0.3, 0.45), w1 = r(0.5, 0.8), w2 = r(0.3, 0.5), d1 = r(0.4, 0.6);
         Scene s = room("boxes", d1);
         Builder b{s};
         b.box(kNear_m, -0.5 * w1, 0.0, kNear_m + d1, 0.5 * w1, h1);
         const double set = r(0.1, 0.25);
         b.box(kNear_m + set, -0.5 * w2, h1, kNear_m + d1, 0.5 * w2, h1 + h2);
         b.box(kNear_m + 0.1, 0.5 * w1 + 0.2, 0.0, kNear_m + 0.5, 0.5 * w1 + 0.6, r(0.25, 0.4));
         return s;
       }},
      {"counter_stools",  // kitchen counter with a recessed toe kick, bar stools in front
       [](Sizes& r) {
         const double h = r(0.88, 0.94), d = r(0.55, 0.65), w = r(1.8, 2.6), sh = r(0.62, 0.78);
         Scene s = room("counter_stools", d + 0.6);
         Builder b{s};
         const double x0 = kNear_m + 0.6;
         b.box(x0 + 0.07, -0.5 * w, 0.0, x0 + d, 0.5 * w, 0.1);
         b.box(x0, -0.5 * w, 0.1, x0 + d, 0.5 * w, h);
         for (double y : {-0.5, 0.0, 0.5}) {
           const double cy = y * 0.8 * w / 1.2, cx = x0 - r(0.2, 0.4);
           b.box(cx - 0.18, cy - 0.18, sh - 0.05, cx + 0.18, cy + 0.18, sh);
           s.cylinders.push_back({{cx, cy, 0.0}, Eigen::Vector3d::UnitZ(), sh - 0.05, 0.025});
           b.box(cx - 0.15, cy - 0.15, r(0.2, 0.3), cx + 0.15, cy + 0.15, r(0.32, 0.34));  // foot ring
         }
         return s;
       }},
      {"bench",
       [](Sizes& r) {
         const double w = r(1.0, 1.8), d = r(0.3, 0.45), h = r(0.4, 0.48);
         Scene s = room("bench", d);
         Builder b{s};
         b.table(kNear_m, -0.5 * w, kNear_m + d, 0.5 * w, h, 0.06);
         return s;
       }},
      {"planter",  // a low wall or planter, solid to the floor
       [](Sizes& r) {
         const double w = r(1.0, 2.5), d = r(0.25, 0.5), h = r(0.35, 0.6);
         Scene s = room("planter", d);
         Builder b{s};
         b.box(kNear_m, -0.5 * w, 0.0, kNear_m + d, 0.5 * w, h);
         return s;
       }},
      {"tv_stand",  // a low solid stand with a flat screen set back on it
       [](Sizes& r) {
         const double w = r(1.2, 1.8), d = r(0.35, 0.45), h = r(0.4, 0.55);
         Scene s = room("tv_stand", d);
         Builder b{s};
         b.box(kNear_m, -0.5 * w, 0.0, kNear_m + d, 0.5 * w, h);
         b.box(kNear_m + 0.5 * d, -0.4 * w, h, kNear_m + 0.5 * d + 0.06, 0.4 * w, h + r(0.5, 0.7));
         return s;
       }}});
}

const std::map<std::string, Make>& families() {
  static const std::map<std::string, Make> m = [] {
    std::map<std::string, Make> t;
    add_families_first(t);
    add_families_second(t);
    return t;
  }();
  return m;
}

}  // namespace

std::vector<std::string> furniture_families() {
  std::vector<std::string> out;
  for (const auto& [name, make] : families()) out.push_back(name);
  return out;
}

bool is_furniture(const std::string& name) { return families().count(name) > 0; }

Scene furniture_scene(const std::string& family, uint64_t seed) {
  const auto it = families().find(family);
  if (it == families().end()) throw std::invalid_argument("unknown furniture family '" + family + "'");
  Sizes sizes(seed);
  return it->second(sizes);
}

void furnish_beside_flight(Scene& stair, const std::string& family, uint64_t seed) {
  constexpr double kBesideGap_m = 0.3;  // between the pieces and the flight: room to walk past, close enough to see
  if (stair.kind != SceneKind::Stairs) throw std::invalid_argument("furniture beside a flight needs a stairs scene");
  if (stair.walls == Walls::Left || stair.walls == Walls::Both)
    throw std::invalid_argument("furniture beside a flight needs its left side open (walls none or right)");
  const Scene f = furniture_scene(family, seed);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = Eigen::Vector3d::Constant(-1e9);
  for (const Box& b : f.boxes) lo = lo.cwiseMin(b.min_m), hi = hi.cwiseMax(b.max_m);
  for (const Cylinder& c : f.cylinders)
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(c.base_m), Eigen::Vector3d(c.base_m + c.length_m * c.axis)}) {
      lo = lo.cwiseMin(p - Eigen::Vector3d::Constant(c.radius_m));
      hi = hi.cwiseMax(p + Eigen::Vector3d::Constant(c.radius_m));
    }
  const Eigen::Vector3d shift(-kBesideGap_m - hi.x(), 0.5 * stair.width_m + kBesideGap_m - lo.y(), 0.0);
  for (Box b : f.boxes) {
    b.min_m += shift, b.max_m += shift;
    stair.boxes.push_back(b);
  }
  for (Cylinder c : f.cylinders) {
    c.base_m += shift;
    stair.cylinders.push_back(c);
  }
  // The room reaches past the pieces on the left as far as on the right: its walls stay out of their way.
  stair.room_width_m = std::max(stair.room_width_m, 2.0 * (hi.y() + shift.y() + 1.0));
}

}  // namespace stairs::sim
