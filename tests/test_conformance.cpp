// The conformance kit: compare's rule, channel matching, non-finite mismatches, percentiles,
// profiles and --suggest; SSIM and min_ssim; the report's colour scale; the float32 example
// backend's stages against the shipped per-stage profiles (and perturbed stages against them).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "conformance/channel_name.h"
#include "conformance/compare.h"
#include "conformance/fields_output.h"
#include "conformance/float32_backend.h"
#include "conformance/report.h"
#include "conformance/sequence.h"
#include "scene/scene.h"
#include "spectrum/model.h"
#include "waves/random.h"
#include "waves/realization.h"

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
  // NaN: no distance from a number (the largest), none from another NaN, whatever its sign.
  constexpr long long kFar = std::numeric_limits<long long>::max();
  CHECK(ulp_distance(kNaN, 1.0f) == kFar);
  CHECK(ulp_distance(-1.0f, kNaN) == kFar);
  CHECK(ulp_distance(kNaN, kInf) == kFar);
  CHECK(ulp_distance(kNaN, -kNaN) == 0);
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
  // The JSON's bin edges 10^-12 … 10^2, one more than the bins, bracket the pixel's bin.
  const nlohmann::json j = nlohmann::json::parse(comparison_json(r, "g.exr", "c.exr"));
  const std::vector<double> edges = j["histogram_edges"];
  const std::vector<std::size_t> bins = j["parts"][0]["channels"][0]["histogram"]["decades"];
  REQUIRE(edges.size() == bins.size() + 1);
  for (std::size_t k = 0; k < edges.size(); ++k) {
    CHECK(edges[k] == doctest::Approx(std::pow(10.0, kHistogramFirstDecade + static_cast<int>(k)))
                          .epsilon(1e-14));
  }
  const auto bin = static_cast<std::size_t>(std::find(bins.begin(), bins.end(), 1) - bins.begin());
  REQUIRE(bin < bins.size());
  CHECK(edges[bin] <= 0.125);
  CHECK(0.125 < edges[bin + 1]);
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
  CHECK_FALSE(is_alpha_channel("c0.height.V"));
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

