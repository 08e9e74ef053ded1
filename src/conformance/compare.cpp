#include "conformance/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/format.h"
#include "core/math.h"

namespace oceanref {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kWorstCount = 8;

std::string lower(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return s;
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out.empty() ? "(none)" : out;
}

std::vector<std::string> channel_names(const ExrImage& image) {
  std::vector<std::string> names;
  for (const ExrChannel& c : image.channels) names.push_back(c.name);
  return names;
}

// The channel named `name` in `image`: by exact name, else the one channel with the same alias.
const ExrChannel* find_channel(const ExrImage& image, const std::string& name, bool* ambiguous) {
  *ambiguous = false;
  for (const ExrChannel& c : image.channels) {
    if (c.name == name) return &c;
  }
  const ExrChannel* found = nullptr;
  const std::string key = channel_alias(name);
  for (const ExrChannel& c : image.channels) {
    if (channel_alias(c.name) != key) continue;
    if (found != nullptr) {
      *ambiguous = true;
      return nullptr;
    }
    found = &c;
  }
  return found;
}

std::string part_label(const ExrPart& p) {
  std::string label = p.name.empty() ? std::string("(unnamed part)") : "part '" + p.name + "'";
  if (p.level_x != 0 || p.level_y != 0) {
    label += " level " + std::to_string(p.level_x) + "," + std::to_string(p.level_y);
  }
  return label;
}

double nearest_rank(const std::vector<double>& sorted, double percent) {
  if (sorted.empty()) return 0.0;
  const double n = static_cast<double>(sorted.size());
  const double rank = std::ceil(percent / 100.0 * n);
  const auto index = static_cast<std::size_t>(std::clamp(rank, 1.0, n)) - 1;
  return sorted[index];
}

bool both_same_nonfinite(float g, float c) {
  if (std::isnan(g) && std::isnan(c)) return true;
  return std::isinf(g) && std::isinf(c) && std::signbit(g) == std::signbit(c);
}

// `allowance` (empty, or one value per value of g): added to each value's tolerance.
ChannelResult compare_channel(const ExrChannel& g, const ExrChannel& c, int part_width,
                              const ChannelThreshold& t, const std::vector<double>& allowance) {
  ChannelResult r;
  r.golden_name = g.name;
  r.candidate_name = c.name;
  r.sampling = g.sampling;
  r.width = part_width / g.sampling;
  r.height =
      r.width > 0 ? static_cast<int>(g.values.size() / static_cast<std::size_t>(r.width)) : 0;
  r.threshold = t;
  r.values = g.values.size();
  r.histogram.decades.assign(static_cast<std::size_t>(kHistogramLastDecade - kHistogramFirstDecade),
                             0);
  double squares = 0.0;
  std::size_t finite = 0;
  double peak = 0.0;
  for (const float v : g.values) {
    if (std::isfinite(v)) {
      squares += static_cast<double>(v) * static_cast<double>(v);
      peak = std::max(peak, std::fabs(static_cast<double>(v)));
      ++finite;
    }
  }
  r.golden_rms = finite > 0 ? std::sqrt(squares / static_cast<double>(finite)) : 0.0;
  const double floor_scale = t.floor * r.golden_rms;
  std::vector<double> absolute(r.values), relative(r.values);
  r.relative_error.assign(r.values, 0.0f);
  r.fails.assign(r.values, 0);
  double error_squares = 0.0;
  std::size_t error_count = 0;
  for (std::size_t i = 0; i < r.values; ++i) {
    const float gv = g.values[i];
    const float cv = c.values[i];
    double a = 0.0;
    double e = 0.0;
    bool fail = false;
    if (!std::isfinite(gv) || !std::isfinite(cv)) {
      if (!both_same_nonfinite(gv, cv)) {
        a = e = kInf;
        fail = true;
        ++r.nonfinite_mismatches;
      }
    } else {
      const double x = static_cast<double>(gv);
      const double y = static_cast<double>(cv);
      a = std::fabs(y - x);
      const double scale = std::max(std::fabs(x), floor_scale);
      e = a == 0.0 ? 0.0 : (scale > 0.0 ? a / scale : kInf);
      const long long u = ulp_distance(gv, cv);
      r.max_ulp = std::max(r.max_ulp, u);
      const double extra = allowance.empty() ? 0.0 : allowance[i];
      fail = !(a <= t.absolute + t.relative * scale + extra) && u > t.ulp;
      error_squares += a * a;
      ++error_count;
    }
    absolute[i] = a;
    relative[i] = e;
    r.relative_error[i] = static_cast<float>(e);
    if (fail) {
      r.fails[i] = 1;
      ++r.failing;
    }
    if (e == 0.0) {
      ++r.histogram.zero;
    } else if (!(e < kInf)) {
      ++r.histogram.nonfinite;
    } else {
      int k = kHistogramFirstDecade;
      double edge = 1e-11;  // 10^(k+1)
      while (k < kHistogramLastDecade - 1 && e >= edge) {
        ++k;
        edge *= 10.0;
      }
      ++r.histogram.decades[static_cast<std::size_t>(k - kHistogramFirstDecade)];
    }
  }
  if (r.nonfinite_mismatches > 0) r.max_ulp = std::numeric_limits<long long>::max();
  r.rmse = error_count > 0 ? std::sqrt(error_squares / static_cast<double>(error_count)) : 0.0;
  r.psnr = r.rmse > 0.0 ? (peak > 0.0 ? 20.0 * math::log10(peak / r.rmse) : -kInf) : kInf;
  // Worst values: largest e, then largest |c − g|, then row-major order.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < r.values; ++i) {
    if (absolute[i] > 0.0) order.push_back(i);
  }
  const auto worse = [&](std::size_t a, std::size_t b) {
    if (relative[a] != relative[b]) return relative[a] > relative[b];
    if (absolute[a] != absolute[b]) return absolute[a] > absolute[b];
    return a < b;
  };
  const std::size_t count = std::min(kWorstCount, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(),
                    worse);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = order[k];
    const auto w = static_cast<std::size_t>(std::max(1, r.width));
    r.worst.push_back({static_cast<int>(i % w), static_cast<int>(i / w), g.values[i], c.values[i],
                       absolute[i], relative[i], r.fails[i] == 0});
  }
  std::sort(absolute.begin(), absolute.end());
  std::sort(relative.begin(), relative.end());
  for (std::size_t p = 0; p < kPercentiles.size(); ++p) {
    r.absolute_percentiles[p] = nearest_rank(absolute, kPercentiles[p]);
    r.relative_percentiles[p] = nearest_rank(relative, kPercentiles[p]);
  }
  r.max_absolute = absolute.empty() ? 0.0 : absolute.back();
  r.max_relative = relative.empty() ? 0.0 : relative.back();
  r.failing_share =
      r.values > 0 ? static_cast<double>(r.failing) / static_cast<double>(r.values) : 0.0;
  r.pass = r.nonfinite_mismatches == 0 && r.failing_share <= t.allowed_share;
  return r;
}

