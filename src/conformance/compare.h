// Comparison of a candidate image (a backend's output) with a golden one (oceanref's), for
// backend authors (`oceanref compare`, docs in README.md "oceanref compare").
//
// The rule, per channel, for a golden value g and a candidate value c (both float32, compared in
// double):
//   scale s   = max(|g|, F·RMS(g))      RMS(g): root mean square of the golden channel's finite
//                                       values; F: the channel's `floor`
//   tolerance = A + R·s                 A: `absolute`, R: `relative`
//   relative error e = |c − g| / s      (0 when c = g; +inf when s = 0 and c ≠ g)
//   the value passes if both are finite and |c − g| ≤ tolerance, or if its float32 ULP distance
//   is ≤ U (`ulp`); a channel passes if at most a share S (`allowed_share`) of its values fail.
// Converged mode (`golden_error`: `compare --converged`, a profile's "golden_error": true): the
// golden's own estimated error of the value is added to the tolerance of R, G and B —
//   tolerance = A + R·s + E_pixel + E_lighting
// from the golden's layers pixel_error.C and lighting_error.C (`render --aov`; pixel_error is
// required, lighting_error used when present): the golden is then the pixel integral with its
// bound, not one set of sample positions (README "Converged pixels").
// Non-finite values: a NaN matches only a NaN, +Inf only +Inf, −Inf only −Inf. Any other pair
// with a non-finite member (NaN vs number, ±Inf vs number, +Inf vs −Inf, NaN vs Inf, either
// way) is a non-finite mismatch: it fails the value and the whole comparison, whatever S is.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/exr.h"

