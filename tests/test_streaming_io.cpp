// Streaming output in bounded memory (io/sha256.h, io/exr.h, io/png.h): the incremental SHA-256,
// the EXR written band by band (ExrRowWriter, read_exr_rows) and the PNG written row by row
// (PngRowWriter) give the same bytes as the whole-image writers, and leave no file unless
// finished.
#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <doctest/doctest.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/exr.h"
#include "io/output_file.h"
#include "io/png.h"
#include "io/sha256.h"

#include "temp_dir.h"
#include "test_support.h"

using namespace oceanref;

namespace {
using testing::channel;
using testing::same_bits;
// A fresh folder per test, named after this file.
using testing::TempDir;

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// SplitMix64: reproducible test data on every platform.
struct Random {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  std::uint8_t byte() { return static_cast<std::uint8_t>(next() >> 56); }
  // Any float bit pattern (NaN payloads, infinities, denormals): every bit of the data path.
  float any_float() {
    const auto bits = static_cast<std::uint32_t>(next() >> 32);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }
};

// ---- EXR helpers ---------------------------------------------------------------------------

// A test image: channels in an order that is not OpenEXR's (sorted) order, arbitrary float bit
// patterns (NaN, infinities, denormals), string and matrix attributes, chromaticities.
ExrImage test_image(int width, int height, std::uint64_t seed) {
  ExrImage image;
  image.width = width;
  image.height = height;
  Random random{seed};
  for (const char* name : {"R", "G", "B", "A.depth"}) {
    ExrChannel c{name, 1, std::vector<float>(static_cast<std::size_t>(width * height))};
    for (float& v : c.values) v = random.any_float();
    image.channels.push_back(std::move(c));
  }
  image.attributes["oceanref.version"] = "test 1.0";
  image.attributes["oceanref.note"] = "bands";
  image.matrices["worldToCamera"] = {
      {{1, 2, 3, 4}, {5, 6, 7, 8}, {9, 10, 11, 12}, {13, 14, 15, 16}}};
  image.srgb_chromaticities = true;
  return image;
}

// The file OpenEXR writes for `image` in one call to its own file writer (independent of
// io/exr.cpp): the bytes every oceanref EXR writer must reproduce.
std::string reference_exr(const std::string& path, const ExrImage& image) {
  const Imath::Box2i window(
      Imath::V2i(image.origin_x, image.origin_y),
      Imath::V2i(image.origin_x + image.width - 1, image.origin_y + image.height - 1));
  Imf::Header header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y,
                     Imf::ZIP_COMPRESSION);
  for (const auto& [key, value] : image.attributes) {
    header.insert(key, Imf::StringAttribute(value));
  }
  for (const auto& [key, m] : image.matrices) {
    Imath::M44f matrix;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        matrix[r][c] = m[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
      }
    }
    header.insert(key, Imf::M44fAttribute(matrix));
  }
  if (image.srgb_chromaticities) {
    Imf::addChromaticities(
        header, Imf::Chromaticities(Imath::V2f(0.64f, 0.33f), Imath::V2f(0.30f, 0.60f),
                                    Imath::V2f(0.15f, 0.06f), Imath::V2f(0.3127f, 0.3290f)));
  }
  Imf::FrameBuffer frame;
  for (const ExrChannel& c : image.channels) {
    header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
    frame.insert(c.name, Imf::Slice::Make(Imf::FLOAT, c.values.data(), window));
  }
  {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  }
  return file_bytes(path);
}

// Rows [first, first + rows) of every channel of `image`, in its channel order.
std::vector<std::vector<float>> band_of(const ExrImage& image, int first, int rows) {
  std::vector<std::vector<float>> band;
  const auto begin = static_cast<std::ptrdiff_t>(first) * image.width;
  const auto end = begin + static_cast<std::ptrdiff_t>(rows) * image.width;
  for (const ExrChannel& c : image.channels) {
    band.emplace_back(c.values.begin() + begin, c.values.begin() + end);
  }
  return band;
}

// Writes `image` through an ExrRowWriter in bands of `band` rows (the last one shorter).
void write_in_bands(const std::string& path, const ExrImage& image, int band) {
  ExrRowWriter writer(path, image);
  for (int y = 0; y < image.height; y += band) {
    const int rows = std::min(band, image.height - y);
    writer.write_rows(band_of(image, y, rows), rows);
  }
  CHECK(writer.rows_written() == image.height);
  writer.finish();
}

