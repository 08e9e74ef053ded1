// A deterministic scanline rasterizer with supersampling (tinyrenderer-sized).
//
// Samples: pixel (i, j) holds S×S samples at (i + (a + ½)/S, j + (b + ½)/S), a, b = 0…S−1, stored
// row-major over the whole image: sample row r = j·S + b, column c = i·S + a.
// Triangles are walked scanline by scanline over the sample rows they cover; each sample row's
// span comes from the edges, and the samples at the span ends are decided by exact edge
// functions evaluated in a canonical orientation (so two triangles sharing an edge compute the
// same value with opposite signs) with the top-left rule for samples exactly on an edge:
// watertight, no double hits. Depth: the smaller view depth wins; a tie keeps the earlier
// triangle (fixed traversal order). Attributes are interpolated perspective-correctly.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace oceanref {

// A vertex after projection: image position [pixels], view depth z > 0 [m].
struct ScreenVertex {
  double x, y, z;
};

struct SampleGrid {
  int width = 0;  // pixels
  int height = 0;
  int samples_per_axis = 1;  // S
  int columns() const { return width * samples_per_axis; }
  int rows() const { return height * samples_per_axis; }
  // The image position of a sample.
  double sample_x(int column) const { return (column + 0.5) / samples_per_axis; }
  double sample_y(int row) const { return (row + 0.5) / samples_per_axis; }
};

// What a sample saw: the nearest triangle and the perspective-correct barycentric weights of its
// three vertices (w_0 + w_1 + w_2 = 1); triangle < 0 if none.
struct Fragment {
  double depth = 0.0;
  std::int64_t triangle = -1;
  std::array<double, 3> weights{};
};

// The sample columns a fragment buffer holds: [first, first + count) of the grid's (count −1: to
// the end of the row).
struct FragmentColumns {
  int first = 0;
  int count = -1;
};

// Rasterizes triangles (vertex indices into `vertices`, in order) into the fragments of sample
// rows [first_row, last_row) of `fragments`, which holds the rows [fragment_row, fragment_row +
// fragments.size()/window columns) of the grid (fragment_row ≤ first_row), each the window's
// columns: disjoint row bands, or windows, can run on different threads, or in different
// processes, with identical results (a sample's fragment does not depend on the window).
// Triangles with a vertex at z ≤ near are skipped (the projected grid keeps the sea in front of
// the camera).
void rasterize(const std::vector<ScreenVertex>& vertices,
               const std::vector<std::array<std::uint32_t, 3>>& triangles, const SampleGrid& grid,
               int first_row, int last_row, double near, std::vector<Fragment>& fragments,
               int fragment_row = 0, FragmentColumns window = {});
// The same for the triangles triangles[i], i in `subset` (ascending: the order of a full pass,
// so that depth ties resolve the same way), e.g. those that reach a band (sample_rows_of).
void rasterize(const std::vector<ScreenVertex>& vertices,
               const std::vector<std::array<std::uint32_t, 3>>& triangles,
               const std::vector<std::uint32_t>& subset, const SampleGrid& grid, int first_row,
               int last_row, double near, std::vector<Fragment>& fragments, int fragment_row = 0,
               FragmentColumns window = {});

// The fragments of arbitrary image positions [pixels] (adaptive pixels' sample patterns,
// raster/pixel_pattern.h) against the triangles triangles[i], i in `subset` (ascending), by the
// same rules as rasterize: a point at a grid's sample position gets the fragment rasterize gives
// that sample. `fragments` (one per point) start empty (triangle −1).
void rasterize_points(const std::vector<ScreenVertex>& vertices,
                      const std::vector<std::array<std::uint32_t, 3>>& triangles,
                      const std::vector<std::uint32_t>& subset,
                      std::span<const std::array<double, 2>> points, double near,
                      std::span<Fragment> fragments);

// The sample rows [first, last) a triangle can cover (first ≥ last when none: a corner on or
// behind the near plane, its depth NaN, or its x or y not finite); rasterize writes no sample
// outside them.
std::pair<double, double> sample_rows_of(const ScreenVertex& a, const ScreenVertex& b,
                                         const ScreenVertex& c, const SampleGrid& grid,
                                         double near);

}  // namespace oceanref
