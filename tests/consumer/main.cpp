// A program linked against an installed oceanref (tests/consumer/CMakeLists.txt). It checks
// numbers that the library must reproduce bit for bit on any machine (DESIGN.md, determinism
// contract), through four of its layers, and exits 1 on any difference:
//   - the spectral moments of the Pierson–Moskowitz spectrum at U10 = 10 m/s, as
//     `oceanref spectrum --model pierson-moskowitz --moments` prints them;
//   - the scene file given (reference/scenes/default.json): its cascades and the m0 of its
//     JONSWAP spectrum, as `oceanref spectrum --model jonswap --wind-speed 10 --fetch 100000
//     --moments` prints it;
//   - SHA-256 of "abc" (FIPS 180-2, appendix B.1) from io/;
//   - the version the library reports (conformance/) against the installed <oceanref/version.h>.
//
//   consumer SCENE.json
#include <oceanref/version.h>

#include <oceanref/conformance/provenance.h>
#include <oceanref/io/sha256.h>
#include <oceanref/scene/scene.h>
#include <oceanref/spectrum/model.h>
#include <oceanref/spectrum/moments.h>
#include <cstdio>
#include <string>

static_assert(OCEANREF_VERSION_MAJOR >= 0 && OCEANREF_VERSION_MINOR >= 1,
              "oceanref/version.h defines the version numbers");

namespace {
int failures = 0;

void check(const char* what, double got, double expected) {
  const bool same = got == expected;  // the same double: 17 significant digits round-trip
  std::printf("%s %s = %.17g (expected %.17g)\n", same ? "ok  " : "FAIL", what, got, expected);
  if (!same) ++failures;
}
void check(const char* what, const std::string& got, const std::string& expected) {
  const bool same = got == expected;
  std::printf("%s %s = %s (expected %s)\n", same ? "ok  " : "FAIL", what, got.c_str(),
              expected.c_str());
  if (!same) ++failures;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer SCENE.json\n");
    return 2;
  }
  using namespace oceanref;
  try {
    SpectrumSettings pm;
    pm.model = SpectrumModel::pierson_moskowitz;
    const SpectralMoments m = spectral_moments(make_spectrum(pm), kDefaultMaxWavenumber);
    check("pierson-moskowitz m0 [m^2]", m.m0, 0.31500142590943031);
    check("pierson-moskowitz Hs [m]", m.significant_wave_height, 2.2449995132629508);
    check("pierson-moskowitz mss", m.mss, 0.032925778260240263);

    const Scene scene = load_scene(argv[1], nullptr);
    check("scene cascades", static_cast<double>(scene.waves.sizes.size()), 4.0);
    const SpectralMoments j =
        spectral_moments(make_spectrum(scene.waves.spectrum), kDefaultMaxWavenumber);
    check("scene spectrum m0 [m^2]", j.m0, 0.25328239613311077);

    check("sha256(abc)", sha256_hex(std::string("abc")),
          "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    check("library version", oceanref_version(), std::string("oceanref ") + OCEANREF_VERSION);
  } catch (const std::exception& e) {
    std::printf("FAIL: %s\n", e.what());
    return 1;
  }
  std::printf("consumer: %s\n", failures == 0 ? "all checks passed" : "FAILED");
  return failures == 0 ? 0 : 1;
}