ChannelThreshold threshold_from_json(const nlohmann::json& j, const ChannelThreshold& base,
                                     const std::string& where) {
  ChannelThreshold t = base;
  const auto number = [&](const char* key, double lo, double hi, double* out) {
    if (!j.contains(key)) return;
    const nlohmann::json& v = j.at(key);
    if (!v.is_number()) throw std::invalid_argument(where + "." + key + ": not a number");
    const double x = v.get<double>();
    if (!(x >= lo && x <= hi)) {
      throw std::invalid_argument(where + "." + key + ": must be in [" + std::to_string(lo) + ", " +
                                  std::to_string(hi) + "]");
    }
    *out = x;
  };
  number("abs", 0.0, 1e30, &t.absolute);
  number("rel", 0.0, 1e30, &t.relative);
  number("floor", 0.0, 1e30, &t.floor);
  number("max_fail_share", 0.0, 1.0, &t.allowed_share);
  double ulp = static_cast<double>(t.ulp);
  number("ulp", 0.0, 4294967296.0, &ulp);
  if (ulp != std::floor(ulp)) throw std::invalid_argument(where + ".ulp: must be an integer");
  t.ulp = static_cast<long long>(ulp);
  return t;
}

nlohmann::json number_json(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
}

nlohmann::json threshold_json(const ChannelThreshold& t) {
  return {{"abs", t.absolute},
          {"rel", t.relative},
          {"floor", t.floor},
          {"ulp", t.ulp},
          {"max_fail_share", t.allowed_share}};
}
}  // namespace

std::string short_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

long long ulp_distance(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) {
    return (std::isnan(a) && std::isnan(b)) ? 0 : std::numeric_limits<long long>::max();
  }
  const auto ordered = [](float f) {
    std::int32_t i = 0;
    std::memcpy(&i, &f, sizeof i);
    return static_cast<long long>(i < 0 ? std::numeric_limits<std::int32_t>::min() - i : i);
  };
  return std::llabs(ordered(a) - ordered(b));
}

