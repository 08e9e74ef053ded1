// The conformance kit: compare's rule, channel matching, non-finite mismatches, percentiles,
// profiles and --suggest; the report's colour scale; the float32 example backend against the
// shipped profile (and two broken variants against the same profile).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "conformance/compare.h"
#include "conformance/float32_backend.h"
#include "conformance/report.h"
#include "scene/scene.h"

using namespace oceanref;

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

ExrPart part(std::vector<ExrChannel> channels, int width, int height) {
  ExrPart p;
  p.image.width = width;
  p.image.height = height;
  p.image.channels = std::move(channels);
  return p;
}

Comparison run(const ExrPart& g, const ExrPart& c, const ChannelThreshold& t = {},
               const ChannelSelection& s = {}) {
  return compare_parts({g}, {c}, s, uniform_profile(t));
}
}  // namespace

TEST_CASE("compare: ULP distance and the metrics of a known difference") {
  CHECK(ulp_distance(1.0f, 1.0f) == 0);
  CHECK(ulp_distance(1.0f, std::nextafter(1.0f, 2.0f)) == 1);
  CHECK(ulp_distance(-0.0f, 0.0f) == 0);
  CHECK(ulp_distance(std::nextafter(0.0f, -1.0f), std::nextafter(0.0f, 1.0f)) == 2);
  const ExrPart g = part({{"R", 1, {1.0f, 2.0f, 3.0f, 4.0f}}}, 2, 2);
  ExrPart c = g;
  c.image.channels[0].values[3] = 4.5f;
  const Comparison r = run(g, c);
  REQUIRE(r.parts.size() == 1);
  REQUIRE(r.parts[0].channels.size() == 1);
  const ChannelResult& ch = r.parts[0].channels[0];
  CHECK(ch.max_absolute == 0.5);
  CHECK(ch.max_relative == 0.125);          // 0.5 / |4|, floor 0
  CHECK(ch.rmse == doctest::Approx(0.25));  // √(0.25/4)
  CHECK(ch.psnr == doctest::Approx(20.0 * std::log10(4.0 / 0.25)));
  CHECK(ch.golden_rms == doctest::Approx(std::sqrt(30.0 / 4.0)));
  REQUIRE(ch.worst.size() == 1);
  CHECK(ch.worst[0].x == 1);
  CHECK(ch.worst[0].y == 1);
  CHECK(ch.failing == 1);
  CHECK(r.parts[0].failing_share == 0.25);
  CHECK_FALSE(r.pass);
  // Nearest-rank percentiles of e over {0, 0, 0, 0.125}: p50 = 0, p90 = p99 = max = 0.125.
  CHECK(ch.relative_percentiles[0] == 0.0);
  CHECK(ch.relative_percentiles[1] == 0.125);
  CHECK(ch.relative_percentiles[4] == 0.125);
  CHECK(ch.histogram.zero == 3);
  CHECK(ch.histogram.decades[static_cast<std::size_t>(-1 - kHistogramFirstDecade)] == 1);
  // The thresholds: A alone, R alone (relative to |g| = 4: 0.5 ≤ 0.125·4), S.
  CHECK(run(g, c, {0.5, 0.0, 0.0, 0, 0.0}).pass);
  CHECK_FALSE(run(g, c, {0.49, 0.0, 0.0, 0, 0.0}).pass);
  CHECK(run(g, c, {0.0, 0.125, 0.0, 0, 0.0}).pass);
  CHECK_FALSE(run(g, c, {0.0, 0.124, 0.0, 0, 0.0}).pass);
  CHECK(run(g, c, {0.0, 0.0, 0.0, 0, 0.25}).pass);
  CHECK_FALSE(run(g, c, {0.0, 0.0, 0.0, 0, 0.24}).pass);
  // ULPs: 4.5 is 2^20 float32 ULPs from 4.
  CHECK(run(g, c, {0.0, 0.0, 0.0, 1 << 20, 0.0}).pass);
  CHECK_FALSE(run(g, c, {0.0, 0.0, 0.0, (1 << 20) - 1, 0.0}).pass);
  c.image.width = 1;
  CHECK_THROWS_WITH_AS(run(g, c), doctest::Contains("differ in size"), std::invalid_argument);
}