namespace oceanref {

struct ChannelThreshold {
  double absolute = 0.0;       // A
  double relative = 0.0;       // R
  double floor = 0.0;          // F, in units of the golden channel's RMS
  long long ulp = 0;           // U
  double allowed_share = 0.0;  // S in [0, 1]
};

// Per-channel thresholds: the first rule whose `part` and `channel` glob patterns ('*' any run
// of characters, '?' one character) match the golden part and channel names; else `fallback`
// when `has_fallback`; else the comparison is refused (a channel the profile does not cover).
struct ThresholdRule {
  std::string part = "*";
  std::string channel;
  ChannelThreshold threshold;
};
struct ThresholdProfile {
  std::string name;
  std::vector<ThresholdRule> rules;
  ChannelThreshold fallback;
  bool has_fallback = true;
  // The lowest SSIM (see below) a part with an SSIM may have; with it set, a comparison where no
  // part has one is refused, and a part whose SSIM cannot be computed fails.
  std::optional<double> min_ssim;
  bool golden_error = false;  // converged mode (above)
};
bool glob_match(const std::string& pattern, const std::string& text);
// Throws std::invalid_argument naming the part and channel when nothing covers them.
ChannelThreshold threshold_for(const ThresholdProfile& profile, const std::string& part,
                               const std::string& channel);
// A profile file (JSON, reference/profiles/*.json): {"name", "default": {abs, rel, floor, ulp,
// max_fail_share}, "channels": [{"part", "match", abs, rel, floor, ulp, max_fail_share}, ...],
// "min_ssim", "golden_error"} plus free documentation keys. Throws std::invalid_argument naming the
// file and the key.
ThresholdProfile parse_profile(const std::string& json_text, const std::string& source);
ThresholdProfile read_profile(const std::string& path);

// Which channels are compared. Empty `pairs`: every candidate channel but alpha, each matched to
// the golden channel of the same name or alias (R/r/red/rgba.R, …, Y/luminance); golden channels
// the candidate lacks are listed as not compared. Otherwise exactly these (candidate, golden)
// names, each resolved by name or alias in its image.
struct ChannelSelection {
  std::vector<std::pair<std::string, std::string>> pairs;
  bool include_alpha = false;
};
// "R,G,B" or "cand=golden,cand=golden" (mixed allowed); throws std::invalid_argument.
ChannelSelection parse_channel_selection(const std::string& text);
// The alias key of a channel name: lower case, a leading "rgba."/"rgb." removed, red/green/blue/
// alpha/luminance → r/g/b/a/y.
std::string channel_alias(const std::string& name);
bool is_alpha_channel(const std::string& name);

// Long-tailed error summaries.
inline constexpr std::array<double, 5> kPercentiles{50.0, 90.0, 99.0, 99.9, 100.0};
inline constexpr std::array<const char*, 5> kPercentileNames{"p50", "p90", "p99", "p99.9", "max"};
// Relative-error histogram: `zero` exact matches, then bins [10^k, 10^(k+1)) for
// k = kHistogramFirstDecade … kHistogramLastDecade − 1 (the first bin also takes (0, 10^first),
// the last also everything ≥ 10^last), then `nonfinite` (non-finite mismatches and e = +inf).
inline constexpr int kHistogramFirstDecade = -12;
inline constexpr int kHistogramLastDecade = 2;
struct ErrorHistogram {
  std::size_t zero = 0;
  std::vector<std::size_t> decades;  // kHistogramLastDecade − kHistogramFirstDecade bins
  std::size_t nonfinite = 0;
};

struct WorstValue {
  int x = 0, y = 0;  // in the channel's own (possibly subsampled) grid
  float golden = 0.0f, candidate = 0.0f;
  double absolute = 0.0, relative = 0.0;
  bool pass = true;
};

struct ChannelResult {
  std::string golden_name, candidate_name;
  int sampling = 1;
  int width = 0, height = 0;  // of the channel's grid
  ChannelThreshold threshold;
  // Converged mode: the golden channels whose values were added to the tolerance (else empty).
  std::vector<std::string> golden_error_channels;
  double golden_rms = 0.0;
  double max_absolute = 0.0, max_relative = 0.0, rmse = 0.0;
  double psnr = 0.0;  // 20 log10(max |g| / RMSE) [dB]; +inf when identical
  long long max_ulp = 0;
  std::array<double, 5> absolute_percentiles{};  // of |c − g|, kPercentiles
  std::array<double, 5> relative_percentiles{};  // of e
  ErrorHistogram histogram;
  std::size_t values = 0, failing = 0, nonfinite_mismatches = 0;
  double failing_share = 0.0;
  std::vector<WorstValue> worst;      // up to 8, largest e first (ties: row-major order)
  std::vector<float> relative_error;  // e per value (for the report's heat maps)
  std::vector<char> fails;            // 1 where the value fails
  bool pass = true;
};

// SSIM, the structural similarity of Wang, Bovik, Sheikh and Simoncelli 2004 ("Image quality
// assessment: from error visibility to structural similarity", IEEE TIP 13(4)), of a rendered
// image's luminance:
//   luminance  Y = 0.2126 R + 0.7152 G + 0.0722 B (linear sRGB, D65: the render's primaries) of
//              the compared R, G, B channels, or the compared Y channel; negative values as 0;
//   HDR → [0, 1] the same mapping for both images, keyed by the golden: Reinhard et al. 2002's
//              global operator t = Y/(Y + Ȳ/0.18) with the golden's log-average luminance
//              Ȳ = exp(mean ln(Y_g + 10⁻³ cd/m²)), then a display encoding d = t^(1/2.2);
//   SSIM       per 11 × 11 window (every position fully inside the image, no padding) with
//              Gaussian weights σ = 1.5 (normalized to sum 1): means μ, variances σ², covariance
//              σ_xy as weighted moments (no sample correction), and
//              SSIM = (2μ_xμ_y + C1)(2σ_xy + C2) / ((μ_x² + μ_y² + C1)(σ_x² + σ_y² + C2)),
//              C1 = (0.01 L)², C2 = (0.03 L)², dynamic range L = 1; the image's SSIM is the mean
//              over the windows. SSIM(x, x) = 1 exactly; 1 is identity, lower is worse.
// Computed in double with a fixed operation order (deterministic) by compare_part for a part
// whose compared channels include R, G, B (or Y) at full resolution, at least 11 × 11.
inline constexpr int kSsimWindow = 11;
inline constexpr double kSsimSigma = 1.5;
inline constexpr double kSsimK1 = 0.01;
inline constexpr double kSsimK2 = 0.03;
inline constexpr double kSsimDynamicRange = 1.0;
inline constexpr double kSsimKeyValue = 0.18;        // Reinhard's key a
inline constexpr double kSsimLuminanceFloor = 1e-3;  // δ of the log average [cd/m²]
inline constexpr double kSsimGamma = 2.2;
struct SsimResult {
  bool applies = false;        // the part has R, G, B (or Y) compared at full resolution
  bool computed = false;       // and its SSIM could be computed (else `reason`)
  double value = 0.0;          // mean SSIM over the windows
  double key_luminance = 0.0;  // Ȳ of the golden [cd/m²]
  std::string source;          // "R,G,B" or "Y" (the golden's channel names)
  std::string reason;          // why it was not computed
  std::size_t windows = 0;
};
// The mean SSIM of two luminance images (width × height, row-major) already in [0, 1]; also the
// SSIM of every window position ((width − 10) × (height − 10), row-major) when `map` is given.
// Throws std::invalid_argument when the image is smaller than 11 × 11 or the sizes differ.
double ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
            std::vector<double>* map = nullptr);
