// Streaming output in bounded memory (io/sha256.h): the incremental SHA-256
// gives the digest of the concatenation of its pieces, however they are split.
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

using namespace oceanref;

namespace {
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
  // Any float bit pattern (NaN payloads, infinities, denormals): every bit of
  // the data path.
  float any_float() {
    const auto bits = static_cast<std::uint32_t>(next() >> 32);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }
};

} // namespace

// ---- SHA-256
// -----------------------------------------------------------------------------------

TEST_CASE(
    "Sha256: the FIPS 180-4 test vectors, the long one fed in uneven pieces") {
  CHECK(sha256_hex(std::string()) ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex(std::string("abc")) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  const std::string m448 =
      "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  CHECK(sha256_hex(m448) ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  // One million 'a', in pieces of 1, 2, 3, ... 200 bytes, again and again.
  const std::string a(1000000, 'a');
  Sha256 hash;
  std::size_t piece = 1;
  for (std::size_t at = 0; at < a.size(); piece = piece % 200 + 1) {
    const std::size_t n = std::min(piece, a.size() - at);
    hash.update(a.data() + at, n);
    at += n;
  }
  CHECK(hash.hex_digest() ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  CHECK(sha256_hex(a) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // The digest ends the hash.
  CHECK_THROWS_AS(hash.hex_digest(), std::logic_error);
  CHECK_THROWS_AS(hash.update("a", 1), std::logic_error);
}

TEST_CASE("Sha256: every padding boundary against Python's hashlib") {
  // Byte i of the message is (7 i + 3) mod 256; digests from hashlib.sha256
  // (Python 3.11).
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
      {1000,
       "1e9bc38cbf860b9ec31918b065f9b52476c549a782e0e7990bed8ce3868d2371"}};
  for (const auto &entry : expected) {
    const std::size_t length =
        entry.first; // not a binding: CAPTURE is a lambda
    std::vector<std::uint8_t> m(length);
    for (std::size_t i = 0; i < length; ++i)
      m[i] = static_cast<std::uint8_t>(7 * i + 3);
    CAPTURE(length);
    CHECK(sha256_hex(m) == entry.second);
  }
}

TEST_CASE("Sha256: random data split at every offset 0..130 equals the "
          "one-shot digest") {
  Random random{42};
  std::vector<std::uint8_t> data(260);
  for (std::uint8_t &b : data)
    b = random.byte();
  for (std::size_t length :
       {std::size_t{130}, std::size_t{200}, std::size_t{260}}) {
    const std::vector<std::uint8_t> m(
        data.begin(), data.begin() + static_cast<std::ptrdiff_t>(length));
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
      for (std::size_t i = 0; i < bytewise; ++i)
        three.update(m.data() + split + i, 1);
      three.update(m.data() + split + bytewise, length - split - bytewise);
      CHECK(three.hex_digest() == whole);
    }
  }
}