bool glob_match(const std::string& pattern, const std::string& text) {
  // Iterative wildcard match with backtracking to the last '*'.
  std::size_t p = 0, t = 0, star = std::string::npos, mark = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p;
      ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = t;
    } else if (star != std::string::npos) {
      p = star + 1;
      t = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

ChannelThreshold threshold_for(const ThresholdProfile& profile, const std::string& part,
                               const std::string& channel) {
  for (const ThresholdRule& r : profile.rules) {
    if (glob_match(r.part, part) && glob_match(r.channel, channel)) return r.threshold;
  }
  if (profile.has_fallback) return profile.fallback;
  throw std::invalid_argument("profile '" + profile.name + "' has no threshold for channel '" +
                              channel + "'" + (part.empty() ? "" : " of part '" + part + "'") +
                              " (add a \"channels\" rule or a \"default\")");
}

ThresholdProfile parse_profile(const std::string& json_text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(source + ": not valid JSON: " + e.what());
  }
  if (!j.is_object()) throw std::invalid_argument(source + ": a profile is a JSON object");
  static const std::set<std::string> known_top{
      "name",    "stage",    "description", "rule",     "derivation",
      "default", "channels", "comment",     "min_ssim", "golden_error"};
  static const std::set<std::string> known_rule{"part",
                                                "match",
                                                "abs",
                                                "rel",
                                                "floor",
                                                "ulp",
                                                "max_fail_share",
                                                "measured_max_relative",
                                                "measured_p99_9_relative",
                                                "measured_max_absolute",
                                                "channels_measured",
                                                "runs",
                                                "comment"};
  for (const auto& [key, value] : j.items()) {
    if (!known_top.contains(key)) {
      throw std::invalid_argument(source + ": unknown key '" + key + "'");
    }
  }
  ThresholdProfile p;
  p.name = j.value("name", source);
  p.has_fallback = j.contains("default");
  if (p.has_fallback) p.fallback = threshold_from_json(j.at("default"), {}, source + ": default");
  if (j.contains("channels")) {
    const nlohmann::json& rules = j.at("channels");
    if (!rules.is_array()) throw std::invalid_argument(source + ": channels: must be an array");
    for (std::size_t i = 0; i < rules.size(); ++i) {
      const nlohmann::json& r = rules[i];
      const std::string where = source + ": channels[" + std::to_string(i) + "]";
      if (!r.is_object() || !r.contains("match") || !r.at("match").is_string()) {
        throw std::invalid_argument(where + ": needs \"match\": a channel name pattern");
      }
      for (const auto& [key, value] : r.items()) {
        if (!known_rule.contains(key)) {
          throw std::invalid_argument(where + ": unknown key '" + key + "'");
        }
      }
      ThresholdRule rule;
      rule.channel = r.at("match").get<std::string>();
      if (r.contains("part")) {
        if (!r.at("part").is_string()) throw std::invalid_argument(where + ".part: not a string");
        rule.part = r.at("part").get<std::string>();
      }
      rule.threshold =
          threshold_from_json(r, p.has_fallback ? p.fallback : ChannelThreshold{}, where);
      p.rules.push_back(rule);
    }
  }
  if (j.contains("min_ssim")) {
    const nlohmann::json& v = j.at("min_ssim");
    if (!v.is_number() || !(v.get<double>() >= -1.0 && v.get<double>() <= 1.0)) {
      throw std::invalid_argument(source + ": min_ssim: must be a number in [-1, 1]");
    }
    p.min_ssim = v.get<double>();
  }
  if (j.contains("golden_error")) {
    if (!j.at("golden_error").is_boolean()) {
      throw std::invalid_argument(source + ": golden_error: must be true or false");
    }
    p.golden_error = j.at("golden_error").get<bool>();
  }
  if (p.rules.empty() && !p.has_fallback) {
    throw std::invalid_argument(source + ": a profile needs \"default\" or \"channels\"");
  }
  return p;
}

ThresholdProfile read_profile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot read the profile");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_profile(text.str(), path);
}

ThresholdProfile uniform_profile(const ChannelThreshold& threshold) {
  ThresholdProfile p;
  p.name = "command-line thresholds";
  p.fallback = threshold;
  return p;
}

std::string channel_alias(const std::string& name) {
  std::string key = lower(name);
  for (const char* prefix : {"rgba.", "rgb."}) {
    if (key.rfind(prefix, 0) == 0) key = key.substr(std::strlen(prefix));
  }
  static const std::map<std::string, std::string> words{
      {"red", "r"}, {"green", "g"}, {"blue", "b"}, {"alpha", "a"}, {"luminance", "y"}};
  const auto it = words.find(key);
  return it == words.end() ? key : it->second;
}

bool is_alpha_channel(const std::string& name) {
  const std::string key = channel_alias(name);
  if (key == "a") return true;
  const std::size_t dot = key.rfind('.');
  return dot != std::string::npos && (key.substr(dot + 1) == "a" || key.substr(dot + 1) == "alpha");
}

ChannelSelection parse_channel_selection(const std::string& text) {
  ChannelSelection s;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    const std::string cand = item.substr(0, eq);
    const std::string gold = eq == std::string::npos ? cand : item.substr(eq + 1);
    if (cand.empty() || gold.empty()) {
      throw std::invalid_argument("'" + text +
                                  "': expected NAME,NAME,... or CANDIDATE=GOLDEN,... (no empty "
                                  "names)");
    }
    s.pairs.emplace_back(cand, gold);
    start = comma + 1;
  }
  return s;
}

double ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
            std::vector<double>* map) {
  const int n = kSsimWindow;
  if (width < n || height < n) {
    throw std::invalid_argument("SSIM needs an image of at least " + std::to_string(n) + "x" +
                                std::to_string(n) + ", got " + std::to_string(width) + "x" +
                                std::to_string(height));
  }
  const auto cells = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (x.size() != cells || y.size() != cells) {
    throw std::invalid_argument("SSIM: the images differ in size");
  }
  // The 1-D Gaussian weights, normalized to sum 1: the 2-D window is their outer product.
  std::array<double, kSsimWindow> w{};
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    const double d = i - (n - 1) / 2;
    w[static_cast<std::size_t>(i)] = math::exp(-d * d / (2.0 * kSsimSigma * kSsimSigma));
    total += w[static_cast<std::size_t>(i)];
  }
  for (double& v : w) v /= total;
  // Separable weighted moments over every window fully inside the image: rows first, then
  // columns, each sum in index order.
  const int out_w = width - n + 1;
  const int out_h = height - n + 1;
  const auto index = [](int col, int row, int stride) {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(stride) +
           static_cast<std::size_t>(col);
  };
  std::array<std::vector<double>, 5> rows;  // x, y, xx, yy, xy filtered along rows
  for (auto& r : rows)
    r.assign(static_cast<std::size_t>(out_w) * static_cast<std::size_t>(height), 0.0);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < out_w; ++col) {
      std::array<double, 5> sum{};
      for (int i = 0; i < n; ++i) {
        const double a = x[index(col + i, row, width)];
        const double b = y[index(col + i, row, width)];
        const double wi = w[static_cast<std::size_t>(i)];
        sum[0] += wi * a;
        sum[1] += wi * b;
        sum[2] += wi * (a * a);
        sum[3] += wi * (b * b);
        sum[4] += wi * (a * b);
      }
      for (std::size_t k = 0; k < 5; ++k) rows[k][index(col, row, out_w)] = sum[k];
    }
  }
  const double c1 = (kSsimK1 * kSsimDynamicRange) * (kSsimK1 * kSsimDynamicRange);
  const double c2 = (kSsimK2 * kSsimDynamicRange) * (kSsimK2 * kSsimDynamicRange);
  if (map != nullptr)
    map->assign(static_cast<std::size_t>(out_w) * static_cast<std::size_t>(out_h), 0.0);
  double mean = 0.0;
  for (int row = 0; row < out_h; ++row) {
    for (int col = 0; col < out_w; ++col) {
      std::array<double, 5> m{};
      for (int i = 0; i < n; ++i) {
        const double wi = w[static_cast<std::size_t>(i)];
        for (std::size_t k = 0; k < 5; ++k) m[k] += wi * rows[k][index(col, row + i, out_w)];
      }
      const double mx = m[0];
      const double my = m[1];
      const double vx = m[2] - mx * mx;
      const double vy = m[3] - my * my;
      const double cxy = m[4] - mx * my;
      const double s =
          ((2.0 * (mx * my) + c1) * (2.0 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
      if (map != nullptr) (*map)[index(col, row, out_w)] = s;
      mean += s;
    }
  }
  return mean / (static_cast<double>(out_w) * static_cast<double>(out_h));
}

double ssim_key_luminance(const std::vector<double>& luminance) {
  double sum = 0.0;
  for (const double v : luminance) sum += math::log(std::max(v, 0.0) + kSsimLuminanceFloor);
  return luminance.empty() ? 1.0 : math::exp(sum / static_cast<double>(luminance.size()));
}

std::vector<double> ssim_display_values(const std::vector<double>& luminance, double key) {
  std::vector<double> d(luminance.size());
  const double white = key / kSsimKeyValue;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double y = std::max(luminance[i], 0.0);
    d[i] = math::pow(y / (y + white), 1.0 / kSsimGamma);
  }
  return d;
}

namespace {
// The SSIM of a part from its compared channel pairs (golden, candidate).
SsimResult part_ssim(const std::vector<std::pair<const ExrChannel*, const ExrChannel*>>& pairs,
                     int width, int height) {
  SsimResult r;
  std::array<std::pair<const ExrChannel*, const ExrChannel*>, 4> rgby{};  // R, G, B, Y
  for (const auto& [gc, cc] : pairs) {
    if (gc->sampling != 1) continue;
    const std::string key = channel_alias(gc->name);
    const std::size_t slot = key == "r" ? 0 : key == "g" ? 1 : key == "b" ? 2 : key == "y" ? 3 : 4;
    if (slot < 4) rgby[slot] = {gc, cc};
  }
  const bool rgb = rgby[0].first && rgby[1].first && rgby[2].first;
  if (!rgb && !rgby[3].first) return r;
  r.applies = true;
  const auto cells = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<double> golden(cells), candidate(cells);
  bool finite = true;
  for (std::size_t i = 0; i < cells; ++i) {
    const auto value = [&](bool candidate_side) {
      const auto v = [&](std::size_t slot) {
        const ExrChannel* c = candidate_side ? rgby[slot].second : rgby[slot].first;
        return static_cast<double>(c->values[i]);
      };
      return rgb ? 0.2126 * v(0) + 0.7152 * v(1) + 0.0722 * v(2) : v(3);
    };
    golden[i] = value(false);
    candidate[i] = value(true);
    finite = finite && std::isfinite(golden[i]) && std::isfinite(candidate[i]);
  }
  r.source = rgb ? rgby[0].first->name + "," + rgby[1].first->name + "," + rgby[2].first->name
                 : rgby[3].first->name;
  if (!finite) {
    r.reason = "non-finite luminance";
    return r;
  }
  if (width < kSsimWindow || height < kSsimWindow) {
    r.reason = "smaller than the 11x11 window";
    return r;
  }
  r.key_luminance = ssim_key_luminance(golden);
  r.value = ssim(ssim_display_values(golden, r.key_luminance),
                 ssim_display_values(candidate, r.key_luminance), width, height);
  r.windows = static_cast<std::size_t>(width - kSsimWindow + 1) *
              static_cast<std::size_t>(height - kSsimWindow + 1);
  r.computed = true;
  return r;
}
}  // namespace

