#include "cli/render_command.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <ostream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cli/text.h"
#include "conformance/render_output.h"
#include "conformance/sequence.h"
#include "io/exr.h"
#include "io/output_file.h"
#include "scene/scene.h"

namespace oceanref::cli {

namespace {
// --spp (already checked in [1, kMaxSamplesPerAxis²] by its option): a square number; its square
// root (0 when not given).
int samples_per_axis(int spp) {
  if (spp == 0) return 0;
  const int axis = static_cast<int>(std::lround(std::sqrt(static_cast<double>(spp))));
  if (axis * axis != spp) {
    throw UsageError("--spp", "must be a square number in [1, " +
                                  std::to_string(kMaxSamplesPerAxis * kMaxSamplesPerAxis) +
                                  "], got " + std::to_string(spp));
  }
  return axis;
}

// `--set KEY=VALUE` (repeatable) of the commands that read a scene file (apply_scene_override).
void add_set_option(CLI::App& cmd, std::vector<std::string>& overrides) {
  cmd.add_option("--set", overrides,
                 "KEY=VALUE: override the scene file's key KEY (its JSON path, e.g. "
                 "shading.accuracy=fast, render.width=320); VALUE is JSON or a bare word, null "
                 "removes the key; validated as in the file and recorded in the outputs' scene; "
                 "repeatable, applied in order")
      ->allow_extra_args(false);
}

void log_progress(const std::string& message) {
  progress("oceanref", message);
}

// --tile I/N: tile I of N (0 <= I < N), {0, 1} when not given.
std::pair<int, int> parse_tile(const std::string& text) {
  if (text.empty()) return {0, 1};
  const auto refuse = [&] {
    return UsageError("--tile",
                      "expected I/N with integers 0 <= I < N <= " + std::to_string(kMaxExrSide) +
                          ", got '" + escape_value(text) + "'");
  };
  // Digits only (no sign, no space), within [lo, hi].
  const auto integer = [&](const std::string& part, int lo, int hi) {
    if (part.empty() || part.size() > 9 ||
        part.find_first_not_of("0123456789") != std::string::npos) {
      throw refuse();
    }
    const int v = std::stoi(part);
    if (v < lo || v > hi) throw refuse();
    return v;
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) throw refuse();
  const int n = integer(text.substr(slash + 1), 1, kMaxExrSide);
  const int i = integer(text.substr(0, slash), 0, n - 1);
  return {i, n};
}

// What render and merge print (the same lines for the same image).
void print_report(std::ostream& out, const RenderReport& r, const Scene& scene,
                  const RenderOutputOptions& options) {
  out << "pixel_sha256," << r.pixel_sha256 << '\n';
  out << "radiance_f64_sha256," << r.radiance_f64_sha256 << '\n';
  const LightingErrorSummary& e = r.lighting_error;
  if (e.estimated) {
    out << "lighting_error_max_relative," << format_number(e.max_relative) << '\n';
    out << "lighting_error_median_relative," << format_number(e.median_relative) << '\n';
  }
  const PixelErrorSummary& pe = r.pixel_error;
  if (pe.estimated) {
    out << "pixel_error_p50_relative," << format_number(pe.p50_relative) << '\n';
    out << "pixel_error_p99_relative," << format_number(pe.p99_relative) << '\n';
    out << "pixel_error_max_relative," << format_number(pe.max_relative) << '\n';
  }
  if (pe.adaptive) {
    out << "pixel_samples_mean," << format_number(pe.mean_samples) << '\n';
    out << "pixel_samples_max," << format_number(pe.max_samples) << '\n';
    out << "capped_pixels," << pe.capped_pixels << '\n';
  }
  if (scene.image.mastin_antialiasing > 0.0) {
    out << "antialiased_pixels," << pe.antialiased_pixels << '\n';
  }
  if (two_level_lighting(scene)) out << "corrected_samples," << r.corrected_samples << '\n';
  out << "unconverged_samples," << r.unconverged_samples << '\n';
  out << "integrand_evaluations," << r.integrand_evaluations << '\n';
  out << "memory_estimate_bytes," << format_number(render_memory_estimate(scene, options).total())
      << '\n';
  if (r.unconverged_samples > 0) {
    warn("oceanref", std::to_string(r.unconverged_samples) +
                         " samples missed the lighting tolerance (their error estimates "
                         "are in --aov lighting_error)");
  }
  if (pe.capped_pixels > 0) {
    warn("oceanref", std::to_string(pe.capped_pixels) +
                         " pixels reached render.max_samples_per_pixel above "
                         "render.pixel_tolerance (their error estimates are in --aov "
                         "pixel_error, their samples in --aov samples)");
  }
}

// A Gerstner ocean's loops (gerstner_loop_check): the bound, and where it is ≥ 1 what a lattice
// below the camera shows, with a warning when the surface folds there.
void print_gerstner_loops(std::ostream& out, const Scene& scene) {
  const GerstnerLoopCheck c = gerstner_loop_check(scene, realize_ocean(scene.waves, 1));
  out << "gerstner_steepness_bound," << format_number(c.steepness_bound) << '\n';
  if (!c.sampled) return;
  out << "gerstner_min_jacobian," << format_number(c.loops.min_jacobian) << '\n';
  out << "gerstner_folded_fraction," << format_number(c.loops.folded_fraction) << '\n';
  if (c.loops.folded_fraction > 0.0) {  // some lattice point has det J < 0
    warn("oceanref",
         "the Gerstner waves loop (|u| sum k A = " + format_number(c.steepness_bound) +
             " >= 1): det J < 0 on " + format_number(100.0 * c.loops.folded_fraction) + "% of a " +
             format_number(c.extent) + " m square below the camera (lowest " +
             format_number(c.loops.min_jacobian) + " at x = " + format_number(c.loops.min_x) +
             ", z = " + format_number(c.loops.min_z) + "); lower waves.choppiness");
  }
}

// A render's progress on stderr with the time left, extrapolated from the share done so far: the
// renderer takes the rows in spread order (spread_order), so any share done is a sample of the
// work, sky and sea alike. On a terminal a bar; elsewhere a line every kProgressLineSeconds. A
// render estimated at kProgressLineSeconds or more prints its estimated total once its first
// kProgressEstimateShare of rows are done (the first row alone, sky at the top, says nothing);
// times count from the first call (the renderer's share 0, when its rows start: the frame's
// preparation is not their cost). Called from worker threads: written under a lock.
std::function<void(double)> progress_reporter() {
  struct State {
    std::mutex mutex;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    double shown = 0.0;  // rows finish out of order: the share never goes back
    double last_line = 0.0;
    bool started = false;
    bool estimated = false;
    bool terminal = isatty(STDERR_FILENO) != 0;
  };
  auto state = std::make_shared<State>();
  return [state](double share) {
    const std::lock_guard lock(state->mutex);
    if (!state->started) {
      state->started = true;
      state->start = std::chrono::steady_clock::now();
    }
    if (share < state->shown) return;
    state->shown = share;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - state->start).count();
    if (!state->estimated && share >= kProgressEstimateShare && share < 1.0) {
      state->estimated = true;
      if (elapsed / share >= kProgressLineSeconds) {
        std::cerr << (state->terminal ? "\r" : "")
                  << "oceanref: " << progress_estimate_text(share, elapsed) << '\n';
      }
    }
    if (state->terminal) {
      std::cerr << progress_bar_text(share, elapsed) << std::flush;
    } else if (elapsed - state->last_line >= kProgressLineSeconds) {
      state->last_line = elapsed;
      std::cerr << "oceanref: " << progress_line_text(share, elapsed) << '\n';
    }
  };
}
}  // namespace

