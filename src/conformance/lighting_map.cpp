#include "conformance/lighting_map.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/format.h"
#include "core/math.h"
#include "core/parallel.h"
#include "core/vec3.h"
#include "io/exr.h"
#include "shading/lighting_terms.h"
#include "shading/ocean_lighting.h"
#include "shading/reference_lighting.h"
#include "waves/fft.h"

namespace oceanref {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// ---- The sweep ------------------------------------------------------------------------------
//
// Views from steep to grazing against the surface normal N, V·N = v_n, at azimuths φ about N
// measured from the direction facing the sun (φ = 0: the mirror of V about N has the sun's
// azimuth, the glitter side; φ = 180°: the sun behind the viewer); slope variances from a
// mirror to a very rough sea, isotropic and anisotropic; the flat normal and one tilted by 30°;
// the sun high, low and at the horizon (disk centre on the horizon, its lower half below).
// Preetham sky of turbidity 2.5, sun azimuth 90°, wind angle 20°, exact Fresnel and erfc.
constexpr double kTurbidity = 2.5;
constexpr double kSunAzimuthDeg = 90.0;
constexpr double kWindAngleDeg = 20.0;
constexpr double kTiltZenithDeg = 30.0, kTiltAzimuthDeg = 45.0;
constexpr double kTruthTolerance = 1e-10;

using SweepSpec = LightingSweepSpec;

SweepSpec full_sweep() {
  return {{0.9, 0.5, 0.2, 0.05, 0.01, 0.002},
          {0.0, 30.0, 90.0, 180.0},
          {{1e-6, 1e-6},
           {1e-4, 1e-4},
           {0.01, 0.01},
           {0.1, 0.1},
           {1.0, 1.0},
           {1e-4, 2e-5},
           {0.02, 0.006}},
          {false, true},
          {{"high", 30.0}, {"low", 80.0}, {"horizon", 89.9}},
          {1, 2, 4, 8, 16, 32, 64, 128, 256},
          {0, 1, 2, 4, 8, 16, 32},
          {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9},
          0.2};
}

SweepSpec quick_sweep() {
  SweepSpec s = full_sweep();
  s.cos_view = {0.5, 0.05};
  s.azimuths_deg = {0.0};
  s.roughness = {{1e-4, 1e-4}, {0.02, 0.006}};
  s.tilted = {false};
  s.suns = {{"high", 30.0}, {"horizon", 89.9}};
  s.fast_orders = {1, 4, 16};
  s.sun_orders = {0, 2, 8};
  s.tolerances = {1e-2, 1e-4, 1e-6};
  s.min_timing_seconds = 0.0;
  return s;
}

using SunSetting = LightingSun;
using Case = LightingCase;
using Sweep = LightingSweep;

}  // namespace

LightingSweep make_lighting_sweep(const LightingSweepSpec& spec) {
  Sweep sweep;
  for (const auto& [name, zenith] : spec.suns) {
    SunSetting sun{name, zenith, make_sky(kTurbidity, zenith * kDeg, kSunAzimuthDeg * kDeg),
                   {},   {},     HUGE_VAL};
    sun.sun_radiance = sun_radiance_rgb(sun.sky);
    const Vec3 irradiance = sky_irradiance(sun.sky).rgb;
    for (std::size_t c = 0; c < 3; ++c) {
      sun.sky_floor[c] = 1e-3 * std::fabs(irradiance[c]) / std::numbers::pi;
      if (sun.sun_radiance[c] > 0.0) {
        sun.sun_floor = std::fmin(sun.sun_floor, sun.sky_floor[c] / sun.sun_radiance[c]);
      }
    }
    if (!(sun.sun_floor < HUGE_VAL)) {
      throw std::logic_error("lighting-map: the sun at zenith " + format_number(zenith) +
                             " deg has no radiance");
    }
    sweep.suns.push_back(sun);
  }
  for (const bool tilted : spec.tilted) {
    const Vec3 normal = tilted
                            ? direction_from_angles(kTiltZenithDeg * kDeg, kTiltAzimuthDeg * kDeg)
                            : Vec3{0.0, 1.0, 0.0};
    const SurfaceFrame frame = wind_frame(normal, kWindAngleDeg * kDeg);
    for (std::size_t k = 0; k < sweep.suns.size(); ++k) {
      const Vec3 sun = sweep.suns[k].sky.sun_direction;
      Vec3 towards = combine(1.0, sun, -dot(sun, normal), normal);
      towards = dot(towards, towards) > 1e-18 ? normalize(towards) : frame.tangent_x;
      const Vec3 side = cross(normal, towards);
      for (const double vn : spec.cos_view) {
        const double tangential = std::sqrt(1.0 - vn * vn);
        for (const double phi : spec.azimuths_deg) {
          const math::SinCos a = math::sincos(phi * kDeg);
          const Vec3 across = combine(-a.cos, towards, a.sin, side);
          const Vec3 view = normalize(combine(vn, normal, tangential, across));
          for (const SlopeVariance& s : spec.roughness) {
            const Case c{view, frame, s, k};
            sweep.lit.push_back(c);
            if (k == 0) sweep.fresnel.push_back(c);
          }
        }
      }
    }
  }
  return sweep;
}