namespace {
// Converged mode: the golden's estimated error of each value of its channel `g` (R, G or B, by
// alias): pixel_error.C (required) + lighting_error.C (when present); nothing for other
// channels. `used` receives the channels' names.
std::vector<double> golden_error_allowance(const ExrPart& golden, const ExrChannel& g,
                                           std::vector<std::string>& used) {
  const std::string alias = channel_alias(g.name);
  if (alias != "r" && alias != "g" && alias != "b") return {};
  const std::string suffix(1, static_cast<char>(alias[0] - 'a' + 'A'));
  std::vector<double> allowance(g.values.size(), 0.0);
  for (const std::string layer : {"pixel_error.", "lighting_error."}) {
    const std::string name = layer + suffix;
    const auto found =
        std::find_if(golden.image.channels.begin(), golden.image.channels.end(),
                     [&](const ExrChannel& c) { return c.name == name && c.sampling == 1; });
    if (found == golden.image.channels.end()) {
      if (layer == "lighting_error.") continue;
      throw std::invalid_argument(part_label(golden) + ": a converged comparison (--converged) " +
                                  "needs the golden's " + name + " (render the golden with --aov)");
    }
    for (std::size_t i = 0; i < allowance.size(); ++i) {
      const double e = static_cast<double>(found->values[i]);
      if (!(e >= 0.0 && std::isfinite(e))) {
        throw std::invalid_argument(part_label(golden) + ": the golden's " + name +
                                    " holds a value that is not a finite error (" +
                                    short_number(e) + ")");
      }
      allowance[i] += e;
    }
    used.push_back(name);
  }
  return allowance;
}
}  // namespace

PartResult compare_part(const ExrPart& golden, const ExrPart& candidate,
                        const ChannelSelection& selection, const ThresholdProfile& profile) {
  const ExrImage& g = golden.image;
  const ExrImage& c = candidate.image;
  if (g.width != c.width || g.height != c.height) {
    throw std::invalid_argument(part_label(golden) + ": the images differ in size: golden " +
                                std::to_string(g.width) + "x" + std::to_string(g.height) +
                                ", candidate " + std::to_string(c.width) + "x" +
                                std::to_string(c.height));
  }
  if (g.origin_x != c.origin_x || g.origin_y != c.origin_y) {
    throw std::invalid_argument(part_label(golden) + ": the data windows differ: golden at (" +
                                std::to_string(g.origin_x) + ", " + std::to_string(g.origin_y) +
                                "), candidate at (" + std::to_string(c.origin_x) + ", " +
                                std::to_string(c.origin_y) + ")");
  }
  std::vector<std::pair<const ExrChannel*, const ExrChannel*>> pairs;  // (golden, candidate)
  if (selection.pairs.empty()) {
    std::vector<std::string> unmatched;
    for (const ExrChannel& cc : c.channels) {
      if (!selection.include_alpha && is_alpha_channel(cc.name)) continue;
      bool ambiguous = false;
      const ExrChannel* gc = find_channel(g, cc.name, &ambiguous);
      if (gc == nullptr) {
        unmatched.push_back(cc.name + (ambiguous ? " (ambiguous alias)" : ""));
      } else {
        pairs.emplace_back(gc, &cc);
      }
    }
    if (!unmatched.empty()) {
      throw std::invalid_argument(part_label(golden) + ": candidate channel(s) " + join(unmatched) +
                                  " have no counterpart among the golden's " +
                                  join(channel_names(g)) + "; map them with --channels");
    }
  } else {
    for (const auto& [cname, gname] : selection.pairs) {
      bool ambiguous_c = false, ambiguous_g = false;
      const ExrChannel* cc = find_channel(c, cname, &ambiguous_c);
      const ExrChannel* gc = find_channel(g, gname, &ambiguous_g);
      if (cc == nullptr) {
        throw std::invalid_argument(part_label(golden) + ": the candidate has no channel '" +
                                    cname + "'" + (ambiguous_c ? " (ambiguous alias)" : "") +
                                    "; it has " + join(channel_names(c)));
      }
      if (gc == nullptr) {
        throw std::invalid_argument(part_label(golden) + ": the golden has no channel '" + gname +
                                    "'" + (ambiguous_g ? " (ambiguous alias)" : "") + "; it has " +
                                    join(channel_names(g)));
      }
      pairs.emplace_back(gc, cc);
    }
  }
  if (pairs.empty()) {
    throw std::invalid_argument(part_label(golden) + ": no channel to compare (candidate has " +
                                join(channel_names(c)) + ")");
  }
  std::set<std::string> used;
  for (const auto& [gc, cc] : pairs) {
    if (!used.insert(gc->name).second) {
      throw std::invalid_argument(part_label(golden) + ": golden channel '" + gc->name +
                                  "' is matched by more than one candidate channel");
    }
    if (gc->sampling != cc->sampling) {
      throw std::invalid_argument(part_label(golden) + ": channel '" + gc->name +
                                  "' is subsampled by " + std::to_string(gc->sampling) +
                                  " in the golden but by " + std::to_string(cc->sampling) +
                                  " in the candidate ('" + cc->name + "')");
    }
  }
  PartResult result;
  result.name = golden.name;
  result.level_x = golden.level_x;
  result.level_y = golden.level_y;
  result.width = g.width;
  result.height = g.height;
  for (const ExrChannel& gc : g.channels) {
    if (!used.contains(gc.name)) result.not_compared.push_back(gc.name);
  }
  const auto pixels = static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height);
  std::vector<char> failing(pixels, 0);
  for (const auto& [gc, cc] : pairs) {
    std::vector<std::string> error_channels;
    const std::vector<double> allowance = profile.golden_error
                                              ? golden_error_allowance(golden, *gc, error_channels)
                                              : std::vector<double>{};
    ChannelResult r = compare_channel(*gc, *cc, g.width,
                                      threshold_for(profile, golden.name, gc->name), allowance);
    r.golden_error_channels = std::move(error_channels);
    if (r.sampling == 1) {
      for (std::size_t i = 0; i < pixels && i < r.fails.size(); ++i) {
        failing[i] = static_cast<char>(failing[i] | r.fails[i]);
      }
    }
    if (!r.pass) result.pass = false;
    result.channels.push_back(std::move(r));
  }
  std::size_t failing_pixels = 0;
  for (const char f : failing) failing_pixels += f != 0 ? 1 : 0;
  result.failing_share =
      pixels > 0 ? static_cast<double>(failing_pixels) / static_cast<double>(pixels) : 0.0;
  result.ssim = part_ssim(pairs, g.width, g.height);
  result.min_ssim = profile.min_ssim;
  if (result.min_ssim && result.ssim.applies &&
      !(result.ssim.computed && result.ssim.value >= *result.min_ssim)) {
    result.pass = false;
  }
  return result;
}

