#include "io/obj_mesh.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <fstream>
#include <ios>
#include <streambuf>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>

#include "core/check.h"
#include "core/format.h"

// tinyobjloader: Debian's libtinyobjloader_double.so (CMake: find_package(tinyobjloader) and the
// target tinyobjloader::tinyobjloader_double, which defines TINYOBJLOADER_USE_DOUBLE), linked
// rather than compiled in from the header: its number parser calls the platform's pow, which no
// oceanref library may import (tools/check_binary.sh); its numbers are not used here anyway.
// Double, not float: the float build converts every number it reads (also those of ignored
// statements, such as `vn 1e300 0 0`) with a cast whose result is undefined beyond float's range.
#include <tiny_obj_loader.h>

static_assert(std::is_same_v<tinyobj::real_t, double>,
              "link tinyobjloader::tinyobjloader_double, which defines TINYOBJLOADER_USE_DOUBLE "
              "(the float library has a different ABI)");

namespace oceanref {

ObjError::ObjError(const std::string& file, std::size_t line, const std::string& reason)
    : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                         reason),
      file_(file),
      line_(line),
      reason_(reason) {}

namespace {

// The file's bytes; ObjError when it is missing, not a regular file, larger than the limit or
// unreadable.
std::string read_obj_bytes(const std::filesystem::path& path, const std::string& name,
                           const std::uintmax_t max_bytes) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    const std::string cause =
        ec ? ec.message() : std::make_error_code(std::errc::no_such_file_or_directory).message();
    throw ObjError(name, 0, "cannot open file: " + cause);
  }
  if (!std::filesystem::is_regular_file(status)) throw ObjError(name, 0, "not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw ObjError(name, 0, "cannot read file: " + ec.message());
  if (size > max_bytes) {
    throw ObjError(name, 0,
                   "file is " + std::to_string(size) + " bytes; an OBJ file may have at most " +
                       std::to_string(max_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ObjError(name, 0, "cannot open file for reading");
  // The size measured above, exactly: a file that shrank or grew meanwhile is refused.
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (static_cast<std::uintmax_t>(in.gcount()) != size) {
    throw ObjError(name, 0, "cannot read file (it is shorter than its size on disk)");
  }
  if (in.peek() != std::ifstream::traits_type::eof()) {
    throw ObjError(name, 0, "cannot read file (it grew while being read)");
  }
  return bytes;
}

// Lines as tinyobjloader splits them (its safeGetline): at "\n", "\r\n" or a lone "\r"; the
// text after the last line end, if any, is a last line. Linear time also for a file of lone
// "\r" line ends: the next "\n" is searched for once, not once a line.
class ObjLines {
 public:
  explicit ObjLines(std::string_view text) : text_(text) {}
  // The next line (without its end) and its number; false after the last.
  bool next(std::string_view& line, std::size_t& number) {
    if (pos_ >= text_.size()) return false;
    if (!newline_known_ || newline_ < pos_) {
      newline_ = std::min(text_.find('\n', pos_), text_.size());
      newline_known_ = true;
    }
    const std::size_t cr = text_.substr(pos_, newline_ - pos_).find('\r');
    const std::size_t end = cr == std::string_view::npos ? newline_ : pos_ + cr;
    line = text_.substr(pos_, end - pos_);
    number = ++number_;
    pos_ = end;
    if (pos_ < text_.size()) {
      const bool crlf = text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n';
      pos_ += crlf ? std::size_t{2} : std::size_t{1};
    }
    return true;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;      // where the next line starts
  std::size_t newline_ = 0;  // the first "\n" at or after pos_ (or the end), once known
  bool newline_known_ = false;
  std::size_t number_ = 0;
};

bool obj_blank(char c) {
  return c == ' ' || c == '\t';
}

// The next token of `rest` (separated by spaces and tabs), removed from it; empty at the end.
std::string_view next_token(std::string_view& rest) {
  std::size_t start = 0;
  while (start < rest.size() && obj_blank(rest[start])) ++start;
  std::size_t end = start;
  while (end < rest.size() && !obj_blank(rest[end])) ++end;
  const std::string_view token = rest.substr(start, end - start);
  rest.remove_prefix(end);
  return token;
}

// The statement's keyword ("" for a blank or comment line); `rest` becomes its arguments.
std::string_view keyword_of(std::string_view line, std::string_view& rest) {
  rest = line;
  const std::string_view keyword = next_token(rest);
  if (!keyword.empty() && keyword.front() == '#') return {};
  return keyword;
}

std::size_t count_tokens(std::string_view rest) {
  std::size_t n = 0;
  while (!next_token(rest).empty()) ++n;
  return n;
}

// Statements read but not used (obj_mesh.h), and the free-form geometry statements (refused).
constexpr std::array<std::string_view, 21> kObjIgnoredStatements = {
    "vt",     "vn",     "vp",     "o",          "g",         "s",        "mg",
    "usemtl", "mtllib", "l",      "p",          "bevel",     "c_interp", "d_interp",
    "lod",    "usemap", "maplib", "shadow_obj", "trace_obj", "ctech",    "stech"};
constexpr std::array<std::string_view, 14> kObjFreeFormStatements = {
    "cstype", "deg",  "bmat", "step", "curv", "curv2", "surf",
    "parm",   "trim", "hole", "scrv", "sp",   "end",   "con"};

template <std::size_t N>
bool is_one_of(std::string_view word, const std::array<std::string_view, N>& words) {
  return std::find(words.begin(), words.end(), word) != words.end();
}

std::string quoted(std::string_view token) {
  return "'" + escape_value(token) + "'";
}

// What the counting pass finds: exact for a file that validates.
struct ObjCounts {
  std::size_t vertices = 0;
  std::size_t faces = 0;    // faces of 3 or more corners
  std::size_t corners = 0;  // their corners
  std::size_t triangles = 0;
};

// The counting pass: the `v` lines and the corners of the `f` lines, with the limits checked
// at the line that passes them, before any allocation in proportion to the mesh.
ObjCounts count_obj(std::string_view text, const std::string& name, const ObjLimits& limits) {
  ObjCounts counts;
  ObjLines lines(text);
  std::string_view line;
  std::size_t number = 0;
  while (lines.next(line, number)) {
    std::string_view rest;
    const std::string_view keyword = keyword_of(line, rest);
    if (keyword == "v") {
      if (++counts.vertices > limits.max_vertices) {
        throw ObjError(name, number,
                       "more than " + std::to_string(limits.max_vertices) +
                           " vertices (the most an OBJ file may have)");
      }
    } else if (keyword == "f") {
      const std::size_t corners = count_tokens(rest);
      if (corners < 3) continue;  // refused by the validator, at this line
      ++counts.faces;
      counts.corners += corners;
      counts.triangles += corners - 2;
      if (counts.triangles > limits.max_triangles) {
        throw ObjError(name, number,
                       "more than " + std::to_string(limits.max_triangles) +
                           " triangles (the most an OBJ file may have)");
      }
    }
  }
  return counts;
}

// A decimal number as std::from_chars reads it, after an optional '+'.
bool parse_number(std::string_view token, double& value, std::errc& error) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '+' && token[1] != '-') {
    token.remove_prefix(1);
  }
  const std::from_chars_result r =
      std::from_chars(token.data(), token.data() + token.size(), value, std::chars_format::general);
  error = r.ec;
  return r.ptr == token.data() + token.size() && r.ptr != token.data();
}

// A nonzero decimal integer with an optional '-' (an index of a face corner).
bool parse_index(std::string_view token, long long& value) {
  if (token.empty() || token.front() == '+') return false;
  const std::from_chars_result r =
      std::from_chars(token.data(), token.data() + token.size(), value);
  return r.ec == std::errc() && r.ptr == token.data() + token.size();
}

// A face as the validator reads it: its line and its corners (0-based vertex indices).
struct ObjFace {
  std::size_t line = 0;
  std::size_t first = 0;  // into ObjFaces::corners
  std::size_t count = 0;
};

struct ObjFaces {
  std::vector<ObjFace> faces;
  std::vector<std::uint32_t> corners;
};

class ObjValidator {
 public:
  ObjValidator(const std::string& name, const ObjCounts& counts) : name_(name), counts_(counts) {
    positions_.reserve(counts.vertices);
    faces_.faces.reserve(counts.faces);
    faces_.corners.reserve(counts.corners);
  }

  void run(std::string_view text) {
    ObjLines lines(text);
    std::string_view line;
    while (lines.next(line, line_)) {
      std::string_view rest;
      const std::string_view keyword = keyword_of(line, rest);
      if (keyword.empty()) continue;
      if (keyword == "v") {
        vertex(rest);
      } else if (keyword == "f") {
        face(rest);
      } else if (is_one_of(keyword, kObjIgnoredStatements)) {
        continue;
      } else if (is_one_of(keyword, kObjFreeFormStatements)) {
        fail("free-form geometry (" + quoted(keyword) +
             ") is not supported; export the object as polygons");
      } else if (keyword == "call" || keyword == "csh") {
        fail(quoted(keyword) + " is not supported");
      } else {
        fail("unknown statement " + quoted(keyword));
      }
    }
  }

  std::vector<glm::dvec3>& positions() { return positions_; }
  const ObjFaces& faces() const { return faces_; }

 private:
  [[noreturn]] void fail(const std::string& reason) const { throw ObjError(name_, line_, reason); }

  double number(std::string_view token, const char* what) const {
    double value = 0.0;
    std::errc error{};
    if (!parse_number(token, value, error)) {
      fail(std::string(what) + " " + quoted(token) + " is not a number");
    }
    if (error == std::errc::result_out_of_range) {
      fail(std::string(what) + " " + quoted(token) + " is beyond the range of a double");
    }
    if (!std::isfinite(value)) fail(std::string(what) + " " + quoted(token) + " is not finite");
    return value;
  }

  void vertex(std::string_view rest) {
    std::array<std::string_view, 7> tokens;
    std::size_t n = 0;
    for (std::string_view t = next_token(rest); !t.empty(); t = next_token(rest)) {
      if (n == tokens.size()) break;
      tokens[n++] = t;
    }
    if (n != 3 && n != 4 && n != 6) {
      fail(
          "a vertex is 3 coordinates, optionally followed by a weight w or a colour r g b; found " +
          (n == tokens.size() ? std::string("more than 6") : std::to_string(n)) + " values");
    }
    glm::dvec3 p(0.0);
    for (std::size_t i = 0; i < 3; ++i) {
      const double c = number(tokens[i], "coordinate");
      if (std::fabs(c) > kMaxObjCoordinate) {
        fail("coordinate " + quoted(tokens[i]) + " is beyond ±" +
             shortest_number(kMaxObjCoordinate) + " m");
      }
      p[static_cast<glm::length_t>(i)] = c;
    }
    for (std::size_t i = 3; i < n; ++i) (void)number(tokens[i], n == 4 ? "weight" : "colour");
    positions_.push_back(p);
  }

  // One corner: v, v/vt, v//vn or v/vt/vn. Returns the 0-based vertex index.
  std::uint32_t corner(std::string_view token) const {
    std::array<std::string_view, 3> parts;  // split at '/'
    std::size_t n = 0;
    bool too_many = false;
    for (std::string_view rest = token;;) {
      if (n == parts.size()) {
        too_many = true;
        break;
      }
      const std::size_t slash = rest.find('/');
      parts[n++] = rest.substr(0, slash);
      if (slash == std::string_view::npos) break;
      rest.remove_prefix(slash + 1);
    }
    std::array<long long, 3> index{};
    bool well_formed = !too_many;
    bool has_zero = false;
    for (std::size_t i = 0; i < n && well_formed; ++i) {
      if (i == 1 && n == 3 && parts[1].empty()) continue;  // v//vn
      const bool parsed = parse_index(parts[i], index[i]);
      has_zero = parsed && index[i] == 0;
      well_formed = parsed && index[i] != 0;
    }
    if (has_zero) {
      fail("index 0 in " + quoted(token) + ": OBJ indices count from 1 (or back from -1)");
    }
    if (!well_formed) {
      fail(quoted(token) +
           " is not a face corner (v, v/vt, v//vn or v/vt/vn, with nonzero integer indices)");
    }
    const long long v = index[0];
    const std::size_t above = positions_.size();
    if (v > 0) {
      if (static_cast<unsigned long long>(v) > counts_.vertices) {
        fail("vertex index " + std::to_string(v) + " is out of range: the file has " +
             std::to_string(counts_.vertices) + " vertices");
      }
      return static_cast<std::uint32_t>(v - 1);
    }
    // -v, written so that it cannot overflow for the most negative long long.
    if (static_cast<unsigned long long>(-(v + 1)) + 1 > above) {
      fail("vertex index " + std::to_string(v) + " is out of range: " + std::to_string(above) +
           " vertices are defined above this line");
    }
    return static_cast<std::uint32_t>(static_cast<long long>(above) + v);
  }

  void face(std::string_view rest) {
    ObjFace f;
    f.line = line_;
    f.first = faces_.corners.size();
    for (std::string_view t = next_token(rest); !t.empty(); t = next_token(rest)) {
      faces_.corners.push_back(corner(t));
    }
    f.count = faces_.corners.size() - f.first;
    if (f.count < 3) {
      fail("a face needs at least 3 corners; found " + std::to_string(f.count));
    }
    faces_.faces.push_back(f);
  }

  const std::string& name_;
  const ObjCounts& counts_;
  std::size_t line_ = 0;
  std::vector<glm::dvec3> positions_;
  ObjFaces faces_;
};

// A read-only stream over the bytes (no copy) for tinyobjloader.
class ViewBuffer : public std::streambuf {
 public:
  explicit ViewBuffer(std::string_view text) {
    // std::streambuf's get area is char*; nothing writes through it (no put area, no putback).
    char* begin = const_cast<char*>(text.data());
    setg(begin, begin, begin + text.size());
  }
};

// tinyobjloader's reading of the bytes compared with the validator's, face by face.
struct CrossCheck {
  const ObjFaces* expected = nullptr;
  std::size_t vertices = 0;
  std::size_t faces = 0;
  std::string difference;  // the first one
};

void cross_check_vertex(void* user, tinyobj::real_t, tinyobj::real_t, tinyobj::real_t,
                        tinyobj::real_t) {
  ++static_cast<CrossCheck*>(user)->vertices;
}

void cross_check_face(void* user, tinyobj::index_t* indices, int count) {
  CrossCheck& check = *static_cast<CrossCheck*>(user);
  const std::size_t k = check.faces++;
  if (!check.difference.empty()) return;
  if (k >= check.expected->faces.size()) {
    check.difference = "tinyobjloader found more faces than the validator";
    return;
  }
  const ObjFace& face = check.expected->faces[k];
  if (count < 0 || static_cast<std::size_t>(count) != face.count) {
    check.difference = "tinyobjloader found " + std::to_string(count) + " corners on line " +
                       std::to_string(face.line) + ", the validator " + std::to_string(face.count);
    return;
  }
  for (std::size_t i = 0; i < face.count; ++i) {
    const long long raw = indices[i].vertex_index;
    const long long resolved = raw > 0 ? raw - 1 : static_cast<long long>(check.vertices) + raw;
    if (resolved != static_cast<long long>(check.expected->corners[face.first + i])) {
      check.difference = "tinyobjloader read vertex index " + std::to_string(raw) + " on line " +
                         std::to_string(face.line) + ", unlike the validator (corner " +
                         std::to_string(i + 1) + ")";
      return;
    }
  }
}

void cross_check_with_tinyobjloader(std::string_view text, const ObjFaces& faces,
                                    const std::size_t vertices) {
  ViewBuffer buffer(text);
  std::istream in(&buffer);
  tinyobj::callback_t callbacks;
  callbacks.vertex_cb = cross_check_vertex;
  callbacks.index_cb = cross_check_face;
  CrossCheck check;
  check.expected = &faces;
  std::string error;
  // No MaterialReader: `mtllib` opens nothing. No warnings wanted (they name missing materials).
  tinyobj::LoadObjWithCallback(in, callbacks, &check, nullptr, nullptr, &error);
  if (check.difference.empty() && check.vertices != vertices) {
    check.difference = "tinyobjloader found " + std::to_string(check.vertices) +
                       " vertices, the validator " + std::to_string(vertices);
  }
  if (check.difference.empty() && check.faces != faces.faces.size()) {
    check.difference = "tinyobjloader found " + std::to_string(check.faces) +
                       " faces, the validator " + std::to_string(faces.faces.size());
  }
  if (check.difference.empty() && !error.empty()) {
    check.difference = "tinyobjloader reported: " + error;
  }
  OCEANREF_EXPECTS(check.difference.empty(),
                   "OBJ parsers disagree on a file the validator accepted: " + check.difference);
}

// Every face as triangles (fans), the zero-area ones dropped, folding polygons refused.
std::vector<std::array<std::uint32_t, 3>> triangulate(const std::vector<glm::dvec3>& positions,
                                                      const ObjFaces& faces,
                                                      const std::size_t triangle_count,
                                                      const std::string& name) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangles.reserve(triangle_count);
  const glm::dvec3 zero(0.0);
  for (const ObjFace& face : faces.faces) {
    const std::uint32_t* c = faces.corners.data() + face.first;
    const glm::dvec3 p0 = positions[c[0]];
    // The polygon's normal: the sum of its fan triangles' normals (twice its vector area).
    glm::dvec3 normal(0.0);
    for (std::size_t k = 1; k + 1 < face.count; ++k) {
      normal += glm::cross(positions[c[k]] - p0, positions[c[k + 1]] - p0);
    }
    const double normal2 = glm::dot(normal, normal);
    for (std::size_t k = 1; k + 1 < face.count; ++k) {
      const glm::dvec3 n = glm::cross(positions[c[k]] - p0, positions[c[k + 1]] - p0);
      if (n == zero) continue;  // zero area: dropped
      if (face.count > 3 && glm::dot(n, normal) <= 0.0 &&
          glm::dot(n, n) > kObjFoldTolerance * kObjFoldTolerance * normal2) {
        throw ObjError(name, face.line,
                       "polygon of " + std::to_string(face.count) +
                           " corners folds when cut into a fan from its first corner: triangle "
                           "(corners 1, " +
                           std::to_string(k + 1) + ", " + std::to_string(k + 2) +
                           ") faces against the polygon's normal (a concave or strongly warped "
                           "polygon: triangulate it before export)");
      }
      triangles.push_back({c[0], c[k], c[k + 1]});
    }
  }
  return triangles;
}

}  // namespace

