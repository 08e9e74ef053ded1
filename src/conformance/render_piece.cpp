#include "conformance/render_piece.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "core/check.h"
#include "core/memory.h"
#include "io/exr.h"
#include "io/output_file.h"
#include "io/sha256.h"

namespace oceanref {

namespace {
constexpr const char* kMagic = "oceanref render piece 3\n";
constexpr std::size_t kMaxHeaderBytes = 1 << 16;

// The buffers of a piece in file order: f(member) for each (a vector of Vec3 or of double), the
// one list the writer, the reader and the merge follow.
template <class F>
void for_each_buffer(bool layers, bool adaptive, const F& f) {
  f(&RenderedImage::radiance);
  f(&RenderedImage::lighting_error);
  f(&RenderedImage::pixel_error);
  f(&RenderedImage::coverage);
  if (adaptive) f(&RenderedImage::pixel_samples);
  if (!layers) return;
  f(&RenderedImage::sun);
  f(&RenderedImage::sky);
  f(&RenderedImage::sea);
  f(&RenderedImage::foam);
  f(&RenderedImage::depth);
  f(&RenderedImage::normal);
  f(&RenderedImage::x0);
}

// Doubles per pixel of a buffer's element: 1 for double, 3 for Vec3.
template <class Value>
constexpr std::size_t channels_of() {
  return std::is_same_v<Value, double> ? 1 : 3;
}

// Doubles per pixel in the file.
std::uint64_t doubles_per_pixel(bool layers, bool adaptive) {
  std::uint64_t n = 0;
  for_each_buffer(layers, adaptive, [&](auto member) {
    n += channels_of<typename std::decay_t<decltype(RenderedImage{}.*member)>::value_type>();
  });
  return n;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw RenderPieceError(path + ": " + what);
}

double read_double(const unsigned char* p) {
  std::uint64_t bits = 0;
  for (int b = 7; b >= 0; --b) bits = (bits << 8) | p[b];  // little-endian on every host
  return std::bit_cast<double>(bits);
}
}  // namespace

std::pair<int, int> tile_rows(int index, int count, int height) {
  OCEANREF_EXPECTS(0 <= index && index < count && count <= height,
                   "tile " + std::to_string(index) + " of " + std::to_string(count) + " over " +
                       std::to_string(height) + " rows");
  const auto row = [&](int i) { return static_cast<int>(static_cast<long>(height) * i / count); };
  return {row(index), row(index + 1)};
}

void write_render_piece(const std::string& path, const RenderPiece& piece) {
  const RenderedImage& b = piece.band;
  nlohmann::json header = {
      {"scene_sha256", piece.scene_sha256},
      {"tile", piece.tile},
      {"tiles", piece.tiles},
      {"width", b.width},
      {"first_row", b.first_row},
      {"rows", b.height},
      {"samples_per_axis", piece.samples_per_axis},
      {"layers", piece.layers},
      {"adaptive", piece.adaptive},
      {"capped_pixels", b.capped_pixels},
      {"unconverged_samples", b.unconverged_samples},
      {"integrand_evaluations", b.integrand_evaluations},
      {"unresolved_slope_variance", {b.unresolved.upwind, b.unresolved.crosswind}},
      {"displacement_bound", b.displacement_bound}};
  // Only with Mastin's anti-aliasing, so that the other pieces of format 3 stay as they were.
  if (piece.antialiased) header["antialiased_pixels"] = b.antialiased_pixels;
  // Only with the two-level lighting (RenderJob::lighting_correction), likewise.
  if (b.corrected_samples > 0) header["corrected_samples"] = b.corrected_samples;
  std::vector<std::uint8_t> bytes;
  const std::string text = kMagic + header.dump() + "\n";
  bytes.insert(bytes.end(), text.begin(), text.end());
  for_each_buffer(piece.layers, piece.adaptive, [&](auto member) {
    for (const auto& v : b.*member) {
      if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>) {
        append_bytes(bytes, v);
      } else {
        for (const double c : v) append_bytes(bytes, c);
      }
    }
  });
  OutputFile out(path);
  out.write(bytes.data(), bytes.size());
  out.commit();
}

