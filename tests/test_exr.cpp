// OpenEXR reading and writing (io/exr.h): multi-part round trips, tiled multi-resolution files
// written with OpenEXR's own API read back at every level, data windows, clear errors.
#include <ImfChannelList.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineOutputFile.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfPreviewImageAttribute.h>
#include <ImfStringVectorAttribute.h>
#include <ImfTiledOutputFile.h>
#include <ImfTiledOutputPart.h>
#include <doctest/doctest.h>
#include <unistd.h>

#include <half.h>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

#include "io/exr.h"
#include "io/exr_camera.h"

#include "temp_dir.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::same_bits;
// A fresh folder per test, named after this file.
using testing::TempDir;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

const ExrChannel* find_channel(const ExrImage& image, const std::string& name) {
  for (const ExrChannel& c : image.channels) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

// The value written at pixel (x, y) of mip level (lx, ly): small integers, exact in half.
float level_value(int lx, int ly, int x, int y) {
  return static_cast<float>(100 * lx + 10 * ly + x + 3 * y);
}
}  // namespace

TEST_CASE("write_exr_parts / read_exr_parts: two parts of different sizes round-trip bit for bit") {
  const TempDir dir;
  ExrPart a{"c0", 0, 0, {}};
  a.image.width = 3;
  a.image.height = 2;
  a.image.channels.push_back({"c0.R", 1, {0.5f, -1.0f, 3.25f, 1e-40f, -0.0f, 65504.0f}});
  a.image.channels.push_back(
      {"c0.G",
       1,
       {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
        -std::numeric_limits<float>::infinity(), 1.0f, 2.0f, 3.0f}});
  a.image.attributes["oceanref.units.c0.R"] = "m";
  a.image.matrices["worldToCamera"] = {
      {{1, 2, 3, 4}, {5, 6, 7, 8}, {9, 10, 11, 12}, {13, 14, 15, 16}}};
  ExrPart b{"c0.low", 0, 0, {}};
  b.image.width = 5;
  b.image.height = 4;
  std::vector<float> values(20);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.1f * static_cast<float>(i) - 0.7f;
  b.image.channels.push_back({"c0.height", 1, values});
  b.image.attributes["oceanref.note"] = "second";
  const std::string path = dir.file("two.exr");
  write_exr_parts(path, {a, b});
  const std::vector<ExrPart> read = read_exr_parts(path);
  REQUIRE(read.size() == 2);
  CHECK(read[0].name == "c0");
  CHECK(read[1].name == "c0.low");
  CHECK(read[0].image.width == 3);
  CHECK(read[0].image.height == 2);
  CHECK(read[1].image.width == 5);
  CHECK(read[1].image.height == 4);
  for (std::size_t p = 0; p < 2; ++p) {
    const ExrImage& original = (p == 0 ? a : b).image;
    CHECK(read[p].level_x == 0);
    CHECK(read[p].level_y == 0);
    CHECK(read[p].image.origin_x == 0);
    CHECK(read[p].image.origin_y == 0);
    CHECK(read[p].image.attributes == original.attributes);  // no `name`/`type` among them
    REQUIRE(read[p].image.channels.size() == original.channels.size());
    for (const ExrChannel& c : original.channels) {
      const ExrChannel* r = find_channel(read[p].image, c.name);
      REQUIRE(r != nullptr);
      REQUIRE(r->values.size() == c.values.size());
      for (std::size_t i = 0; i < c.values.size(); ++i) {
        CHECK(same_bits(r->values[i], c.values[i]));
      }
    }
  }
  REQUIRE(read[0].image.matrices.contains("worldToCamera"));
  CHECK(read[0].image.matrices.at("worldToCamera")[3][0] == 13.0f);
  CHECK(read[0].image.matrices.at("worldToCamera")[0][3] == 4.0f);
  CHECK(read[1].image.matrices.empty());
  // The single-part reader refuses to read just part 0 of it.
  CHECK(error_of([&] { read_exr(path); })
            .find("2 parts; read multi-part files with "
                  "read_exr_parts") != std::string::npos);
  // A one-part file is an ordinary file that read_exr reads.
  write_exr_parts(dir.file("one.exr"), {b});
  const ExrImage single = read_exr(dir.file("one.exr"));
  CHECK(single.width == 5);
  REQUIRE(single.channels.size() == 1);
  CHECK(single.channels[0].values == values);
}