namespace {

// ---- The integrals --------------------------------------------------------------------------

using Integral = LightingIntegral;
constexpr Integral kIntegrals[] = {Integral::sky, Integral::fresnel, Integral::sun};
const char* integral_name(Integral i) {
  return i == Integral::sky       ? "reflected_sky"
         : i == Integral::fresnel ? "mean_fresnel"
                                  : "sun_disk";
}
const char* integral_title(Integral i) {
  return i == Integral::sky       ? "Reflected sky"
         : i == Integral::fresnel ? "Mean Fresnel"
                                  : "Sun disk";
}

// One result: up to three channels (the sky's R, G, B; F̄ and the sun's reflectance in [0]).
struct Value {
  Vec3 value{};
  Vec3 error{};
  long evaluations = 0;
  bool converged = true;
};
std::size_t channels(Integral i) {
  return i == Integral::sky ? 3 : 1;
}

Value reference_value(Integral integral, const Sweep& sweep, const Case& c, double tolerance) {
  const BrdfOptions options;
  const SunSetting& sun = sweep.suns[c.sun];
  Value v;
  if (integral == Integral::sky) {
    const Vec3 absolute{tolerance * sun.sky_floor[0], tolerance * sun.sky_floor[1],
                        tolerance * sun.sky_floor[2]};
    const RgbEstimate e =
        reflected_sky_reference(c.view, c.frame, c.s, sun.sky, options, tolerance, absolute);
    v.value = e.value;
    v.error = e.error;
    v.evaluations = e.evaluations;
    v.converged = e.converged;
    return v;
  }
  const ScalarEstimate e =
      integral == Integral::fresnel
          ? mean_fresnel_reference(c.view, c.frame, c.s, options, tolerance)
          : reflected_sun_reference(sun.sky.sun_direction, kSunAngularRadius, c.view, c.frame, c.s,
                                    options, tolerance, tolerance * sun.sun_floor);
  v.value[0] = e.value;
  v.error[0] = e.error;
  v.evaluations = e.evaluations;
  v.converged = e.converged;
  return v;
}

}  // namespace

double lighting_relative_error(LightingIntegral integral, const LightingSun& sun, const Vec3& x,
                               const Vec3& t) {
  if (integral == Integral::fresnel) {
    return std::fabs(x[0] - t[0]) / std::fmax(std::fabs(1.0 - t[0]), 1e-300);
  }
  if (integral == Integral::sun) {
    return std::fabs(x[0] - t[0]) / std::fmax(std::fabs(t[0]), sun.sun_floor);
  }
  double worst = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    worst = std::fmax(worst, std::fabs(x[c] - t[c]) / std::fmax(std::fabs(t[c]), sun.sky_floor[c]));
  }
  return worst;
}
double lighting_tolerance_bound(LightingIntegral integral, const LightingSun& sun, double tolerance,
                                double t, std::size_t c) {
  if (integral == Integral::fresnel) return tolerance * std::fabs(1.0 - t);
  if (integral == Integral::sun) return tolerance * std::fmax(std::fabs(t), sun.sun_floor);
  return tolerance * std::fmax(std::fabs(t), sun.sky_floor[c]);
}

