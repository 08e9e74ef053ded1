// Strict parsing (issue 15 point 4): scene JSON with duplicate keys, bytes after the value, NUL
// bytes, numbers that overflow a double, integers out of range and wrong types is rejected with
// the JSON path, the value (escaped) and the accepted range; the same for command-line numbers.
// Each check compares exact message parts, so a looser parser or a vaguer message fails it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/text.h"
#include "core/choice.h"
#include "core/format.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "waves/ocean.h"

using namespace oceanref;
using nlohmann::json;

namespace {
// The tiny valid scene every case starts from (8x8 grid, one cascade).
const std::string kBase =
    R"({"seed": 1, "waves": {"resolution": 8, "cascades": {"sizes": [50]}},
        "render": {"width": 8, "height": 8, "samples_per_pixel": 1}})";

// The message of the SceneError that parsing `text` throws ("" when it parses).
std::string scene_error(const std::string& text) {
  try {
    (void)parse_scene(parse_scene_json(text, "scene.json"));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// A scene whose waves section has `waves_members` (raw JSON text, ", key: value...") added.
std::string with_waves(const std::string& waves_members) {
  return R"({"seed": 1, "waves": {"resolution": 8, "cascades": {"sizes": [50]})" + waves_members +
         "}}";
}

std::string usage_error(void (*f)()) {
  try {
    f();
  } catch (const cli::UsageError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("strict parsing: the base scene parses") {
  CHECK(scene_error(kBase).empty());
}

TEST_CASE("strict parsing: escape_value") {
  CHECK(escape_value("abc-1.5e3") == "abc-1.5e3");
  CHECK(escape_value(std::string("a\0b", 3)) == "a\\x00b");
  CHECK(escape_value("\x1b[31mred") == "\\x1B[31mred");
  CHECK(escape_value("tab\there\n") == "tab\\x09here\\x0A");
  CHECK(escape_value("back\\slash") == "back\\\\slash");
  CHECK(escape_value("\x7f") == "\\x7F");
  // Non-UTF-8 and UTF-8 alike: every byte over 0x7F as \xNN.
  CHECK(escape_value("\xff\xfe") == "\\xFF\\xFE");
  CHECK(escape_value("\xc3\xa9") == "\\xC3\\xA9");
  // Cut at max_bytes, marked with the ellipsis (U+2026).
  CHECK(escape_value(std::string(100, 'x'), 10) == std::string(10, 'x') + "\u2026");
  CHECK(escape_value(std::string(10, 'x'), 10) == std::string(10, 'x'));
}

TEST_CASE("strict parsing: duplicate keys at any depth name their path") {
  CHECK(scene_error(R"({"seed": 1, "seed": 2, "waves": {}})") ==
        "seed: duplicate key (given more than once in the same object; give each key once)");
  CHECK(scene_error(with_waves(R"(, "resolution": 16)"))
            .rfind("waves.resolution: duplicate key", 0) == 0);
  CHECK(scene_error(R"({"waves": {"cascades": {"sizes": [50], "sizes": [60]}}})")
            .rfind("waves.cascades.sizes: duplicate key", 0) == 0);
  // Inside an array: the index is part of the path.
  CHECK(scene_error(R"({"waves": {"cascades": {"sizes": [50, {"a": 1, "a": 2}]}}})")
            .rfind("waves.cascades.sizes[1].a: duplicate key", 0) == 0);
  // The same key in two different objects is fine.
  CHECK(scene_error(R"({"seed": 1, "waves": {"resolution": 8, "cascades": {"sizes": [50]}},
      "render": {"width": 8, "height": 8, "samples_per_pixel": 1},
      "grid": {"columns": 8, "rows": 8}})")
            .empty());
  // A duplicated key's name is escaped.
  CHECK(scene_error("{\"se\\u001bd\": 1, \"se\\u001bd\": 2}").rfind("se\\x1Bd: duplicate key", 0) ==
        0);
}

TEST_CASE("strict parsing: bytes after the value and NUL bytes") {
  CHECK(scene_error(kBase + " \n\t ").empty());
  const std::string trailing = scene_error(kBase + " x");
  CHECK(trailing.rfind("scene.json: not valid JSON: parse error at line 2, column 70: ", 0) == 0);
  CHECK(trailing.find("expected end of input") != std::string::npos);
  CHECK(scene_error("{} {}").rfind("scene.json: not valid JSON: parse error at line 1, column 4: ",
                                   0) == 0);
  // A NUL byte ends nlohmann's input: "{...}\0garbage" used to parse.
  const std::string nul = kBase + std::string("\0garbage", 8);
  CHECK(scene_error(nul) ==
        "scene.json: not valid JSON: a NUL byte at line 2, column 69 (a scene file is UTF-8 JSON "
        "text)");
  CHECK(scene_error(std::string("\0", 1)) ==
        "scene.json: not valid JSON: a NUL byte at line 1, column 1 (a scene file is UTF-8 JSON "
        "text)");
  // Raw bytes in a syntax error are escaped: nlohmann's "last read" quotes the input (it writes
  // control bytes as <U+001B> itself, but passes bytes over 0x7F through).
  const std::string raw = scene_error("{\"seed\": \x1b[2J\xff}");
  CHECK(raw.find('\x1b') == std::string::npos);
  CHECK(raw.find("\xff") == std::string::npos);
  CHECK(raw.find("last read: '\"seed\": <U+001B>'") != std::string::npos);
  const std::string high = scene_error("{\"seed\": \xff\xfe}");
  CHECK(high.find("\xff") == std::string::npos);
  CHECK(high.find("last read: '\"seed\": \\xFF'") != std::string::npos);
}

TEST_CASE("strict parsing: nesting deeper than 64 levels is refused at its path") {
  // 63 levels deep under "extra" (an unknown key, so only the depth limit can reject it) parse;
  // 64 do not. Deeper input used to overflow the stack when a message printed the value.
  const auto nested = [](std::size_t depth) {
    return R"({"seed": 1, "extra": )" + std::string(depth, '[') + std::string(depth, ']') + "}";
  };
  CHECK(scene_error(nested(63)).find("nested more than") == std::string::npos);
  const std::string deep = scene_error(nested(64));
  CHECK(deep.find("nested more than 64 objects or arrays deep") != std::string::npos);
  CHECK(deep.rfind("extra[0][0]", 0) == 0);
  CHECK(scene_error(nested(100000)) == deep);
}

TEST_CASE("strict parsing: a peak frequency too small to converge is a range error") {
  // 5e-324 rad/s used to pass validation and end in "m0 did not converge", naming no key.
  CHECK(scene_error(with_waves(R"(, "spectrum": {"peak_omega": 5e-324})")) ==
        "waves.spectrum.peak_omega: must be in [0.0001, 10000] rad/s, got 5e-324");
  CHECK(scene_error(with_waves(R"(, "spectrum": {"peak_omega": 0.0001})")).empty());
}

TEST_CASE("strict parsing: numbers that overflow a double name the JSON path") {
  CHECK(scene_error(R"({"waves": {"spectrum": {"wind_speed": 1e309}}})") ==
        "waves.spectrum.wind_speed: the number 1e309 is out of the range of a double (accepted: "
        "finite numbers, magnitude at most 1.7976931348623157e+308)");
  CHECK(scene_error(R"({"waves": {"cascades": {"sizes": [50, -2e400]}}})")
            .rfind("waves.cascades.sizes[1]: the number -2e400 is out of the range", 0) == 0);
  CHECK(scene_error(R"({"camera": {"position": [0, 1e999, 0]}, "waves": {}})")
            .rfind("camera.position[1]: the number 1e999", 0) == 0);
}

TEST_CASE("strict parsing: integers out of range show the value and the range") {
  // 2^64 - 1 was read as -1 ("must be in [1, 16384], got -1").
  CHECK(scene_error(R"({"waves": {"resolution": 8, "cascades": {"sizes": [50]}},
      "render": {"width": 18446744073709551615}})") ==
        "render.width: must be in [1, 16384], got 18446744073709551615");
  CHECK(scene_error(R"({"waves": {"resolution": 8, "cascades": {"sizes": [50]}},
      "render": {"width": 9223372036854775808}})") ==
        "render.width: must be in [1, 16384], got 9223372036854775808");
  CHECK(scene_error(R"({"waves": {"resolution": 8, "cascades": {"sizes": [50]}},
      "render": {"width": -9223372036854775808}})") ==
        "render.width: must be in [1, 16384], got -9223372036854775808");
  CHECK(scene_error(R"({"waves": {"resolution": 8, "cascades": {"sizes": [50]}},
      "grid": {"columns": 1}})") == "grid.columns: must be in [2, 8192], got 1");
  // The largest seed is accepted; one more (read as a double) is not an integer.
  CHECK(scene_error(R"({"seed": 18446744073709551615, "waves": {"resolution": 8,
      "cascades": {"sizes": [50]}}, "render": {"width": 8, "height": 8,
      "samples_per_pixel": 1}})")
            .empty());
  CHECK(scene_error(R"({"seed": 18446744073709551616, "waves": {}})") ==
        "seed: expected an integer in [0, 18446744073709551615] (2^64 - 1), got the number "
        "1.8446744073709552e+19");
  CHECK(scene_error(R"({"seed": -1, "waves": {}})") ==
        "seed: expected an integer in [0, 18446744073709551615] (2^64 - 1), got the number -1");
}