// The display values d in [0, 1] of a luminance image, keyed by `key` (Ȳ above).
std::vector<double> ssim_display_values(const std::vector<double>& luminance, double key);
// Ȳ = exp(mean ln(Y + δ)) of a golden luminance image.
double ssim_key_luminance(const std::vector<double>& luminance);

struct PartResult {
  std::string name;
  int level_x = 0, level_y = 0;
  int width = 0, height = 0;
  std::vector<ChannelResult> channels;
  std::vector<std::string> not_compared;  // golden channels without a candidate counterpart
  double failing_share = 0.0;             // pixels failing in any full-resolution channel
  SsimResult ssim;
  std::optional<double> min_ssim;  // the profile's threshold, when it has one
  bool pass = true;
};

struct Comparison {
  std::vector<PartResult> parts;
  std::vector<std::string> parts_not_compared;  // golden parts the candidate lacks
  std::size_t nonfinite_mismatches = 0;
  bool pass = true;
};

// Distance in units in the last place between two float32 values (ordered integer mapping);
// NaNs are infinitely far from everything but themselves.
long long ulp_distance(float a, float b);

// One part: throws std::invalid_argument (sizes differ, channels cannot be matched, sampled
// differently, a profile without a threshold for a channel).
PartResult compare_part(const ExrPart& golden, const ExrPart& candidate,
                        const ChannelSelection& selection, const ThresholdProfile& profile);
// Every part and level: matched by (name, level); two single-part files match whatever their
// names. Throws std::invalid_argument when a candidate part has no golden counterpart.
Comparison compare_parts(const std::vector<ExrPart>& golden, const std::vector<ExrPart>& candidate,
                         const ChannelSelection& selection, const ThresholdProfile& profile);
// A single uniform threshold for every channel.
ThresholdProfile uniform_profile(const ChannelThreshold& threshold);

// A number in tables and reports: three significant digits (%.3g); nan, inf, -inf spelled out.
std::string short_number(double v);

// The parts and levels of an EXR file as compare reads them: every part, every resolution level
// (read_exr_parts, io/exr.h).
// At most `max_bytes` of pixels are read (a larger file is an error naming its size).
std::vector<ExrPart> read_parts_for_compare(const std::string& path,
                                            double max_bytes = kDefaultMaxMemory / 4.0);

// --suggest: per-channel thresholds from a set of candidate runs. Channels are grouped by their
// name with every run of digits replaced by '*' (c0.height.V, c1.height.V → c*.height.V), over all
// parts (the rule's part pattern is "*"); per group R = safety · (largest e over all runs and
// channels of the group), A = 0, U = 0, S = 0, F = floor. Groups where every run matched exactly
// get R = 0.
struct SuggestedRule {
  std::string part, channel;
  double measured_max_relative = 0.0;
  double measured_p99_9_relative = 0.0;
  double measured_max_absolute = 0.0;
  std::size_t channels = 0, runs = 0;
  ChannelThreshold threshold;
};
std::vector<SuggestedRule> suggest_thresholds(const std::vector<Comparison>& runs, double safety,
                                              double floor);
std::string generalize_name(const std::string& name);

// Machine-readable result (JSON text, 2-space indent) and the readable text table.
std::string comparison_json(const Comparison& c, const std::string& golden_path,
                            const std::string& candidate_path);
std::string comparison_text(const Comparison& c);
std::string suggested_profile_json(const std::vector<SuggestedRule>& rules, const std::string& name,
                                   const std::string& derivation, double safety, double floor);

}  // namespace oceanref