namespace {

// ---- Measurement ----------------------------------------------------------------------------

using Row = LightingMapRow;

// Runs `pass` (every case once) until min_seconds have passed; the mean time per case.
double time_per_case(std::size_t cases, double min_seconds, const std::function<void()>& pass) {
  const auto start = std::chrono::steady_clock::now();
  int passes = 0;
  double elapsed = 0.0;
  do {
    pass();
    ++passes;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } while (elapsed < min_seconds);
  return elapsed / (static_cast<double>(passes) * static_cast<double>(cases));
}

void set_statistics(Row& row, std::vector<double> errors) {
  std::sort(errors.begin(), errors.end());
  const std::size_t n = errors.size();
  row.cases = n;
  row.median = errors[n / 2];
  const auto at95 = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n)));
  row.p95 = errors[std::max<std::size_t>(at95, 1) - 1];
  row.max = errors.back();
}

std::string order_label(Integral integral, int order) {
  if (integral == Integral::sun) {
    return order == 0 ? std::string("point")
                      : std::to_string(order) + "x" + std::to_string(4 * order);
  }
  return std::to_string(order) + "x" + std::to_string(order);
}
std::string short_number(double v, int digits = 2) {
  if (v == 0.0) return "0";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}
std::string tolerance_label(double t) {
  return short_number(t, 1);
}

using Map = LightingMap;

Map measure(const Sweep& sweep, const SweepSpec& spec, int threads) {
  Map map;
  map.spec = spec;
  map.threads = threads;
  map.lit_cases = sweep.lit.size();
  map.fresnel_cases = sweep.fresnel.size();
  for (const Integral integral : kIntegrals) {
    const std::vector<Case>& cases = integral == Integral::fresnel ? sweep.fresnel : sweep.lit;
    const std::size_t n = cases.size();
    const std::size_t k = static_cast<std::size_t>(integral);
    // The truths, in parallel (not timed per integral: a reference of its own).
    std::vector<Value> truth(n);
    const auto t0 = std::chrono::steady_clock::now();
    parallel_for(static_cast<int>(n), threads, [&](int i) {
      const auto j = static_cast<std::size_t>(i);
      truth[j] = reference_value(integral, sweep, cases[j], kTruthTolerance);
    });
    map.truth_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const Value& t : truth) {
      if (!t.converged) ++map.truth_unconverged[k];
      map.truth_evaluations[k] += static_cast<double>(t.evaluations) / static_cast<double>(n);
    }
    // Fast: the rules are built once (per frame in the renderer), outside the timing.
    const std::vector<int>& orders = integral == Integral::sun ? spec.sun_orders : spec.fast_orders;
    for (const int order : orders) {
      const BrdfOptions options;
      const QuadratureRule hermite =
          integral == Integral::sun ? QuadratureRule{} : gauss_hermite(order);
      std::vector<std::vector<SunDiskNode>> nodes;
      if (integral == Integral::sun) {
        const QuadratureRule disk = order > 0 ? gauss_legendre(order) : QuadratureRule{};
        for (const SunSetting& s : sweep.suns) {
          nodes.push_back(sun_disk_nodes(s.sky.sun_direction, kSunAngularRadius, disk));
        }
      }
      std::vector<Vec3> values(n);
      const double seconds = time_per_case(n, spec.min_timing_seconds, [&] {
        for (std::size_t i = 0; i < n; ++i) {
          const Case& c = cases[i];
          if (integral == Integral::sky) {
            values[i] =
                reflected_sky(c.view, c.frame, c.s, sweep.suns[c.sun].sky, hermite, options);
          } else if (integral == Integral::fresnel) {
            values[i][0] = mean_fresnel(c.view, c.frame, c.s, hermite, options);
          } else {
            values[i][0] = reflected_sun(nodes[c.sun], c.view, c.frame, c.s, options);
          }
        }
      });
      Row row;
      row.integral = integral;
      row.fast = true;
      row.setting = static_cast<double>(order);
      row.label = order_label(integral, order);
      std::vector<double> errors(n);
      for (std::size_t i = 0; i < n; ++i) {
        errors[i] =
            lighting_relative_error(integral, sweep.suns[cases[i].sun], values[i], truth[i].value);
      }
      set_statistics(row, errors);
      row.seconds = seconds;
      map.rows.push_back(row);
    }
    // Reference at each tolerance: its error against the truth, and against its own estimate.
    for (const double tolerance : spec.tolerances) {
      std::vector<Value> values(n);
      const double seconds = time_per_case(n, spec.min_timing_seconds, [&] {
        for (std::size_t i = 0; i < n; ++i) {
          values[i] = reference_value(integral, sweep, cases[i], tolerance);
        }
      });
      Row row;
      row.integral = integral;
      row.fast = false;
      row.setting = tolerance;
      row.label = tolerance_label(tolerance);
      std::vector<double> errors(n);
      double evaluations = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const SunSetting& sun = sweep.suns[cases[i].sun];
        errors[i] = lighting_relative_error(integral, sun, values[i].value, truth[i].value);
        evaluations += static_cast<double>(values[i].evaluations);
        if (!values[i].converged) ++row.unconverged;
        bool beyond_estimate = false, beyond_tolerance = false;
        for (std::size_t c = 0; c < channels(integral); ++c) {
          const double actual = std::fabs(values[i].value[c] - truth[i].value[c]);
          // The truth is itself uncertain by its own estimate (≈ 10⁻¹⁰ relative).
          const double allowed = values[i].error[c] + truth[i].error[c];
          if (actual > allowed) beyond_estimate = true;
          row.worst_ratio = std::fmax(
              row.worst_ratio, allowed > 0.0 ? actual / allowed : (actual > 0.0 ? HUGE_VAL : 0.0));
          if (actual > lighting_tolerance_bound(integral, sun, tolerance, truth[i].value[c], c) +
                           truth[i].error[c]) {
            beyond_tolerance = true;
          }
        }
        row.estimate_violations += beyond_estimate ? 1 : 0;
        row.tolerance_misses += beyond_tolerance ? 1 : 0;
      }
      set_statistics(row, errors);
      row.seconds = seconds;
      row.evaluations = evaluations / static_cast<double>(n);
      map.rows.push_back(row);
    }
  }
  return map;
}