// ---- PNG helpers ---------------------------------------------------------------------------

std::uint32_t get32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
         static_cast<std::uint32_t>(p[2]) << 8 | static_cast<std::uint32_t>(p[3]);
}

struct PngChunk {
  std::string type;
  std::vector<std::uint8_t> data;
};

// The chunks of a PNG file; every CRC checked.
std::vector<PngChunk> png_chunks(const std::vector<std::uint8_t>& png) {
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  REQUIRE(png.size() >= 8);
  REQUIRE(std::memcmp(png.data(), signature, 8) == 0);
  std::vector<PngChunk> chunks;
  for (std::size_t at = 8; at < png.size();) {
    REQUIRE(at + 12 <= png.size());
    const std::uint32_t length = get32(png.data() + at);
    REQUIRE(at + 12 + length <= png.size());
    const std::uint8_t* type = png.data() + at + 4;
    const uLong crc = crc32(crc32(0L, type, 4), type + 4, length);
    CHECK(get32(type + 4 + length) == static_cast<std::uint32_t>(crc));
    chunks.push_back(
        {std::string(type, type + 4), std::vector<std::uint8_t>(type + 4, type + 4 + length)});
    at += 12 + length;
  }
  return chunks;
}

// The RGB rows of an 8-bit RGB PNG written by oceanref: IHDR checked, the IDAT chunks
// concatenated and inflated, each row's filter byte 0.
std::vector<std::uint8_t> decode_png(const std::vector<std::uint8_t>& png, int width, int height) {
  const std::vector<PngChunk> chunks = png_chunks(png);
  REQUIRE(chunks.size() >= 3);
  CHECK(chunks.front().type == "IHDR");
  REQUIRE(chunks.front().data.size() == 13);
  CHECK(get32(chunks.front().data.data()) == static_cast<std::uint32_t>(width));
  CHECK(get32(chunks.front().data.data() + 4) == static_cast<std::uint32_t>(height));
  CHECK(std::vector<std::uint8_t>(chunks.front().data.begin() + 8, chunks.front().data.end()) ==
        std::vector<std::uint8_t>{8, 2, 0, 0, 0});
  CHECK(chunks.back().type == "IEND");
  CHECK(chunks.back().data.empty());
  std::vector<std::uint8_t> compressed;
  for (std::size_t i = 1; i + 1 < chunks.size(); ++i) {
    CHECK(chunks[i].type == "IDAT");
    compressed.insert(compressed.end(), chunks[i].data.begin(), chunks[i].data.end());
  }
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(height) * (row + 1) + 1);
  uLongf size = static_cast<uLongf>(raw.size());
  REQUIRE(uncompress(raw.data(), &size, compressed.data(), static_cast<uLong>(compressed.size())) ==
          Z_OK);
  REQUIRE(size == static_cast<uLongf>(raw.size() - 1));  // no byte beyond the rows
  std::vector<std::uint8_t> rgb;
  for (int y = 0; y < height; ++y) {
    const auto* line = raw.data() + static_cast<std::size_t>(y) * (row + 1);
    CHECK(line[0] == 0);
    rgb.insert(rgb.end(), line + 1, line + 1 + row);
  }
  return rgb;
}

std::vector<std::uint8_t> random_rgb(int width, int height, std::uint64_t seed) {
  Random random{seed};
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width * height * 3));
  for (std::uint8_t& b : rgb) b = random.byte();
  return rgb;
}

std::vector<std::uint8_t> write_png_by_rows(const std::string& path, int width, int height,
                                            const std::vector<std::uint8_t>& rgb) {
  PngRowWriter writer(path, width, height);
  for (int y = 0; y < height; ++y) {
    writer.write_row(rgb.data() + static_cast<std::size_t>(y * width * 3));
  }
  writer.finish();
  const std::string bytes = file_bytes(path);
  return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
}
}  // namespace

// ---- SHA-256 -----------------------------------------------------------------------------------

