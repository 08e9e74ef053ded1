// The OBJ loader (io/obj_mesh.h): the reference buoy loads closed, consistently oriented and with
// the volume of the shapes it was built from; polygons become fans; and every malformed file is
// refused with an ObjError naming the file and the offending line.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/check.h"
#include "io/obj_mesh.h"
#include "temp_dir.h"

using namespace oceanref;

namespace {

// Writes `text` (bytes as they are) to `name` in `dir`; returns the path.
std::string obj_write(const oceanref::testing::TempDir& dir, const std::string& name,
                      const std::string& text) {
  const std::string path = dir.file(name);
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  return path;
}

// The ObjError of loading `path` (an empty one, with a failed check, when the file loads).
ObjError obj_error_of(const std::string& path, const ObjLimits& limits = ObjLimits{}) {
  try {
    (void)load_obj(path, limits);
  } catch (const ObjError& e) {
    return e;
  }
  FAIL_CHECK("loaded without an ObjError: " << path);
  return ObjError(path, 0, "");
}

// Twice the vector area of a triangle.
glm::dvec3 obj_area2(const TriangleMesh& m, const std::array<std::uint32_t, 3>& t) {
  return glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

double obj_total_area(const TriangleMesh& m) {
  double sum = 0.0;
  for (const auto& t : m.triangles) sum += glm::length(obj_area2(m, t)) / 2.0;
  return sum;
}

// The area of a regular polygon of `n` corners on a circle of radius r.
double obj_polygon_area(int n, double r) {
  return n / 2.0 * r * r * std::sin(2.0 * std::numbers::pi / n);
}

const char* const obj_unit_square =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n";

}  // namespace

TEST_CASE("obj mesh: the reference buoy loads closed, outward and with its built volume") {
  const TriangleMesh m = load_obj(OCEANREF_SOURCE_DIR "/reference/objects/buoy.obj");
  // 24 segments: the bottom 24-gon (22 triangles), four bands of 24 quads (hull side, deck cone,
  // mast, topmark underside) and the topmark cone's 24 triangles.
  REQUIRE(m.triangles.size() == 22 + 4 * 2 * 24 + 24);
  REQUIRE(m.positions.size() == 5 * 24 + 1);

  // Closed and consistently oriented: every directed edge appears once, and its reverse once.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles) {
    for (std::size_t k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  int unmatched = 0;
  for (const auto& [edge, count] : edges) {
    const auto reverse = edges.find({edge.second, edge.first});
    if (count != 1 || reverse == edges.end() || reverse->second != 1) ++unmatched;
  }
  CHECK(unmatched == 0);
  CHECK(edges.size() == 3 * m.triangles.size());

  // The volume by the divergence theorem, Σ p0 · (p1 × p2) / 6, against the exact volume of the
  // faceted shapes: prisms and pyramid frustums over regular 24-gons. The coordinates are written
  // with 6 decimals, which moves the volume by 9e-7 of itself; a missing or flipped face moves it
  // by percents.
  double volume = 0.0;
  for (const auto& t : m.triangles) {
    volume += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]])) / 6.0;
  }
  const double hull = obj_polygon_area(24, 0.6) * (0.6 + 0.8);
  const double a_deck = obj_polygon_area(24, 0.6);
  const double a_mast = obj_polygon_area(24, 0.08);
  const double deck = 0.4 / 3.0 * (a_deck + a_mast + std::sqrt(a_deck * a_mast));
  const double mast = a_mast * 0.9;
  const double topmark = obj_polygon_area(24, 0.25) * 0.4 / 3.0;
  const double expected = hull + deck + mast + topmark;
  CHECK(volume > 0.0);
  CHECK(std::fabs(volume / expected - 1.0) < 1e-5);

  // Extent: the keel 0.8 m below the waterline, the apex 2.3 m above, radius 0.6 m.
  double y_min = 1e9, y_max = -1e9, r_max = 0.0;
  for (const glm::dvec3& p : m.positions) {
    y_min = std::min(y_min, p.y);
    y_max = std::max(y_max, p.y);
    r_max = std::max(r_max, std::hypot(p.x, p.z));
  }
  CHECK(y_min == -0.8);
  CHECK(y_max == 2.3);
  CHECK(r_max == doctest::Approx(0.6).epsilon(1e-6));
}