RenderPiece read_render_piece(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the render piece");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
  in.seekg(0);
  std::string magic(std::strlen(kMagic), '\0');
  if (!in.read(magic.data(), static_cast<std::streamsize>(magic.size())) || magic != kMagic) {
    fail(path, "not an oceanref render piece of this version (its first line is not '" +
                   std::string(kMagic, std::strlen(kMagic) - 1) + "')");
  }
  std::string line;
  line.reserve(1024);
  for (char c = 0; in.get(c) && c != '\n';) {
    if (line.size() >= kMaxHeaderBytes) fail(path, "header line longer than 64 KiB");
    line.push_back(c);
  }
  const std::uint64_t body = static_cast<std::uint64_t>(in.tellg());
  if (!in) fail(path, "the header line is not terminated");
  RenderPiece piece;
  RenderedImage& b = piece.band;
  try {
    const nlohmann::json h = nlohmann::json::parse(line);
    const auto integer = [&](const char* key, long lo, long hi) {
      const nlohmann::json& v = h.at(key);
      if (!v.is_number_integer() || v.get<long>() < lo || v.get<long>() > hi) {
        fail(path, std::string("header key ") + key + ": an integer in [" + std::to_string(lo) +
                       ", " + std::to_string(hi) + "] expected, got " + v.dump());
      }
      return v.get<long>();
    };
    const auto number = [&](const nlohmann::json& v, const char* key) {
      if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0.0) {
        fail(path,
             std::string("header key ") + key + ": a finite number >= 0 expected, got " + v.dump());
      }
      return v.get<double>();
    };
    if (!h.at("scene_sha256").is_string() || h["scene_sha256"].get<std::string>().size() != 64) {
      fail(path, "header key scene_sha256: 64 hex digits expected");
    }
    for (const char* key : {"layers", "adaptive"}) {
      if (!h.at(key).is_boolean()) {
        fail(path, std::string("header key ") + key + ": true or false expected");
      }
    }
    piece.scene_sha256 = h["scene_sha256"].get<std::string>();
    piece.layers = h["layers"].get<bool>();
    piece.adaptive = h["adaptive"].get<bool>();
    piece.tiles = static_cast<int>(integer("tiles", 1, kMaxExrSide));
    piece.tile = static_cast<int>(integer("tile", 0, piece.tiles - 1));
    piece.samples_per_axis = static_cast<int>(integer("samples_per_axis", 1, kMaxSamplesPerAxis));
    b.samples_per_axis = piece.samples_per_axis;
    b.width = static_cast<int>(integer("width", 1, kMaxExrSide));
    b.first_row = static_cast<int>(integer("first_row", 0, kMaxExrSide - 1));
    b.height = static_cast<int>(integer("rows", 1, kMaxExrSide - b.first_row));
    b.capped_pixels = integer("capped_pixels", 0, static_cast<long>(b.width) * b.height);
    piece.antialiased = h.contains("antialiased_pixels");
    if (piece.antialiased) {
      b.antialiased_pixels =
          integer("antialiased_pixels", 0, static_cast<long>(b.width) * b.height);
    }
    b.unconverged_samples = integer("unconverged_samples", 0, std::numeric_limits<long>::max());
    if (h.contains("corrected_samples")) {
      b.corrected_samples = integer("corrected_samples", 1, std::numeric_limits<long>::max());
    }
    b.integrand_evaluations = integer("integrand_evaluations", 0, std::numeric_limits<long>::max());
    const nlohmann::json& u = h.at("unresolved_slope_variance");
    if (!u.is_array() || u.size() != 2) {
      fail(path, "header key unresolved_slope_variance: [upwind, crosswind] expected");
    }
    b.unresolved = {number(u[0], "unresolved_slope_variance"),
                    number(u[1], "unresolved_slope_variance")};
    b.displacement_bound = number(h.at("displacement_bound"), "displacement_bound");
    if (h.size() != (piece.antialiased ? 15u : 14u)) {
      fail(path, "the header has keys other than those of format 3");
    }
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("unreadable header: ") + e.what());
  }
  const std::uint64_t pixels =
      static_cast<std::uint64_t>(b.width) * static_cast<std::uint64_t>(b.height);
  const std::uint64_t expected =
      body + pixels * doubles_per_pixel(piece.layers, piece.adaptive) * 8;
  if (size != expected) {
    fail(path, "the file holds " + std::to_string(size) + " bytes; its header describes " +
                   std::to_string(expected));
  }
  std::vector<unsigned char> row;
  for_each_buffer(piece.layers, piece.adaptive, [&](auto member) {
    auto& buffer = b.*member;
    using Value = typename std::decay_t<decltype(buffer)>::value_type;
    constexpr std::size_t channels = channels_of<Value>();
    buffer = allocate_buffer<Value>(static_cast<std::size_t>(pixels), "a render piece's buffer");
    row.resize(static_cast<std::size_t>(pixels) * channels * 8);
    if (!in.read(reinterpret_cast<char*>(row.data()), static_cast<std::streamsize>(row.size()))) {
      fail(path, "cannot read the pixel buffers");
    }
    for (std::size_t i = 0; i < buffer.size(); ++i) {
      if constexpr (channels == 1) {
        buffer[i] = read_double(&row[8 * i]);
      } else {
        for (std::size_t c = 0; c < 3; ++c) buffer[i][c] = read_double(&row[8 * (3 * i + c)]);
      }
    }
  });
  return piece;
}