TEST_CASE("Sha256: the FIPS 180-4 test vectors, the long one fed in uneven pieces") {
  CHECK(sha256_hex(std::string()) ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex(std::string("abc")) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  const std::string m448 = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  CHECK(sha256_hex(m448) == "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  // One million 'a', in pieces of 1, 2, 3, ... 200 bytes, again and again.
  const std::string a(1000000, 'a');
  Sha256 hash;
  std::size_t piece = 1;
  for (std::size_t at = 0; at < a.size(); piece = piece % 200 + 1) {
    const std::size_t n = std::min(piece, a.size() - at);
    hash.update(a.data() + at, n);
    at += n;
  }
  CHECK(hash.hex_digest() == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  CHECK(sha256_hex(a) == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // The digest ends the hash.
  CHECK_THROWS_AS(hash.hex_digest(), std::logic_error);
  CHECK_THROWS_AS(hash.update("a", 1), std::logic_error);
}

TEST_CASE("Sha256: every padding boundary against Python's hashlib") {
  // Byte i of the message is (7 i + 3) mod 256; digests from hashlib.sha256 (Python 3.11).
  const std::map<std::size_t, std::string> expected{
      {1, "084fed08b978af4d7d196a7446a86b58009e636b611db16211b65a9aadff29c5"},
      {55, "e7313d333c272e639f790978283f9eb392e843d0f29b7016828bb1daa4aac70b"},
      {56, "4324d65f3c103567f5589c710bc08f8523f929a9272e3af36fc968e52abc6c27"},
      {63, "81c80242132f230c3bd41b3e63bbcff16107339549214a99614ff26664625055"},
      {64, "39e3d7b6b5d075d37d053ad89b24b41bef4f3c29760c84447cab3f3be1882241"},
      {65, "aacca6ff74fdbb296d165a45cecfa04e5127bc008770fbbdd48006f2d2fae95e"},
      {119, "9ce7368e4daf32341631b492e80359dc9f594b48453cd0dd5bf0b19279cc177e"},
      {120, "7836b787757e95e58b3ca5aec90b1b004e8deba1e50e9675af9cabf1a13a04b5"},
      {127, "a8d23e75d936f303d248888d9b165ee543f4cbafcad3c9dd2a79bd84faa11d07"},
      {128, "d2742f1f4ac6bb7ca2b239ee18402ba8b3f9f8e652d2a72973c2b9ba11c08cf6"},
      {129, "307f8fc2c1622b92762e818d39a185d4d667ad49a4b07ceae1f4afa008a93ec4"},
      {130, "4d5e47a2e8510a314576c238f6ff19d389d3ef3aaaca8b2e530263a5d15741da"},
      {1000, "1e9bc38cbf860b9ec31918b065f9b52476c549a782e0e7990bed8ce3868d2371"}};
  for (const auto& entry : expected) {
    const std::size_t length = entry.first;  // not a binding: CAPTURE is a lambda
    std::vector<std::uint8_t> m(length);
    for (std::size_t i = 0; i < length; ++i) m[i] = static_cast<std::uint8_t>(7 * i + 3);
    CAPTURE(length);
    CHECK(sha256_hex(m) == entry.second);
  }
}

TEST_CASE("Sha256: random data split at every offset 0..130 equals the one-shot digest") {
  Random random{42};
  std::vector<std::uint8_t> data(260);
  for (std::uint8_t& b : data) b = random.byte();
  for (std::size_t length : {std::size_t{130}, std::size_t{200}, std::size_t{260}}) {
    const std::vector<std::uint8_t> m(data.begin(),
                                      data.begin() + static_cast<std::ptrdiff_t>(length));
    const std::string whole = sha256_hex(m);
    for (std::size_t split = 0; split <= 130; ++split) {
      CAPTURE(length);
      CAPTURE(split);
      Sha256 two;
      two.update(m.data(), split);
      two.update(m.data() + split, length - split);
      CHECK(two.hex_digest() == whole);
      // Three pieces: the split, then byte by byte for a while, then the rest.
      Sha256 three;
      three.update(m.data(), split);
      const std::size_t bytewise = std::min<std::size_t>(70, length - split);
      for (std::size_t i = 0; i < bytewise; ++i) three.update(m.data() + split + i, 1);
      three.update(m.data() + split + bytewise, length - split - bytewise);
      CHECK(three.hex_digest() == whole);
    }
  }
}

// ---- ExrRowWriter ------------------------------------------------------------------------------

TEST_CASE("ExrRowWriter: bands of 1, 7, 16, 17 rows and all rows give write_exr's bytes") {
  const TempDir dir;
  const ExrImage image = test_image(13, 40, 7);
  const std::string reference = reference_exr(dir.file("reference.exr"), image);
  REQUIRE(reference.size() > 1000);
  // write_exr (one band through ExrRowWriter) is OpenEXR's one-call file.
  write_exr(dir.file("whole.exr"), image);
  CHECK(file_bytes(dir.file("whole.exr")) == reference);
  for (const int band : {1, 7, 16, 17, 40}) {
    CAPTURE(band);
    const std::string path = dir.file("band" + std::to_string(band) + ".exr");
    write_in_bands(path, image, band);
    CHECK(file_bytes(path) == reference);
  }
  // Read back: every channel bit for bit, the attributes and matrices.
  const ExrImage back = read_exr(dir.file("band7.exr"));
  CHECK(back.width == 13);
  CHECK(back.height == 40);
  for (const ExrChannel& c : image.channels) {
    CHECK(same_bits(channel(back, c.name).values, c.values));
  }
  CHECK(back.attributes.at("oceanref.version") == "test 1.0");
  CHECK(back.attributes.at("oceanref.note") == "bands");
  CHECK(back.matrices.at("worldToCamera") == image.matrices.at("worldToCamera"));
  // Only the finished files are in the folder: no temporary.
  CHECK(dir.entries() == std::vector<std::string>{"band1.exr", "band16.exr", "band17.exr",
                                                  "band40.exr", "band7.exr", "reference.exr",
                                                  "whole.exr"});
}

TEST_CASE("ExrRowWriter: a data window off the origin, one row, one column; no channel refused") {
  const TempDir dir;
  ExrImage image = test_image(5, 23, 11);
  image.origin_x = 3;
  image.origin_y = -5;
  image.srgb_chromaticities = false;
  const std::string reference = reference_exr(dir.file("reference.exr"), image);
  write_in_bands(dir.file("off.exr"), image, 7);
  CHECK(file_bytes(dir.file("off.exr")) == reference);
  const ExrImage back = read_exr(dir.file("off.exr"));
  CHECK(back.origin_x == 3);
  CHECK(back.origin_y == -5);
  CHECK(same_bits(channel(back, "G").values, channel(image, "G").values));
  for (const auto& [width, height] : {std::pair{1, 1}, std::pair{1, 33}, std::pair{40, 1}}) {
    const ExrImage small = test_image(width, height, 3);
    write_in_bands(dir.file("small.exr"), small, 16);
    CHECK(file_bytes(dir.file("small.exr")) == reference_exr(dir.file("small_ref.exr"), small));
  }
  // No channel: OpenEXR refuses the header, an error naming the file, no file left.
  ExrImage empty = test_image(4, 20, 5);
  empty.channels.clear();
  const std::string path = dir.file("empty.exr");
  CHECK_THROWS_WITH_AS(ExrRowWriter(path, empty), doctest::Contains(path.c_str()),
                       std::runtime_error);
  CHECK(!std::filesystem::exists(path));
  CHECK(dir.entries().size() == 4);  // off, reference, small, small_ref
}

TEST_CASE("ExrRowWriter: deferred attributes set at the end give write_exr's bytes") {
  const TempDir dir;
  ExrImage image = test_image(9, 37, 23);
  // The pixel hashes of the render file, known only once every row is written.
  auto pixel_bytes = [](const ExrImage& im, int first, int rows) {
    std::vector<std::uint8_t> bytes;
    for (auto i = static_cast<std::size_t>(first * im.width);
         i < static_cast<std::size_t>((first + rows) * im.width); ++i) {
      for (std::size_t c = 0; c < 3; ++c) append_bytes(bytes, im.channels[c].values[i]);
    }
    return bytes;
  };
  const std::string pixel_sha = sha256_hex(pixel_bytes(image, 0, image.height));
  image.attributes["oceanref.pixel_sha256"] = pixel_sha;
  image.attributes["oceanref.z_last"] = "final";
  image.attributes["a_first"] = "12345678";
  write_exr(dir.file("whole.exr"), image);
  const std::string whole = file_bytes(dir.file("whole.exr"));
  CHECK(whole == reference_exr(dir.file("reference.exr"), image));

  ExrImage layout = image;
  for (const char* name : {"oceanref.pixel_sha256", "oceanref.z_last", "a_first"}) {
    layout.attributes[name] = "";  // the layout's value is ignored
  }
  for (ExrChannel& c : layout.channels) c.values.clear();  // and its pixels
  ExrRowWriter writer(dir.file("deferred.exr"), layout,
                      {{"oceanref.pixel_sha256", 64}, {"oceanref.z_last", 5}, {"a_first", 8}});
  Sha256 hash;
  for (int y = 0; y < image.height; y += 10) {
    const int rows = std::min(10, image.height - y);
    writer.write_rows(band_of(image, y, rows), rows);
    const std::vector<std::uint8_t> bytes = pixel_bytes(image, y, rows);
    hash.update(bytes.data(), bytes.size());
  }
  // Every deferred attribute must be set, with exactly its length, by name.
  CHECK_THROWS_AS(writer.finish(), std::logic_error);
  CHECK_THROWS_AS(writer.set_deferred("oceanref.pixel_sha256", "abc"), std::invalid_argument);
  CHECK_THROWS_AS(writer.set_deferred("oceanref.version", "test 1.0"), std::logic_error);
  writer.set_deferred("oceanref.pixel_sha256", hash.hex_digest());
  writer.set_deferred("a_first", "12345678");
  CHECK_THROWS_AS(writer.finish(), std::logic_error);
  writer.set_deferred("oceanref.z_last", "FINAL");
  writer.set_deferred("oceanref.z_last", "final");  // the last value counts
  writer.finish();
  CHECK(file_bytes(dir.file("deferred.exr")) == whole);
  const ExrImage back = read_exr(dir.file("deferred.exr"));
  CHECK(back.attributes.at("oceanref.pixel_sha256") == pixel_sha);
  CHECK(back.attributes.at("oceanref.z_last") == "final");
  CHECK(same_bits(channel(back, "R").values, channel(image, "R").values));
  // A finished writer takes no further call.
  CHECK_THROWS_AS(writer.finish(), std::logic_error);
  CHECK_THROWS_AS(writer.write_rows(band_of(image, 0, 1), 1), std::logic_error);
  // Not even a deferred attribute (the file is written: a value set now would never reach it).
  CHECK_THROWS_WITH_AS(writer.set_deferred("oceanref.z_last", "LATER"),
                       doctest::Contains("ExrRowWriter::set_deferred after finish()"),
                       std::logic_error);
  CHECK(file_bytes(dir.file("deferred.exr")) == whole);
}

TEST_CASE("ExrRowWriter: deferred attributes it cannot locate are refused, leaving no file") {
  const TempDir dir;
  ExrImage layout = test_image(4, 4, 1);
  const std::string path = dir.file("x.exr");
  // Not an attribute of the layout, or not a string attribute (a matrix).
  CHECK_THROWS_WITH_AS(ExrRowWriter(path, layout, {{"oceanref.missing", 4}}),
                       doctest::Contains("oceanref.missing is not a string attribute"),
                       std::logic_error);
  CHECK_THROWS_AS(ExrRowWriter(path, layout, {{"worldToCamera", 64}}), std::logic_error);
  // A placeholder found twice: `sha\0string\0<4>????` is also inside `x.sha`'s.
  layout.attributes["sha"] = "";
  layout.attributes["x.sha"] = "";
  CHECK_THROWS_WITH_AS(ExrRowWriter(path, layout, {{"sha", 4}, {"x.sha", 4}}),
                       doctest::Contains("found 2 times"), std::logic_error);
  // Different lengths tell them apart.
  {
    ExrRowWriter writer(path, layout, {{"sha", 4}, {"x.sha", 5}});
    CHECK(writer.rows_written() == 0);
  }
  CHECK(dir.entries().empty());
}

TEST_CASE("ExrRowWriter: wrong bands and early finish throw; unfinished writers leave no file") {
  const TempDir dir;
  const ExrImage image = test_image(6, 20, 9);
  const std::string path = dir.file("out.exr");
  {
    ExrRowWriter writer(path, image);
    std::vector<std::vector<float>> band = band_of(image, 0, 4);
    // Wrong channel count, wrong value count, no rows, more rows than are left.
    std::vector<std::vector<float>> three(band.begin(), band.begin() + 3);
    CHECK_THROWS_WITH_AS(writer.write_rows(three, 4), doctest::Contains(path.c_str()),
                         std::invalid_argument);
    CHECK_THROWS_AS(writer.write_rows(band, 3), std::invalid_argument);
    CHECK_THROWS_AS(writer.write_rows(band, 0), std::invalid_argument);
    CHECK_THROWS_AS(writer.write_rows(band_of(image, 0, 20), 21), std::invalid_argument);
    writer.write_rows(band, 4);
    CHECK_THROWS_WITH_AS(writer.finish(), doctest::Contains("after 4 of 20 rows"),
                         std::logic_error);
    // 17 rows (of a taller image) where 16 are left.
    CHECK_THROWS_AS(writer.write_rows(band_of(test_image(6, 21, 9), 4, 17), 17),
                    std::invalid_argument);
    CHECK(writer.rows_written() == 4);
    // Still usable after refused calls: the same file as write_exr.
    writer.write_rows(band_of(image, 4, 16), 16);
    writer.finish();
  }
  CHECK(file_bytes(path) == reference_exr(dir.file("reference.exr"), image));
  std::filesystem::remove(dir.file("reference.exr"));
  const std::string before = file_bytes(path);
  {
    // Destroyed without finish, after some rows or after all of them: the target is untouched
    // and no temporary is left.
    ExrRowWriter some(path, test_image(6, 20, 10));
    some.write_rows(band_of(image, 0, 5), 5);
    ExrRowWriter all(dir.file("new.exr"), image);
    all.write_rows(band_of(image, 0, 20), 20);
    CHECK(dir.entries().size() == 3);  // out.exr and two temporaries
  }
  CHECK(dir.entries() == std::vector<std::string>{"out.exr"});
  CHECK(file_bytes(path) == before);
  // Subsampled channels, repeated names and empty sizes are not written band by band.
  ExrImage sampled = test_image(4, 4, 2);
  sampled.channels.push_back({"half", 2, std::vector<float>(4)});
  CHECK_THROWS_AS(ExrRowWriter(dir.file("s.exr"), sampled), std::invalid_argument);
  ExrImage twice = test_image(4, 4, 2);
  twice.channels.push_back(twice.channels.front());
  CHECK_THROWS_AS(ExrRowWriter(dir.file("s.exr"), twice), std::invalid_argument);
  ExrImage empty = test_image(4, 4, 2);
  empty.height = 0;
  CHECK_THROWS_AS(ExrRowWriter(dir.file("s.exr"), empty), std::invalid_argument);
  // A missing folder is refused before anything is written.
  CHECK_THROWS_AS(ExrRowWriter(dir.file("no/such.exr"), image), OutputPathError);
  CHECK(dir.entries() == std::vector<std::string>{"out.exr"});
}

TEST_CASE("write_exr: subsampled channels keep their own path and still round-trip") {
  const TempDir dir;
  ExrImage image = test_image(4, 6, 4);
  image.channels.push_back({"low", 2, {1, 2, 3, 4, 5, 6}});
  write_exr(dir.file("s.exr"), image);
  const ExrImage back = read_exr(dir.file("s.exr"));
  CHECK(channel(back, "low").sampling == 2);
  CHECK(same_bits(channel(back, "low").values, {1, 2, 3, 4, 5, 6}));
  CHECK(same_bits(channel(back, "B").values, channel(image, "B").values));
}

// ---- read_exr_rows -----------------------------------------------------------------------------

TEST_CASE("read_exr_rows: any rows of any channels, as read_exr reads them") {
  const TempDir dir;
  ExrImage image = test_image(11, 45, 31);
  image.origin_x = -2;
  image.origin_y = 7;
  const std::string path = dir.file("in.exr");
  write_exr(path, image);
  const ExrImage whole = read_exr(path);
  const std::vector<std::string> names{"B", "A.depth", "R"};
  for (const auto& range : {std::pair{0, 1}, std::pair{0, 16}, std::pair{5, 22}, std::pair{15, 17},
                            std::pair{44, 45}, std::pair{0, 45}, std::pair{20, 20}}) {
    const int first = range.first, last = range.second;
    CAPTURE(first);
    CAPTURE(last);
    const std::vector<std::vector<float>> rows = read_exr_rows(path, names, first, last);
    REQUIRE(rows.size() == names.size());
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::vector<float>& all = channel(whole, names[i]).values;
      CHECK(same_bits(rows[i],
                      std::vector<float>(all.begin() + first * 11, all.begin() + last * 11)));
    }
  }
}

TEST_CASE("EXR writers and readers: one column, one row, one pixel") {
  // The smallest images a render writes (--width 1, --height 1): no writer or reader takes one
  // for an empty data window. Written whole and by rows (the same bytes), read whole and by rows.
  const TempDir dir;
  for (const auto& size : {std::pair{1, 5}, std::pair{6, 1}, std::pair{1, 1}}) {
    CAPTURE(size.first);
    CAPTURE(size.second);
    const ExrImage image = test_image(size.first, size.second, 3);
    const std::string path = dir.file("thin.exr");
    write_exr(path, image);
    write_in_bands(dir.file("bands.exr"), image, 2);
    CHECK(file_bytes(dir.file("bands.exr")) == file_bytes(path));
    const ExrImage back = read_exr(path);
    CHECK(back.width == size.first);
    CHECK(back.height == size.second);
    CHECK(same_bits(channel(back, "G").values, channel(image, "G").values));
    const std::vector<std::vector<float>> rows = read_exr_rows(path, {"G"}, 0, size.second);
    REQUIRE(rows.size() == 1);
    CHECK(same_bits(rows[0], channel(image, "G").values));
  }
}

TEST_CASE("read_exr_rows: reads only the blocks of its rows, and refuses what it cannot read") {
  const TempDir dir;
  const ExrImage image = test_image(8, 64, 17);
  const std::string path = dir.file("in.exr");
  write_exr(path, image);
  // Cut the file inside its last block (rows 48-63): the first rows still read, the whole
  // image does not.
  const std::string bytes = file_bytes(path);
  const std::string cut = dir.file("cut.exr");
  std::ofstream(cut, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()) - 20);
  const std::vector<std::vector<float>> top = read_exr_rows(cut, {"G"}, 0, 48);
  CHECK(same_bits(top[0], std::vector<float>(channel(image, "G").values.begin(),
                                             channel(image, "G").values.begin() + 48 * 8)));
  CHECK_THROWS_WITH_AS(read_exr_rows(cut, {"G"}, 40, 64), doctest::Contains(cut.c_str()),
                       std::runtime_error);
  CHECK_THROWS_AS(read_exr(cut), std::runtime_error);
  // A missing channel, rows outside the data window, a multi-part file, no file.
  CHECK_THROWS_WITH_AS(read_exr_rows(path, {"R", "Z"}, 0, 1), doctest::Contains("no channel Z"),
                       std::runtime_error);
  CHECK_THROWS_WITH_AS(read_exr_rows(path, {"R"}, 60, 65), doctest::Contains("outside the 64 rows"),
                       std::runtime_error);
  CHECK_THROWS_AS(read_exr_rows(path, {"R"}, -1, 3), std::runtime_error);
  CHECK_THROWS_WITH_AS(read_exr_rows(path, {"R", "G", "R"}, 0, 1),
                       doctest::Contains("channel R asked twice"), std::runtime_error);
  CHECK_THROWS_AS(read_exr_rows(path, {"R"}, 5, 4), std::runtime_error);
  ExrPart a{"a", 0, 0, test_image(2, 2, 1)};
  ExrPart b{"b", 0, 0, test_image(2, 2, 2)};
  a.image.srgb_chromaticities = b.image.srgb_chromaticities = false;
  write_exr_parts(dir.file("parts.exr"), {a, b});
  CHECK_THROWS_WITH_AS(read_exr_rows(dir.file("parts.exr"), {"R"}, 0, 1),
                       doctest::Contains("2 parts"), std::runtime_error);
  CHECK_THROWS_WITH_AS(read_exr_rows(dir.file("none.exr"), {"R"}, 0, 1),
                       doctest::Contains("none.exr"), std::runtime_error);
  // A subsampled channel.
  ExrImage sampled = test_image(4, 4, 2);
  sampled.channels.push_back({"low", 2, std::vector<float>(4)});
  write_exr(dir.file("sampled.exr"), sampled);
  CHECK_THROWS_WITH_AS(read_exr_rows(dir.file("sampled.exr"), {"low"}, 0, 2),
                       doctest::Contains("subsampled"), std::runtime_error);
  CHECK(read_exr_rows(dir.file("sampled.exr"), {"R"}, 0, 2)[0].size() == 8);
}

// ---- PngRowWriter ------------------------------------------------------------------------------

TEST_CASE("PngRowWriter: the bytes of encode_png, decoding to the rows, valid CRCs") {
  const TempDir dir;
  for (const auto& size :
       {std::pair{1, 1}, std::pair{3, 5}, std::pair{1000, 70}, std::pair{64, 1}}) {
    const int width = size.first, height = size.second;
    CAPTURE(width);
    CAPTURE(height);
    const std::vector<std::uint8_t> rgb =
        random_rgb(width, height, static_cast<std::uint64_t>(width * 1000 + height));
    const std::vector<std::uint8_t> encoded = encode_png(width, height, rgb);
    CHECK(write_png_by_rows(dir.file("rows.png"), width, height, rgb) == encoded);
    write_png(dir.file("whole.png"), width, height, rgb);
    const std::string whole = file_bytes(dir.file("whole.png"));
    CHECK(std::vector<std::uint8_t>(whole.begin(), whole.end()) == encoded);
    CHECK(decode_png(encoded, width, height) == rgb);
  }
  CHECK(dir.entries() == std::vector<std::string>{"rows.png", "whole.png"});
}

TEST_CASE("PngRowWriter: a large image in several IDAT chunks of 64 KiB, the last shorter") {
  const TempDir dir;
  const int width = 1000, height = 70;  // 210 000 random bytes: about 210 KB compressed
  const std::vector<std::uint8_t> rgb = random_rgb(width, height, 5);
  const std::vector<std::uint8_t> png = write_png_by_rows(dir.file("big.png"), width, height, rgb);
  const std::vector<PngChunk> chunks = png_chunks(png);
  std::size_t idat = 0;
  for (std::size_t i = 1; i + 1 < chunks.size(); ++i) {
    CHECK(chunks[i].type == "IDAT");
    if (i + 2 < chunks.size()) CHECK(chunks[i].data.size() == kPngIdatBytes);
    CHECK(!chunks[i].data.empty());
    ++idat;
  }
  CHECK(idat >= 3);
  CHECK(decode_png(png, width, height) == rgb);
  // A smooth image compresses to one chunk.
  std::vector<std::uint8_t> smooth(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t i = 0; i < smooth.size(); ++i) smooth[i] = static_cast<std::uint8_t>(i / 3000);
  CHECK(png_chunks(encode_png(width, height, smooth)).size() == 3);
}

TEST_CASE("PngRowWriter: a small image is the single-IDAT file of one compress2 call") {
  // Deflate's output does not depend on how its input is split, so a preview under 64 KiB
  // compressed keeps the bytes of the earlier one-IDAT writer (zlib compress2 at level 9).
  const int width = 37, height = 21;
  const std::vector<std::uint8_t> rgb = random_rgb(width, height, 77);
  std::vector<std::uint8_t> raw;
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgb.begin() + y * width * 3, rgb.begin() + (y + 1) * width * 3);
  }
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> compressed(size);
  REQUIRE(compress2(compressed.data(), &size, raw.data(), static_cast<uLong>(raw.size()), 9) ==
          Z_OK);
  compressed.resize(size);
  const std::vector<PngChunk> chunks = png_chunks(encode_png(width, height, rgb));
  REQUIRE(chunks.size() == 3);
  CHECK(chunks[1].data == compressed);
}