TEST_CASE("write_exr_parts rejects what it cannot write, leaving no file") {
  const TempDir dir;
  ExrPart p{"a", 0, 0, {}};
  p.image.width = 2;
  p.image.height = 2;
  p.image.channels.push_back({"Y", 1, {1, 2, 3, 4}});
  const std::string path = dir.file("bad.exr");
  CHECK(error_of([&] { write_exr_parts(path, {p, p}); }).find("unique") != std::string::npos);
  ExrPart unnamed = p;
  unnamed.name.clear();
  CHECK(error_of([&] { write_exr_parts(path, {unnamed}); }).find("needs a name") !=
        std::string::npos);
  ExrPart sub = p;
  sub.image.channels.push_back({"Z", 2, {1}});
  CHECK(error_of([&] { write_exr_parts(path, {sub}); }).find("channel Z is subsampled") !=
        std::string::npos);
  ExrPart short_channel = p;
  short_channel.image.channels[0].values.pop_back();
  CHECK(error_of([&] { write_exr_parts(path, {short_channel}); }).find("3 values, expected 4") !=
        std::string::npos);
  ExrPart reserved = p;
  reserved.image.attributes["type"] = "scanlineimage";
  CHECK(error_of([&] { write_exr_parts(path, {reserved}); }).find("reserved") != std::string::npos);
  ExrPart level = p;
  level.level_x = 1;
  CHECK(error_of([&] { write_exr_parts(path, {level}); }).find("level 0, 0") != std::string::npos);
  CHECK(std::filesystem::is_empty(dir.path));
}

TEST_CASE("read_exr_parts: the reading buffers of one part are released before the next") {
  // Two 32 x 32 parts of one float channel (4096 B each), uncompressed: OpenEXR's line buffer is
  // one row (128 B), its tile buffers two 16 x 16 tiles (2048 B). max_bytes must hold every part's
  // pixels plus the largest buffer once, not once per part.
  const TempDir dir;
  for (const bool tiled : {false, true}) {
    CAPTURE(tiled);
    std::vector<Imf::Header> headers;
    for (const char* name : {"a", "b"}) {
      Imf::Header h(32, 32);
      h.compression() = Imf::NO_COMPRESSION;
      h.channels().insert("Y", Imf::Channel(Imf::FLOAT));
      h.setName(name);
      if (tiled) h.setTileDescription(Imf::TileDescription(16, 16, Imf::ONE_LEVEL));
      h.setType(tiled ? Imf::TILEDIMAGE : Imf::SCANLINEIMAGE);
      headers.push_back(h);
    }
    const std::string path = dir.file(tiled ? "tiled_parts.exr" : "scanline_parts.exr");
    std::vector<float> y(32 * 32, 0.5f);
    {
      Imf::MultiPartOutputFile file(path.c_str(), headers.data(), 2);
      for (int i = 0; i < 2; ++i) {
        Imf::FrameBuffer frame;
        frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), sizeof(float),
                                     32 * sizeof(float)));
        if (tiled) {
          Imf::TiledOutputPart part(file, i);
          part.setFrameBuffer(frame);
          part.writeTiles(0, part.numXTiles() - 1, 0, part.numYTiles() - 1);
        } else {
          Imf::OutputPart part(file, i);
          part.setFrameBuffer(frame);
          part.writePixels(32);
        }
      }
    }
    const double needed = 2 * 4096.0 + (tiled ? 2048.0 : 128.0);
    CHECK(read_exr_parts(path, needed).size() == 2);
    const std::string e = error_of([&] { read_exr_parts(path, needed - 1.0); });
    CAPTURE(e);
    CHECK(e.find("part 1 'b': 32 x 32 pixels of 1 channels need") != std::string::npos);
  }
}

