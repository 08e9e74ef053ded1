#include "conformance/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/format.h"
#include "core/math.h"
#include "io/output_file.h"
#include "io/png.h"
#include "shading/tone_mapping.h"

namespace oceanref {

namespace {
using Rgb = std::array<std::uint8_t, 3>;
constexpr Rgb kNonFinite{0, 230, 230};  // cyan: a non-finite mismatch (heat), non-finite value
constexpr Rgb kFail{230, 30, 30};
constexpr Rgb kPass{225, 225, 225};

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t b0 = bytes[i];
    const std::uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0u;
    const std::uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0u;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[v & 63] : '=';
  }
  return out;
}

struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

std::string data_uri(const Picture& p) {
  return "data:image/png;base64," + base64(encode_png(p.width, p.height, p.rgb));
}

void put(Picture& p, std::size_t i, const Rgb& c) {
  p.rgb[3 * i] = c[0];
  p.rgb[3 * i + 1] = c[1];
  p.rgb[3 * i + 2] = c[2];
}

Picture blank(int width, int height) {
  Picture p;
  p.width = std::max(1, width);
  p.height = std::max(1, height);
  p.rgb.assign(static_cast<std::size_t>(p.width) * static_cast<std::size_t>(p.height) * 3, 0);
  return p;
}

// Nearest-neighbour enlargement (crops are small).
Picture enlarge(const Picture& p, int factor) {
  Picture out = blank(p.width * factor, p.height * factor);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const auto src = static_cast<std::size_t>(y / factor) * static_cast<std::size_t>(p.width) +
                       static_cast<std::size_t>(x / factor);
      const auto dst = static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) +
                       static_cast<std::size_t>(x);
      put(out, dst, {p.rgb[3 * src], p.rgb[3 * src + 1], p.rgb[3 * src + 2]});
    }
  }
  return out;
}

std::uint8_t byte(double v) {
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
}

Rgb grey(double v, double lo, double hi) {
  if (!std::isfinite(v)) return {255, 0, 255};
  const std::uint8_t g = byte(hi > lo ? (v - lo) / (hi - lo) : 0.5);
  return {g, g, g};
}

// A w × h window of a channel's grid (x0, y0 its corner), each value coloured by `colour`.
template <class Colour>
Picture window_picture(const std::vector<float>& values, int grid_width, int x0, int y0, int w,
                       int h, const Colour& colour) {
  Picture p = blank(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto i = static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(grid_width) +
                     static_cast<std::size_t>(x0 + x);
      put(p,
          static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x),
          colour(static_cast<double>(values[i])));
    }
  }
  return p;
}

// The window as grey between lo and hi.
Picture grey_picture(const std::vector<float>& values, int grid_width, int x0, int y0, int w, int h,
                     double lo, double hi) {
  return window_picture(values, grid_width, x0, y0, w, h,
                        [&](double v) { return grey(v, lo, hi); });
}

// The window of relative errors as a heat map.
Picture heat_picture(const std::vector<float>& e, int grid_width, int x0, int y0, int w, int h) {
  return window_picture(e, grid_width, x0, y0, w, h, [](double v) { return heat_colour(v); });
}

std::string escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '&') {
      out += "&amp;";
    } else if (c == '"') {
      out += "&quot;";
    } else {
      out += c;
    }
  }
  return out;
}

// Display width of an image in CSS pixels: small grids enlarged, large ones shrunk to fit.
int display_width(int width) {
  if (width <= 0) return 1;
  const int factor = std::max(1, 256 / width);
  return std::min(384, width * factor);
}

std::string img(const std::string& uri, int width, const std::string& cls, const std::string& alt) {
  return "<img class=\"" + cls + "\" src=\"" + uri + "\" width=\"" +
         std::to_string(display_width(width)) + "\" alt=\"" + escape(alt) + "\">";
}