Comparison compare_parts(const std::vector<ExrPart>& golden, const std::vector<ExrPart>& candidate,
                         const ChannelSelection& selection, const ThresholdProfile& profile) {
  Comparison result;
  if (golden.empty() || candidate.empty()) {
    throw std::invalid_argument(std::string(golden.empty() ? "the golden" : "the candidate") +
                                " has no image part");
  }
  std::vector<std::pair<const ExrPart*, const ExrPart*>> matched;
  if (golden.size() == 1 && candidate.size() == 1) {
    matched.emplace_back(&golden[0], &candidate[0]);
  } else {
    std::vector<std::string> unmatched;
    for (const ExrPart& c : candidate) {
      const auto it = std::find_if(golden.begin(), golden.end(), [&](const ExrPart& g) {
        return g.name == c.name && g.level_x == c.level_x && g.level_y == c.level_y;
      });
      if (it == golden.end()) {
        unmatched.push_back(part_label(c));
      } else {
        matched.emplace_back(&*it, &c);
      }
    }
    if (!unmatched.empty()) {
      std::vector<std::string> available;
      for (const ExrPart& g : golden) available.push_back(part_label(g));
      throw std::invalid_argument("candidate " + join(unmatched) +
                                  " not found in the golden, which has " + join(available));
    }
    for (const ExrPart& g : golden) {
      if (std::none_of(matched.begin(), matched.end(),
                       [&](const auto& m) { return m.first == &g; }))
        result.parts_not_compared.push_back(part_label(g));
    }
  }
  bool any_ssim = false;
  for (const auto& [g, c] : matched) {
    PartResult p = compare_part(*g, *c, selection, profile);
    any_ssim = any_ssim || p.ssim.applies;
    for (const ChannelResult& ch : p.channels)
      result.nonfinite_mismatches += ch.nonfinite_mismatches;
    if (!p.pass) result.pass = false;
    result.parts.push_back(std::move(p));
  }
  if (profile.min_ssim && !any_ssim) {
    throw std::invalid_argument("profile '" + profile.name +
                                "' sets min_ssim, but no compared part " +
                                "has R, G, B (or Y) channels at full resolution for an SSIM");
  }
  if (result.nonfinite_mismatches > 0) result.pass = false;
  return result;
}

std::vector<ExrPart> read_parts_for_compare(const std::string& path, double max_bytes) {
  return read_exr_parts(path, max_bytes);
}

std::string generalize_name(const std::string& name) {
  std::string out;
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name[i] >= '0' && name[i] <= '9') {
      if (out.empty() || out.back() != '*') out += '*';
    } else {
      out += name[i];
    }
  }
  return out;
}

std::vector<SuggestedRule> suggest_thresholds(const std::vector<Comparison>& runs, double safety,
                                              double floor) {
  std::map<std::pair<std::string, std::string>, SuggestedRule> groups;
  std::map<std::pair<std::string, std::string>, std::set<std::size_t>> runs_of;
  for (std::size_t run = 0; run < runs.size(); ++run) {
    for (const PartResult& p : runs[run].parts) {
      for (const ChannelResult& c : p.channels) {
        if (c.nonfinite_mismatches > 0) {
          throw std::invalid_argument("run " + std::to_string(run + 1) + ": channel '" +
                                      c.golden_name + "' has " +
                                      std::to_string(c.nonfinite_mismatches) +
                                      " non-finite mismatches: no threshold accepts them");
        }
        if (!(c.max_relative < kInf)) {
          throw std::invalid_argument("run " + std::to_string(run + 1) + ": channel '" +
                                      c.golden_name +
                                      "' differs where the golden is 0: raise --floor");
        }
        const std::pair key{std::string("*"), generalize_name(c.golden_name)};
        SuggestedRule& r = groups[key];
        r.part = key.first;
        r.channel = key.second;
        r.measured_max_relative = std::max(r.measured_max_relative, c.max_relative);
        r.measured_p99_9_relative = std::max(r.measured_p99_9_relative, c.relative_percentiles[3]);
        r.measured_max_absolute = std::max(r.measured_max_absolute, c.max_absolute);
        ++r.channels;
        runs_of[key].insert(run);
      }
    }
  }
  std::vector<SuggestedRule> out;
  for (auto& [key, r] : groups) {
    r.runs = runs_of[key].size();
    r.threshold.floor = floor;
    r.threshold.relative = safety * r.measured_max_relative;
    out.push_back(r);
  }
  return out;
}