TEST_CASE("compare: inputs it cannot compare fairly are refused, naming what is wrong") {
  const auto refused = [](auto&& call, const std::string& expected) {
    try {
      call();
      FAIL("accepted; expected an error containing: " << expected);
    } catch (const std::invalid_argument& e) {
      CHECK_MESSAGE(std::string(e.what()).find(expected) != std::string::npos,
                    std::string(e.what()));
    }
  };
  const ExrPart g = part({{"R", 1, {1.0f, 1.0f}}, {"G", 1, {2.0f, 2.0f}}}, 2, 1);
  // Data windows at other origins: the same size is not the same pixels.
  ExrPart shifted = g;
  shifted.image.origin_y = 3;
  refused([&] { run(g, shifted); }, "data windows differ: golden at (0, 0), candidate at (0, 3)");
  // An explicit map whose golden channel is missing names it and the golden's channels.
  refused([&] { run(g, g, {}, parse_channel_selection("R=Q")); },
          "golden has no channel 'Q'; it has 'R', 'G'");
  // Two golden channels with one alias are ambiguous (by alias only; an exact name decides).
  const ExrPart two_reds = part({{"R", 1, {1.0f, 1.0f}}, {"rgba.R", 1, {1.0f, 1.0f}}}, 2, 1);
  refused([&] { run(two_reds, part({{"red", 1, {1.0f, 1.0f}}}, 2, 1)); }, "(ambiguous alias)");
  CHECK(run(two_reds, part({{"rgba.R", 1, {1.0f, 1.0f}}}, 2, 1)).pass);
  // Nothing left once alpha is set aside.
  refused(
      [&] {
        run(g, part({{"A", 1, {1.0f, 1.0f}}}, 2, 1));
      },
      "no channel to compare (candidate has 'A')");
  // Two candidate channels onto one golden channel.
  refused(
      [&] {
        run(g, part({{"R", 1, {1.0f, 1.0f}}, {"red", 1, {1.0f, 1.0f}}}, 2, 1));
      },
      "golden channel 'R' is matched by more than one candidate channel");
  // No part at all, on either side.
  refused([&] { compare_parts({}, {g}, {}, uniform_profile({})); }, "the golden has no image part");
  refused([&] { compare_parts({g}, {}, {}, uniform_profile({})); },
          "the candidate has no image part");
  // A converged comparison needs finite, non-negative error estimates in the golden.
  ThresholdProfile converged = uniform_profile({});
  converged.golden_error = true;
  for (const float e : {-0.5f, kNaN, kInf}) {
    const ExrPart bad_error = part({{"R", 1, {1.0f, 1.0f}}, {"pixel_error.R", 1, {0.0f, e}}}, 2, 1);
    refused(
        [&] {
          compare_parts({bad_error}, {part({{"R", 1, {1.0f, 1.0f}}}, 2, 1)}, {}, converged);
        },
        "pixel_error.R holds a value that is not a finite error");
  }
  // Profiles: every key's type and presence.
  refused([] { parse_profile(R"({"default": {"rel": 1})", "f"); }, "f: not valid JSON: ");
  refused([] { parse_profile("[1]", "f"); }, "f: a profile is a JSON object");
  refused([] { parse_profile(R"({"name": "x"})", "f"); },
          "f: a profile needs \"default\" or \"channels\"");
  refused([] { parse_profile(R"({"channels": [{"rel": 1}]})", "f"); },
          "f: channels[0]: needs \"match\"");
  refused([] { parse_profile(R"({"channels": {"match": "*"}})", "f"); }, "must be an array");
  refused([] { parse_profile(R"({"default": {"rel": "0.1"}})", "f"); },
          "f: default.rel: not a number");
  refused([] { parse_profile(R"({"channels": [{"match": "*", "part": 3}]})", "f"); },
          "channels[0].part: not a string");
  // --suggest cannot derive a threshold from runs no threshold would accept.
  const ExrPart zero = part({{"h", 1, {0.0f}}}, 1, 1);
  refused(
      [&] {
        suggest_thresholds({run(zero, part({{"h", 1, {1e-3f}}}, 1, 1))}, 4.0, 0.0);
      },
      "run 1: channel 'h' differs where the golden is 0: raise --floor");
  refused(
      [&] {
        suggest_thresholds({run(zero, part({{"h", 1, {kNaN}}}, 1, 1))}, 4.0, 0.0);
      },
      "run 1: channel 'h' has 1 non-finite mismatches");
  refused([] { ssim(std::vector<double>(144), std::vector<double>(143), 12, 12); },
          "SSIM: the images differ in size");
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
  // A rip-map level (x 2, y 1) is matched as such and reported as [x, y] in the JSON.
  ExrPart rip = b;
  rip.level_x = 2;
  rip.level_y = 1;
  const Comparison at_level = compare_parts({a, rip}, {rip}, {}, uniform_profile({}));
  REQUIRE(at_level.parts.size() == 1);
  CHECK(at_level.parts[0].level_x == 2);
  CHECK(at_level.parts[0].level_y == 1);
  const nlohmann::json j = nlohmann::json::parse(comparison_json(at_level, "g.exr", "c.exr"));
  CHECK(j["parts"][0]["level"] == nlohmann::json::array({2, 1}));
  CHECK(j["parts"][0]["name"] == "c1");
}

