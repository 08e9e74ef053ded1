// Render pieces (`render --tile I/N`, `merge`): the tiles partition the rows, a piece file keeps
// every bit, the merged pieces are the whole render, and bad pieces are refused by name.
#include <doctest/doctest.h>

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "conformance/render_output.h"
#include "conformance/render_piece.h"
#include "scene/scene.h"

#include "temp_dir.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::same_bits;
// A fresh folder per test, named after this file.
using testing::TempDir;

std::string piece_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const RenderPieceError& e) {
    return e.what();
  }
  return "";
}

// A small fast scene with waves, sun and sky (whitecaps on, so every buffer has content).
Scene piece_scene() {
  const nlohmann::json s = nlohmann::json::parse(R"({
    "seed": 7,
    "waves": {"spectrum": {"model": "jonswap", "wind_speed": 9, "fetch": 60000},
              "cascades": {"largest": 200, "count": 2, "factor": "golden-small"},
              "resolution": 32, "choppiness": -1.0},
    "camera": {"position": [0, 4, 0], "look_at": [0, 1, 40]},
    "grid": {"columns": 64, "rows": 64},
    "atmosphere": {"sun_zenith_deg": 70, "sun_azimuth_deg": 10},
    "shading": {"accuracy": "fast", "whitecaps": true, "whitecap_threshold": 0.7},
    "render": {"width": 24, "height": 17, "samples_per_pixel": 4}})");
  return parse_scene(s);
}

RenderPiece piece_of(const Scene& scene, int tile, int tiles, bool aov) {
  RenderOutputOptions options;
  options.threads = 2;
  options.tile = tile;
  options.tiles = tiles;
  options.aov = aov;
  return render_scene_piece(scene, options);
}
}  // namespace

TEST_CASE("tiles partition the rows: contiguous, in order, none empty") {
  for (const int height : {1, 2, 7, 17, 360, 65536}) {
    for (const int count : {1, 2, 3, 7, 64}) {
      if (count > height) continue;
      int next = 0;
      for (int i = 0; i < count; ++i) {
        const auto [first, last] = tile_rows(i, count, height);
        CHECK(first == next);
        CHECK(last > first);
        next = last;
      }
      CHECK(next == height);
    }
  }
}

TEST_CASE("merged pieces are the whole render, bit for bit, with and without the layers") {
  const Scene scene = piece_scene();
  TempDir dir;
  for (const bool aov : {false, true}) {
    CAPTURE(aov);
    RenderOutputOptions options;
    options.threads = 2;
    options.aov = aov;
    const RenderedScene whole = render_scene(scene, options);
    for (const int tiles : {1, 2, 5, 17}) {
      CAPTURE(tiles);
      std::vector<RenderPiece> pieces;
      std::vector<std::string> paths;
      for (int i = tiles - 1; i >= 0; --i) {  // any order
        paths.push_back(dir.file("t" + std::to_string(i) + ".piece"));
        write_render_piece(paths.back(), piece_of(scene, i, tiles, aov));
        pieces.push_back(read_render_piece(paths.back()));
      }
      const RenderedScene merged =
          scene_output(scene, merge_render_pieces(scene, pieces, paths), aov);
      CHECK(merged.pixel_sha256 == whole.pixel_sha256);
      CHECK(merged.radiance_f64_sha256 == whole.radiance_f64_sha256);
      const RenderedImage& a = merged.image;
      const RenderedImage& b = whole.image;
      CHECK(same_bits(a.radiance, b.radiance));
      CHECK(same_bits(a.lighting_error, b.lighting_error));
      CHECK(same_bits(a.coverage, b.coverage));
      CHECK(same_bits(a.foam, b.foam));
      CHECK(same_bits(a.depth, b.depth));
      CHECK(same_bits(a.x0, b.x0));
      CHECK(a.unconverged_samples == b.unconverged_samples);
      CHECK(a.integrand_evaluations == b.integrand_evaluations);
      CHECK(a.unresolved.upwind == b.unresolved.upwind);
      CHECK(merged.exr.attributes == whole.exr.attributes);
      REQUIRE(merged.exr.channels.size() == whole.exr.channels.size());
      for (std::size_t c = 0; c < merged.exr.channels.size(); ++c) {
        CHECK(merged.exr.channels[c].name == whole.exr.channels[c].name);
        CHECK(same_bits(merged.exr.channels[c].values, whole.exr.channels[c].values));
      }
    }
    if (aov) {  // the layers are there and not all zero
      double foam = 0.0;
      for (const Vec3& f : whole.image.foam) foam += f[0];
      CHECK(foam > 0.0);
    }
  }
}