TriangleMesh load_obj(const std::filesystem::path& path) {
  return load_obj(path, ObjLimits{});
}

TriangleMesh load_obj(const std::filesystem::path& path, const ObjLimits& limits) {
  OCEANREF_EXPECTS(limits.max_vertices <= static_cast<std::size_t>(INT_MAX),
                   "max_vertices " + std::to_string(limits.max_vertices) + " above 2^31 - 1");
  OCEANREF_EXPECTS(limits.max_triangles <= static_cast<std::size_t>(INT_MAX) - 2,
                   "max_triangles " + std::to_string(limits.max_triangles) + " above 2^31 - 3");
  const std::string name = path.string();
  const std::string bytes = read_obj_bytes(path, name, limits.max_file_bytes);
  std::string_view text = bytes;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte-order mark

  const ObjCounts counts = count_obj(text, name, limits);
  ObjValidator validator(name, counts);
  validator.run(text);
  const ObjFaces& faces = validator.faces();
  if (faces.faces.empty()) throw ObjError(name, 0, "no faces (an OBJ mesh needs 'f' lines)");
  cross_check_with_tinyobjloader(text, faces, validator.positions().size());

  TriangleMesh mesh;
  mesh.triangles = triangulate(validator.positions(), faces, counts.triangles, name);
  if (mesh.triangles.empty()) {
    throw ObjError(name, 0, "every face has zero area (no triangle is left)");
  }
  mesh.positions = std::move(validator.positions());
  return mesh;
}

namespace detail {
void cross_check_obj_reading(std::string_view text, const std::vector<ObjFaceReading>& faces,
                             std::size_t vertices) {
  ObjFaces reading;
  for (const ObjFaceReading& f : faces) {
    reading.faces.push_back({f.line, reading.corners.size(), f.corners.size()});
    reading.corners.insert(reading.corners.end(), f.corners.begin(), f.corners.end());
  }
  cross_check_with_tinyobjloader(text, reading, vertices);
}
}  // namespace detail

}  // namespace oceanref