const Row& find_row(const Map& map, Integral integral, bool fast, double setting) {
  for (const Row& r : map.rows) {
    if (r.integral == integral && r.fast == fast && r.setting == setting) return r;
  }
  throw std::logic_error("lighting-map: no row for the setting");
}

// ---- Output ---------------------------------------------------------------------------------

std::string csv_text(const Map& map) {
  std::ostringstream s;
  s << "integral,mode,setting,cases,median_relative_error,p95_relative_error,max_relative_error,"
       "seconds_per_integral,mean_integrand_evaluations,estimate_violations,"
       "worst_actual_over_estimate,tolerance_misses,unconverged\n";
  for (const Row& r : map.rows) {
    s << integral_name(r.integral) << ',' << (r.fast ? "fast" : "reference") << ','
      << (r.fast ? r.label : format_number(r.setting)) << ',' << r.cases << ','
      << format_number(r.median) << ',' << format_number(r.p95) << ',' << format_number(r.max)
      << ',' << format_number(r.seconds) << ',' << format_number(r.evaluations) << ','
      << r.estimate_violations << ',' << format_number(r.worst_ratio) << ',' << r.tolerance_misses
      << ',' << r.unconverged << '\n';
  }
  return s.str();
}

// Relative errors below 10⁻¹⁶ are rounding (and a sun far from the lobe gives ~10⁻⁸⁰).
std::string error_text(double e) {
  return e > 0.0 && e < 1e-16 ? std::string("<1e-16") : short_number(e);
}

std::string time_text(double seconds) {
  if (seconds < 1e-3) return short_number(seconds * 1e6, 3) + " µs";
  if (seconds < 1.0) return short_number(seconds * 1e3, 3) + " ms";
  return short_number(seconds, 3) + " s";
}