TEST_CASE("compare: the floor makes the error relative to the channel's RMS near zero") {
  // Golden values near a zero crossing: without a floor e = 1e-3/1e-6 = 1000.
  const ExrPart g = part({{"h", 1, {1e-6f, 1.0f, -1.0f, 1.0f}}}, 4, 1);
  ExrPart c = g;
  c.image.channels[0].values[0] = 1e-6f + 1e-3f;
  const double rms = std::sqrt((1e-12 + 3.0) / 4.0);
  CHECK(run(g, c).parts[0].channels[0].max_relative == doctest::Approx(1e-3 / 1e-6).epsilon(1e-3));
  const ChannelResult f = run(g, c, {0.0, 0.0, 1.0, 0, 0.0}).parts[0].channels[0];
  CHECK(f.max_relative == doctest::Approx(1e-3 / rms).epsilon(1e-3));
  CHECK(run(g, c, {0.0, 1.2e-3, 1.0, 0, 0.0}).pass);
  CHECK_FALSE(run(g, c, {0.0, 1.1e-3, 1.0, 0, 0.0}).pass);
}

TEST_CASE("compare: every non-finite mismatch fails, in either file, whatever the thresholds") {
  const ChannelThreshold lax{1e30, 1e30, 1.0, 4294967296LL, 1.0};
  const ExrPart ones = part({{"R", 1, {1.0f, 1.0f, 1.0f, 1.0f}}}, 2, 2);
  // The regression: a candidate made entirely of +Inf passed against a golden of ones.
  ExrPart inf = ones;
  for (float& v : inf.image.channels[0].values) v = kInf;
  CHECK_FALSE(run(ones, inf, lax).pass);
  CHECK(run(ones, inf, lax).nonfinite_mismatches == 4);
  CHECK_FALSE(run(inf, ones, lax).pass);
  const struct {
    float golden, candidate;
  } mismatches[] = {{1.0f, kNaN},  {kNaN, 1.0f},  {1.0f, kInf},  {kInf, 1.0f},
                    {1.0f, -kInf}, {-kInf, 1.0f}, {kInf, -kInf}, {-kInf, kInf},
                    {kNaN, kInf},  {kInf, kNaN},  {kNaN, -kInf}, {0.0f, kNaN}};
  for (const auto& m : mismatches) {
    ExrPart g = ones, c = ones;
    g.image.channels[0].values[2] = m.golden;
    c.image.channels[0].values[2] = m.candidate;
    const Comparison r = run(g, c, lax);
    CAPTURE(m.golden);
    CAPTURE(m.candidate);
    CHECK_FALSE(r.pass);
    CHECK(r.nonfinite_mismatches == 1);
    CHECK(r.parts[0].channels[0].histogram.nonfinite == 1);
    REQUIRE_FALSE(r.parts[0].channels[0].worst.empty());
    CHECK(r.parts[0].channels[0].worst[0].x == 0);  // the mismatch ranks first
    CHECK(r.parts[0].channels[0].worst[0].y == 1);
  }
  // Matching non-finite values are equal values.
  for (const float v : {kNaN, kInf, -kInf}) {
    ExrPart g = ones;
    g.image.channels[0].values[1] = v;
    CHECK(run(g, g).pass);
  }
  // Through files, too.
  const auto dir = std::filesystem::temp_directory_path() / "oceanref_test_conformance";
  std::filesystem::create_directories(dir);
  write_exr((dir / "ones.exr").string(), ones.image);
  write_exr((dir / "inf.exr").string(), inf.image);
  CHECK_FALSE(compare_parts(read_parts_for_compare((dir / "ones.exr").string()),
                            read_parts_for_compare((dir / "inf.exr").string()), {},
                            uniform_profile(lax))
                  .pass);
  std::filesystem::remove_all(dir);
}

