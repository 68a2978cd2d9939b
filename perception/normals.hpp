// Stage 1: organized grid of cell-mean points and their surface normals.
#pragma once

#include "common/types.hpp"
#include "perception/config.hpp"

#include <Eigen/Core>
#include <vector>

namespace stairs {

// A downsampled organized cloud in the camera optical frame: one point per
// cell of cell x cell pixels (mean of its valid pixels), NaN-free: `valid`
// says which cells hold a point and which a normal.
struct NormalGrid {
  int width = 0, height = 0;  // cells
  int cell_px = 1;            // pixels per cell side
  int margin_cells = 0;       // cells at each border without normals (the normal radius)
  std::vector<Eigen::Vector3f> points;   // m, optical frame
  std::vector<Eigen::Vector3f> normals;  // unit, pointing towards the camera
  std::vector<uint8_t> has_point, has_normal;
  // The point's surface fills the cell (cell_min_valid_fraction of its area, not only of its measured
  // pixels): where pixels are missing the point may stand for the surface behind the one they missed.
  std::vector<uint8_t> filled;
  int index(int gx, int gy) const { return gy * width + gx; }

  // Per-column and per-cell working rows of compute_normals, kept so that a
  // steady stream of frames allocates nothing.
  struct Scratch {
    std::vector<uint16_t> column_min, column_limit;
    std::vector<uint32_t> column_sum, column_count, column_row_sum;
    std::vector<uint16_t> cell_min, cell_limit;
    std::vector<float> x, y, z, iz;  // points and 1/z, struct-of-arrays (0: no point)
    std::vector<float> nx, ny, nz;   // normals, struct-of-arrays (0: no normal)
    std::vector<float> sx, sy, sz;   // smoothing sums
  } scratch;
};

// Cell side in pixels for a frame of the given width (grid_cell_px is for 640).
int grid_cell_px(const NormalsConfig& cfg, int image_width);

// Fills `grid` (its buffers are reused across frames).
void compute_normals(const DepthImage& frame, const NormalsConfig& cfg, NormalGrid& grid);

}  // namespace stairs