TEST_CASE("obj mesh: quads and pentagons become fans covering the same area") {
  const oceanref::testing::TempDir dir;
  SUBCASE("quad") {
    const TriangleMesh m =
        load_obj(obj_write(dir, "quad.obj", std::string(obj_unit_square) + "f 1 2 3 4\n"));
    REQUIRE(m.triangles.size() == 2);
    CHECK(m.triangles[0] == std::array<std::uint32_t, 3>{0, 1, 2});
    CHECK(m.triangles[1] == std::array<std::uint32_t, 3>{0, 2, 3});
    CHECK(obj_total_area(m) == 1.0);
  }
  SUBCASE("pentagon, written with texture coordinates and normals") {
    const TriangleMesh m = load_obj(obj_write(dir, "pentagon.obj",
                                              "v 0 0 0\nv 2 0 0\nv 3 1.5 0\nv 1 3 0\nv -1 1.5 0\n"
                                              "vt 0 0\nvt 1 0\nvn 0 0 1\n"
                                              "f 1/1/1 2/2/1 3/1/1 4/2/1 5/1/1\n"));
    REQUIRE(m.triangles.size() == 3);
    CHECK(m.triangles[0] == std::array<std::uint32_t, 3>{0, 1, 2});
    CHECK(m.triangles[1] == std::array<std::uint32_t, 3>{0, 2, 3});
    CHECK(m.triangles[2] == std::array<std::uint32_t, 3>{0, 3, 4});
    // Shoelace: ½ Σ (x_i y_{i+1} − x_{i+1} y_i) = ½ (0 + 3 + 7.5 + 4.5 + 0) = 7.5.
    CHECK(obj_total_area(m) == doctest::Approx(7.5).epsilon(1e-15));
    for (const auto& t : m.triangles) CHECK(obj_area2(m, t).z > 0.0);  // the file's winding
  }
  SUBCASE("the other corner forms: v//vn and v/vt") {
    const TriangleMesh m = load_obj(obj_write(dir, "forms.obj",
                                              std::string(obj_unit_square) +
                                                  "vt 0 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1/1 3/1 "
                                                  "4/1\n"));
    CHECK(m.triangles.size() == 2);
    CHECK(obj_total_area(m) == 1.0);
  }
  SUBCASE("a warped quad (its corners not in one plane)") {
    const TriangleMesh m = load_obj(
        obj_write(dir, "warped.obj", "v 0 0 0\nv 1 0 0.2\nv 1 1 0\nv 0 1 0.2\nf 1 2 3 4\n"));
    REQUIRE(m.triangles.size() == 2);
    for (const auto& t : m.triangles) CHECK(obj_area2(m, t).z > 0.0);
  }
  SUBCASE("a concave polygon that is star-shaped from its first corner") {
    // An arrowhead (0, 0), (1, 0.5), (2, 0), (1, 3) written from its reflex corner (1, 0.5):
    // both fan triangles face +Z.
    const TriangleMesh m =
        load_obj(obj_write(dir, "arrow.obj", "v 1 0.5 0\nv 2 0 0\nv 1 3 0\nv 0 0 0\nf 1 2 3 4\n"));
    REQUIRE(m.triangles.size() == 2);
    for (const auto& t : m.triangles) CHECK(obj_area2(m, t).z > 0.0);
    CHECK(obj_total_area(m) == 2.5);
  }
}

TEST_CASE("obj mesh: indices — relative, forward, and the vertices no face uses") {
  const oceanref::testing::TempDir dir;
  // Negative indices count back from the last vertex above the face's line.
  const TriangleMesh m = load_obj(obj_write(dir, "relative.obj",
                                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                                            "v 5 0 0\nv 6 0 0\nv 5 1 0\nv 9 9 9\nf -4 -3 -2\n"
                                            "f 1 2 -1\n"));
  REQUIRE(m.triangles.size() == 3);
  CHECK(m.triangles[0] == std::array<std::uint32_t, 3>{0, 1, 2});
  CHECK(m.triangles[1] == std::array<std::uint32_t, 3>{3, 4, 5});
  CHECK(m.triangles[2] == std::array<std::uint32_t, 3>{0, 1, 6});
  CHECK(m.positions.size() == 7);
  CHECK(m.positions[6] == glm::dvec3(9.0, 9.0, 9.0));
  // A positive index may name a vertex written below the face.
  const TriangleMesh forward =
      load_obj(obj_write(dir, "forward.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"));
  CHECK(forward.triangles.size() == 1);
}