RenderedImage merge_render_pieces(const Scene& scene, const std::vector<RenderPiece>& pieces,
                                  const std::vector<std::string>& paths) {
  OCEANREF_EXPECTS(paths.size() == pieces.size(), "one path per piece");
  if (pieces.empty()) throw RenderPieceError("no render pieces to merge");
  const std::string scene_hash = sha256_hex(scene.canonical);
  const RenderPiece& first = pieces.front();
  const int width = scene.image.width;
  const int height = scene.image.height;
  std::vector<int> order(static_cast<std::size_t>(first.tiles), -1);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const RenderPiece& p = pieces[i];
    const std::string& path = paths[i];
    if (p.scene_sha256 != scene_hash) {
      fail(path, "rendered from another scene (scene_sha256 " + p.scene_sha256 + ", this scene's " +
                     scene_hash + ")");
    }
    if (p.tiles != first.tiles || p.samples_per_axis != first.samples_per_axis ||
        p.layers != first.layers || p.adaptive != first.adaptive) {
      fail(path, "its tile count, samples per pixel, layers or adaptive sampling differ from " +
                     paths.front() + "'s (one render's pieces share them)");
    }
    if (p.band.width != width || p.tiles > height ||
        tile_rows(p.tile, p.tiles, height) !=
            std::pair{p.band.first_row, p.band.first_row + p.band.height}) {
      fail(path, "its rows are not tile " + std::to_string(p.tile) + " of " +
                     std::to_string(p.tiles) + " of the scene's " + std::to_string(width) + "x" +
                     std::to_string(height) + " image");
    }
    if (std::bit_cast<std::uint64_t>(p.band.unresolved.upwind) !=
            std::bit_cast<std::uint64_t>(first.band.unresolved.upwind) ||
        std::bit_cast<std::uint64_t>(p.band.unresolved.crosswind) !=
            std::bit_cast<std::uint64_t>(first.band.unresolved.crosswind) ||
        p.band.displacement_bound != first.band.displacement_bound) {
      fail(path, "its BRDF roughness or displacement bound differs from " + paths.front() +
                     "'s (another build or scene?)");
    }
    int& slot = order[static_cast<std::size_t>(p.tile)];
    if (slot >= 0) {
      fail(path, "tile " + std::to_string(p.tile) + " again (also in " +
                     paths[static_cast<std::size_t>(slot)] + ")");
    }
    slot = static_cast<int>(i);
  }
  for (std::size_t t = 0; t < order.size(); ++t) {
    if (order[t] < 0) {
      throw RenderPieceError("tile " + std::to_string(t) + " of " + std::to_string(first.tiles) +
                             " is missing");
    }
  }
  RenderedImage image;
  image.width = width;
  image.height = height;
  image.unresolved = first.band.unresolved;
  image.displacement_bound = first.band.displacement_bound;
  image.samples_per_axis = first.samples_per_axis;
  for (const int i : order) {
    const RenderedImage& band = pieces[static_cast<std::size_t>(i)].band;
    image.unconverged_samples += band.unconverged_samples;
    image.integrand_evaluations += band.integrand_evaluations;
    image.capped_pixels += band.capped_pixels;
    image.corrected_samples += band.corrected_samples;
    image.antialiased_pixels += band.antialiased_pixels;
    for_each_buffer(first.layers, first.adaptive, [&](auto member) {
      (image.*member).insert((image.*member).end(), (band.*member).begin(), (band.*member).end());
    });
  }
  require_finite(image);
  return image;
}

}  // namespace oceanref