const ExrChannel* channel_named(const ExrImage& image, const std::string& name) {
  for (const ExrChannel& c : image.channels) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

const ExrChannel* rgb_channel(const ExrImage& image, const char* key) {
  for (const ExrChannel& c : image.channels) {
    if (c.sampling == 1 && channel_alias(c.name) == key) return &c;
  }
  return nullptr;
}

// Tone-mapped colour of an RGB part (the golden's exposure for both), or an empty picture.
Picture tone_mapped(const ExrImage& image, double average, double white) {
  const ExrChannel* r = rgb_channel(image, "r");
  const ExrChannel* g = rgb_channel(image, "g");
  const ExrChannel* b = rgb_channel(image, "b");
  if (!r || !g || !b) return {};
  Picture p = blank(image.width, image.height);
  for (std::size_t i = 0; i < r->values.size(); ++i) {
    const Vec3 c{static_cast<double>(r->values[i]), static_cast<double>(g->values[i]),
                 static_cast<double>(b->values[i])};
    if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2])) {
      put(p, i, {255, 0, 255});
      continue;
    }
    const Vec3 m = reinhard(c, average, 0.18, white);
    put(p, i, {byte(srgb_encode(m[0])), byte(srgb_encode(m[1])), byte(srgb_encode(m[2]))});
  }
  return p;
}

std::vector<Vec3> finite_colours(const ExrImage& image) {
  const ExrChannel* r = rgb_channel(image, "r");
  const ExrChannel* g = rgb_channel(image, "g");
  const ExrChannel* b = rgb_channel(image, "b");
  std::vector<Vec3> out;
  if (!r || !g || !b) return out;
  for (std::size_t i = 0; i < r->values.size(); ++i) {
    const Vec3 c{static_cast<double>(r->values[i]), static_cast<double>(g->values[i]),
                 static_cast<double>(b->values[i])};
    if (std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2])) out.push_back(c);
  }
  return out;
}

std::string flip_figure(const std::string& golden_uri, const std::string& candidate_uri, int width,
                        const std::string& what) {
  std::ostringstream h;
  h << "<figure class=\"flip\" data-golden=\"" << golden_uri << "\" data-candidate=\""
    << candidate_uri << "\">" << img(golden_uri, width, "values", what + " (golden)")
    << "<figcaption><button type=\"button\">golden: click or hover to flip</button> " << what
    << "</figcaption></figure>";
  return h.str();
}

std::string legend(const ChannelThreshold& t) {
  Picture bar = blank(300, 14);
  for (int x = 0; x < bar.width; ++x) {
    const double decade = kHeatLowDecade + (kHeatHighDecade - kHeatLowDecade) * (x + 0.5) / 300.0;
    const Rgb c = heat_colour(math::pow(10.0, decade));
    for (int y = 0; y < bar.height; ++y) {
      put(bar, static_cast<std::size_t>(y) * 300 + static_cast<std::size_t>(x), c);
    }
  }
  std::ostringstream h;
  h << "<div class=\"legend\"><span class=\"swatch\" style=\"background:#000\"></span> e = 0 "
    << "<span class=\"swatch\" style=\"background:rgb(" << int{kNonFinite[0]} << ","
    << int{kNonFinite[1]} << "," << int{kNonFinite[2]} << ")\"></span> non-finite "
    << "<div class=\"bar\"><img src=\"" << data_uri(bar) << "\" width=\"300\" height=\"14\" "
    << "alt=\"colour bar\">";
  const int decades = kHeatHighDecade - kHeatLowDecade;
  for (int k = 0; k <= decades; ++k) {
    h << "<span class=\"tick\" style=\"left:" << 300 * k / decades << "px\">1e"
      << kHeatLowDecade + k << "</span>";
  }
  if (t.relative > 0.0 && t.absolute == 0.0) {
    const double position = (math::log10(t.relative) - kHeatLowDecade) / decades;
    if (position >= 0.0 && position <= 1.0) {
      h << "<span class=\"threshold\" style=\"left:" << std::lround(300.0 * position)
        << "px\" title=\"threshold R\"></span>";
    }
  }
  h << "</div> relative error e = |c&minus;g| / max(|g|, F&middot;RMS(g)), log scale";
  if (t.relative > 0.0 && t.absolute == 0.0)
    h << "; the white mark is the threshold R = " << short_number(t.relative);
  h << "</div>";
  return h.str();
}