// The plot: one panel per integral, log-log, x = time per integral, y = relative error (95th
// percentile marked, a bar from the median to the largest), one line per mode, each point
// labelled by its order or tolerance.
std::string svg_text(const Map& map) {
  constexpr double kPanelWidth = 400.0, kPanelHeight = 360.0;
  constexpr double kLeft = 70.0, kRight = 20.0, kTop = 56.0, kBottom = 50.0;
  constexpr double kFloor = 1e-17;  // errors of 0 are drawn here
  double x_lo = HUGE_VAL, x_hi = 0.0, y_lo = HUGE_VAL, y_hi = 0.0;
  for (const Row& r : map.rows) {
    x_lo = std::fmin(x_lo, r.seconds);
    x_hi = std::fmax(x_hi, r.seconds);
    y_lo = std::fmin(y_lo, std::fmax(r.median, kFloor));
    y_hi = std::fmax(y_hi, std::fmax(r.max, kFloor));
  }
  const double ex_lo = std::floor(math::log10(x_lo)), ex_hi = std::ceil(math::log10(x_hi));
  const double ey_lo = std::floor(math::log10(y_lo)),
               ey_hi = std::fmax(std::ceil(math::log10(y_hi)), ey_lo + 1.0);
  const double plot_w = kPanelWidth - kLeft - kRight, plot_h = kPanelHeight - kTop - kBottom;
  const double width = 3.0 * kPanelWidth, height = kPanelHeight + 36.0;
  std::ostringstream s;
  const auto num = [](double v) { return short_number(v, 6); };
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\""
    << num(height) << "\" viewBox=\"0 0 " << num(width) << ' ' << num(height)
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << num(width / 2) << "\" y=\"20\" text-anchor=\"middle\" font-size=\"15\">"
    << "Lighting integrals: relative error vs time per integral (oceanref bench lighting-map)"
    << "</text>\n";
  const char* fast_colour = "#d62728";
  const char* reference_colour = "#1f77b4";
  for (std::size_t p = 0; p < 3; ++p) {
    const Integral integral = kIntegrals[p];
    const double ox = static_cast<double>(p) * kPanelWidth + kLeft, oy = kTop;
    const auto px = [&](double t) {
      return ox + (math::log10(t) - ex_lo) / (ex_hi - ex_lo) * plot_w;
    };
    const auto py = [&](double e) {
      return oy + (ey_hi - math::log10(std::fmax(e, kFloor))) / (ey_hi - ey_lo) * plot_h;
    };
    s << "<g>\n<text x=\"" << num(ox + plot_w / 2) << "\" y=\"" << num(oy - 12)
      << "\" text-anchor=\"middle\" font-size=\"13\">" << integral_title(integral) << "</text>\n"
      << "<rect x=\"" << num(ox) << "\" y=\"" << num(oy) << "\" width=\"" << num(plot_w)
      << "\" height=\"" << num(plot_h) << "\" fill=\"none\" stroke=\"#444\"/>\n";
    for (double e = ex_lo; e <= ex_hi + 0.5; e += 1.0) {
      const double x = ox + (e - ex_lo) / (ex_hi - ex_lo) * plot_w;
      s << "<line x1=\"" << num(x) << "\" y1=\"" << num(oy) << "\" x2=\"" << num(x) << "\" y2=\""
        << num(oy + plot_h) << "\" stroke=\"#ddd\"/>\n<text x=\"" << num(x) << "\" y=\""
        << num(oy + plot_h + 14) << "\" text-anchor=\"middle\">1e" << static_cast<int>(e)
        << "</text>\n";
    }
    const int y_step = ey_hi - ey_lo > 12.0 ? 2 : 1;
    for (double e = ey_lo; e <= ey_hi + 0.5; e += y_step) {
      const double y = oy + (ey_hi - e) / (ey_hi - ey_lo) * plot_h;
      s << "<line x1=\"" << num(ox) << "\" y1=\"" << num(y) << "\" x2=\"" << num(ox + plot_w)
        << "\" y2=\"" << num(y) << "\" stroke=\"#ddd\"/>\n<text x=\"" << num(ox - 4) << "\" y=\""
        << num(y + 4) << "\" text-anchor=\"end\">1e" << static_cast<int>(e) << "</text>\n";
    }
    s << "<text x=\"" << num(ox + plot_w / 2) << "\" y=\"" << num(oy + plot_h + 32)
      << "\" text-anchor=\"middle\">time per integral [s]</text>\n"
      << "<text transform=\"translate(" << num(ox - 48) << ',' << num(oy + plot_h / 2)
      << ") rotate(-90)\" text-anchor=\"middle\">relative error</text>\n";
    // Point labels, placed greedily where they overlap no earlier label of the panel (else
    // left out: the CSV has every point).
    std::vector<std::array<double, 4>> placed;  // x0, y0, x1, y1
    const auto place_label = [&](double x, double y, const std::string& text, bool above) {
      const double w = 5.6 * static_cast<double>(text.size()), h = 10.0;
      const double candidates[][2] = {{5.0, above ? -5.0 : 12.0},
                                      {5.0, above ? 12.0 : -5.0},
                                      {-5.0 - w, above ? -5.0 : 12.0},
                                      {8.0, 3.0},
                                      {-8.0 - w, 3.0}};
      for (const auto& d : candidates) {
        const double x0 = x + d[0], y1 = y + d[1], y0 = y1 - h, x1 = x0 + w;
        bool free = true;
        for (const auto& b : placed) {
          if (x0 < b[2] && b[0] < x1 && y0 < b[3] && b[1] < y1) free = false;
        }
        if (!free) continue;
        placed.push_back({x0, y0, x1, y1});
        return std::optional<std::array<double, 2>>({x0, y1});
      }
      return std::optional<std::array<double, 2>>();
    };
    for (const bool fast : {true, false}) {
      const char* colour = fast ? fast_colour : reference_colour;
      std::ostringstream line;
      for (const Row& r : map.rows) {
        if (r.integral != integral || r.fast != fast) continue;
        const double x = px(r.seconds);
        line << (line.tellp() > 0 ? " " : "") << num(x) << ',' << num(py(r.p95));
        s << "<line x1=\"" << num(x) << "\" y1=\"" << num(py(r.median)) << "\" x2=\"" << num(x)
          << "\" y2=\"" << num(py(r.max)) << "\" stroke=\"" << colour
          << "\" stroke-opacity=\"0.45\" stroke-width=\"3\"/>\n"
          << "<circle cx=\"" << num(x) << "\" cy=\"" << num(py(r.p95)) << "\" r=\"3\" fill=\""
          << colour << "\"/>\n";
        if (const auto at = place_label(x, py(r.p95), r.label, fast)) {
          s << "<text x=\"" << num((*at)[0]) << "\" y=\"" << num((*at)[1])
            << "\" font-size=\"9\" fill=\"" << colour << "\">" << r.label << "</text>\n";
        }
      }
      s << "<polyline points=\"" << line.str() << "\" fill=\"none\" stroke=\"" << colour
        << "\" stroke-width=\"1.5\"" << (fast ? " stroke-dasharray=\"5,3\"" : "") << "/>\n";
    }
    s << "</g>\n";
  }
  // Legend: two lines under the panels.
  const double ly = kPanelHeight + 8.0;
  s << "<line x1=\"" << num(kLeft) << "\" y1=\"" << num(ly) << "\" x2=\"" << num(kLeft + 30)
    << "\" y2=\"" << num(ly) << "\" stroke=\"" << fast_colour
    << "\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"/>\n<text x=\"" << num(kLeft + 36)
    << "\" y=\"" << num(ly + 4)
    << "\">fast: fixed-order rule (labels: nodes per axis; sun: radius x azimuth nodes, point = "
       "order 0)</text>\n<line x1=\""
    << num(kLeft + 3.0 * kPanelWidth / 2.0) << "\" y1=\"" << num(ly) << "\" x2=\""
    << num(kLeft + 3.0 * kPanelWidth / 2.0 + 30) << "\" y2=\"" << num(ly) << "\" stroke=\""
    << reference_colour << "\" stroke-width=\"1.5\"/>\n<text x=\""
    << num(kLeft + 3.0 * kPanelWidth / 2.0 + 36) << "\" y=\"" << num(ly + 4)
    << "\">reference: adaptive (labels: relative tolerance)</text>\n<text x=\"" << num(kLeft)
    << "\" y=\"" << num(ly + 20)
    << "\">Dot: 95th percentile of the relative error over the sweep; bar: median to largest; "
       "errors of 0 drawn at 1e-17. Data: lighting_accuracy_map.csv.</text>\n";
  s << "</svg>\n";
  return s.str();
}