TEST_CASE("PngRowWriter: finish before the last row throws; no file without finish") {
  const TempDir dir;
  const std::string path = dir.file("p.png");
  const std::vector<std::uint8_t> rgb = random_rgb(4, 3, 1);
  {
    PngRowWriter writer(path, 4, 3);
    writer.write_row(rgb.data());
    writer.write_row(rgb.data() + 12);
    CHECK_THROWS_WITH_AS(writer.finish(), doctest::Contains("after 2 of 3 rows"), std::logic_error);
    CHECK(writer.rows_written() == 2);
    CHECK(dir.entries().size() == 1);  // the temporary
  }
  CHECK(dir.entries().empty());
  {
    PngRowWriter writer(path, 4, 3);
    for (int y = 0; y < 3; ++y) writer.write_row(rgb.data() + 12 * y);
    CHECK_THROWS_WITH_AS(writer.write_row(rgb.data()), doctest::Contains(path.c_str()),
                         std::logic_error);
    writer.finish();
    CHECK_THROWS_AS(writer.finish(), std::logic_error);
  }
  CHECK(file_bytes(path).size() > 8);
  CHECK(decode_png(encode_png(4, 3, rgb), 4, 3) == rgb);
  CHECK_THROWS_AS(PngRowWriter(dir.file("e.png"), 0, 3), std::invalid_argument);
  CHECK_THROWS_AS(PngRowWriter(dir.file("e.png"), 3, -1), std::invalid_argument);
  CHECK_THROWS_AS(PngRowWriter(dir.file("no/such.png"), 3, 3), OutputPathError);
  CHECK_THROWS_AS(encode_png(2, 2, std::vector<std::uint8_t>(11)), std::invalid_argument);
  CHECK_THROWS_AS(write_png(path, 2, 2, std::vector<std::uint8_t>(11)), std::invalid_argument);
  CHECK(dir.entries() == std::vector<std::string>{"p.png"});
}