// --frames A:B (or K): the first and last frame, 0 <= A <= B <= kMaxFrame.
std::pair<int, int> parse_frames(const std::string& text) {
  const auto refuse = [&] {
    return UsageError("--frames", "expected A:B (or K) with integers 0 <= A <= B <= " +
                                      std::to_string(kMaxFrame) + ", got '" + escape_value(text) +
                                      "'");
  };
  const auto integer = [&](const std::string& part) {
    if (part.empty() || part.size() > 7 ||
        part.find_first_not_of("0123456789") != std::string::npos) {
      throw refuse();
    }
    const int v = std::stoi(part);
    if (v > kMaxFrame) throw refuse();
    return v;
  };
  const std::size_t colon = text.find(':');
  const int first = integer(text.substr(0, colon));
  const int last = colon == std::string::npos ? first : integer(text.substr(colon + 1));
  if (last < first) throw refuse();
  return {first, last};
}

// The folders of PATH hold an executable `name`.
bool on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::string folders = path;
  for (std::size_t start = 0; start <= folders.size();) {
    const std::size_t end = std::min(folders.find(':', start), folders.size());
    const std::string file = folders.substr(start, end - start) + "/" + name;
    if (end > start && access(file.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

// `render --frames`: each frame k of [first, last] to the --output (and --png) pattern, its
// report lines after a line "frame,k"; progress with the time left over the frames.
void render_sequence(std::ostream& out, const Scene& scene, const RenderOutputOptions& base,
                     const std::string& output, const std::string& png, std::pair<int, int> frames,
                     double fps, const std::vector<std::string>& inputs) {
  const auto [first, last] = frames;
  const std::vector<SequenceFrame> adaptation =
      adaptation_through(scene, last, fps, base.threads, base.log);
  const auto start = std::chrono::steady_clock::now();
  for (int k = first; k <= last; ++k) {
    const int done = k - first, count = last - first + 1;
    std::string eta;
    if (done > 0) {
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      eta = ", about " + std::to_string(std::lround(elapsed / done * (count - done))) + " s left";
    }
    log_progress("frame " + std::to_string(k) + " (" + std::to_string(done + 1) + " of " +
                 std::to_string(count) + ", t = " +
                 format_number(adaptation[static_cast<std::size_t>(k)].time) + " s" + eta + ")");
    RenderOutputOptions options = base;
    options.frame = adaptation[static_cast<std::size_t>(k)];
    if (base.progress) options.progress = progress_reporter();  // per frame
    const std::string exr = frame_path(output, k);
    const std::string preview = png.empty() ? std::string() : frame_path(png, k);
    check_output_paths({{"--output", exr}, {"--png", preview}}, inputs);
    const Scene s = frame_scene(scene, k, fps);
    out << "frame," << k << '\n';
    print_report(out, render_scene_to_files(s, options, exr, preview), s, options);
  }
}

// Runs `argv` (argv[0] looked up on PATH) without a shell, so that no character of a path or
// an option is interpreted: whether it started and exited with status 0.
bool run_program(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0) return false;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return false;
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// `render --video`: the previews of frames [first, last] assembled by ffmpeg into `video`,
// written under a temporary name and renamed (no partial file).
void assemble_video(const std::string& png, std::pair<int, int> frames, double fps,
                    const std::string& video) {
  const std::filesystem::path target(video);
  const std::filesystem::path temporary =
      target.parent_path() /
      (".oceanref-" + target.stem().string() + ".partial" + target.extension().string());
  const std::vector<std::string> command{"ffmpeg",
                                         "-y",
                                         "-loglevel",
                                         "error",
                                         "-framerate",
                                         format_number(fps),
                                         "-start_number",
                                         std::to_string(frames.first),
                                         "-i",
                                         ffmpeg_pattern(png),
                                         "-frames:v",
                                         std::to_string(frames.second - frames.first + 1),
                                         "-c:v",
                                         "libx264",
                                         "-pix_fmt",
                                         "yuv420p",
                                         "-vf",
                                         "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                         temporary.string()};
  log_progress("assembling " + video + " with ffmpeg");
  if (!run_program(command)) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    std::string words;
    for (const std::string& a : command) words += (words.empty() ? "" : " ") + a;
    throw std::runtime_error("ffmpeg failed to assemble " + video + " (command: " + words + ")");
  }
  std::filesystem::rename(temporary, target);
}

std::function<void(std::ostream&)> add_render_command(CLI::App& app) {
  struct Flags {
    std::string scene, output, png, max_memory, tile, samples, renderer, frames, video;
    double fps = 0.0;
    int threads = 0;
    int spp = 0;
    bool aov = false;
    bool lighting_error = false;
    std::vector<std::string> overrides;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a scene to a linear EXR (cd/m^2 per linear sRGB channel), bit-identical "
      "for any thread count; optional tone-mapped PNG preview.");
  cmd->add_option("SCENE", f->scene, "scene file (JSON)")->required();
  cmd->add_option("-o,--output", f->output, "OUT.exr")->required();
  cmd->add_option("--png", f->png, "PREVIEW.png: Reinhard 2002 tone mapping, sRGB transfer");
  cmd->add_option("--threads", f->threads, "worker threads (default: all cores)")
      ->check(integer_in(0, 1024, " (0: all cores)"));
  cmd->add_option("--spp", f->spp, "samples per pixel, a square number (overrides the scene)")
      ->check(integer_in(1, kMaxSamplesPerAxis * kMaxSamplesPerAxis, " (a square number)"));
  add_set_option(*cmd, f->overrides);
  cmd->add_flag(
      "--aov", f->aov,
      "also write the layers depth, coverage, normal.RGB (= x, y, z), x0.RGB (= x0, 0, z0), "
      "sun.RGB, sky.RGB, sea.RGB, foam.RGB, lighting_error.RGB (the estimated absolute error of "
      "the lighting per channel; 0 for shading.accuracy fast without --lighting-error; with "
      "render.pixel_tolerance at reference accuracy the bound of the two-level correction), "
      "pixel_error.RGB (the estimated absolute error of each pixel as the pixel integral: 3 "
      "standard errors of its samples' mean; 0 at 1 spp) and, with render.pixel_tolerance, "
      "samples (the samples behind each pixel)");
  cmd->add_flag("--lighting-error", f->lighting_error,
                "shading.accuracy fast: also compute the reference lighting of every sample, so "
                "that the report and lighting_error give the fast mode's error (|fast - "
                "reference| + the reference's estimate; costs a reference render)");
  cmd->add_option("--samples", f->samples,
                  "SAMPLES.exr: also every sample's R, G, B, at S times the image's resolution "
                  "(sample (c, r) at image position ((c + 0.5)/S, (r + 0.5)/S); a pixel is the "
                  "mean of its S x S samples): the fixed grid for a backend that replicates it "
                  "(README, 'Same samples or converged'); not with render.pixel_tolerance or "
                  "--tile");
  cmd->add_option("--renderer", f->renderer,
                  "raster (the scanline rasterizer), raytrace (Mastin's height-field ray tracer "
                  "on the same displaced grid: the second renderer, to check the first's "
                  "visibility, and one that reflects the scene's objects in the sea) or "
                  "raytrace_surface (the ray tracer against the continuous surface the grid "
                  "samples, to render.surface_tolerance: ground-truth visibility, slower; also "
                  "reflects objects); README, 'Two renderers'; default: the scene's "
                  "render.renderer (raster); not with --tile");
  cmd->add_option("--max-memory", f->max_memory, kMaxMemoryHelp);
  cmd->add_option("--frames", f->frames,
                  "A:B (or K): render frames A to B of an animated sequence, frame k at the "
                  "scene's time + k/fps, each to --output (and --png) with the last run of '#' "
                  "replaced by k (ocean_####.exr); every frame is the same bytes as the frame "
                  "rendered alone (foam and the preview's temporal adaptation are replayed from "
                  "frame 0: README, 'Sequences'); 0 <= A <= B <= " +
                      std::to_string(kMaxFrame));
  cmd->add_option("--fps", f->fps, "frames per second of --frames (default 30)")
      ->check(CLI::Range(1e-3, kMaxFrameRate));
  cmd->add_option("--video", f->video,
                  "OUT.mp4: with --frames and --png, also assemble the previews into an H.264 "
                  "video with ffmpeg (which must be installed: Debian package ffmpeg)");
  cmd->add_option("--tile", f->tile,
                  "I/N: render only tile I of N (pixel rows I*H/N to (I+1)*H/N - 1, 0 <= I < N "
                  "<= H) and write it to --output as a render piece, for `oceanref merge` "
                  "(docs/DISTRIBUTED.md); not with --png");
  return [f](std::ostream& out) {
    check_output_paths({{"--output", f->output}, {"--png", f->png}, {"--samples", f->samples}},
                       {f->scene});
    RenderOutputOptions options;
    options.threads = resolve_threads(f->threads);
    options.max_memory = max_memory_flag(f->max_memory);
    std::tie(options.tile, options.tiles) = parse_tile(f->tile);
    if (!f->tile.empty() && !f->png.empty()) {
      throw UsageError("--png", "not with --tile (merge the pieces, then ask merge for --png)");
    }
    if (!f->renderer.empty()) {
      options.renderer = parse_choice<UsageError>(kRenderers, "--renderer", f->renderer);
    }
    if (!f->tile.empty() && options.renderer && *options.renderer != Renderer::raster) {
      throw UsageError("--renderer", "not with --tile (the pieces are rasterized)");
    }
    if (!f->tile.empty() && !f->samples.empty()) {
      throw UsageError("--samples", "not with --tile (render the whole image)");
    }
    if (f->frames.empty()) {
      if (f->fps != 0.0) throw UsageError("--fps", "only with --frames");
      if (!f->video.empty()) throw UsageError("--video", "only with --frames");
    } else {
      for (const auto& [flag, given] :
           {std::pair{"--tile", !f->tile.empty()}, std::pair{"--samples", !f->samples.empty()}}) {
        if (given) throw UsageError(flag, "not with --frames");
      }
      for (const auto& [flag, path] :
           {std::pair{"--output", f->output}, std::pair{"--png", f->png}}) {
        if (!path.empty() && path.find('#') == std::string::npos) {
          throw UsageError(flag,
                           "with --frames, a pattern with a run of '#' for the frame number "
                           "(e.g. ocean_####.exr), got '" +
                               escape_value(path) + "'");
        }
      }
      if (!f->video.empty() && f->png.empty()) {
        throw UsageError("--video", "assembles the previews: give --png too");
      }
      if (!f->video.empty() && !on_path("ffmpeg")) {
        throw UsageError("--video", "needs ffmpeg on PATH (Debian: apt-get install ffmpeg)");
      }
    }
    const std::pair<int, int> frames =
        f->frames.empty() ? std::pair{0, 0} : parse_frames(f->frames);
    const Scene scene = load_scene(f->scene, f->overrides, &std::cerr);
    if (options.tiles > scene.image.height) {
      throw UsageError("--tile", "N must be <= the image's " + std::to_string(scene.image.height) +
                                     " rows, got " + std::to_string(options.tiles));
    }
    options.samples_per_axis = samples_per_axis(f->spp);
    options.aov = f->aov;
    if (f->lighting_error && two_level_lighting(scene)) {
      throw UsageError("--lighting-error",
                       "measures the fast rules' error at every sample; with shading.accuracy "
                       "reference and render.pixel_tolerance the lighting_error layer is already "
                       "the two-level estimate's bound (README, 'One error budget per pixel')");
    }
    options.fast_lighting_error = f->lighting_error;
    options.log = log_progress;
    options.progress = progress_reporter();
    if (!f->tile.empty()) {
      const RenderPiece piece = render_scene_piece(scene, options);
      progress("oceanref", "writing " + f->output);
      write_render_piece(f->output, piece);
      out << "tile," << piece.tile << '/' << piece.tiles << '\n';
      out << "rows," << piece.band.first_row << ',' << piece.band.first_row + piece.band.height
          << '\n';
      if (piece.adaptive) out << "capped_pixels," << piece.band.capped_pixels << '\n';
      out << "unconverged_samples," << piece.band.unconverged_samples << '\n';
      out << "integrand_evaluations," << piece.band.integrand_evaluations << '\n';
      return;
    }
    if (!f->samples.empty() && scene.image.pixel_tolerance > 0.0) {
      throw UsageError("--samples",
                       "the fixed grid's samples only: not with render.pixel_tolerance (adaptive "
                       "sampling)");
    }
    options.streamed = true;
    if (!f->frames.empty()) {
      const double fps = f->fps == 0.0 ? 30.0 : f->fps;
      render_sequence(out, scene, options, f->output, f->png, frames, fps, {f->scene});
      if (!f->video.empty()) assemble_video(f->png, frames, fps, f->video);
      return;
    }
    options.keep_samples = !f->samples.empty();
    print_report(out, render_scene_to_files(scene, options, f->output, f->png, f->samples), scene,
                 options);
    if (scene.waves.model == WaveModel::gerstner) print_gerstner_loops(out, scene);
  };
}

std::function<void(std::ostream&)> add_merge_command(CLI::App& app) {
  struct Flags {
    std::string scene, output, png;
    std::vector<std::string> pieces, overrides;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Merge the render pieces of `oceanref render --tile I/N` (every tile once, each from this "
      "scene) into the EXR, preview and report one `oceanref render` would write: the same "
      "bytes.");
  cmd->add_option("SCENE", f->scene, "scene file (JSON) the pieces were rendered from")->required();
  cmd->add_option("PIECES", f->pieces, "the N render pieces, in any order")->required();
  cmd->add_option("-o,--output", f->output, "OUT.exr")->required();
  cmd->add_option("--png", f->png, "PREVIEW.png: Reinhard 2002 tone mapping, sRGB transfer");
  add_set_option(*cmd, f->overrides);
  return [f](std::ostream& out) {
    std::vector<std::string> inputs = f->pieces;
    inputs.push_back(f->scene);
    check_output_paths({{"--output", f->output}, {"--png", f->png}}, inputs);
    Scene scene = load_scene(f->scene, f->overrides, &std::cerr);
    std::vector<RenderPiece> pieces;
    for (const std::string& path : f->pieces) {
      progress("oceanref", "reading " + path);
      pieces.push_back(read_render_piece(path));
    }
    RenderOutputOptions options;  // as render had them: the report's memory estimate
    options.samples_per_axis = pieces.front().samples_per_axis;
    options.aov = pieces.front().layers;
    options.streamed = true;
    scene.image.samples_per_axis = options.samples_per_axis;
    const RenderedScene r =
        scene_output(scene, merge_render_pieces(scene, pieces, f->pieces), options.aov);
    progress("oceanref", "writing " + f->output);
    write_exr(f->output, r.exr);
    if (!f->png.empty()) write_preview_png(f->png, r.image, r.settings);
    print_report(out, report_of(r), scene, options);
  };
}

std::function<void(std::ostream&)> add_probe_command(CLI::App& app) {
  struct Flags {
    std::string scene, pixel;
    int threads = 0;
    std::vector<std::string> overrides;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "probe",
      "Every intermediate value behind one pixel: per sample the triangle hit, x0, the "
      "displaced position, fields, normal, F_mean, each lighting term and its estimated error "
      "(reference accuracy: the integrator's estimate; fast: |fast - reference| + that "
      "estimate); then the pixel.");
  cmd->add_option("SCENE", f->scene, "scene file (JSON)")->required();
  cmd->add_option("--pixel", f->pixel, "x,y (column, row from the top-left)")->required();
  cmd->add_option("--threads", f->threads, "worker threads (default: all cores)")
      ->check(integer_in(0, 1024, " (0: all cores)"));
  add_set_option(*cmd, f->overrides);
  return [f](std::ostream& out) {
    const int threads = resolve_threads(f->threads);
    const std::vector<double> xy = parse_number_list("--pixel", f->pixel);
    const auto p =
        prepare_render(load_scene(f->scene, f->overrides, &std::cerr), threads, 0, log_progress);
    p->job.estimate_fast_error = true;  // probe prints each term's error in either mode
    if (xy.size() != 2 || xy[0] < 0 || xy[1] < 0 || xy[0] >= p->scene.image.width ||
        xy[1] >= p->scene.image.height || xy[0] != std::floor(xy[0]) ||
        xy[1] != std::floor(xy[1])) {
      throw UsageError("--pixel", "expected integer x,y inside the " +
                                      std::to_string(p->scene.image.width) + "x" +
                                      std::to_string(p->scene.image.height) + " image, got '" +
                                      escape_value(f->pixel) + "'");
    }
    const std::vector<SampleProbe> samples =
        probe_pixel(p->job, p->unresolved, static_cast<int>(xy[0]), static_cast<int>(xy[1]));
    out << "sample,image_x,image_y,hit,depth,triangle,x0,z0,x,y,z,height,slope_x,slope_z,jacobian,"
           "normal_x,"
           "normal_y,normal_z,view_x,view_y,view_z,sigma2_upwind,sigma2_crosswind,F_mean,"
           "sun_R,sun_G,sun_B,sky_R,sky_G,sky_B,sea_R,sea_G,sea_B,foam_coverage,R,G,B,F_mean_error,"
           "sun_error_R,sun_error_G,sun_error_B,sky_error_R,sky_error_G,sky_error_B,sea_error_R,"
           "sea_error_G,sea_error_B,error_R,error_G,error_B,evaluations,converged,object,"
           "reflects_object\n";
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const SampleProbe& s = samples[i];
      const double values[] = {s.depth,
                               static_cast<double>(s.triangle),
                               s.x0.x,
                               s.x0.y,
                               s.position.x,
                               s.position.y,
                               s.position.z,
                               s.fields.height,
                               s.fields.slope_x,
                               s.fields.slope_z,
                               s.fields.jacobian,
                               s.normal[0],
                               s.normal[1],
                               s.normal[2],
                               s.view[0],
                               s.view[1],
                               s.view[2],
                               p->unresolved.upwind,
                               p->unresolved.crosswind,
                               s.lighting.mean_fresnel,
                               s.lighting.sun[0],
                               s.lighting.sun[1],
                               s.lighting.sun[2],
                               s.lighting.sky[0],
                               s.lighting.sky[1],
                               s.lighting.sky[2],
                               s.lighting.sea[0],
                               s.lighting.sea[1],
                               s.lighting.sea[2],
                               s.whitecap_coverage,
                               s.radiance[0],
                               s.radiance[1],
                               s.radiance[2],
                               s.lighting.mean_fresnel_error,
                               s.lighting.sun_error[0],
                               s.lighting.sun_error[1],
                               s.lighting.sun_error[2],
                               s.lighting.sky_error[0],
                               s.lighting.sky_error[1],
                               s.lighting.sky_error[2],
                               s.lighting.sea_error[0],
                               s.lighting.sea_error[1],
                               s.lighting.sea_error[2],
                               s.lighting_error[0],
                               s.lighting_error[1],
                               s.lighting_error[2],
                               static_cast<double>(s.lighting.evaluations),
                               s.lighting.converged ? 1.0 : 0.0};
      out << i << ',' << format_number(s.image_x) << ',' << format_number(s.image_y) << ','
          << (s.hit ? 1 : 0);
      for (const double v : values) out << ',' << format_number(v);
      out << ',' << (s.object ? 1 : 0) << ',' << (s.reflects_object ? 1 : 0) << '\n';
    }
    // The pixel exactly as render writes it (its float32 is the EXR's value).
    const Vec3 pixel = resolve_pixel(samples);
    out << "pixel,R,G,B\npixel," << format_number(pixel[0]) << ',' << format_number(pixel[1]) << ','
        << format_number(pixel[2]) << '\n';
  };
}

}  // namespace oceanref::cli