void print_markdown(std::ostream& out, const Map& map) {
  const SweepSpec& spec = map.spec;
  const ShadingSettings defaults;
  out << "Sweep: v_n = V·N ∈ {";
  for (std::size_t i = 0; i < spec.cos_view.size(); ++i)
    out << (i ? ", " : "") << short_number(spec.cos_view[i], 3);
  out << "} × azimuth from the sun's side ∈ {";
  for (std::size_t i = 0; i < spec.azimuths_deg.size(); ++i)
    out << (i ? ", " : "") << short_number(spec.azimuths_deg[i], 3) << "°";
  out << "} × σ² (upwind/crosswind) ∈ {";
  for (std::size_t i = 0; i < spec.roughness.size(); ++i) {
    const SlopeVariance& s = spec.roughness[i];
    out << (i ? ", " : "") << short_number(s.upwind, 2);
    if (s.crosswind != s.upwind) out << '/' << short_number(s.crosswind, 2);
  }
  out << "} × normal ∈ {flat" << (spec.tilted.size() > 1 ? ", tilted 30°" : "")
      << "} × sun zenith ∈ {";
  for (std::size_t i = 0; i < spec.suns.size(); ++i)
    out << (i ? ", " : "") << short_number(spec.suns[i].second, 3) << "°";
  out << "}: " << map.lit_cases << " cases for the reflected sky and the sun disk, "
      << map.fresnel_cases << " for F̄ (independent of the sun). Truth: the reference at tolerance "
      << short_number(kTruthTolerance, 1) << " (" << time_text(map.truth_seconds) << " on "
      << map.threads << " threads; unconverged: " << map.truth_unconverged[0] << " / "
      << map.truth_unconverged[1] << " / " << map.truth_unconverged[2]
      << "; mean integrand evaluations: " << short_number(map.truth_evaluations[0], 3) << " / "
      << short_number(map.truth_evaluations[1], 3) << " / "
      << short_number(map.truth_evaluations[2], 3)
      << " for sky / F̄ / sun). Times: one thread, wall clock, mean per integral.\n\n";
  for (const Integral integral : kIntegrals) {
    out << "**" << integral_title(integral) << "** ("
        << (integral == Integral::sky ? "largest channel, relative to max(|L|, 10⁻³·E_sky/π)"
            : integral == Integral::fresnel
                ? "relative to 1 − F̄"
                : "the reflectance ∫f cos θ dω, relative to max(value, 10⁻³·E_sky/(π·L_sun))")
        << ")\n\n"
        << "| mode | setting | median | 95% | max | time per integral | integrand evaluations | "
           "estimate violations (worst actual/estimate) | tolerance misses |\n"
           "|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : map.rows) {
      if (r.integral != integral) continue;
      const bool is_default =
          r.fast ? static_cast<int>(r.setting) ==
                       (integral == Integral::sun ? defaults.sun_order : defaults.sky_order)
                 : r.setting == defaults.tolerance;
      out << "| " << (r.fast ? "fast" : "reference") << " | "
          << (r.fast ? (integral == Integral::sun
                            ? "order " + std::to_string(static_cast<int>(r.setting))
                            : "order " + r.label)
                     : "tol " + r.label)
          << (is_default ? " (default)" : "") << " | " << error_text(r.median) << " | "
          << error_text(r.p95) << " | " << error_text(r.max) << " | " << time_text(r.seconds)
          << " | "
          << (r.fast ? std::to_string(static_cast<long>(
                           integral == Integral::sun
                               ? (r.setting == 0.0 ? 1.0 : 4.0 * r.setting * r.setting)
                               : r.setting * r.setting))
                     : short_number(r.evaluations, 3))
          << " | "
          << (r.fast ? std::string("–")
                     : std::to_string(r.estimate_violations) + "/" + std::to_string(r.cases) +
                           " (" + short_number(r.worst_ratio) + ")")
          << " | "
          << (r.fast ? std::string("–")
                     : std::to_string(r.tolerance_misses) + "/" + std::to_string(r.cases))
          << " |\n";
    }
    out << '\n';
  }
  // The cost of the reference against the fast defaults, per integral and for a sea sample.
  const bool has_defaults = [&] {
    for (const Integral i : kIntegrals) {
      const int order = i == Integral::sun ? defaults.sun_order : defaults.sky_order;
      bool fast = false, reference = false;
      for (const Row& r : map.rows) {
        if (r.integral != i) continue;
        fast = fast || (r.fast && static_cast<int>(r.setting) == order);
        reference = reference || (!r.fast && r.setting == defaults.tolerance);
      }
      if (!fast || !reference) return false;
    }
    return true;
  }();
  if (!has_defaults) return;
  out << "**Cost and error: reference at tolerance " << short_number(defaults.tolerance, 1)
      << " vs fast at the default orders (sky_order " << defaults.sky_order << ", sun_order "
      << defaults.sun_order << ")**\n\n"
      << "| integral | fast time | reference time | time ratio reference/fast | fast 95% / max "
         "error | reference 95% / max error |\n|---|---|---|---|---|---|\n";
  double fast_total = 0.0, reference_total = 0.0;
  for (const Integral i : kIntegrals) {
    const Row& f =
        find_row(map, i, true, i == Integral::sun ? defaults.sun_order : defaults.sky_order);
    const Row& r = find_row(map, i, false, defaults.tolerance);
    fast_total += f.seconds;
    reference_total += r.seconds;
    out << "| " << integral_title(i) << " | " << time_text(f.seconds) << " | "
        << time_text(r.seconds) << " | " << short_number(r.seconds / f.seconds, 3) << " | "
        << error_text(f.p95) << " / " << error_text(f.max) << " | " << error_text(r.p95) << " / "
        << error_text(r.max) << " |\n";
  }
  out << "| all three (one sea sample) | " << time_text(fast_total) << " | "
      << time_text(reference_total) << " | " << short_number(reference_total / fast_total, 3)
      << " | | |\n\n";
  int violations = 0, misses = 0, cases = 0;
  double worst = 0.0;
  for (const Row& r : map.rows) {
    if (r.fast) continue;
    violations += r.estimate_violations;
    misses += r.tolerance_misses;
    cases += static_cast<int>(r.cases);
    worst = std::fmax(worst, r.worst_ratio);
  }
  out << "Reference error estimates below the actual error (against the truth, allowing the "
         "truth's own estimate; every tolerance and integral): "
      << violations << " of " << cases << ", the worst actual/estimate " << short_number(worst)
      << "; actual error above the tolerance: " << misses << " of " << cases << ".\n";
}

}  // namespace