TEST_CASE("compare: channels are matched by name or alias, alpha ignored, subsets allowed") {
  CHECK(channel_alias("rgba.R") == "r");
  CHECK(channel_alias("Red") == "r");
  CHECK(channel_alias("luminance") == "y");
  CHECK(is_alpha_channel("A"));
  CHECK(is_alpha_channel("rgba.A"));
  CHECK(is_alpha_channel("diffuse.alpha"));
  CHECK_FALSE(is_alpha_channel("c0.height"));
  const ExrPart g = part({{"R", 1, {1.0f}}, {"G", 1, {2.0f}}, {"B", 1, {3.0f}}}, 1, 1);
  // Lower-case names and an alpha channel (whose value would fail).
  const ExrPart c =
      part({{"r", 1, {1.0f}}, {"g", 1, {2.0f}}, {"b", 1, {3.0f}}, {"a", 1, {9.0f}}}, 1, 1);
  Comparison r = run(g, c);
  CHECK(r.pass);
  CHECK(r.parts[0].channels.size() == 3);
  CHECK(r.parts[0].channels[0].candidate_name == "r");
  CHECK(r.parts[0].channels[0].golden_name == "R");
  // A subset: only G; R and B are listed as not compared.
  const ExrPart only_g = part({{"rgba.G", 1, {2.5f}}}, 1, 1);
  r = run(g, only_g);
  CHECK_FALSE(r.pass);
  REQUIRE(r.parts[0].channels.size() == 1);
  CHECK(r.parts[0].channels[0].golden_name == "G");
  CHECK(r.parts[0].not_compared == std::vector<std::string>{"R", "B"});
  // An explicit map and an explicit selection.
  ChannelSelection map = parse_channel_selection("r=B");
  r = run(g, part({{"r", 1, {3.0f}}}, 1, 1), {}, map);
  CHECK(r.pass);
  CHECK(r.parts[0].channels[0].golden_name == "B");
  CHECK(parse_channel_selection("R,G").pairs.size() == 2);
  CHECK_THROWS_AS(parse_channel_selection("R,,G"), std::invalid_argument);
  // Errors name the channels.
  CHECK_THROWS_WITH_AS(run(g, part({{"Z", 1, {1.0f}}}, 1, 1)), doctest::Contains("'Z'"),
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(run(g, c, {}, parse_channel_selection("Q")),
                       doctest::Contains("no channel 'Q'"), std::invalid_argument);
  ChannelSelection alpha;
  alpha.include_alpha = true;
  CHECK_THROWS_WITH_AS(run(g, c, {}, alpha), doctest::Contains("'a'"), std::invalid_argument);
  const ExrPart sub = part({{"R", 2, {1.0f}}}, 2, 2);
  const ExrPart full = part({{"R", 1, {1.0f, 1.0f, 1.0f, 1.0f}}}, 2, 2);
  CHECK_THROWS_WITH_AS(run(full, sub), doctest::Contains("subsampled"), std::invalid_argument);
}

TEST_CASE("compare: parts are matched by name and level") {
  ExrPart a = part({{"h", 1, {1.0f}}}, 1, 1);
  a.name = "c0";
  ExrPart b = a;
  b.name = "c1";
  b.image.channels[0].values[0] = 2.0f;
  ExrPart b_level1 = b;
  b_level1.level_x = b_level1.level_y = 1;
  const std::vector<ExrPart> golden{a, b, b_level1};
  ExrPart wrong = b;
  wrong.image.channels[0].values[0] = 5.0f;
  const Comparison r = compare_parts(golden, {wrong, a}, {}, uniform_profile({}));
  REQUIRE(r.parts.size() == 2);
  CHECK(r.parts[0].name == "c1");
  CHECK_FALSE(r.parts[0].pass);
  CHECK(r.parts[1].pass);
  CHECK(r.parts_not_compared.size() == 1);
  ExrPart missing = a;
  missing.name = "c7";
  CHECK_THROWS_WITH_AS(compare_parts(golden, {missing, a}, {}, uniform_profile({})),
                       doctest::Contains("'c7'"), std::invalid_argument);
}

TEST_CASE("compare: profiles give per-channel thresholds; --suggest derives them") {
  CHECK(glob_match("c*.height", "c12.height"));
  CHECK_FALSE(glob_match("c*.height", "c1.slope_x"));
  CHECK(glob_match("?", "R"));
  CHECK(glob_match("*", ""));
  const ThresholdProfile p = parse_profile(
      R"({"name": "t", "channels": [{"match": "c*.height", "rel": 0.1, "floor": 1},
                                    {"match": "*", "part": "x", "abs": 2}]})",
      "test");
  CHECK(threshold_for(p, "", "c3.height").relative == 0.1);
  CHECK(threshold_for(p, "", "c3.height").floor == 1.0);
  CHECK(threshold_for(p, "x", "anything").absolute == 2.0);
  CHECK_THROWS_WITH_AS(threshold_for(p, "", "c3.slope_x"), doctest::Contains("'c3.slope_x'"),
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(parse_profile(R"({"channels": [{"match": "a", "rell": 1}]})", "f"),
                       doctest::Contains("'rell'"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(parse_profile(R"({"default": {"rel": -1}})", "f"),
                       doctest::Contains("default.rel"), std::invalid_argument);
  // Two runs with relative errors 1e-3 and 2e-3 (golden 1, floor 1): R = 4 · 2e-3.
  const ExrPart g = part({{"c0.h", 1, {1.0f, 1.0f}}, {"c1.h", 1, {1.0f, 1.0f}}}, 2, 1);
  ExrPart c1 = g, c2 = g;
  c1.image.channels[0].values[0] = 1.001f;
  c2.image.channels[1].values[1] = 0.998f;
  ChannelThreshold measure;
  measure.floor = 1.0;
  const std::vector<SuggestedRule> rules =
      suggest_thresholds({run(g, c1, measure), run(g, c2, measure)}, 4.0, 1.0);
  REQUIRE(rules.size() == 1);
  CHECK(rules[0].channel == "c*.h");
  CHECK(rules[0].channels == 4);
  CHECK(rules[0].runs == 2);
  CHECK(rules[0].measured_max_relative == doctest::Approx(2e-3).epsilon(1e-3));
  CHECK(rules[0].threshold.relative == doctest::Approx(8e-3).epsilon(1e-3));
  // The suggested profile reads back and accepts both runs, and not a 10x larger error.
  const ThresholdProfile back =
      parse_profile(suggested_profile_json(rules, "s", "test", 4.0, 1.0), "suggested");
  CHECK(compare_parts({g}, {c1}, {}, back).pass);
  CHECK(compare_parts({g}, {c2}, {}, back).pass);
  ExrPart bad = g;
  bad.image.channels[1].values[0] = 1.1f;
  CHECK_FALSE(compare_parts({g}, {bad}, {}, back).pass);
}

TEST_CASE("report: the heat map's log colour scale") {
  CHECK(heat_colour(0.0) == std::array<std::uint8_t, 3>{0, 0, 0});
  CHECK(heat_colour(std::numeric_limits<double>::infinity())[1] == 230);
  CHECK(heat_colour(1e-12) == heat_colour(1e-9));  // clamped below
  CHECK(heat_colour(10.0) == heat_colour(1.0));    // and above
  // Monotone in the sum of the channels (lightness) over the scale.
  int previous = -1;
  for (double e = 1e-9; e <= 1.0; e *= 10.0) {
    const auto c = heat_colour(e);
    const int sum = c[0] + c[1] + c[2];
    CHECK(sum > previous);
    previous = sum;
  }
}

TEST_CASE("float32 backend: passes the shipped profile; broken backends fail it") {
  // A scene and a time that the profile was not derived from (see its "derivation").
  const Scene scene = load_scene(std::string(OCEANREF_SOURCE_DIR) +
                                 "/reference/scenes/golden/unified_capillary_horizon_sun.json");
  const ThresholdProfile profile =
      read_profile(std::string(OCEANREF_SOURCE_DIR) + "/reference/profiles/fields_float32.json");
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const double time = 5.0;
  const std::vector<ExrPart> golden = reference_fields_parts(ocean, time, 2);
  REQUIRE(golden.size() >= 2);
  const Comparison good = compare_parts(golden, float32_fields_parts(ocean, time), {}, profile);
  CHECK(good.pass);
  CHECK(good.parts.size() == golden.size());
  for (const PartResult& p : good.parts) {
    for (const ChannelResult& c : p.channels) {
      CAPTURE(c.golden_name);
      CHECK(c.max_relative > 0.0);  // really float32: not bit-identical
      CHECK(c.max_relative < c.threshold.relative);
      // Margin: the profile's safety factor is 4; an unseen run should stay well inside.
      CHECK(c.max_relative < 0.75 * c.threshold.relative);
    }
  }
  for (const Float32Defect d :
       {Float32Defect::drop_conjugate_term, Float32Defect::half_float_phase}) {
    const Comparison bad = compare_parts(golden, float32_fields_parts(ocean, time, d), {}, profile);
    CHECK_FALSE(bad.pass);
    for (const PartResult& p : bad.parts) {
      for (const ChannelResult& c : p.channels) {
        CAPTURE(c.golden_name);
        CHECK_FALSE(c.pass);  // every field catches the bug
      }
    }
  }
}