TEST_CASE("strict parsing: wrong types name the path, the expected type and range, the value") {
  CHECK(scene_error(with_waves(R"(, "minimum_wavelength": "0.5")")) ==
        "waves.minimum_wavelength: expected a number in [0, 100] m, got the string \"0.5\"");
  CHECK(scene_error(R"({"waves": {"resolution": 8.0}})") ==
        "waves.resolution: expected an integer in [4, 8192], got the number 8.0");
  CHECK(scene_error(R"({"waves": {"resolution": true}})") ==
        "waves.resolution: expected an integer in [4, 8192], got the boolean true");
  CHECK(scene_error(R"({"waves": {"band_partitioning": 1}})") ==
        "waves.band_partitioning: expected true or false, got the number 1");
  CHECK(scene_error(R"({"waves": {"realization": null}})") ==
        "waves.realization: expected a string, got null");
  CHECK(scene_error(R"({"waves": {"cascades": {"sizes": [50, "big"]}}})") ==
        "waves.cascades.sizes[1]: expected a number in [0.01, 1000000] m, got the string \"big\"");
  CHECK(scene_error(R"({"waves": {"cascades": {"sizes": 50}}})") ==
        "waves.cascades.sizes: expected an array of 1 to 16 sizes in [0.01, 1000000] m, got the "
        "number 50");
  CHECK(scene_error(R"({"waves": [1, 2]})") == "waves: expected an object, got an array [1,2]");
  CHECK(scene_error(R"({"camera": {"up": [0, "1", 0]}, "waves": {}})")
            .rfind("camera.up[1]: expected a number in [-1000, 1000], got the string \"1\"", 0) ==
        0);
  CHECK(scene_error(R"({"camera": {"up": [0, 1]}, "waves": {}})") ==
        "camera.up: expected [x, y, z], each in [-1000, 1000], got an array [0,1]");
  CHECK(scene_error(with_waves(R"(, "choppiness": [-1, -2])")) ==
        "waves.choppiness: expected a number or an array with one number per cascade (1) in "
        "[-10, 0], got an array [-1,-2]");
  CHECK(scene_error(with_waves(R"(, "choppiness": "x")")) ==
        "waves.choppiness: expected a number or an array with one number per cascade (1) in "
        "[-10, 0], got the string \"x\"");
  // Spectrum parameters: their ranges depend on the model and are checked by make_spectrum.
  CHECK(scene_error(R"({"waves": {"spectrum": {"fetch": "far"}}})") ==
        "waves.spectrum.fetch: expected a number, got the string \"far\"");
  // Echoed values are escaped and cut.
  const std::string long_text = std::string(200, 'y');
  CHECK(scene_error(R"({"waves": {"realization": ")" + long_text + "\"}}") ==
        "waves.realization: expected gaussian or mastin; got '" + std::string(64, 'y') + "\u2026'");
  CHECK(scene_error(R"({"waves": {"realization": "\u001b[2J"}})") ==
        "waves.realization: expected gaussian or mastin; got '\\x1B[2J'");
  // The same escaping in the command line's choices (core/choice.h).
  CHECK(usage_error([] {
          (void)parse_choice<cli::UsageError>(kRealizations, "--x", "\xff\x1b");
        }) == "--x: expected gaussian or mastin; got '\\xFF\\x1B'");
  CHECK(scene_error(R"({"waves": {"resolution": "\u001b"}})") ==
        "waves.resolution: expected an integer in [4, 8192], got the string \"\\\\u001b\"");
}