TEST_CASE("compare: profiles give per-channel thresholds; --suggest derives them") {
  CHECK(glob_match("c*.height.V", "c12.height.V"));
  CHECK_FALSE(glob_match("c*.height.V", "c1.slope_x.V"));
  CHECK(glob_match("?", "R"));
  CHECK(glob_match("*", ""));
  const ThresholdProfile p = parse_profile(
      R"({"name": "t", "channels": [{"match": "c*.height.V", "rel": 0.1, "floor": 1},
                                    {"match": "*", "part": "x", "abs": 2}]})",
      "test");
  CHECK(threshold_for(p, "", "c3.height.V").relative == 0.1);
  CHECK(threshold_for(p, "", "c3.height.V").floor == 1.0);
  CHECK(threshold_for(p, "x", "anything").absolute == 2.0);
  CHECK_THROWS_WITH_AS(threshold_for(p, "", "c3.slope_x.V"), doctest::Contains("'c3.slope_x.V'"),
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

namespace {
// oceanref's stage as `oceanref fields --stage X` writes it (the golden side).
std::vector<ExrPart> golden_stage(const Scene& scene, const Ocean& ocean, Stage stage) {
  return stage == Stage::fields ? fields_image(scene, ocean, 2).parts
                                : stage_image(scene, ocean, stage, 2);
}
ThresholdProfile stage_profile(Stage stage) {
  return read_profile(std::string(OCEANREF_SOURCE_DIR) + "/reference/profiles/" +
                      kStageNames[static_cast<std::size_t>(stage)] + "_float32.json");
}
}  // namespace

TEST_CASE("float32 backend: every stage passes its shipped profile; perturbed stages fail it") {
  // A scene and a time that the profiles were not derived from (see their "derivation"): two
  // cascades without band partitioning, Pierson-Moskowitz for U19.5, the printed cos2 spreading.
  Scene scene = load_scene(std::string(OCEANREF_SOURCE_DIR) +
                           "/reference/scenes/golden/cos2_printed_bilinear_unpartitioned.json");
  scene.time = 5.0;
  const Ocean ocean = realize_ocean(scene.waves, 2);
  for (std::size_t s = 0; s < kStageNames.size(); ++s) {
    const Stage stage = Stage(s);
    CAPTURE(kStageNames[s]);
    const ThresholdProfile profile = stage_profile(stage);
    const std::vector<ExrPart> golden = golden_stage(scene, ocean, stage);
    const Comparison good =
        compare_parts(golden, float32_stage_parts(scene.waves, stage, scene.time), {}, profile);
    CHECK(good.pass);
    bool rounded = false;  // really float32: some channel of the stage is not bit-identical
    for (const PartResult& p : good.parts) {
      for (const ChannelResult& c : p.channels) {
        CAPTURE(c.golden_name);
        rounded = rounded || c.max_relative > 0.0;
        CHECK(c.max_relative <= c.threshold.relative);
        // Margin: the profiles' safety factor is 4; an unseen run should stay well inside.
        if (c.threshold.relative > 0.0) CHECK(c.max_relative < 0.75 * c.threshold.relative);
      }
    }
    CHECK(rounded);
    // Every channel is a field name plus ".V" (conformance/channel_name.h), on oceanref's side
    // and on the backend's (compare_parts refuses a candidate channel without a counterpart);
    // the unit attributes are keyed by the field name.
    std::size_t named = 0;
    for (const ExrPart& p : golden) {
      for (const ExrChannel& c : p.image.channels) {
        CAPTURE(c.name);
        REQUIRE(c.name.ends_with(".V"));
        const std::string field = field_name_of_channel(c.name);
        CHECK(field.size() + 2 == c.name.size());
        CHECK(p.image.attributes.count("oceanref.units." + field) == 1);
        ++named;
      }
    }
    CHECK(named > 0);
    // Perturbed stages fail the profile, in every channel of cascade 0 that the defect reaches:
    // Θ without the polar Jacobian 1/k (every stage but omega), one wave's phase flipped (h0 of
    // cascade 0's strongest wave negated: h0, hkt, fields), the conjugate term dropped and the
    // phase ωt in half precision (hkt, fields), a float16-rounded copy (omega and fields, whose
    // profiles are tight enough: the others allow the float32 conditioning near the upwind
    // direction, up to 4e-4 of the RMS, more than float16's 2.4e-4).
    std::vector<Float32Defect> defects;
    if (stage != Stage::omega) defects.push_back(Float32Defect::drop_polar_jacobian);
    if (stage == Stage::omega || stage == Stage::fields) {
      defects.push_back(Float32Defect::half_float_output);
    }
    if (stage == Stage::h0 || stage == Stage::hkt || stage == Stage::fields) {
      defects.push_back(Float32Defect::flip_one_phase);
    }
    if (stage == Stage::hkt || stage == Stage::fields) {
      defects.push_back(Float32Defect::drop_conjugate_term);
      defects.push_back(Float32Defect::half_float_phase);
    }
    for (const Float32Defect d : defects) {
      CAPTURE(kFloat32DefectNames[static_cast<std::size_t>(d)]);
      const Comparison bad = compare_parts(
          golden, float32_stage_parts(scene.waves, stage, scene.time, d), {}, profile);
      CHECK_FALSE(bad.pass);
      const bool one_wave = d == Float32Defect::flip_one_phase && stage != Stage::fields;
      for (const PartResult& p : bad.parts) {
        if (p.name != "c0") continue;
        for (const ChannelResult& c : p.channels) {
          CAPTURE(c.golden_name);
          if (c.golden_name == "c0.in_band.V" || c.golden_name == "c0.kx.V" ||
              c.golden_name == "c0.kz.V" || c.golden_name == "c0.k.V")
            continue;
          CHECK_FALSE(c.pass);
          // One wave: exactly its entry fails (in hkt also its conjugate partner's).
          if (one_wave) CHECK(c.failing == (stage == Stage::h0 ? 1u : 2u));
        }
      }
    }
  }
}

TEST_CASE(
    "float32 backend: every supported spectrum, spreading and dispersion within its profile") {
  // The backend's float formulas for each model (its spectrum, omega and h0 stages) against
  // oceanref's double ones, through the shipped profiles: a float formula written wrongly for a
  // model that the golden scenes do not use fails here.
  Scene scene =
      load_scene(std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/backend_example.json");
  const auto passes = [&](const Scene& s) {
    const Ocean ocean = realize_ocean(s.waves, 1);
    for (const Stage stage : {Stage::spectrum, Stage::omega, Stage::h0}) {
      CAPTURE(kStageNames[static_cast<std::size_t>(stage)]);
      const Comparison c =
          compare_parts(golden_stage(s, ocean, stage), float32_stage_parts(s.waves, stage, s.time),
                        {}, stage_profile(stage));
      CHECK(c.pass);
      if (!c.pass) return false;
    }
    return true;
  };
  int combinations = 0;
  // (Choice members, not structured bindings: CAPTURE's lambda cannot capture those in clang.)
  for (const auto& model : kSpectrumModels) {
    if (model.value == SpectrumModel::unified) continue;  // refused by the backend (below)
    for (const auto& spreading : kSpreadingModels) {
      if (spreading.value == SpreadingModel::unified) continue;
      CAPTURE(model.name);
      CAPTURE(spreading.name);
      Scene s = scene;
      s.waves.spectrum.model = model.value;
      s.waves.spectrum.spreading = spreading.value;
      if (model.value == SpectrumModel::tma) {
        s.waves.spectrum.depth = 20.0;
        s.waves.spectrum.depth_attenuation = DepthAttenuation::thompson_vincent;
      }
      combinations += passes(s) ? 1 : 0;
    }
  }
  CHECK(combinations == 5 * 8);
  for (const auto& dispersion : kDispersionKinds) {
    CAPTURE(dispersion.name);
    Scene s = scene;
    s.waves.spectrum.dispersion = dispersion.value;
    s.waves.spectrum.depth = 8.0;  // shallow enough for finite depth to matter at 100 m
    CHECK(passes(s));
    if (dispersion.value == DispersionKind::capillary) {  // and a 0.3 m tile, k up to k_m/2
      s.waves.sizes = {0.3};
      CHECK(passes(s));
    }
  }
}

TEST_CASE("float32 backend: its draws and stages against oceanref's, entry by entry") {
  // The shipped example, and the same with each cos-2s spreading of the backend plus a swell
  // (Lutz eq. 29: s + 16 tanh(ω_p/ω) swell²), so that every branch of its spreading is compared,
  // and one blended with the forward cos² lobe (Alimardanov Algorithm 2, spread_blend 0.4).
  const std::string example =
      std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/backend_example.json";
  std::vector<Scene> scenes{load_scene(example)};
  for (const char* model : {"mitsuyasu", "hasselmann", "mastin", "gamper"}) {
    nlohmann::json j = nlohmann::json::parse(std::ifstream(example));
    j["waves"]["spreading"] = {{"model", model}, {"swell", 0.7}};
    scenes.push_back(parse_scene(j));
  }
  nlohmann::json blended = nlohmann::json::parse(std::ifstream(example));
  blended["waves"]["spreading"] = {{"model", "mastin"}, {"spread_blend", 0.4}};
  scenes.push_back(parse_scene(blended));
  // And multi-resolution (N_l = 8 < N_h = 16): each cascade's second grid, with its own band.
  nlohmann::json two_grids = nlohmann::json::parse(std::ifstream(example));
  two_grids["waves"]["low_resolution"] = 8;
  scenes.push_back(parse_scene(two_grids));
  for (std::size_t n = 0; n < 2 * scenes.size(); ++n) {
    const Scene& scene = scenes[n / 2];
    const bool low = n % 2 == 1;
    CAPTURE(n);
    const Ocean ocean = realize_ocean(scene.waves, 1);
    const std::vector<Float32Cascade> f32 = float32_cascades(scene.waves);
    REQUIRE(f32.size() == 1);
    const PatternSpectrum& d = low ? ocean.cascades[0].low : ocean.cascades[0].high;
    const Float32Pattern& p = low ? f32[0].low : f32[0].high;
    CHECK(p.pattern.resolution == d.pattern.resolution);
    CHECK(p.pattern.band.lower == d.pattern.band.lower);
    CHECK(p.pattern.band.upper == d.pattern.band.upper);
    REQUIRE(p.h0.size() == d.h0.size());
    double peak = 0.0;
    for (const Complex& z : d.h0) peak = std::max(peak, std::fabs(z.re) + std::fabs(z.im));
    int drawn = 0;
    for (std::size_t i = 0; i < d.h0.size(); ++i) {
      // The same entries drawn; each h0 within 1e-5 of the largest (float32 rounding of Θ, the
      // uniforms and Box-Muller: a few 1e-7 relative, larger where the spectrum's exponentials
      // amplify the rounding of their arguments).
      CHECK((p.h0[i].re != 0.0f) == (d.h0[i].re != 0.0));
      CHECK(std::fabs(double(p.h0[i].re) - d.h0[i].re) < 1e-5 * peak);
      CHECK(std::fabs(double(p.h0[i].im) - d.h0[i].im) < 1e-5 * peak);
      CHECK(std::fabs(double(p.omega[i]) - d.omega[i]) <= 4e-7 * d.omega[i]);
      drawn += d.h0[i].re != 0.0 ? 1 : 0;
    }
    CHECK(2 * static_cast<std::size_t>(drawn) > d.h0.size());  // 192 of 256, 44 of 64
  }
}

TEST_CASE(
    "float32 backend: at each branch point r = ω/ω_p of its spreading it takes oceanref's branch") {
  // The spreading functions change formula at fixed r = ω/ω_p: Hasselmann's and Gamper's s(ω) at
  // r = 1 (6.97 below, 9.77 at and above: Gamper eq. 3.57), Donelan's β at 0.56, 0.95 and 1.6 and
  // Donelan-Banner's at 0.95 and 1.6 (Vincevičius eq. 1.12, spectrum/spreading.cpp). For each
  // branch point c and each grid entry across the wind, ω_p is set so that the backend's float
  // ω/ω_p is exactly float(c), and oceanref's double ω_p (which rounds to the backend's float ω_p)
  // is moved within that rounding interval so that oceanref's r is on the side the float
  // comparison takes at float(c): r ≥ c for the comparisons r < c, r ≤ 0.56 for Donelan's
  // r > 0.56 (float(0.56) > 0.56). There Θ agrees to float rounding (1e-5), while the other branch
  // changes Θ by 0.03 % (Banner's β is nearly continuous at 1.6) up to a factor of 16.
  struct BranchPoint {
    const char* model;
    double ratio;
    bool above;  // the float comparison at float(ratio) takes the branch above ratio
  };
  const BranchPoint points[] = {{"hasselmann", 1.0, true},    {"gamper", 1.0, true},
                                {"donelan", 0.56, false},     {"donelan", 0.95, true},
                                {"donelan", 1.6, true},       {"donelan-banner", 0.95, true},
                                {"donelan-banner", 1.6, true}};
  const std::string example =
      std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/backend_example.json";
  const nlohmann::json example_json = nlohmann::json::parse(std::ifstream(example));
  const Scene base = parse_scene(example_json);
  const std::vector<Float32Cascade> grid = float32_cascades(base.waves);
  const int n = base.waves.resolution;
  const double dk = wavenumber_spacing(base.waves.sizes[0]);
  const double wind = 30.0 * std::numbers::pi / 180.0;
  for (const BranchPoint& point : points) {
    CAPTURE(point.model);
    CAPTURE(point.ratio);
    const float ratio = static_cast<float>(point.ratio);
    int compared = 0;
    for (int b = 0; b < n; ++b) {
      for (int a = 0; a < n; ++a) {
        const double kx = wave_index(a, n) * dk, kz = wave_index(b, n) * dk;
        // Entries about 90° from the wind, where the spreading depends most on s or β.
        if (!(kx != 0.0 || kz != 0.0) || std::fabs(std::cos(std::atan2(kz, kx) - wind)) > 0.3) {
          continue;
        }
        const std::size_t i = grid_offset(a, b, n);
        const float omega = grid[0].high.omega[i];
        // A float ω_p with omega / ω_p == float(c) in float arithmetic, if one is near omega / c.
        float peak = omega / ratio;
        for (int step = 0; step < 8 && omega / peak != ratio; ++step) {
          peak = std::nextafter(peak, omega / peak > ratio ? 1e30f : 0.0f);
        }
        if (omega / peak != ratio) continue;
        // Oceanref's ω_p: 0.45 of a float ulp below (r up) or above (r down), same float.
        const double ulp = double(std::nextafter(peak, 1e30f)) - double(peak);
        const double peak_omega = double(peak) + (point.above ? -0.45 : 0.45) * ulp;
        REQUIRE(static_cast<float>(peak_omega) == peak);
        nlohmann::json j = example_json;
        j["waves"]["spectrum"]["peak_omega"] = peak_omega;
        j["waves"]["spreading"] = {{"model", point.model}};
        const Scene scene = parse_scene(j);
        const Ocean ocean = realize_ocean(scene.waves, 1);
        const double r = ocean.cascades[0].high.omega[i] / ocean.spectrum.peak_frequency;
        if (point.above ? r < point.ratio : r > point.ratio) continue;
        const double expected = wavevector_spectrum(ocean.spectrum, kx, kz);
        const std::vector<Float32Cascade> f32 = float32_cascades(scene.waves);
        CAPTURE(a);
        CAPTURE(b);
        REQUIRE(f32[0].high.omega[i] == omega);
        REQUIRE(expected > 0.0);
        CHECK(std::fabs(double(f32[0].high.theta[i]) - expected) < 1e-5 * expected);
        ++compared;
      }
    }
    CHECK(compared >= 4);
  }
}

TEST_CASE("fields output: a foam sequence's channels are the accumulated foam, not the indicator") {
  // The stormy golden scene made to fold (u = -6) with 12 earlier frames instead of its steady
  // count: each c<i>.foam is accumulate_foam's - decayed foam of earlier frames, values strictly
  // between 0 and 1 - not the instantaneous indicator 1(J < 0).
  Scene scene = load_scene(std::string(OCEANREF_SOURCE_DIR) +
                           "/reference/scenes/golden/jonswap_storm_foam_steady.json");
  scene.foam.steps = 12;
  scene.waves.choppiness.assign(scene.waves.sizes.size(), -6.0);
  const Ocean ocean = realize_ocean(scene.waves, 2);
  const FieldsImage image = fields_image(scene, ocean, 2);
  const AccumulatedFoam foam =
      accumulate_foam(ocean, scene.time, scene.foam, scene.shading.normals, 2);
  for (std::size_t i = 0; i < foam.cascades.size(); ++i) {
    const std::string name = "c" + std::to_string(i) + ".foam.V";
    CAPTURE(name);
    const std::vector<float>* channel = nullptr;
    for (const ExrPart& p : image.parts) {
      for (const ExrChannel& c : p.image.channels) {
        if (c.name == name) channel = &c.values;
      }
    }
    REQUIRE(channel != nullptr);
    REQUIRE(channel->size() == foam.cascades[i].size());
    int fractional = 0, different = 0;
    for (std::size_t k = 0; k < channel->size(); ++k) {
      different += (*channel)[k] != static_cast<float>(foam.cascades[i][k]) ? 1 : 0;
      fractional += (*channel)[k] > 0.0f && (*channel)[k] < 1.0f ? 1 : 0;
    }
    CHECK(different == 0);
    CHECK(fractional > 0);
  }
}

TEST_CASE("float32 backend: scenes it cannot reproduce are refused by name") {
  const std::string root = std::string(OCEANREF_SOURCE_DIR) + "/reference/scenes/golden/";
  const Scene unified = load_scene(root + "unified_capillary_horizon_sun.json");
  CHECK_THROWS_WITH_AS(check_float32_support(unified.waves),
                       doctest::Contains("waves.spectrum.model: unified is not supported"),
                       std::invalid_argument);
  const Scene mastin = load_scene(root + "phillips_mastin_looking_up.json");
  CHECK_THROWS_WITH_AS(float32_stage_parts(mastin.waves, Stage::h0, 0.0),
                       doctest::Contains("waves.realization: mastin"), std::invalid_argument);
  const WaveSettings tma = load_scene(root + "tma_shallow_grazing.json").waves;
  CHECK_NOTHROW(check_float32_support(tma));
  // Each refusal of a setting beside the same scene with the supported choice.
  WaveSettings exact_tma = tma;
  exact_tma.spectrum.depth_attenuation = DepthAttenuation::exact;
  CHECK_THROWS_WITH_AS(check_float32_support(exact_tma),
                       doctest::Contains("waves.spectrum.tma_attenuation: exact"),
                       std::invalid_argument);
  exact_tma.spectrum.depth = std::numeric_limits<double>::infinity();  // deep: Φ = 1 either way
  CHECK_NOTHROW(check_float32_support(exact_tma));
  WaveSettings spread = tma;
  spread.spectrum.spreading = SpreadingModel::unified;
  CHECK_THROWS_WITH_AS(check_float32_support(spread),
                       doctest::Contains("waves.spreading.model: unified is not supported"),
                       std::invalid_argument);
  spread.spectrum.spreading = SpreadingModel::mitsuyasu;
  spread.spectrum.swell = 0.5;
  spread.spectrum.swell_model = SwellModel::alimardanov;
  CHECK_THROWS_WITH_AS(check_float32_support(spread),
                       doctest::Contains("waves.spreading.swell_model: only lutz"),
                       std::invalid_argument);
  spread.spectrum.swell_model = SwellModel::lutz;
  CHECK_NOTHROW(check_float32_support(spread));
}

namespace {
// A deterministic HDR test image (linear radiance): a gradient, texture from the project's
// counter-based hash and one bright highlight; `noise` multiplies each value by 1 + noise·u,
// u uniform in [−1, 1) from the same hash with another key.
std::vector<float> hdr_values(int width, int height, std::uint64_t key, double noise) {
  std::vector<float> v(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * width + x);
      const double texture = uniform_open(random_word(1234, i));
      double value = 1000.0 * (1.0 + y / double(height)) * (0.7 + 0.6 * texture);
      if (x == 7 && y == 5) value = 1e6;
      const double u = 2.0 * uniform_open(random_word(key, i)) - 1.0;
      v[i] = static_cast<float>(value * (1.0 + noise * u));
    }
  }
  return v;
}
ExrPart rgb_part(int width, int height, std::uint64_t key, double noise) {
  return part({{"R", 1, hdr_values(width, height, key, noise)},
               {"G", 1, hdr_values(width, height, key + 1, noise)},
               {"B", 1, hdr_values(width, height, key + 2, noise)}},
              width, height);
}
}  // namespace