std::string comparison_json(const Comparison& c, const std::string& golden_path,
                            const std::string& candidate_path) {
  nlohmann::json j;
  j["golden"] = golden_path;
  j["candidate"] = candidate_path;
  j["result"] = c.pass ? "pass" : "fail";
  j["nonfinite_mismatches"] = c.nonfinite_mismatches;
  j["parts_not_compared"] = c.parts_not_compared;
  j["percentiles"] = kPercentileNames;
  nlohmann::json edges = nlohmann::json::array();
  double edge = 1.0;
  for (int k = 0; k > kHistogramFirstDecade; --k) edge /= 10.0;
  for (int k = kHistogramFirstDecade; k <= kHistogramLastDecade; ++k) {
    edges.push_back(edge);
    edge *= 10.0;
  }
  j["histogram_edges"] = edges;
  j["parts"] = nlohmann::json::array();
  for (const PartResult& p : c.parts) {
    nlohmann::json pj{{"name", p.name},
                      {"level", {p.level_x, p.level_y}},
                      {"width", p.width},
                      {"height", p.height},
                      {"result", p.pass ? "pass" : "fail"},
                      {"failing_pixels_share", p.failing_share},
                      {"not_compared", p.not_compared}};
    if (p.ssim.applies) {
      nlohmann::json sj{
          {"value", p.ssim.computed ? nlohmann::json(p.ssim.value) : nlohmann::json()},
          {"channels", p.ssim.source},
          {"luminance", "Y = 0.2126 R + 0.7152 G + 0.0722 B (or Y), negatives as 0"},
          {"mapping",
           "t = Y/(Y + key/0.18), d = t^(1/2.2), key = the golden's "
           "exp(mean ln(Y + 1e-3))"},
          {"key_luminance", p.ssim.key_luminance},
          {"dynamic_range", kSsimDynamicRange},
          {"window", "11x11 Gaussian, sigma 1.5, valid positions only"},
          {"K1", kSsimK1},
          {"K2", kSsimK2},
          {"windows", p.ssim.windows}};
      if (!p.ssim.computed) sj["reason"] = p.ssim.reason;
      if (p.min_ssim) sj["min_ssim"] = *p.min_ssim;
      pj["ssim"] = sj;
    }
    pj["channels"] = nlohmann::json::array();
    for (const ChannelResult& r : p.channels) {
      nlohmann::json cj{{"golden", r.golden_name},
                        {"candidate", r.candidate_name},
                        {"sampling", r.sampling},
                        {"result", r.pass ? "pass" : "fail"},
                        {"threshold", threshold_json(r.threshold)},
                        {"golden_error_channels", r.golden_error_channels},
                        {"golden_rms", r.golden_rms},
                        {"values", r.values},
                        {"failing", r.failing},
                        {"failing_share", r.failing_share},
                        {"nonfinite_mismatches", r.nonfinite_mismatches},
                        {"max_abs", number_json(r.max_absolute)},
                        {"max_rel", number_json(r.max_relative)},
                        {"rmse", number_json(r.rmse)},
                        {"psnr_db", number_json(r.psnr)},
                        {"max_ulp", r.max_ulp}};
      nlohmann::json ap = nlohmann::json::array(), rp = nlohmann::json::array();
      for (std::size_t k = 0; k < kPercentiles.size(); ++k) {
        ap.push_back(number_json(r.absolute_percentiles[k]));
        rp.push_back(number_json(r.relative_percentiles[k]));
      }
      cj["abs_percentiles"] = ap;
      cj["rel_percentiles"] = rp;
      cj["histogram"] = {{"zero", r.histogram.zero},
                         {"decades", r.histogram.decades},
                         {"nonfinite", r.histogram.nonfinite}};
      nlohmann::json worst = nlohmann::json::array();
      for (const WorstValue& w : r.worst) {
        worst.push_back({{"x", w.x},
                         {"y", w.y},
                         {"golden", number_json(static_cast<double>(w.golden))},
                         {"candidate", number_json(static_cast<double>(w.candidate))},
                         {"abs", number_json(w.absolute)},
                         {"rel", number_json(w.relative)},
                         {"pass", w.pass}});
      }
      cj["worst"] = worst;
      pj["channels"].push_back(cj);
    }
    j["parts"].push_back(pj);
  }
  return j.dump(2) + "\n";
}