TEST_CASE("strict parsing: command-line numbers") {
  using cli::parse_integer_in;
  using cli::parse_number;
  using cli::parse_number_in;
  CHECK(parse_number_in("--x", "2.5", 0.0, 10.0) == 2.5);
  CHECK(usage_error([] { (void)parse_number_in("--x", "11", 0.0, 10.0, " m"); }) ==
        "--x: must be in [0, 10] m, got '11'");
  CHECK(usage_error([] { (void)parse_number_in("--x", "1e999", 0.0, 10.0); }) ==
        "--x: expected a finite number in [0, 10], got '1e999'");
  CHECK(usage_error([] { (void)parse_number_in("--x", "nan", 0.0, 10.0); }) ==
        "--x: expected a finite number in [0, 10], got 'nan'");
  CHECK(usage_error([] { (void)parse_number_in("--x", "3abc", 0.1, 1e30); }) ==
        "--x: expected a finite number in [0.1, 1e+30], got '3abc'");
  CHECK(usage_error([] { (void)parse_number_in("--x", " 3", 0.0, 10.0); }) ==
        "--x: expected a finite number in [0, 10], got ' 3'");
  CHECK(usage_error([] { (void)parse_number_in("--x", std::string("3\0x", 3), 0.0, 10.0); }) ==
        "--x: expected a finite number in [0, 10], got '3\\x00x'");
  CHECK(usage_error([] { (void)parse_number("--x", "\x1b[2J", false, "[1, 2]"); }) ==
        "--x: expected a finite number in [1, 2], got '\\x1B[2J'");
  CHECK(parse_integer_in("--n", "-7", -10, 10) == -7);
  CHECK(parse_integer_in("--n", "+7", -10, 10) == 7);
  CHECK(usage_error([] { (void)parse_integer_in("--n", "99999999999999999999", 0, 1024); }) ==
        "--n: must be in [0, 1024], got '99999999999999999999'");
  CHECK(usage_error([] { (void)parse_integer_in("--n", "4.0", 0, 1024, " (0: all)"); }) ==
        "--n: expected an integer in [0, 1024] (0: all), got '4.0'");
  CHECK(usage_error([] { (void)parse_integer_in("--n", "4x", 0, 1024); }) ==
        "--n: expected an integer in [0, 1024], got '4x'");
  CHECK(usage_error([] { (void)parse_integer_in("--n", "", 0, 1024); }) ==
        "--n: expected an integer in [0, 1024], got ''");
  CHECK(usage_error([] { (void)parse_integer_in("--n", "-1", 0, 1024); }) ==
        "--n: must be in [0, 1024], got '-1'");
  CHECK(usage_error([] { (void)cli::parse_number_list("--l", "1,x", "[0, 1] each"); }) ==
        "--l: expected a finite number in [0, 1] each, got 'x'");
  // errno belongs to the C library and outlives a call: an earlier out-of-range number (or any
  // libc call) leaves ERANGE behind, and the next valid number must still be read, so each parse
  // clears errno before strtod / strtoll.
  errno = ERANGE;
  CHECK(parse_integer_in("--n", "7", 0, 10) == 7);
  errno = ERANGE;
  CHECK(parse_number_in("--x", "2.5", 0.0, 10.0) == 2.5);
}