TEST_CASE("read_exr_parts: a tiled mip-mapped and a rip-mapped file read at every level") {
  const TempDir dir;
  for (const Imf::LevelMode mode : {Imf::MIPMAP_LEVELS, Imf::RIPMAP_LEVELS}) {
    CAPTURE(static_cast<int>(mode));
    const int width = 16;
    const int height = 8;
    Imf::Header header(width, height);
    header.setTileDescription(Imf::TileDescription(4, 4, mode, Imf::ROUND_DOWN));
    header.channels().insert("Y", Imf::Channel(Imf::HALF));
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    const std::string path = dir.file("tiled.exr");
    {
      Imf::TiledOutputFile file(path.c_str(), header);
      for (int ly = 0; ly < (mode == Imf::RIPMAP_LEVELS ? file.numYLevels() : 1); ++ly) {
        for (int lx = 0; lx < file.numXLevels(); ++lx) {
          const int level_y = mode == Imf::RIPMAP_LEVELS ? ly : lx;
          const int w = file.levelWidth(lx);
          const int h = file.levelHeight(level_y);
          std::vector<half> y(static_cast<std::size_t>(w * h));
          std::vector<float> z(y.size());
          for (int r = 0; r < h; ++r) {
            for (int c = 0; c < w; ++c) {
              y[static_cast<std::size_t>(r * w + c)] = half(level_value(lx, level_y, c, r));
              z[static_cast<std::size_t>(r * w + c)] = -level_value(lx, level_y, c, r);
            }
          }
          Imf::FrameBuffer frame;
          frame.insert("Y", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(y.data()), sizeof(half),
                                       sizeof(half) * static_cast<std::size_t>(w)));
          frame.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(float),
                                       sizeof(float) * static_cast<std::size_t>(w)));
          file.setFrameBuffer(frame);
          file.writeTiles(0, file.numXTiles(lx) - 1, 0, file.numYTiles(level_y) - 1, lx, level_y);
        }
      }
    }
    const std::vector<ExrPart> parts = read_exr_parts(path);
    // 16×8: x levels 16, 8, 4, 2, 1; y levels 8, 4, 2, 1 (mip: 5 levels, the last 1×1).
    const std::size_t expected = mode == Imf::MIPMAP_LEVELS ? 5 : 5 * 4;
    REQUIRE(parts.size() == expected);
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const ExrPart& p = parts[i];
      const int lx = p.level_x;
      const int ly = p.level_y;
      if (mode == Imf::MIPMAP_LEVELS) {
        CHECK(lx == static_cast<int>(i));
        CHECK(ly == static_cast<int>(i));
      } else {
        CHECK(lx == static_cast<int>(i % 5));
        CHECK(ly == static_cast<int>(i / 5));
      }
      const int w = std::max(1, width >> lx);
      const int h = std::max(1, height >> ly);
      CHECK(p.image.width == w);
      CHECK(p.image.height == h);
      const ExrChannel* y = find_channel(p.image, "Y");
      const ExrChannel* z = find_channel(p.image, "Z");
      REQUIRE(y != nullptr);
      REQUIRE(z != nullptr);
      REQUIRE(y->values.size() == static_cast<std::size_t>(w * h));
      int wrong = 0;
      for (int r = 0; r < h; ++r) {
        for (int c = 0; c < w; ++c) {
          const std::size_t k = static_cast<std::size_t>(r * w + c);
          wrong += y->values[k] != level_value(lx, ly, c, r);
          wrong += z->values[k] != -level_value(lx, ly, c, r);
        }
      }
      CHECK(wrong == 0);
    }
  }
}