TEST_CASE("obj mesh: numbers are read exactly; what is ignored is ignored") {
  const oceanref::testing::TempDir dir;
  // Correctly rounded (tinyobjloader's own parser gives 0.30000000000000004), a '+' sign,
  // exactly the largest coordinate, weights and colours read and dropped, a byte-order mark,
  // CRLF and lone CR line ends, names, groups, smoothing, materials whose file does not exist,
  // lines and points.
  const std::string text =
      "\xEF\xBB\xBF# a comment\r\n"
      "mtllib missing.mtl\r\n"
      "o thing\rg part\n"
      "v 0.3 +1e-3 -1000000\n"
      "v 1000000 0.1 0.7 1.0\n"
      "  v\t0 1 0  0.5 0.5 0.5  \n"
      "usemtl red\ns 1\nl 1 2\np 3\nvn 0 0 1\n"
      "f 1 2 3\n";
  const TriangleMesh m = load_obj(obj_write(dir, "exact.obj", text));
  REQUIRE(m.positions.size() == 3);
  CHECK(m.positions[0] == glm::dvec3(0.3, 1e-3, -1e6));
  CHECK(m.positions[1] == glm::dvec3(1e6, 0.1, 0.7));
  CHECK(m.positions[2] == glm::dvec3(0.0, 1.0, 0.0));
  CHECK(m.triangles.size() == 1);
}

TEST_CASE("obj mesh: zero-area triangles are dropped, folding polygons refused") {
  const oceanref::testing::TempDir dir;
  SUBCASE("a repeated corner and exactly collinear corners") {
    const TriangleMesh m = load_obj(obj_write(
        dir, "degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 2\nf 1 2 4\nf 1 2 3\n"));
    REQUIRE(m.triangles.size() == 1);
    CHECK(m.triangles[0] == std::array<std::uint32_t, 3>{0, 1, 2});
  }
  SUBCASE("a T-junction: a corner on an edge of the polygon") {
    const TriangleMesh m = load_obj(obj_write(
        dir, "t_junction.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4 5\n"));
    CHECK(m.triangles.size() == 2);  // (1, 2, 3) has no area
    CHECK(obj_total_area(m) == 2.0);
  }
  SUBCASE("every face without area") {
    const std::string path =
        obj_write(dir, "flat.obj", "v 0 0 0\nv 1 1 1\nv 3 3 3\nf 1 2 3\nf 1 1 2\n");
    const ObjError e = obj_error_of(path);
    CHECK(std::string(e.what()) == path + ": every face has zero area (no triangle is left)");
    CHECK(e.line() == 0);
  }
  SUBCASE("a concave polygon whose fan from the first corner folds") {
    // The arrowhead of the other test written from a convex corner: (1, 2, 3) faces −Z.
    const std::string path =
        obj_write(dir, "fold.obj", "v 0 0 0\nv 1 0.5 0\nv 2 0 0\nv 1 3 0\n\nf 1 2 3 4\n");
    const ObjError e = obj_error_of(path);
    CHECK(e.line() == 6);
    CHECK(e.reason().find("polygon of 4 corners folds when cut into a fan from its first corner: "
                          "triangle (corners 1, 2, 3) faces against") == 0);
  }
  SUBCASE("a self-intersecting quad (a bow tie)") {
    const std::string path =
        obj_write(dir, "bowtie.obj", "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n");
    CHECK(obj_error_of(path).line() == 5);
  }
  SUBCASE("a corner off its edge by the rounding of 6 decimals is not a fold") {
    // The triangle (0, 0), (1, 2), (-1, 2) with a corner at (1/3, 2/3) on its first edge,
    // written 0.333333 0.666667: 1e-6 to the left of the edge, so the fan triangle with it faces
    // −Z — an area of 2.5e-7 of the polygon's, below kObjFoldTolerance: kept.
    const TriangleMesh m = load_obj(
        obj_write(dir, "rounded.obj",
                  "v 0 0 0\nv 0.333333 0.666667 0\nv 1 2 0\nv -1 2 0\nf 1 2 3 4\nf 3 4 1 2\n"));
    REQUIRE(m.triangles.size() == 4);
    CHECK(obj_area2(m, m.triangles[0]).z < 0.0);
    CHECK(obj_area2(m, m.triangles[3]).z < 0.0);
  }
}