std::string comparison_text(const Comparison& c) {
  std::ostringstream out;
  const auto pad = [](const std::string& s, std::size_t w) {
    return s.size() >= w ? s + " " : s + std::string(w - s.size(), ' ');
  };
  for (const PartResult& p : c.parts) {
    out << "part " << (p.name.empty() ? "(single)" : "'" + p.name + "'");
    if (p.level_x != 0 || p.level_y != 0) out << " level " << p.level_x << "," << p.level_y;
    out << ", " << p.width << "x" << p.height << ": " << (p.pass ? "pass" : "FAIL")
        << ", failing pixels " << short_number(100.0 * p.failing_share) << "%\n";
    std::size_t name_width = 8;
    for (const ChannelResult& r : p.channels) {
      std::string n = r.golden_name == r.candidate_name ? r.golden_name
                                                        : r.candidate_name + "=" + r.golden_name;
      name_width = std::max(name_width, n.size() + 1);
    }
    out << pad("channel", name_width) << pad("result", 7) << pad("failing", 10)
        << pad("rel p50", 10) << pad("p90", 10) << pad("p99", 10) << pad("p99.9", 10)
        << pad("max", 10) << pad("abs max", 10) << pad("RMS(g)", 10) << pad("max ULP", 11)
        << pad("threshold A+R*max(|g|,F*RMS)", 1) << "   worst (x,y)\n";
    for (const ChannelResult& r : p.channels) {
      const std::string n = r.golden_name == r.candidate_name
                                ? r.golden_name
                                : r.candidate_name + "=" + r.golden_name;
      out << pad(n, name_width) << pad(r.pass ? "pass" : "FAIL", 7)
          << pad(short_number(100.0 * r.failing_share) + "%", 10);
      for (const double v : r.relative_percentiles) out << pad(short_number(v), 10);
      out << pad(short_number(r.max_absolute), 10) << pad(short_number(r.golden_rms), 10)
          << pad(r.max_ulp == std::numeric_limits<long long>::max() ? "inf"
                                                                    : std::to_string(r.max_ulp),
                 11)
          << "A=" << short_number(r.threshold.absolute)
          << " R=" << short_number(r.threshold.relative)
          << " F=" << short_number(r.threshold.floor);
      if (r.threshold.ulp > 0) out << " U=" << r.threshold.ulp;
      if (r.threshold.allowed_share > 0) out << " S=" << short_number(r.threshold.allowed_share);
      for (const std::string& e : r.golden_error_channels) out << " +" << e;
      if (!r.worst.empty()) {
        out << "   " << r.worst[0].x << "," << r.worst[0].y << " (g "
            << short_number(static_cast<double>(r.worst[0].golden)) << ", c "
            << short_number(static_cast<double>(r.worst[0].candidate)) << ")";
      }
      if (r.nonfinite_mismatches > 0) {
        out << "   NON-FINITE MISMATCHES: " << r.nonfinite_mismatches;
      }
      out << '\n';
    }
    if (p.ssim.applies) {
      out << "SSIM (" << p.ssim.source << " luminance, tone-mapped by the golden's key "
          << short_number(p.ssim.key_luminance) << "): ";
      if (p.ssim.computed) {
        char value[32];
        std::snprintf(value, sizeof value, "%.6f", p.ssim.value);
        out << value;
      } else {
        out << "not computed (" << p.ssim.reason << ")";
      }
      if (p.min_ssim) {
        out << ", min_ssim " << shortest_number(*p.min_ssim) << ": "
            << (p.ssim.computed && p.ssim.value >= *p.min_ssim ? "pass" : "FAIL");
      }
      out << '\n';
    }
    if (!p.not_compared.empty())
      out << "not compared (golden only): " << join(p.not_compared) << '\n';
  }
  if (!c.parts_not_compared.empty()) {
    std::string parts;  // the labels carry their own quotes: part 'sum', (unnamed part)
    for (const std::string& p : c.parts_not_compared) parts += (parts.empty() ? "" : ", ") + p;
    out << "parts not compared (golden only): " << parts << '\n';
  }
  if (c.nonfinite_mismatches > 0) {
    out << "non-finite mismatches: " << c.nonfinite_mismatches << " (always a failure)\n";
  }
  out << "result: " << (c.pass ? "pass" : "fail") << '\n';
  return out.str();
}

std::string suggested_profile_json(const std::vector<SuggestedRule>& rules, const std::string& name,
                                   const std::string& derivation, double safety, double floor) {
  nlohmann::ordered_json j;
  j["name"] = name;
  j["rule"] =
      "a value passes if |c - g| <= abs + rel * max(|g|, floor * RMS(g)) (or within ulp float32 "
      "ULPs); a channel passes if at most max_fail_share of its values fail; any non-finite "
      "mismatch fails";
  j["derivation"] = derivation + "; rel = " + short_number(safety) +
                    " x the largest relative error measured over the runs (floor " +
                    short_number(floor) + " x RMS)";
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const SuggestedRule& r : rules) {
    list.push_back({{"match", r.channel},
                    {"part", r.part},
                    {"abs", r.threshold.absolute},
                    {"rel", r.threshold.relative},
                    {"floor", r.threshold.floor},
                    {"ulp", r.threshold.ulp},
                    {"max_fail_share", r.threshold.allowed_share},
                    {"measured_max_relative", r.measured_max_relative},
                    {"measured_p99_9_relative", r.measured_p99_9_relative},
                    {"measured_max_absolute", r.measured_max_absolute},
                    {"channels_measured", r.channels},
                    {"runs", r.runs}});
  }
  j["channels"] = list;
  return j.dump(2) + "\n";
}

}  // namespace oceanref