TEST_CASE("read_exr_parts: data windows not at the origin and half channels") {
  const TempDir dir;
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(9, 9));
  const Imath::Box2i window(Imath::V2i(3, -2), Imath::V2i(6, 0));  // 4 × 3 pixels
  Imf::Header header(display, window);
  header.channels().insert("R", Imf::Channel(Imf::HALF));
  std::vector<half> r(12);
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = half(static_cast<float>(i) * 0.25f);
  const std::string path = dir.file("window.exr");
  {
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert("R", Imf::Slice::Make(Imf::HALF, r.data(), window));
    file.setFrameBuffer(frame);
    file.writePixels(3);
  }
  const std::vector<ExrPart> parts = read_exr_parts(path);
  REQUIRE(parts.size() == 1);
  const ExrImage& image = parts[0].image;
  CHECK(parts[0].name.empty());
  CHECK(image.origin_x == 3);
  CHECK(image.origin_y == -2);
  CHECK(image.width == 4);
  CHECK(image.height == 3);
  REQUIRE(image.channels.size() == 1);
  for (std::size_t i = 0; i < r.size(); ++i)
    CHECK(image.channels[0].values[i] == 0.25f * static_cast<float>(i));
  // Our own writer keeps the origin too.
  ExrPart shifted{"shifted", 0, 0, image};
  write_exr_parts(dir.file("shifted.exr"), {shifted});
  const ExrImage back = read_exr(dir.file("shifted.exr"));
  CHECK(back.origin_x == 3);
  CHECK(back.origin_y == -2);
  CHECK(back.channels[0].values == image.channels[0].values);
}

TEST_CASE("read_exr_parts: clear errors for a missing file, a non-EXR file and deep data") {
  const TempDir dir;
  const std::string missing = dir.file("missing.exr");
  const std::string e1 = error_of([&] { read_exr_parts(missing); });
  CHECK(e1 == missing + ": cannot read the EXR file: no such file");
  CHECK(error_of([&] { read_exr(missing); }) == e1);
  const std::string text = dir.file("text.exr");
  std::ofstream(text) << "not an image\n";
  const std::string e2 = error_of([&] { read_exr_parts(text); });
  CHECK(e2.find(text + ": cannot read the EXR file: ") == 0);
  CHECK(e2.size() > (text + ": cannot read the EXR file: ").size());
  CHECK(error_of([&] { read_exr_parts(dir.path.string()); }).find("not a regular file") !=
        std::string::npos);
  // A deep scanline file written with OpenEXR's API: one sample per pixel.
  const std::string deep = dir.file("deep.exr");
  {
    Imf::Header header(2, 1);
    header.setType(Imf::DEEPSCANLINE);
    header.compression() = Imf::ZIPS_COMPRESSION;
    header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
    Imf::DeepScanLineOutputFile file(deep.c_str(), header);
    std::vector<unsigned int> counts{1, 1};
    std::vector<float> samples{1.0f, 2.0f};
    std::vector<float*> pointers{&samples[0], &samples[1]};
    Imf::DeepFrameBuffer frame;
    frame.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()),
                                            sizeof(unsigned int), 2 * sizeof(unsigned int)));
    frame.insert("Z", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(pointers.data()),
                                     sizeof(float*), 2 * sizeof(float*), sizeof(float)));
    file.setFrameBuffer(frame);
    file.writePixels(1);
  }
  const std::string e3 = error_of([&] { read_exr_parts(deep); });
  CHECK(e3.find("part 0: deep data (deepscanline) is not supported") != std::string::npos);
}