TEST_CASE("SSIM: 1 for identical images, the closed form for constant ones, monotone in noise") {
  // Identical images: exactly 1 (every window's numerator and denominator are the same sums).
  const ExrPart g = rgb_part(40, 30, 99, 0.0);
  const Comparison same = run(g, g);
  REQUIRE(same.parts[0].ssim.computed);
  CHECK(same.parts[0].ssim.value == 1.0);
  CHECK(same.parts[0].ssim.windows == 30u * 20u);
  CHECK(same.parts[0].ssim.source == "R,G,B");
  // Constant images a and b: σ = 0, so SSIM = (2ab + C1)/(a² + b² + C1) (C2/C2 = 1), to the
  // rounding of the window sums (11² terms of ~1e-16).
  for (const double b : {0.5, 0.25, 0.9}) {
    const double a = 0.6;
    const std::vector<double> x(20 * 15, a), y(20 * 15, b);
    const double c1 = 1e-4;
    CHECK(ssim(x, y, 20, 15) ==
          doctest::Approx((2 * a * b + c1) / (a * a + b * b + c1)).epsilon(1e-11));
  }
  CHECK_THROWS_WITH_AS(ssim(std::vector<double>(100), std::vector<double>(100), 10, 10),
                       doctest::Contains("at least 11x11"), std::invalid_argument);
  // Growing noise: strictly decreasing SSIM.
  double previous = 1.0;
  for (const double noise : {1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3}) {
    CAPTURE(noise);
    const Comparison c = run(g, rgb_part(40, 30, 99, noise), {1e30, 0.0, 1.0});
    REQUIRE(c.parts[0].ssim.computed);
    CHECK(c.parts[0].ssim.value < previous);
    previous = c.parts[0].ssim.value;
  }
  CHECK(previous < 0.9);
  // Too small an image, or no R, G, B / Y: no SSIM (and no failure without min_ssim).
  const Comparison small = run(rgb_part(10, 30, 1, 0.0), rgb_part(10, 30, 1, 0.0));
  CHECK(small.parts[0].ssim.applies);
  CHECK_FALSE(small.parts[0].ssim.computed);
  CHECK(small.pass);
  const ExrPart field = part({{"c0.height.V", 1, std::vector<float>(16 * 16, 1.0f)}}, 16, 16);
  CHECK_FALSE(run(field, field).parts[0].ssim.applies);
}