TEST_CASE("strict parsing: memory sizes, each end of [16M, 1048576G] and just beyond") {
  using cli::parse_memory_size;
  // K, M, G, T are powers of 1024; a plain number is bytes.
  CHECK(parse_memory_size("--m", "16M") == 16.0 * 1024 * 1024);
  CHECK(parse_memory_size("--m", "16384K") == 16.0 * 1024 * 1024);
  CHECK(parse_memory_size("--m", "16777216") == 16.0 * 1024 * 1024);
  CHECK(parse_memory_size("--m", "1048576G") == std::ldexp(1.0, 50));
  CHECK(parse_memory_size("--m", "1024T") == std::ldexp(1.0, 50));
  const std::string refusal =
      "--m: must be in [16M, 1048576G] (bytes, or with a binary suffix K, M, G, T), got ";
  CHECK(usage_error([] { (void)parse_memory_size("--m", "16777215"); }) == refusal + "'16777215'");
  CHECK(usage_error([] { (void)parse_memory_size("--m", "1125899906842625"); }) ==
        refusal + "'1125899906842625'");
  CHECK(usage_error([] { (void)parse_memory_size("--m", "1048577G"); }) == refusal + "'1048577G'");
}

TEST_CASE("strict parsing: CLI11 options convert through integer_in and number_in") {
  CLI::App app;
  int threads = 0;
  double share = 0.0;
  app.add_option("--threads", threads)->check(cli::integer_in(0, 1024, " (0: all cores)"));
  app.add_option("--share", share)->check(cli::number_in(0.0, 1.0));
  const auto parse_error = [&](std::vector<std::string> args) -> std::string {
    std::reverse(args.begin(), args.end());  // CLI11 takes the arguments in reverse order
    try {
      app.parse(args);
    } catch (const CLI::ParseError& e) {
      return e.what();
    }
    return "";
  };
  CHECK(parse_error({"--threads", "8", "--share", "0.25"}).empty());
  CHECK(threads == 8);
  CHECK(share == 0.25);
  CHECK(parse_error({"--threads", "abc"}) ==
        "--threads: expected an integer in [0, 1024] (0: all cores), got 'abc'");
  CHECK(parse_error({"--threads", "99999999999999999999"}) ==
        "--threads: must be in [0, 1024] (0: all cores), got '99999999999999999999'");
  CHECK(parse_error({"--threads", "2000"}) ==
        "--threads: must be in [0, 1024] (0: all cores), got '2000'");
  CHECK(parse_error({"--share", "inf"}) ==
        "--share: expected a finite number in [0, 1], got 'inf'");
  CHECK(parse_error({"--share", "1.5"}) == "--share: must be in [0, 1], got '1.5'");
}