TEST_CASE("read_exr_parts: an attribute claiming more bytes than the file holds, in any header") {
  // Headers by hand (magic, version 2 with the multi-part flag, then name\0type\0size value
  // attributes, an empty name ending each header, an empty header ending the list). OpenEXR reads
  // the first header even when it is empty, and the ones after it: so does the size check.
  const auto attribute = [](const std::string& name, const std::string& type, std::int32_t claimed,
                            const std::string& value) {
    std::string a = name + '\0' + type + '\0';
    for (int b = 0; b < 4; ++b) a += static_cast<char>((claimed >> (8 * b)) & 0xff);
    return a + value;
  };
  const std::string magic("\x76\x2f\x31\x01\x02\x10\x00\x00", 8);
  const std::string claim = attribute("name", "string", 2000000000, "abc");
  const std::string small = attribute("a", "int", 4, std::string(4, '\0'));
  const TempDir dir;
  for (const std::pair<std::string, std::string>& c :
       {std::pair<std::string, std::string>{"second header", small + '\0' + claim + '\0' + '\0'},
        std::pair<std::string, std::string>{"after an empty first header",
                                            '\0' + claim + '\0' + '\0'}}) {
    CAPTURE(c.first);
    const std::string path = dir.file("claims.exr");
    std::ofstream(path, std::ios::binary) << magic + c.second;
    CHECK(error_of([&] { read_exr_parts(path); }) ==
          path +
              ": cannot read the EXR file: header attribute name (string) claims 2000000000 "
              "bytes, but only 5 bytes of the file follow");
  }
}

TEST_CASE("EXR sampling and size: what oceanref cannot hold is refused, naming the channel") {
  const TempDir dir;
  // Written: an empty image; a channel whose sampling does not divide the size.
  ExrImage empty;
  empty.width = 0;
  empty.height = 3;
  const std::string out = dir.file("out.exr");
  CHECK(error_of([&] { write_exr(out, empty); }) == out + ": size 0x3 is empty");
  ExrImage odd;
  odd.width = 3;
  odd.height = 2;
  odd.channels.push_back({"Y", 2, {1.0f}});
  CHECK(error_of([&] { write_exr(out, odd); }) ==
        out + ": channel Y has sampling 2, which does not divide the size");
  odd.width = 4;  // 2 divides 4 x 2: accepted, and read back with its sampling
  odd.channels[0].values = {1.0f, 2.0f};
  write_exr(out, odd);
  const ExrImage back = read_exr(out);
  REQUIRE(back.channels.size() == 1);
  CHECK(back.channels[0].sampling == 2);
  CHECK(back.channels[0].values == std::vector<float>{1.0f, 2.0f});
  // Read: x and y sampling that differ (OpenEXR allows it; ExrChannel has one factor).
  const std::string uneven = dir.file("uneven.exr");
  {
    Imf::Header header(4, 2);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT, 2, 1));
    Imf::OutputFile file(uneven.c_str(), header);
    std::vector<float> y(4, 1.0f);
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), sizeof(float),
                                 2 * sizeof(float), 2, 1));
    file.setFrameBuffer(frame);
    file.writePixels(2);
  }
  CHECK(error_of([&] { read_exr(uneven); })
            .find("channel Y has sampling 2,1 (supported: equal x and y sampling dividing the "
                  "data window)") != std::string::npos);
}

