// Triangle meshes from Wavefront OBJ files (the objects a scene places on the sea: buoys, hulls),
// read strictly: a file is either loaded exactly as written or refused with an ObjError that
// names the file and, when the fault is on one line, its 1-based line number.
//
// What a file may hold (everything else is refused):
// - Lines end at "\n", "\r\n" or a lone "\r"; a UTF-8 byte-order mark at the start is skipped.
//   Blank lines and comment lines (first non-blank character '#') are skipped; there are no
//   comments after a statement, and no "\" line continuations.
// - `v x y z`, optionally followed by a weight w or by a colour r g b (4 or 6 numbers in all):
//   decimal numbers as std::from_chars reads them (an optional leading '+'; no hexadecimal, no
//   thousands separators). x, y, z must be finite and within ±kMaxObjCoordinate; the optional
//   numbers must be finite and are otherwise ignored.
// - `f a b c …`: three or more corners, each `v`, `v/vt`, `v//vn` or `v/vt/vn` with nonzero
//   decimal integers. A positive v counts from the first vertex of the file (1 … the number of
//   `v` lines in the whole file); a negative v counts back from the last vertex above the line
//   (-1 is that vertex). vt and vn must be nonzero integers and are otherwise ignored.
// - Statements read but ignored (their arguments are not checked): `vt`, `vn`, `vp` (texture
//   coordinates, normals, parameter vertices), `o`, `g`, `s`, `mg` (names, groups, smoothing),
//   `usemtl`, `mtllib` (no material file is opened, so a missing .mtl does not matter), `l`, `p`
//   (lines and points have no surface) and the display attributes `bevel`, `c_interp`,
//   `d_interp`, `lod`, `usemap`, `maplib`, `shadow_obj`, `trace_obj`, `ctech`, `stech`.
// - Refused: free-form geometry (`cstype`, `deg`, `bmat`, `step`, `curv`, `curv2`, `surf`, `parm`,
//   `trim`, `hole`, `scrv`, `sp`, `end`, `con` — dropping it silently would lose a surface),
//   `call` and `csh`, and any other statement.
//
// Triangles: a face with n corners c0 … c(n-1) becomes the fan (c0, ck, ck+1), k = 1 … n-2, in
// the file's corner order, so it keeps the file's winding. A fan is right for convex polygons and
// for polygons star-shaped from their first corner; any other polygon — concave, or so warped
// that one fan triangle turns over — would fold, so a polygon of four or more corners is refused
// when one of its fan triangles faces against the polygon's normal (the sum of its fan
// triangles' normals) and that triangle's area is more than kObjFoldTolerance times the
// polygon's (smaller ones come from the rounding of the written coordinates — a corner on an
// edge, written with a few decimals — and are kept).
// Degenerate triangles: a triangle whose edge cross product is exactly zero in double arithmetic
// (a repeated corner, coincident or exactly collinear corners) has no area and no normal; it is
// dropped, so that a polygon with a corner on one of its edges (a T-junction) loads correctly. A
// file whose faces all have zero area is refused.
//
// Limits (below), checked in a counting pass over the bytes (a few comparisons a line) before
// anything in proportion to the mesh is allocated; the file size is checked before the file is
// read. Memory: the file's bytes, its longest line once more (tinyobjloader's line buffer), 24 B
// a vertex and at most 48 B a triangle — about 1.3 GiB for a file at every default limit.
//
// Parsing: the validator (obj_mesh.cpp) reads the numbers (correctly rounded, std::from_chars)
// and the indices. tinyobjloader (Debian's libtinyobjloader_double) parses the same bytes
// independently, and its vertex count and every face's vertex indices must equal the
// validator's; a difference is a bug here (PreconditionError, core/check.h). Its own numbers are
// not used: they are not correctly rounded ("0.3" becomes 0.30000000000000004) and depend on the
// platform's std::pow, which the determinism contract rules out (DESIGN.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace oceanref {

// A mesh in the OBJ's own units and axes (metres, +Y up).
struct TriangleMesh {
  // Every vertex of the file (also those no face uses), in file order.
  std::vector<glm::dvec3> positions;
  // Indices into positions, counter-clockwise seen from outside as in the file.
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// The most triangles a file may describe (the sum over its faces of corners − 2, counted before
// zero-area triangles are dropped).
inline constexpr std::size_t kMaxObjTriangles = 2'000'000;
// The most `v` lines: three per triangle, enough for a mesh whose triangles share no vertex.
inline constexpr std::size_t kMaxObjVertices = 3 * kMaxObjTriangles;
// The largest file (bytes), read whole: room for kMaxObjTriangles triangles written with
// texture coordinates and normals (`f 123456/123456/123456 …`, about 70 B a face) and their
// vertex, texture coordinate and normal lines.
inline constexpr std::uintmax_t kMaxObjFileBytes = 512ull * 1024 * 1024;
// The largest |x|, |y|, |z| of a vertex (metres): 1000 km.
inline constexpr double kMaxObjCoordinate = 1e6;
// A polygon's fan triangle that faces against the polygon's normal is a fold (an error) when its
// area is more than this fraction of the polygon's.
inline constexpr double kObjFoldTolerance = 1e-3;

// The limits of one load (tests lower them; a caller may too). Larger than the defaults is
// allowed up to what the index types hold: max_vertices ≤ 2^31 − 1 and max_triangles ≤ 2^31 − 3
// (larger values are a PreconditionError).
struct ObjLimits {
  std::uintmax_t max_file_bytes = kMaxObjFileBytes;
  std::size_t max_vertices = kMaxObjVertices;
  std::size_t max_triangles = kMaxObjTriangles;
};

// A file that cannot be loaded. what() is "PATH:LINE: reason", or "PATH: reason" when the fault
// is not on one line (the file is missing, unreadable, too large, or has no faces).
class ObjError : public std::runtime_error {
 public:
  ObjError(const std::string& file, std::size_t line, const std::string& reason);
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }  // 1-based; 0 when not about one line
  const std::string& reason() const { return reason_; }

 private:
  std::string file_;
  std::size_t line_;
  std::string reason_;
};

// Loads every vertex and every face of the file as triangles (see above). Throws ObjError.
TriangleMesh load_obj(const std::filesystem::path& path);
TriangleMesh load_obj(const std::filesystem::path& path, const ObjLimits& limits);

namespace detail {
// The cross-check of load_obj, for its own tests: tinyobjloader's reading of `text` against a
// reading given as faces (each its 1-based line and its corners' 0-based vertex indices) and a
// vertex count. Throws PreconditionError naming the first difference.
struct ObjFaceReading {
  std::size_t line = 0;
  std::vector<std::uint32_t> corners;
};
void cross_check_obj_reading(std::string_view text, const std::vector<ObjFaceReading>& faces,
                             std::size_t vertices);
}  // namespace detail

}  // namespace oceanref