TEST_CASE("render's progress bar: the filled share, the percentage and the time left") {
  using oceanref::cli::progress_bar_text;
  const auto bar = [](int filled) {
    return "\r  [" + std::string(static_cast<std::size_t>(filled), '#') +
           std::string(static_cast<std::size_t>(40 - filled), ' ') + "] ";
  };
  // Nothing done yet: no rate, no ETA.
  CHECK(progress_bar_text(0.0, 3.0) == bar(0) + "0%");
  // A quarter in 10 s: 30 s left at that rate.
  CHECK(progress_bar_text(0.25, 10.0) == bar(10) + "25%  ETA 30 s ");
  // Half in 100 s: 100 s left = 1 min 40 s; 59.6 s rounds to a whole minute.
  CHECK(progress_bar_text(0.5, 100.0) == bar(20) + "50%  ETA 1 min 40 s ");
  CHECK(progress_bar_text(0.5, 59.6) == bar(20) + "50%  ETA 1 min 0 s ");
  CHECK(progress_bar_text(0.5, 59.4) == bar(20) + "50%  ETA 59 s ");
  // 10% after 450 s: 4050 s = 67 min 30 s.
  CHECK(progress_bar_text(0.1, 450.0) == bar(4) + "10%  ETA 67 min 30 s ");
  // Done: the time taken and the end of the line; shares round down.
  CHECK(progress_bar_text(1.0, 12.4) == bar(40) + "100%  12 s\n");
  CHECK(progress_bar_text(0.999, 1.0).find(bar(39) + "99%  ETA 0 s ") == 0);
}

TEST_CASE("render's progress off a terminal and its estimated total") {
  using oceanref::cli::progress_estimate_text;
  using oceanref::cli::progress_line_text;
  CHECK(progress_line_text(0.25, 10.0) == "25% after 10 s, ETA 30 s");
  CHECK(progress_line_text(0.5, 100.0) == "50% after 1 min 40 s, ETA 1 min 40 s");
  CHECK(progress_line_text(1.0, 150.2) == "100% after 2 min 30 s");
  // 2% of the rows in 5 s: 250 s in all.
  CHECK(progress_estimate_text(0.02, 5.0) ==
        "estimated total 4 min 10 s (from the first 2% of rows, spread over the image)");
}

TEST_CASE("render's rows in spread order: a permutation whose every prefix covers the band") {
  for (const int count : {1, 2, 3, 50, 64, 360, 1000}) {
    const std::vector<int> order = oceanref::spread_order(count);
    REQUIRE(order.size() == static_cast<std::size_t>(count));
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < count; ++i) CHECK(sorted[static_cast<std::size_t>(i)] == i);
    // Every prefix of n rows leaves no gap between consecutive rows taken (or the band's ends)
    // wider than 4·count/n: the share done is spread over the band.
    for (int n = 1; n <= count; n = 2 * n + 1) {
      std::vector<int> prefix(order.begin(), order.begin() + n);
      prefix.push_back(-1);
      prefix.push_back(count);
      std::sort(prefix.begin(), prefix.end());
      for (std::size_t i = 1; i < prefix.size(); ++i) {
        CHECK(prefix[i] - prefix[i - 1] <= 4.0 * count / n + 1.0);
      }
    }
  }
  CHECK(oceanref::spread_order(8) == std::vector<int>{0, 4, 2, 6, 1, 5, 3, 7});
}