TEST_CASE(
    "read_exr_parts: string-vector and preview attributes measured before OpenEXR reads them") {
  // A file another tool could write: a multi-view list (stringvector) and a 3 × 2 preview.
  const TempDir dir;
  const std::string path = dir.file("views.exr");
  {
    Imf::Header header(2, 1);
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.insert("multiView", Imf::StringVectorAttribute({"left", "right", "centre"}));
    header.insert("preview", Imf::PreviewImageAttribute(Imf::PreviewImage(3, 2)));
    Imf::OutputFile file(path.c_str(), header);
    std::vector<float> r{0.25f, -2.0f};
    Imf::FrameBuffer frame;
    frame.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.data()), sizeof(float),
                                 2 * sizeof(float)));
    file.setFrameBuffer(frame);
    file.writePixels(1);
  }
  const std::vector<ExrPart> parts = read_exr_parts(path);
  REQUIRE(parts.size() == 1);
  REQUIRE(parts[0].image.channels.size() == 1);
  CHECK(parts[0].image.channels[0].values == std::vector<float>{0.25f, -2.0f});
  // The same file with the first string's length past the attribute's end: refused, named.
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string key("multiView\0stringvector\0", 23);
  const std::size_t at = bytes.find(key);
  REQUIRE(at != std::string::npos);
  std::int32_t size = 0, first = 0;
  std::memcpy(&size, bytes.data() + at + key.size(), 4);
  std::memcpy(&first, bytes.data() + at + key.size() + 4, 4);
  CHECK(size == 3 * 4 + 4 + 5 + 6);  // each string: its length (int32), then its bytes
  CHECK(first == 4);
  const std::int32_t too_long = size;
  std::memcpy(bytes.data() + at + key.size() + 4, &too_long, 4);
  const std::string broken = dir.file("broken.exr");
  std::ofstream(broken, std::ios::binary) << bytes;
  const std::string e = error_of([&] { read_exr_parts(broken); });
  CAPTURE(e);
  CHECK(e.find("multiView") != std::string::npos);
  CHECK(e.find("holds a string of 27 bytes past its end") != std::string::npos);
  // A preview of (2^32 - 1)^2 pixels, whose byte count (4 per pixel) overflows 64 bits: refused,
  // named (the fuzzer found that overflow).
  std::memcpy(bytes.data() + at + key.size() + 4, &first, 4);  // the string restored
  const std::string preview_key("preview\0preview\0", 16);
  const std::size_t p = bytes.find(preview_key);
  REQUIRE(p != std::string::npos);
  std::memset(bytes.data() + p + preview_key.size() + 4, 0xff, 8);  // width, height
  const std::string huge = dir.file("huge_preview.exr");
  std::ofstream(huge, std::ios::binary) << bytes;
  const std::string e2 = error_of([&] { read_exr_parts(huge); });
  CAPTURE(e2);
  CHECK(e2.find("attribute preview (preview) declares 32 bytes, but its preview of 4294967295 x "
                "4294967295 pixels needs more") != std::string::npos);
}

TEST_CASE("worldToCamera and worldToNDC reproduce the camera's projection") {
  const Camera camera = make_camera({3.0, 6.0, -2.0}, {10.0, 1.0, 90.0}, {0.0, 1.0, 0.0},
                                    50.0 * 3.141592653589793 / 180.0, 640, 360);
  const ExrMatrix view = world_to_camera_matrix(camera);
  const ExrMatrix ndc = world_to_ndc_matrix(camera);
  const auto times = [](const ExrMatrix& m, const glm::dvec3& p) {
    std::array<double, 4> out{};
    for (std::size_t c = 0; c < 4; ++c) {
      const auto e = [&](std::size_t r) { return static_cast<double>(m[r][c]); };
      out[c] = p.x * e(0) + p.y * e(1) + p.z * e(2) + e(3);
    }
    return out;
  };
  int checked = 0;
  for (const glm::dvec3 p : {glm::dvec3{10.0, 1.0, 90.0}, glm::dvec3{-20.0, 0.0, 40.0},
                             glm::dvec3{35.0, -3.0, 200.0}, glm::dvec3{0.0, 12.0, 15.0}}) {
    const glm::dvec3 pixel = project(camera, p);  // x, y [pixels], depth z [m]
    const std::array<double, 4> c = times(view, p);
    // Camera space: +z forward (the depth), +x right, +y up (left-handed, RenderMan).
    CHECK(c[2] == doctest::Approx(pixel.z).epsilon(1e-6));
    const std::array<double, 4> h = times(ndc, p);
    // float32 matrices: the error is a few float ulps of the entries times |p| (< 1e-3 px here).
    CHECK(h[0] / h[3] * 640.0 == doctest::Approx(pixel.x).epsilon(2e-6).scale(640.0));
    CHECK(h[1] / h[3] * 360.0 == doctest::Approx(pixel.y).epsilon(2e-6).scale(360.0));
    CHECK(std::fabs(c[0]) + std::fabs(c[1]) > 0.0);
    ++checked;
  }
  CHECK(checked == 4);
  // The look-at point projects to the image centre.
  const std::array<double, 4> centre = times(ndc, {10.0, 1.0, 90.0});
  CHECK(centre[0] / centre[3] == doctest::Approx(0.5).epsilon(1e-6));
  CHECK(centre[1] / centre[3] == doctest::Approx(0.5).epsilon(1e-6));
}