TEST_CASE("SSIM: a profile's min_ssim fails a part below it; parse errors name the key") {
  const ExrPart g = rgb_part(24, 24, 5, 0.0);
  const ExrPart c = rgb_part(24, 24, 5, 0.05);
  ThresholdProfile p = uniform_profile({1e30, 0.0, 1.0});
  const double value = compare_parts({g}, {c}, {}, p).parts[0].ssim.value;
  p.min_ssim = value - 1e-6;
  CHECK(compare_parts({g}, {c}, {}, p).pass);
  p.min_ssim = value + 1e-6;
  const Comparison fails = compare_parts({g}, {c}, {}, p);
  CHECK_FALSE(fails.pass);
  CHECK(comparison_text(fails).find("min_ssim") != std::string::npos);
  CHECK(comparison_json(fails, "g", "c").find("\"min_ssim\"") != std::string::npos);
  // Non-finite luminance where a min_ssim applies: the part fails (and so does the NaN itself).
  ExrPart nan = c;
  nan.image.channels[0].values[3] = kNaN;
  CHECK_FALSE(compare_parts({g}, {nan}, {}, p).pass);
  // min_ssim without any part that has R, G, B: refused.
  const ExrPart field = part({{"c0.height.V", 1, std::vector<float>(16 * 16, 1.0f)}}, 16, 16);
  CHECK_THROWS_WITH_AS(compare_parts({field}, {field}, {}, p), doctest::Contains("min_ssim"),
                       std::invalid_argument);
  CHECK(parse_profile(R"({"default": {"rel": 1}, "min_ssim": 0.98})", "t").min_ssim == 0.98);
  // The range's ends are valid (1: only an identical image passes; −1: any image does).
  CHECK(parse_profile(R"({"default": {"rel": 1}, "min_ssim": 1})", "t").min_ssim == 1.0);
  CHECK(parse_profile(R"({"default": {"rel": 1}, "min_ssim": -1})", "t").min_ssim == -1.0);
  CHECK_THROWS_WITH_AS(parse_profile(R"({"default": {"rel": 1}, "min_ssim": -1.0001})", "t"),
                       doctest::Contains("min_ssim: must be a number in [-1, 1]"),
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(parse_profile(R"({"default": {"rel": 1}, "min_ssim": 2})", "t"),
                       doctest::Contains("min_ssim: must be a number in [-1, 1]"),
                       std::invalid_argument);
}

TEST_CASE("compare --converged: the golden's pixel_error + lighting_error join the tolerance") {
  // Golden R = 4 in each pixel, its estimated errors 0.25 (pixel) + 0.125 (lighting) in pixel
  // 0 and 0 elsewhere; `depth` has no error layer and gets no allowance.
  const ExrPart g = part({{"R", 1, {4.0f, 4.0f}},
                          {"depth", 1, {10.0f, 10.0f}},
                          {"pixel_error.R", 1, {0.25f, 0.0f}},
                          {"lighting_error.R", 1, {0.125f, 0.0f}}},
                         2, 1);
  ExrPart c = part({{"R", 1, {4.375f, 4.0f}}, {"depth", 1, {10.0f, 10.0f}}}, 2, 1);
  ThresholdProfile profile = uniform_profile({});
  CHECK_FALSE(compare_parts({g}, {c}, {}, profile).pass);
  profile.golden_error = true;
  const Comparison within = compare_parts({g}, {c}, {}, profile);
  CHECK(within.pass);  // 0.375 = 0.25 + 0.125
  REQUIRE(within.parts[0].channels.size() == 2);
  CHECK(within.parts[0].channels[0].golden_error_channels ==
        std::vector<std::string>{"pixel_error.R", "lighting_error.R"});
  CHECK(within.parts[0].channels[1].golden_error_channels.empty());
  c.image.channels[0].values[0] = 4.376f;  // just over the golden's bound
  CHECK_FALSE(compare_parts({g}, {c}, {}, profile).pass);
  c.image.channels[0].values[0] = 4.0f;
  c.image.channels[0].values[1] = 4.001f;  // the second pixel's golden is exact: no allowance
  CHECK_FALSE(compare_parts({g}, {c}, {}, profile).pass);
  c.image.channels[1].values[1] = 10.5f;  // depth: never an allowance
  c.image.channels[0].values[1] = 4.0f;
  CHECK_FALSE(compare_parts({g}, {c}, {}, profile).pass);
  // Without the golden's pixel_error the comparison is refused, naming the layer.
  const ExrPart bare = part({{"R", 1, {4.0f, 4.0f}}, {"depth", 1, {10.0f, 10.0f}}}, 2, 1);
  try {
    compare_parts({bare}, {c}, {}, profile);
    FAIL("a converged comparison without the golden's pixel_error was accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("pixel_error.R") != std::string::npos);
  }
  // The profile key.
  CHECK(parse_profile(R"({"default": {"rel": 0}, "golden_error": true})", "p").golden_error);
  CHECK_THROWS_AS(parse_profile(R"({"default": {"rel": 0}, "golden_error": 1})", "p"),
                  std::invalid_argument);
}

TEST_CASE("sequence names: the last run of '#' is the frame number; ffmpeg's form of the pattern") {
  CHECK(frame_path("ocean_####.exr", 7) == "ocean_0007.exr");
  CHECK(frame_path("run#2/f_##.png", 3) == "run#2/f_03.png");  // the last run only
  CHECK(frame_path("f_##.exr", 12345) == "f_12345.exr");       // never truncated
  CHECK(frame_path("#", 0) == "0");
  CHECK(frame_path("a##b#", 42) == "a##b42");
  CHECK_THROWS_AS(frame_path("ocean.exr", 1), std::invalid_argument);
  CHECK(ffmpeg_pattern("ocean_####.png") == "ocean_%04d.png");
  CHECK(ffmpeg_pattern("50%/run#2_##%.png") == "50%%/run#2_%02d%%.png");
  CHECK(ffmpeg_pattern("#") == "%01d");
  CHECK_THROWS_AS(ffmpeg_pattern("ocean.png"), std::invalid_argument);
}

TEST_CASE("sequence frames: frame k is the scene at time + k/fps, nothing else changed") {
  const Scene scene = parse_scene(nlohmann::json::parse(R"({"time": 1.5, "waves": {}})"));
  const Scene f = frame_scene(scene, 3, 12.0);
  CHECK(f.time == 1.5 + 3.0 / 12.0);
  CHECK(frame_scene(scene, 0, 24.0).time == 1.5);
  CHECK(f.image.width == scene.image.width);
}