std::string histogram_html(const ErrorHistogram& hist) {
  std::size_t largest = std::max(hist.zero, hist.nonfinite);
  for (const std::size_t c : hist.decades) largest = std::max(largest, c);
  std::ostringstream h;
  h << "<table class=\"hist\"><tr><th>e</th><th>values</th><th></th></tr>";
  const auto row = [&](const std::string& label, std::size_t count) {
    const double w =
        largest > 0 ? 200.0 * static_cast<double>(count) / static_cast<double>(largest) : 0.0;
    h << "<tr><td>" << label << "</td><td>" << count << "</td><td><span class=\"hbar\" "
      << "style=\"width:" << std::lround(w) << "px\"></span></td></tr>";
  };
  row("0", hist.zero);
  for (std::size_t k = 0; k < hist.decades.size(); ++k) {
    if (hist.decades[k] == 0) continue;
    const int d = kHistogramFirstDecade + static_cast<int>(k);
    row("[1e" + std::to_string(d) + ", 1e" + std::to_string(d + 1) + ")", hist.decades[k]);
  }
  if (hist.nonfinite > 0) row("non-finite", hist.nonfinite);
  h << "</table>";
  return h.str();
}

const char* kStyle =
    "body{font-family:sans-serif;margin:1em 2em;color:#222}h1.pass{color:#176b1a}"
    "h1.fail{color:#b00}table{border-collapse:collapse;margin:.5em 0}"
    "td,th{padding:2px 8px;text-align:right;border-bottom:1px solid #ddd}"
    "td:first-child,th:first-child{text-align:left}tr.fail td{color:#b00}"
    "img{image-rendering:pixelated;border:1px solid #999}figure{display:inline-block;"
    "vertical-align:top;margin:0 1em .5em 0}figcaption{font-size:85%;max-width:384px}"
    "section.channel{border-top:2px solid #ccc;padding-top:.3em;margin-top:1em}"
    ".legend{font-size:85%;margin:.3em 0 1.6em 0}.bar{position:relative;display:inline-block;"
    "width:300px;height:14px;margin:0 1em;vertical-align:middle}.bar img{border:0;display:block}"
    ".tick{position:absolute;top:16px;font-size:70%;transform:translateX(-50%)}"
    ".threshold{position:absolute;top:-3px;width:2px;height:20px;background:#fff;"
    "outline:1px solid #000}.swatch{display:inline-block;width:12px;height:12px;"
    "border:1px solid #999;vertical-align:middle}.hist{font-size:80%}.hbar{display:inline-block;"
    "height:9px;background:#7a4ba0}.crops td{vertical-align:top}#toc a{margin-right:.8em}"
    "#toc a.fail{color:#b00;font-weight:bold}#rendered-channels{color:#999;font-size:70%;"
    "white-space:pre}#script-error{color:#fff;background:#b00;padding:.5em}"
    "figure.flip.candidate img{outline:3px solid #e90}";

const char* kScript = R"JS(
window.onerror = function (message, source, line) {
  var e = document.getElementById('script-error');
  if (!e) {
    e = document.createElement('pre');
    e.id = 'script-error';
    document.body.insertBefore(e, document.body.firstChild);
  }
  e.textContent += message + ' (line ' + line + ')\n';
};
window.addEventListener('load', function () {
  document.querySelectorAll('figure.flip').forEach(function (figure) {
    var image = figure.querySelector('img');
    var button = figure.querySelector('button');
    var showing = 'golden';
    function show(which) {
      showing = which;
      image.src = figure.dataset[which];
      button.textContent = which + ': click or hover to flip';
      figure.classList.toggle('candidate', which === 'candidate');
    }
    button.addEventListener('click', function () {
      show(showing === 'golden' ? 'candidate' : 'golden');
    });
    image.addEventListener('mouseenter', function () { show('candidate'); });
    image.addEventListener('mouseleave', function () { show('golden'); });
  });
  var toc = document.getElementById('toc');
  var rendered = [];
  document.querySelectorAll('section.channel').forEach(function (section) {
    var images = section.querySelectorAll('img');
    var decoded = images.length > 0;
    images.forEach(function (i) { if (!(i.complete && i.naturalWidth > 0)) decoded = false; });
    if (decoded) rendered.push(section.dataset.channel);
    var link = document.createElement('a');
    link.href = '#' + section.id;
    link.textContent = section.dataset.channel;
    link.className = section.dataset.result;
    toc.appendChild(link);
  });
  var marker = document.createElement('div');
  marker.id = 'rendered-channels';
  marker.dataset.count = String(rendered.length);
  marker.textContent = 'channels rendered by the script:\n' + rendered.join('\n');
  document.body.appendChild(marker);
});
)JS";
}  // namespace