TEST_CASE("a tile's memory estimate counts its own rows") {
  const Scene scene = piece_scene();
  RenderOutputOptions options;
  const double whole = render_memory_estimate(scene, options).total();
  options.tiles = 17;
  const double tile = render_memory_estimate(scene, options).total();
  CHECK(tile < whole);
  options.aov = true;
  CHECK(render_memory_estimate(scene, options).total() > tile);
}

TEST_CASE("bad pieces are refused, naming the file and what is wrong") {
  const Scene scene = piece_scene();
  TempDir dir;
  const std::string p0 = dir.file("p0.piece"), p1 = dir.file("p1.piece");
  write_render_piece(p0, piece_of(scene, 0, 2, false));
  write_render_piece(p1, piece_of(scene, 1, 2, false));
  const RenderPiece a = read_render_piece(p0), b = read_render_piece(p1);
  CHECK(piece_error_of([&] { merge_render_pieces(scene, {a, b}, {p0, p1}); }).empty());
  CHECK(piece_error_of([&] { merge_render_pieces(scene, {a}, {p0}); }) == "tile 1 of 2 is missing");
  CHECK(piece_error_of([&] {
          merge_render_pieces(scene, {a, a}, {p0, p0});
        }).find("tile 0 again") != std::string::npos);
  Scene other = scene;
  other.canonical += " ";
  CHECK(piece_error_of([&] {
          merge_render_pieces(other, {a, b}, {p0, p1});
        }).find(p0 + ": rendered from another scene") == 0);
  const RenderPiece c = piece_of(scene, 1, 3, false);
  CHECK(piece_error_of([&] {
          merge_render_pieces(scene, {a, c}, {p0, "c"});
        }).find("c: its tile count") == 0);
  const RenderPiece d = piece_of(scene, 1, 2, true);
  CHECK(piece_error_of([&] {
          merge_render_pieces(scene, {a, d}, {p0, "d"});
        }).find("layers") != std::string::npos);
  RenderPiece e = b;
  e.band.unresolved.upwind *= 1.0 + 1e-15;
  CHECK(piece_error_of([&] {
          merge_render_pieces(scene, {a, e}, {p0, "e"});
        }).find("e: its BRDF roughness") == 0);

  // Damaged files: each refused before its pixels are used.
  std::ifstream in(p1, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string header_end = "}\n";
  const std::size_t body = bytes.find(header_end) + header_end.size();
  const auto damaged = [&](const std::string& content) {
    const std::string path = dir.file("damaged.piece");
    std::ofstream(path, std::ios::binary) << content;
    return piece_error_of([&] { read_render_piece(path); });
  };
  CHECK(damaged(bytes).empty());
  CHECK(damaged("").find("not an oceanref render piece") != std::string::npos);
  CHECK(damaged("x" + bytes.substr(1)).find("not an oceanref render piece") != std::string::npos);
  CHECK(damaged(bytes.substr(0, body - 1)).find("not terminated") != std::string::npos);
  CHECK(damaged(bytes.substr(0, bytes.size() - 8)).find("its header describes") !=
        std::string::npos);
  CHECK(damaged(bytes + "x").find("its header describes") != std::string::npos);
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = bytes;
    const std::size_t at = s.find(from);
    REQUIRE(at < body);
    return damaged(s.replace(at, from.size(), to));
  };
  CHECK(replaced("\"tile\":1", "\"tile\":2").find("header key tile") != std::string::npos);
  CHECK(replaced("\"rows\":", "\"rows\":-").find("header key rows") != std::string::npos);
  CHECK(replaced("\"layers\":false", "\"layers\":0").find("header key layers") !=
        std::string::npos);
  CHECK(replaced("\"width\":24", "\"width\":2400000000").find("header key width") !=
        std::string::npos);
  CHECK(replaced("{", "[").find("unreadable header") != std::string::npos);
  CHECK(replaced("\"scene_sha256\":\"", "\"scene_sha256\":\"0")
            .find("header key scene_sha256: 64 hex digits expected") != std::string::npos);
  CHECK(replaced("\"unresolved_slope_variance\":[", "\"unresolved_slope_variance\":[1,")
            .find("header key unresolved_slope_variance: [upwind, crosswind]") !=
        std::string::npos);
  CHECK(replaced("\"displacement_bound\":", "\"displacement_bound\":-")
            .find("header key displacement_bound: a finite number >= 0") != std::string::npos);
  CHECK(replaced("{", "{\"extra\":1,").find("keys other than those of format 3") !=
        std::string::npos);
  // A piece whose rows are not its tile's.
  RenderPiece shifted = b;
  shifted.band.first_row -= 1;
  CHECK(piece_error_of([&] {
          merge_render_pieces(scene, {a, shifted}, {p0, "s"});
        }).find("s: its rows are not tile 1 of 2 of the scene's 24x17 image") == 0);
}