LightingSweepSpec lighting_map_sweep(bool quick) {
  return quick ? quick_sweep() : full_sweep();
}

LightingMap measure_lighting_map(const LightingSweepSpec& spec, int threads) {
  return measure(make_lighting_sweep(spec), spec, threads);
}

std::string lighting_map_csv(const LightingMap& map) {
  return csv_text(map);
}

std::string lighting_map_svg(const LightingMap& map) {
  return svg_text(map);
}

std::string lighting_map_markdown(const LightingMap& map) {
  std::ostringstream out;
  print_markdown(out, map);
  return out.str();
}

LightingPixelErrors lighting_pixel_errors(const ExrImage& fast, const ExrImage& ref) {
  if (fast.width != ref.width || fast.height != ref.height) {
    throw LightingPixelsInputError(true, "the images differ in size");
  }
  const auto channel = [](const ExrImage& image, const std::string& name,
                          bool is_reference) -> const std::vector<float>& {
    for (const ExrChannel& c : image.channels) {
      if (c.name == name && c.sampling == 1) return c.values;
    }
    throw LightingPixelsInputError(is_reference, "no channel '" + name + "' (render with --aov)");
  };
  const std::vector<float>& coverage = channel(fast, "coverage", false);
  const char* names[] = {"R", "G", "B"};
  std::vector<const std::vector<float>*> f, r, e;
  for (const char* n : names) {
    f.push_back(&channel(fast, n, false));
    r.push_back(&channel(ref, n, true));
    e.push_back(&channel(fast, std::string("lighting_error.") + n, false));
  }
  std::vector<double> difference, layer;
  for (std::size_t i = 0; i < coverage.size(); ++i) {
    if (!(coverage[i] > 0.0f)) continue;
    double d = 0.0, l = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double reference_value = std::fabs(static_cast<double>((*r[c])[i]));
      const double delta =
          std::fabs(static_cast<double>((*f[c])[i]) - static_cast<double>((*r[c])[i]));
      const double estimate = static_cast<double>((*e[c])[i]);
      d = std::fmax(
          d, reference_value > 0.0 ? delta / reference_value : (delta > 0.0 ? HUGE_VAL : 0.0));
      l = std::fmax(l, reference_value > 0.0 ? estimate / reference_value
                                             : (estimate > 0.0 ? HUGE_VAL : 0.0));
    }
    difference.push_back(d);
    layer.push_back(l);
  }
  LightingPixelErrors result;
  result.pixels = coverage.size();
  result.sea_pixels = difference.size();
  for (auto [v, stats] :
       {std::pair{&difference, &result.difference}, std::pair{&layer, &result.layer}}) {
    if (v->empty()) continue;
    Row row;
    set_statistics(row, *v);
    *stats = {row.median, row.p95, row.max};
  }
  return result;
}

std::string lighting_pixels_csv(const LightingPixelErrors& e) {
  std::ostringstream out;
  out << "sea_pixels,pixels,median,p95,max,layer_median,layer_p95,layer_max\n"
      << e.sea_pixels << ',' << e.pixels;
  for (const LightingPixelErrors::Statistics* s : {&e.difference, &e.layer}) {
    if (e.sea_pixels == 0) {
      out << ",0,0,0";
      continue;
    }
    out << ',' << format_number(s->median) << ',' << format_number(s->p95) << ','
        << format_number(s->max);
  }
  out << '\n';
  return out.str();
}

}  // namespace oceanref
