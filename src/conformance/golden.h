// The golden suite (ROOT/golden/manifest.json; `oceanref golden verify|update`): every scene of
// the manifest re-rendered and its fields re-synthesized, checked bit for bit against the
// stored SHA-256 of the float32 pixels and fields and of the doubles behind them
// (conformance/render_output.h, conformance/fields_output.h; docs/FILES.md).
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace oceanref {

struct RenderedImage;
struct Scene;

struct GoldenOptions {
  int threads = 1;
  std::vector<std::string> only;                // just these scenes of the manifest (empty: all)
  std::function<void(const std::string&)> log;  // progress notes (may be empty)
};

// The hashes of one entry, in the manifest's key order of the contract.
inline constexpr const char* kGoldenHashKeys[] = {"pixel_sha256", "radiance_f64_sha256",
                                                  "fields_sha256", "fields_f64_sha256"};

struct GoldenSceneResult {
  std::string name;
  bool same = false;  // every hash of kGoldenHashKeys equals the manifest's
  // verify: "identical" or "MISMATCH"; update: "unchanged" or "updated".
  std::string status;
  std::string pixel_sha256;          // as computed now
  std::vector<std::string> differs;  // the keys of kGoldenHashKeys that differ
  // verify, on a mismatch: compare's table of the stored image against the new one, or
  // "# cannot compare with FILE: why".
  std::string comparison;
  // golden_physics_failures of the render: a scene with any is "INVALID" (update writes nothing
  // of it), whatever its hashes.
  std::vector<std::string> physics;
};

struct GoldenReport {
  std::vector<GoldenSceneResult> scenes;
  int mismatches = 0;  // verify: scenes that differ (update: 0)
  int invalid = 0;     // scenes whose render fails golden_physics_failures
  bool pass() const { return mismatches == 0 && invalid == 0; }
};

// What a golden render must show besides its hashes, one line per failure (a hash cannot tell a
// correct image from a bug, and `golden update` would bake a bug in): every key of the scene has
// an effect (Scene::unused is empty: no feature is inert), a scene with whitecaps shows foam,
// every radiance and lighting term is finite with luminance >= 0 (a channel of linear sRGB may be
// negative outside its gamut: a grazing sun), every lighting error >= 0, the coverage in [0, 1],
// and a pixel of open sky (no sea in it or around it, a fixed sample grid, no objects, away from
// the sun) is the mean of the Preetham sky over its samples' rays, to 1e-12 relative. `image`
// holds the layers.
std::vector<std::string> golden_physics_failures(const Scene& scene, const RenderedImage& image);

// Bad input: no or invalid manifest (`option` "root"), a scene of `only` not in it ("only").
class GoldenInputError : public std::invalid_argument {
 public:
  GoldenInputError(std::string option, const std::string& message)
      : std::invalid_argument(message), option_(std::move(option)) {}
  const std::string& option() const { return option_; }

 private:
  std::string option_;
};

// Re-renders every selected scene and compares its four hashes with the manifest.
GoldenReport verify_golden(const std::filesystem::path& root, const GoldenOptions& options);
// Re-renders every selected scene, rewrites ROOT/golden/NAME.exr and NAME.fields.exr and the
// manifest's entries (hashes, scene hash, size, version, lighting accuracy and error); the
// manifest is written to a temporary name and renamed.
GoldenReport update_golden(const std::filesystem::path& root, const GoldenOptions& options);

// The CSV `oceanref golden` prints: name,status,pixel_sha256 per scene; after a mismatch the
// line "# differs: KEY…" and the comparison.
std::string golden_text(const GoldenReport& report);

}  // namespace oceanref