TEST_CASE("pieces of a render with Mastin's anti-aliasing keep its count of antialiased pixels") {
  // Only those pieces carry the key (format 3 unchanged otherwise); the merged count is the
  // whole render's, and not 0.
  Scene scene = piece_scene();
  scene.image.mastin_antialiasing = 0.02;
  TempDir dir;
  RenderOutputOptions options;
  options.threads = 2;
  const RenderedScene whole = render_scene(scene, options);
  REQUIRE(whole.image.antialiased_pixels > 0);
  std::vector<RenderPiece> pieces;
  std::vector<std::string> paths;
  for (int i = 0; i < 3; ++i) {
    paths.push_back(dir.file("m" + std::to_string(i) + ".piece"));
    write_render_piece(paths.back(), piece_of(scene, i, 3, false));
    pieces.push_back(read_render_piece(paths.back()));
    CHECK(pieces.back().antialiased);
  }
  const RenderedImage merged = merge_render_pieces(scene, pieces, paths);
  CHECK(merged.antialiased_pixels == whole.image.antialiased_pixels);
  CHECK(same_bits(merged.radiance, whole.image.radiance));
}

TEST_CASE("merge: the image's counters are the sums of its pieces' counters") {
  // Each counter of each piece set to its own value (a fast render has no lighting evaluations
  // or unconverged samples to sum): the merged image carries the three sums.
  const Scene scene = piece_scene();
  std::vector<RenderPiece> pieces;
  for (int i = 0; i < 3; ++i) {
    RenderPiece p = piece_of(scene, i, 3, false);
    p.band.unconverged_samples = 1 + i;
    p.band.integrand_evaluations = 100 * (1 + i);
    p.band.capped_pixels = 10 * (1 + i);
    p.band.antialiased_pixels = 1000 * (1 + i);
    pieces.push_back(p);
  }
  const RenderedImage merged = merge_render_pieces(scene, pieces, {"a", "b", "c"});
  CHECK(merged.unconverged_samples == 6);
  CHECK(merged.integrand_evaluations == 600);
  CHECK(merged.capped_pixels == 60);
  CHECK(merged.antialiased_pixels == 6000);
}