Rgb heat_colour(double e) {
  if (e == 0.0) return {0, 0, 0};
  if (!(e < std::numeric_limits<double>::infinity())) return kNonFinite;
  const double t =
      std::clamp((math::log10(e) - kHeatLowDecade) / (kHeatHighDecade - kHeatLowDecade), 0.0, 1.0);
  // Piecewise linear through five anchors (dark blue, purple, red, orange, pale yellow): monotone
  // in lightness, so the order of errors reads without the legend.
  static constexpr std::array<std::array<double, 3>, 5> anchors{
      {{20, 11, 82}, {110, 30, 130}, {200, 50, 80}, {245, 140, 20}, {252, 250, 170}}};
  const double s = t * 4.0;
  const auto k = static_cast<std::size_t>(std::min(3.0, std::floor(s)));
  const double f = s - static_cast<double>(k);
  Rgb c{};
  for (std::size_t i = 0; i < 3; ++i) {
    c[i] = static_cast<std::uint8_t>(
        std::lround(anchors[k][i] + f * (anchors[k + 1][i] - anchors[k][i])));
  }
  return c;
}

void write_report(const std::string& directory, const std::string& golden_name,
                  const std::string& candidate_name, const std::vector<ExrPart>& golden,
                  const std::vector<ExrPart>& candidate, const Comparison& comparison) {
  std::filesystem::create_directories(directory);
  const std::filesystem::path dir(directory);
  const auto find_part = [](const std::vector<ExrPart>& parts, const PartResult& p,
                            bool single) -> const ExrPart* {
    if (single) return &parts[0];
    for (const ExrPart& part : parts) {
      if (part.name == p.name && part.level_x == p.level_x && part.level_y == p.level_y) {
        return &part;
      }
    }
    return nullptr;
  };
  const bool single = golden.size() == 1 && candidate.size() == 1;
  std::ostringstream html;
  html << "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
       << "<title>oceanref compare: " << (comparison.pass ? "pass" : "FAIL") << "</title><style>"
       << kStyle << "</style></head><body>\n"
       << "<h1 id=\"verdict\" class=\"" << (comparison.pass ? "pass\">PASS" : "fail\">FAIL")
       << "</h1>\n<p>golden: <code>" << escape(golden_name) << "</code><br>candidate: <code>"
       << escape(candidate_name) << "</code></p>\n"
       << "<p>Rule per value: e = |c&minus;g| / max(|g|, F&middot;RMS(g)); the value passes if "
          "|c&minus;g| &le; A + R&middot;max(|g|, F&middot;RMS(g)) or within U float32 ULPs; a "
          "channel passes if at most S of its values fail; a non-finite mismatch always fails";
  if (comparison.nonfinite_mismatches > 0) {
    html << " (<b>" << comparison.nonfinite_mismatches << " non-finite mismatches</b>)";
  }
  html << ".</p>\n<nav id=\"toc\">channels: </nav>\n";
  if (!comparison.parts_not_compared.empty()) {
    html << "<p>golden parts not compared:";
    for (const std::string& n : comparison.parts_not_compared) html << ' ' << escape(n);
    html << "</p>\n";
  }
  int section = 0;
  for (std::size_t pi = 0; pi < comparison.parts.size(); ++pi) {
    const PartResult& p = comparison.parts[pi];
    const ExrPart* gp = find_part(golden, p, single);
    const ExrPart* cp = find_part(candidate, p, single);
    if (gp == nullptr || cp == nullptr) continue;
    html << "<h2>part " << (p.name.empty() ? std::string("(single)") : escape(p.name));
    if (p.level_x != 0 || p.level_y != 0) html << " level " << p.level_x << "," << p.level_y;
    html << ": " << p.width << "&times;" << p.height << ", " << (p.pass ? "pass" : "FAIL")
         << ", failing pixels " << short_number(100.0 * p.failing_share) << "%</h2>\n";
    // Colour overview with a flip.
    {
      const std::vector<Vec3> colours = finite_colours(gp->image);
      if (!colours.empty()) {
        const double average = log_average_luminance(colours);
        double white = 0.0;
        for (const Vec3& c : colours) {
          white = std::max(white, 0.18 / std::max(average, 1e-30) * relative_luminance(c));
        }
        const Picture g = tone_mapped(gp->image, average, white);
        const Picture c = tone_mapped(cp->image, average, white);
        if (!g.rgb.empty() && !c.rgb.empty()) {
          html << flip_figure(data_uri(g), data_uri(c), g.width,
                              "R, G, B tone-mapped with the golden's exposure")
               << "\n";
        }
      }
    }
    // Summary table.
    html << "<table><tr><th>channel</th><th>result</th><th>failing</th>";
    for (const char* n : kPercentileNames) html << "<th>e " << n << "</th>";
    html << "<th>max |c&minus;g|</th><th>RMS(g)</th><th>max ULP</th><th>threshold</th></tr>\n";
    for (const ChannelResult& r : p.channels) {
      html << "<tr class=\"" << (r.pass ? "pass" : "fail") << "\"><td>" << escape(r.golden_name)
           << (r.candidate_name != r.golden_name ? " &larr; " + escape(r.candidate_name) : "")
           << "</td><td>" << (r.pass ? "pass" : "FAIL") << "</td><td>"
           << short_number(100.0 * r.failing_share) << "%</td>";
      for (const double v : r.relative_percentiles) html << "<td>" << short_number(v) << "</td>";
      html << "<td>" << short_number(r.max_absolute) << "</td><td>" << short_number(r.golden_rms)
           << "</td><td>"
           << (r.nonfinite_mismatches > 0 ? std::string("inf") : std::to_string(r.max_ulp))
           << "</td><td>A " << short_number(r.threshold.absolute) << ", R "
           << short_number(r.threshold.relative) << ", F " << short_number(r.threshold.floor)
           << "</td></tr>\n";
    }
    html << "</table>\n";
    if (p.ssim.applies) {
      // The perceptual metric beside the numeric ones (compare.h: SSIM).
      char value[32];
      std::snprintf(value, sizeof value, "%.6f", p.ssim.value);
      html << "<p class=\"ssim\">SSIM (Wang et al. 2004; luminance of " << escape(p.ssim.source)
           << ", tone-mapped by the golden's log-average " << short_number(p.ssim.key_luminance)
           << " cd/m&sup2;, 11&times;11 Gaussian window &sigma; 1.5, L = 1): <b>"
           << (p.ssim.computed ? std::string(value)
                               : "not computed (" + escape(p.ssim.reason) + ")")
           << "</b>";
      if (p.min_ssim) {
        html << ", min_ssim " << shortest_number(*p.min_ssim) << ": "
             << (p.ssim.computed && p.ssim.value >= *p.min_ssim ? "pass" : "FAIL");
      }
      html << "</p>\n";
    }
    if (!p.not_compared.empty()) {
      html << "<p>golden channels not compared:";
      for (const std::string& n : p.not_compared) html << ' ' << escape(n);
      html << "</p>\n";
    }
    ExrImage diff;
    diff.width = p.width;
    diff.height = p.height;
    std::vector<float> largest(
        static_cast<std::size_t>(p.width) * static_cast<std::size_t>(p.height), 0.0f);
    for (const ChannelResult& r : p.channels) {
      const ExrChannel* g = channel_named(gp->image, r.golden_name);
      const ExrChannel* c = channel_named(cp->image, r.candidate_name);
      if (g == nullptr || c == nullptr) continue;
      diff.channels.push_back({r.golden_name, r.sampling, r.relative_error});
      if (r.sampling == 1) {
        for (std::size_t i = 0; i < largest.size(); ++i) {
          largest[i] = std::max(largest[i], r.relative_error[i]);
          if (std::isnan(r.relative_error[i])) largest[i] = r.relative_error[i];
        }
      }
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const float v : g->values) {
        if (std::isfinite(v)) {
          lo = std::min(lo, static_cast<double>(v));
          hi = std::max(hi, static_cast<double>(v));
        }
      }
      const std::string label = (p.name.empty() ? std::string() : p.name + "/") + r.golden_name;
      html << "<section class=\"channel\" id=\"channel-" << section++ << "\" data-channel=\""
           << escape(label) << "\" data-result=\"" << (r.pass ? "pass" : "fail") << "\">\n<h3>"
           << escape(label) << ": " << (r.pass ? "pass" : "FAIL") << " &mdash; " << r.failing
           << " of " << r.values << " values fail (" << short_number(100.0 * r.failing_share)
           << "%), e p50 " << short_number(r.relative_percentiles[0]) << ", p99.9 "
           << short_number(r.relative_percentiles[3]) << ", max "
           << short_number(r.relative_percentiles[4]);
      if (r.nonfinite_mismatches > 0) {
        html << ", <b>" << r.nonfinite_mismatches << " non-finite mismatches</b>";
      }
      html << "</h3>\n";
      const std::string gv =
          data_uri(grey_picture(g->values, r.width, 0, 0, r.width, r.height, lo, hi));
      const std::string cv =
          data_uri(grey_picture(c->values, r.width, 0, 0, r.width, r.height, lo, hi));
      Picture mask = blank(r.width, r.height);
      for (std::size_t i = 0; i < r.fails.size(); ++i) put(mask, i, r.fails[i] ? kFail : kPass);
      html << flip_figure(gv, cv, r.width,
                          "values, grey from " + short_number(lo) + " (black) to " +
                              short_number(hi) + " (white), magenta non-finite")
           << "<figure>"
           << img(data_uri(heat_picture(r.relative_error, r.width, 0, 0, r.width, r.height)),
                  r.width, "heat", "relative error heat map")
           << "<figcaption>relative error e (log scale, legend below)</figcaption></figure>"
           << "<figure>" << img(data_uri(mask), r.width, "mask", "fail mask")
           << "<figcaption>fail mask: red = fails (" << r.failing << ")</figcaption></figure>\n"
           << legend(r.threshold) << "\n"
           << histogram_html(r.histogram) << "\n";
      if (!r.worst.empty()) {
        html << "<table class=\"crops\"><tr><th>worst</th><th>golden</th><th>candidate</th>"
                "<th>error</th></tr>\n";
        const std::size_t crops = std::min<std::size_t>(4, r.worst.size());
        for (std::size_t k = 0; k < crops; ++k) {
          const WorstValue& w = r.worst[k];
          constexpr int kCrop = 15;
          const int cw = std::min(kCrop, r.width), ch = std::min(kCrop, r.height);
          const int x0 = std::clamp(w.x - cw / 2, 0, r.width - cw);
          const int y0 = std::clamp(w.y - ch / 2, 0, r.height - ch);
          double clo = std::numeric_limits<double>::infinity(), chi = -clo;
          for (int y = y0; y < y0 + ch; ++y) {
            for (int x = x0; x < x0 + cw; ++x) {
              const double v = static_cast<double>(
                  g->values[static_cast<std::size_t>(y) * static_cast<std::size_t>(r.width) +
                            static_cast<std::size_t>(x)]);
              if (std::isfinite(v)) {
                clo = std::min(clo, v);
                chi = std::max(chi, v);
              }
            }
          }
          const int factor = 8;
          html << "<tr><td>(" << w.x << ", " << w.y << ")<br>g "
               << short_number(static_cast<double>(w.golden)) << "<br>c "
               << short_number(static_cast<double>(w.candidate)) << "<br>|c&minus;g| "
               << short_number(w.absolute) << "<br>e " << short_number(w.relative) << "<br>"
               << (w.pass ? "passes" : "fails") << "</td>";
          for (const Picture& crop : {grey_picture(g->values, r.width, x0, y0, cw, ch, clo, chi),
                                      grey_picture(c->values, r.width, x0, y0, cw, ch, clo, chi),
                                      heat_picture(r.relative_error, r.width, x0, y0, cw, ch)}) {
            html << "<td><img src=\"" << data_uri(enlarge(crop, factor)) << "\" width=\""
                 << cw * factor << "\" alt=\"crop\"></td>";
          }
          html << "</tr>\n";
        }
        html << "</table><p>Crops: " << 15 << "&times;" << 15
             << " values around each worst value, enlarged 8&times;; golden and candidate in grey "
                "over the golden crop's range.</p>\n";
      }
      html << "</section>\n";
    }
    if (!largest.empty()) diff.channels.push_back({"max_e", 1, largest});
    const std::string name = comparison.parts.size() == 1 ? std::string("diff.exr")
                                                          : "diff." + std::to_string(pi) + ".exr";
    write_exr((dir / name).string(), diff);
  }
  html << "<script>" << kScript << "</script>\n</body></html>\n";
  write_output_file((dir / "index.html").string(), html.str());
}

}  // namespace oceanref