TEST_CASE("obj mesh: each malformed line is refused with its file and line number") {
  const oceanref::testing::TempDir dir;
  using namespace std::string_view_literals;
  struct Case {
    std::string_view text;
    std::size_t line;
    const char* reason;  // a part of it
  };
  const std::vector<Case> cases = {
      {"v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", 3, "coordinate 'nan' is not finite"},
      {"v 0 0 0\n\n# inf below\nv 1 -inf 0\n", 4, "coordinate '-inf' is not finite"},
      {"v 0 0 1e400\n", 1, "coordinate '1e400' is beyond the range of a double"},
      {"v 0 0 0\nv 1.2.3 0 0\n", 2, "coordinate '1.2.3' is not a number"},
      {"v 0x10 0 0\n", 1, "coordinate '0x10' is not a number"},
      {"v 1,5 0 0\n", 1, "coordinate '1,5' is not a number"},
      {"v 0 1000000.5 0\n", 1, "coordinate '1000000.5' is beyond ±1000000 m"},
      {"v 0 0 -1e7\n", 1, "coordinate '-1e7' is beyond ±1000000 m"},
      {"v 1 2\n", 1, "found 2 values"},
      {"v 1 2 3 4 5\n", 1, "found 5 values"},
      {"v 1 2 3 4 5 6 7\n", 1, "found more than 6 values"},
      {"v 0 0 0 #comment\n", 1, "weight '#comment' is not a number"},
      {"v 0 0 0 1 0 inf\n", 1, "colour 'inf' is not finite"},
      {"v 0 0\x01 0\n", 1, "coordinate '0\\x01' is not a number"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 2\n", 4, "index 0 in '0': OBJ indices count from 1"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/0 2/1 3/1\n", 4, "index 0 in '1/0'"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4,
       "vertex index 4 is out of range: the file has 3 vertices"},
      {"v 0 0 0\nv 1 0 0\nf -3 -2 -1\nv 0 1 0\n", 3,
       "vertex index -3 is out of range: 2 vertices are defined above this line"},
      {"f -1 -2 -3\nv 0 0 0\n", 1, "0 vertices are defined above this line"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 4, "a face needs at least 3 corners; found 2"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf\n", 4, "found 0"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1.5 2 3\n", 4, "'1.5' is not a face corner"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", 4, "'1/1/1/1' is not a face corner"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1// 2 3\n", 4, "'1//' is not a face corner"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf +1 2 3\n", 4, "'+1' is not a face corner"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 99999999999999999999 2 3\n", 4,
       "'99999999999999999999' is not a face corner"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # done\n", 4, "'#' is not a face corner"},
      {"v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 x\r\n", 4, "'x' is not a face corner"},
      {"v 0 0 0\rv 1 0 0\rv nan 1 0\r", 3, "'nan' is not finite"},
      {"\xEF\xBB\xBFv 0 0 0\nv nan 0 0\n", 2, "'nan' is not finite"},
      {"v 0 0 0\ncurv 0 1 1 2\n", 2, "free-form geometry ('curv') is not supported"},
      {"call other.obj\n", 1, "'call' is not supported"},
      {"v 0 0 0\nvx 1 2 3\n", 2, "unknown statement 'vx'"},
      {"v 0 0 0\n\xEF\xBB\xBFv 1 0 0\n", 2, "unknown statement '\\xEF\\xBB\\xBFv'"},
      {"v 0 0 0\n\0v 1 0 0\n"sv, 2, "unknown statement '\\x00v'"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const std::string text(c.text);
    const std::string path = obj_write(dir, "case" + std::to_string(i) + ".obj", text);
    CAPTURE(text);
    const ObjError e = obj_error_of(path);
    CHECK(e.file() == path);
    CHECK(e.line() == c.line);
    CAPTURE(e.reason());
    CHECK(e.reason().find(c.reason) != std::string::npos);
    CHECK(std::string(e.what()) == path + ":" + std::to_string(c.line) + ": " + e.reason());
  }
  // The whole message, once.
  const std::string path = obj_write(dir, "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  CHECK(std::string(obj_error_of(path).what()) == path + ":3: coordinate 'nan' is not finite");
}

TEST_CASE("obj mesh: files that are missing, not files, or hold no faces") {
  const oceanref::testing::TempDir dir;
  const std::string missing = dir.file("missing.obj");
  CHECK(std::string(obj_error_of(missing).what()) ==
        missing + ": cannot open file: No such file or directory");
  CHECK(std::string(obj_error_of(dir.path.string()).what()) ==
        dir.path.string() + ": not a regular file");
  for (const char* text : {"", "# only a comment\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "\n\n   \t\n",
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n"}) {
    const std::string path = obj_write(dir, "empty.obj", text);
    CAPTURE(text);
    const ObjError e = obj_error_of(path);
    CHECK(std::string(e.what()) == path + ": no faces (an OBJ mesh needs 'f' lines)");
    CHECK(e.line() == 0);
  }
}

TEST_CASE("obj mesh: the size limits are checked before the mesh is read") {
  const oceanref::testing::TempDir dir;
  const std::string square = std::string(obj_unit_square) + "f 1 2 3\nf 1 3 4\n";
  SUBCASE("exactly at the limits loads") {
    const ObjLimits limits{square.size(), 4, 2};
    CHECK(load_obj(obj_write(dir, "at.obj", square), limits).triangles.size() == 2);
  }
  SUBCASE("file size") {
    const std::string path = obj_write(dir, "big.obj", square);
    const ObjError e = obj_error_of(path, ObjLimits{square.size() - 1, 4, 2});
    CHECK(std::string(e.what()) == path + ": file is " + std::to_string(square.size()) +
                                       " bytes; an OBJ file may have at most " +
                                       std::to_string(square.size() - 1));
  }
  SUBCASE("vertices: refused at the line that passes the limit") {
    const ObjError e = obj_error_of(obj_write(dir, "v.obj", square), ObjLimits{1000, 3, 2});
    CHECK(e.line() == 4);
    CHECK(e.reason() == "more than 3 vertices (the most an OBJ file may have)");
  }
  SUBCASE("triangles: counted as corners − 2 per face, before any is dropped") {
    const std::string text = std::string(obj_unit_square) + "f 1 2 3\nf 1 1 1\nf 1 2 3 4\n";
    const ObjError e = obj_error_of(obj_write(dir, "t.obj", text), ObjLimits{1000, 4, 3});
    CHECK(e.line() == 7);
    CHECK(e.reason() == "more than 3 triangles (the most an OBJ file may have)");
  }
  SUBCASE("kMaxObjTriangles + 1 faces, refused by the counting pass") {
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    text.reserve(text.size() + 8 * (kMaxObjTriangles + 1));
    for (std::size_t i = 0; i <= kMaxObjTriangles; ++i) text += "f 1 2 3\n";
    const ObjError e = obj_error_of(obj_write(dir, "huge.obj", text));
    CHECK(e.line() == 3 + kMaxObjTriangles + 1);
    CHECK(e.reason() == "more than 2000000 triangles (the most an OBJ file may have)");
  }
  SUBCASE("limits beyond the index types are a bug of the caller") {
    const std::string path = obj_write(dir, "ok.obj", square);
    CHECK_THROWS_AS(load_obj(path, ObjLimits{1000, std::size_t{1} << 31, 2}), PreconditionError);
    CHECK_THROWS_AS(load_obj(path, ObjLimits{1000, 4, std::size_t{1} << 31}), PreconditionError);
  }
}

TEST_CASE("obj mesh: the tinyobjloader cross-check names the first difference from a reading") {
  // load_obj compares tinyobjloader's reading of the bytes with the validator's; the two agree on
  // every file the tests load, so here the validator's side is given by hand: the true reading
  // passes, and each kind of difference is named (a corner, a corner count, a face too many or
  // too few, the vertex count), through positive and negative (relative) indices alike.
  using detail::cross_check_obj_reading;
  using detail::ObjFaceReading;
  const std::string text = std::string(obj_unit_square) + "f 1 2 3\nf -4 -2 -1\n";
  const std::vector<ObjFaceReading> truth = {{5, {0, 1, 2}}, {6, {0, 2, 3}}};
  CHECK_NOTHROW(cross_check_obj_reading(text, truth, 4));
  const auto difference = [&](const std::vector<ObjFaceReading>& reading, std::size_t vertices) {
    try {
      cross_check_obj_reading(text, reading, vertices);
    } catch (const PreconditionError& e) {
      return std::string(e.what());
    }
    return std::string("no difference found");
  };
  const auto names = [](const std::string& message, const std::string& what) {
    INFO(message);
    CHECK(message.find(what) != std::string::npos);
  };
  names(difference({{5, {0, 1, 2}}, {6, {0, 2, 1}}}, 4),
        "tinyobjloader read vertex index -1 on line 6, unlike the validator (corner 3)");
  names(difference({{5, {0, 3, 2}}, {6, {0, 2, 3}}}, 4),
        "tinyobjloader read vertex index 2 on line 5, unlike the validator (corner 2)");
  names(difference({{5, {0, 1, 2, 3}}, {6, {0, 2, 3}}}, 4),
        "tinyobjloader found 3 corners on line 5, the validator 4");
  names(difference({{5, {0, 1, 2}}}, 4), "tinyobjloader found more faces than the validator");
  names(difference({{5, {0, 1, 2}}, {6, {0, 2, 3}}, {7, {1, 2, 3}}}, 4),
        "tinyobjloader found 2 faces, the validator 3");
  names(difference(truth, 5), "tinyobjloader found 4 vertices, the validator 5");
}
